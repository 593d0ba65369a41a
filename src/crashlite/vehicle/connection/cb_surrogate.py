"""Step 4 with the replaced structure as a Craig–Bampton superelement (beyond the paper).

``build_cb_surrogate`` keeps the front structure up to the cut as the other
surrogates do and joins the cut nodes, and the nodes behind it kept for
output (the cell frame's history nodes), to one linear superelement with
stiffness and mass (``craig_bampton``; *ELEMENT_DIRECT_MATRIX_INPUT with
STIF and MASS in a DMIG file beside the deck). No rear rigid body: the
superelement's mass is the replaced structure's, its rigid motions exact,
its held modes ring on their own. Each mode's amplitude is the y of one
extra node (x and z held, no element but the superelement); q = s·y with
s² = ``MODAL_MASS``, so the mode's mass at that node is a gram, as the
condensed surrogate's modal nodes.

Mass the static model does not carry (on nodes outside it: nodal rigid
bodies, masses on nothing) would be lost; it is put on the boundary
nodes rigidly (each boundary node's share by least squares of the six
rigid motions), and said.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ...model.mesh import Nodes
from ..car.records import id_list, record
from ..steps.cut import Cut
from ..steps.massprops import ReplacedMass
from ..steps.surrogate import Surrogate, _Ids, kept_front, retitle
from .condense import rigid_modes
from .condensed import MODAL_MASS, CondensedSurrogate
from .craig_bampton import craig_bampton


def build_cb_surrogate(
    cut: Cut,
    mass: ReplacedMass,
    modes: int = 20,
    keep_nodes: ArrayLike | None = None,
    drill: float = 1e-3,
    stiffness: float = 0.0,
    shells: str = "static",
) -> Surrogate:
    """The surrogate deck with the replaced structure a Craig–Bampton
    superelement (module docstring); ``stiffness``: step 3's K, reported
    (the superelement carries the structure's own); ``shells``: the shells'
    stiffness (``stiffness.build_static``)."""
    full = cut.model
    tr, ride = kept_front(cut, keep_nodes)
    cb = craig_bampton(cut, modes=modes, kept=ride, drill=drill, shells=shells)
    notes = list(cut.notes) + [n for n in cb.notes if n not in cut.notes] + tr.notes
    m = tr.model
    ids = _Ids(m)
    nq = len(cb.omega2)
    s = np.sqrt(MODAL_MASS)
    scale = np.concatenate([np.ones(3 * len(cb.nodes)), np.full(nq, s)])
    k = cb.stiffness * scale[:, None] * scale[None, :]
    mm = cb.mass * scale[:, None] * scale[None, :]
    # what the static model does not carry, put on the boundary as a rigid mass (module docstring)
    st = mass.structure
    missing = st.mass - cb.structure_mass
    if missing > 1e-6 * st.mass:
        xyz_b = full.nodes.xyz[cb.nodes]
        r = rigid_modes(xyz_b, st.cog).reshape(-1, 6)
        have = r.T @ mm[: len(r), : len(r)] @ r
        want = np.zeros((6, 6))
        want[:3, :3] = np.eye(3) * st.mass
        want[3:, 3:] = np.asarray(st.inertia)
        p = np.linalg.pinv(r.T)  # (3k, 6): a boundary load pattern for each rigid motion
        mm[: len(r), : len(r)] += p @ (want - have) @ p.T
        notes.append(
            f"{1e3 * missing:.1f} kg of the replaced structure is not on its static model: put on the "
            "boundary so that mass and inertia are the structure's"
        )
    modal_ids = np.arange(ids.node, ids.node + nq, dtype=np.int64)
    ids.node += nq
    if nq:
        mn = Nodes.zeros(nq)
        mn.ids, mn.xyz = modal_ids, np.repeat(cb.cog[None], nq, axis=0)
        mn.tc[:], mn.rc[:] = 6, 7
        m.nodes = Nodes.concat([m.nodes, mn])
    dofs = np.concatenate([np.repeat(full.nodes.ids[cb.nodes], 3), modal_ids])
    comps = np.concatenate([np.tile([1, 2, 3], len(cb.nodes)), np.full(nq, 2)])
    eid = ids.take("element")
    m.keywords.append(
        record("ELEMENT_DIRECT_MATRIX_INPUT", eid=eid, ifrmt=1, filename="simplified.dmig", mass="MCUT", stif="KCUT")
    )
    sid = ids.take("set")  # the cut nodes, for the verification's split (no rigid body on them)
    m.sets[("NODE", sid)] = id_list(
        "SET_NODE_LIST_TITLE", sid, full.nodes.ids[cb.nodes[: cb.cut_nodes]], title="surrogate interface (condensed)"
    )
    retitle(m, "Craig-Bampton")
    notes.append(
        f"the replaced structure as a Craig-Bampton superelement on {cb.cut_nodes} cut nodes and "
        f"{len(cb.nodes) - cb.cut_nodes} kept nodes behind the cut ({3 * len(cb.nodes)} DOFs) and its {nq} "
        "lowest modes held at them"
        + (f" ({cb.frequencies[0]:.3g} to {cb.frequencies[-1]:.3g} per time unit)" if nq else "")
    )
    return CondensedSurrogate(
        m,
        [],
        float(stiffness),
        mass,
        tr,
        {"modes": [int(i) for i in modal_ids]} if nq else {},
        {},
        {},
        "craig-bampton",
        notes,
        {},
        (np.stack([dofs, comps], axis=1), 0.5 * (k + k.T)),
        0.5 * (mm + mm.T),
        cb,
    )
