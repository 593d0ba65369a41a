"""Step 4 with the condensed structure instead of springs (beyond the paper).

``build_condensed_surrogate`` keeps the front structure up to the cut as
``surrogate.build_surrogate`` does, but leaves the cut nodes free (no
interface rigid body) and joins each of them to the rear body through the
replaced structure's condensed stiffness (``condense``): one linear
superelement (*ELEMENT_DIRECT_MATRIX_INPUT, the matrix in a NASTRAN DMIG
file next to the deck) on the cut nodes' translations and on four anchor
nodes of the rear body, whose translations stand for its rigid motion q
(q = L·u_anchor, L the least-squares inverse of the anchors' rigid modes):

    K = [[K_s, −K_s B L], [−Lᵀ Bᵀ K_s, Lᵀ Bᵀ K_s B L]]

with B the cut nodes' rigid modes about the CoG: the cut's displacement
relative to the rear body's rigid motion, u_b − B q, meets the structure's
stiffness, and any rigid motion of the whole is free. So the cut bends as
the elastic structure behind it would under the crash's quasi-static
deceleration, which a rigid interface holds flat; the springs' load-path
shares are not needed (the condensed matrix distributes the load).

Waves: dashpots between each cut node and the rear body along the axis,
of the replaced structure's impedance there (``impedance``), let a stress
wave that reaches the cut run out as it runs on into the full model's
structure, instead of coming back from light nodes on springs.

Mass: the replaced elements' share at the cut nodes (``relief.
replaced_node_masses``) stays on them (*ELEMENT_MASS), so the cut's nodes
are as heavy as in the full model; the rear body (*CONSTRAINED_NODAL_RIGID_
BODY_INERTIA) carries the rest with its own CoG and inertia: mass, CoG and
inertia of the whole are exact.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from ...model import mass as mk
from ...model.mesh import Discretes, Masses, Nodes
from ..car.records import id_list, record
from ..steps.cut import Cut
from ..steps.massprops import ReplacedMass
from ..steps.surrogate import Surrogate, _Ids, _whole_vehicle_sets, kept_front, retitle
from .condense import Condensation, rigid_modes
from .impedance import axial_impedance

ANCHOR = 300.0  # [length] distance of the rear body's four anchor nodes from its CoG
DASHPOT_ARM = 100.0  # [length] a cut dashpot's rear end: this far behind its cut node, on the rear body
MODAL_MASS = 1e-6  # [mass] of each modal node (1 g in mm–t–s): η = √μ·y, its kinetic energy ½μẏ² = ½η̇²


def superelement_matrix(cond: Condensation, anchors: np.ndarray, modal_mass: float = MODAL_MASS) -> np.ndarray:
    """(3k + 12 + N, 3k + 12 + N) the superelement on the cut nodes' and the
    four anchors' translations and the N modal nodes' y (module docstring):
    Cᵀ K_r C + diag(0, μΩ²), C = [I, −B L, −√μ Φ]."""
    b = rigid_modes(cond.xyz_nodes, cond.cog).reshape(-1, 6)
    lmap = np.linalg.pinv(rigid_modes(anchors, cond.cog).reshape(-1, 6))  # (6, 12)
    n = 0 if cond.modal is None else cond.modal.shape[1]
    parts = [np.eye(len(b)), -b @ lmap] + ([-np.sqrt(modal_mass) * cond.modal] if n else [])
    c = np.hstack(parts)
    kr = cond.stiffness if not n else cond.residual
    k = c.T @ kr @ c
    if n:
        k[-n:, -n:] += np.diag(modal_mass * cond.omega2)
    return 0.5 * (k + k.T)


@dataclass
class CondensedSurrogate(Surrogate):
    """A Surrogate whose deck needs its matrix file beside it."""

    matrix: tuple | None = None  # (dofs (k, 2) [node ID, component], K)
    mass_matrix: np.ndarray | None = None  # (k, k) M on the same DOFs, or None (no mass in the superelement)
    craig_bampton: object | None = None  # the craig_bampton.CraigBampton it was built from, if any

    def write(self, path: Path | str, fmt: str = "fixed") -> Path:
        from ...keyword.dmig import write_dmig

        path = Path(path)
        name = path.stem + ".dmig"
        for rec in self.model.find("ELEMENT_DIRECT_MATRIX_INPUT"):
            rec["filename"] = name
        mats = {"KCUT": self.matrix}
        if self.mass_matrix is not None:
            mats["MCUT"] = (self.matrix[0], self.mass_matrix)
        write_dmig(path.parent / name, mats)
        return super().write(path, fmt)


def build_condensed_surrogate(
    cut: Cut, cond: Condensation, mass: ReplacedMass, keep_nodes: ArrayLike | None = None, dashpots: bool = True
) -> Surrogate:
    """The surrogate deck joined at the cut by the condensed structure
    (module docstring); ``dashpots``: the cut's wave impedance along the
    axis (``impedance``) between each cut node and the rear body."""
    full = cut.model
    notes = list(cut.notes) + [n for n in cond.notes if n not in cut.notes]
    tr, ride = kept_front(cut, keep_nodes)
    notes += tr.notes
    m = tr.model
    ids = _Ids(m)
    st = mass.structure
    # the cut nodes keep the replaced elements' share of their mass; the rear body the rest
    mb = cond.node_mass[cond.nodes]
    whole = mk.point_moments([st.cog], [st.mass], [st.inertia])
    rest_mp = mk.combine(whole, mk.point_moments(cond.xyz_nodes, mb), weights_mask=[None, -np.ones(len(mb))])
    rest, c, inertia = rest_mp.mass, rest_mp.cog, rest_mp.inertia
    tet = np.array([[1.0, 1.0, 1.0], [1.0, -1.0, -1.0], [-1.0, 1.0, -1.0], [-1.0, -1.0, 1.0]]) / np.sqrt(3.0)
    anchors = cond.cog + ANCHOR * tet
    dc = axial_impedance(cut, cond.nodes) if dashpots else np.zeros(len(cond.nodes))
    damped = np.flatnonzero(dc > 0)
    ends = cond.xyz_nodes[damped] - DASHPOT_ARM * cut.axis
    new_xyz = np.vstack([[c], anchors, ends])
    new_ids = np.arange(ids.node, ids.node + len(new_xyz), dtype=np.int64)
    ids.node += len(new_xyz)
    nodes = Nodes.zeros(len(new_ids))
    nodes.ids, nodes.xyz = new_ids, new_xyz
    m.nodes = Nodes.concat([m.nodes, nodes])
    _whole_vehicle_sets(full, cut, m, new_ids, notes)
    g_id, a_ids, end_ids = int(new_ids[0]), new_ids[1:5], new_ids[5:]
    # one node per kept mode: its y is the modal coordinate (x and z held, so a vehicle's initial velocity
    # along x leaves it at rest); its mass μ comes off the rear body
    n_modes = 0 if cond.modal is None else cond.modal.shape[1]
    modal_ids = np.arange(ids.node, ids.node + n_modes, dtype=np.int64)
    ids.node += n_modes
    if n_modes:
        mn = Nodes.zeros(n_modes)
        mn.ids, mn.xyz = modal_ids, np.repeat(c[None], n_modes, axis=0)
        mn.tc[:], mn.rc[:] = 6, 7
        m.nodes = Nodes.concat([m.nodes, mn])
        rest -= n_modes * MODAL_MASS
    # the cut nodes' masses
    lumps = Masses.zeros(len(mb) + n_modes)
    lumps.ids = np.arange(ids.element, ids.element + len(lumps.ids), dtype=np.int64)
    ids.element += len(lumps.ids)
    lumps.node = m.node_index(np.concatenate([full.nodes.ids[cond.nodes], modal_ids])).astype(np.int32)
    lumps.mass = np.concatenate([mb, np.full(n_modes, MODAL_MASS)])
    m.masses = Masses.concat([m.masses, lumps])
    # the superelement
    dofs = np.concatenate([np.repeat(full.nodes.ids[cond.nodes], 3), np.repeat(a_ids, 3), modal_ids])
    comps = np.concatenate([np.tile([1, 2, 3], len(cond.nodes) + len(a_ids)), np.full(n_modes, 2)])
    k = superelement_matrix(cond, anchors)
    eid = ids.take("element")
    m.keywords.append(record("ELEMENT_DIRECT_MATRIX_INPUT", eid=eid, ifrmt=1, filename="simplified.dmig", stif="KCUT"))
    sid = ids.take("set")  # the cut nodes, for the verification's split (no rigid body on them)
    m.sets[("NODE", sid)] = id_list(
        "SET_NODE_LIST_TITLE", sid, full.nodes.ids[cond.nodes], title="surrogate interface (condensed)"
    )
    if len(damped):  # one damper material of unit constant, each element's S its node's ρ·c·A
        sec, mid, pid = ids.take("section"), ids.take("material"), ids.take("part")
        m.sections[sec] = record("SECTION_DISCRETE_TITLE", card_title="surrogate cut dashpots", secid=sec)
        m.materials[mid] = record("MAT_DAMPER_VISCOUS_TITLE", card_title="surrogate cut dashpots", mid=mid, dc=1.0)
        m.parts[pid] = record("PART", heading="surrogate cut dashpots", pid=pid, secid=sec, mid=mid)
        d = Discretes.zeros(len(damped))
        d.ids = np.arange(ids.element, ids.element + len(damped), dtype=np.int64)
        ids.element += len(damped)
        d.pid[:] = pid
        d.nodes = np.stack([m.node_index(full.nodes.ids[cond.nodes[damped]]), m.node_index(end_ids)], axis=1).astype(
            np.int32
        )
        d.scale = dc[damped]
        m.discretes = Discretes.concat([m.discretes, d])
        notes.append(
            f"{len(damped)} dashpots along the axis between the cut nodes and the rear body, "
            f"{dc.sum():.4g} in all: the replaced structure's wave impedance at the cut"
        )
    # the rear body
    pid = ids.take("part")
    sid = ids.take("set")
    members = np.unique(np.concatenate([[g_id], a_ids, end_ids, full.nodes.ids[ride]]))
    m.sets[("NODE", sid)] = id_list("SET_NODE_LIST_TITLE", sid, members, title="surrogate rear body")
    m.keywords.append(
        record(
            "CONSTRAINED_NODAL_RIGID_BODY_INERTIA",
            pid=pid,
            nsid=sid,
            xc=float(c[0]),
            yc=float(c[1]),
            zc=float(c[2]),
            tm=rest,
            nodeid=g_id,
            ixx=float(inertia[0, 0]),
            ixy=float(inertia[0, 1]),
            ixz=float(inertia[0, 2]),
            iyy=float(inertia[1, 1]),
            iyz=float(inertia[1, 2]),
            izz=float(inertia[2, 2]),
        )
    )
    retitle(m, "condensed")
    notes.append(
        f"the replaced structure condensed on {len(cond.nodes)} cut nodes ({3 * len(cond.nodes)} DOFs), "
        f"{1e3 * mb.sum():.1f} kg of it on them, the rest on the rear body"
        + (
            f"; its {n_modes} lowest free modes ({cond.frequencies[0]:.3g} to {cond.frequencies[-1]:.3g} per "
            "time unit) move on their own, the rest as residual stiffness"
            if n_modes
            else ""
        )
    )
    if len(cond.left_out):
        notes.append(f"{len(cond.left_out)} cut node(s) left free (not condensed)")
    # along the axis, the cut held rigid and free to turn (as step 3 loads its interface)
    flex = np.linalg.inv(cond.rigid_stiffness(cond.xyz_nodes.mean(axis=0)))[:3, :3]
    return CondensedSurrogate(
        m,
        [],
        float(1.0 / (cut.axis @ flex @ cut.axis)),
        mass,
        tr,
        {
            "cog": g_id,
            **{f"anchor {i + 1}": int(a) for i, a in enumerate(a_ids)},
            **({"modes": [int(i) for i in modal_ids]} if n_modes else {}),
        },
        {"rear body": pid},
        {},
        "condensed",
        notes,
        {"rear body": mk.MassProperties(rest, c, inertia)},
        (np.stack([dofs, comps], axis=1), k),
    )
