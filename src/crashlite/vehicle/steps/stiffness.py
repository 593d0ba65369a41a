"""Step 3 of the simplified vehicle: longitudinal stiffness of the replaced structure.

The replaced structure of a ``Cut`` (its replaced elements), borne at the
rear-axle attachment points (all six DOFs held by default), is loaded by a
rigid body that ties every interface node to a master at their centroid,
with a force F along the load direction (default: rearwards, −axis, the
way the front structure pushes it). A linear static solve (``statics``,
``elements``) gives the master's displacement u along that direction, and

    K = F / u        (the paper's table 3: 1000 N / 0.0424 mm = 23 584.9 N/mm)

What the static model takes from the deck:

- shells (section thickness or nodal thickness, E and ν of the material),
  solids (hexahedra), beams (*SECTION_BEAM resultants or shapes), discrete
  springs (MAT_SPRING_ELASTIC k; the initial slope of nonlinear and
  inelastic spring curves; dampers carry no static load);
- rigid parts (*MAT_RIGID, extra nodes, merged bodies), nodal rigid bodies
  and spot welds as rigid links between their nodes in the structure;
- materials without E (or with E = 0) carry nothing and are listed in
  ``notes``; so are contacts, tied contacts and joints (not modelled).

``structure_stiffness`` does the same for any element selection of a
Model, with explicit support and load nodes (used by the tests on tubes,
plates and frames with closed-form answers).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ...model.model import Model
from . import elements as el
from .cut import ELEMENT_TABLES, Cut, rigid_part_ids
from .massprops import NodeSelection, node_indices
from .statics import LinearStatic, MechanismError, StaticSolution


@dataclass
class StiffnessResult:
    """Result of the stiffness solve (step 3)."""

    stiffness: float  # K = F / u [force/length]
    force: float  # F [force]
    displacement: float  # u, the load point's displacement along the load direction [length]
    direction: np.ndarray  # (3,) unit load direction
    load_point: np.ndarray  # (3,) master of the rigid interface [length]
    load_point_motion: np.ndarray  # (6,) its displacement [length] and rotation [rad]
    support_reaction: np.ndarray  # (3,) sum of the support reactions [force]
    elements: dict  # element type -> count in the static model
    n_dofs: int
    notes: list = field(default_factory=list)
    solution: StaticSolution | None = None
    nodes: np.ndarray | None = None  # (n,) node indices of the model in the static model
    transverse: dict | None = None  # lateral, vertical, shear and roll stiffness on the same factorisation
    flexibility: np.ndarray | None = None  # (6, 6) [u; θ] per unit [F; M] at load_point (inertia relief)

    def table(self) -> dict:
        """The paper's table 3."""
        return {"force": self.force, "displacement": self.displacement, "stiffness": self.stiffness}


def _material(model: Model, pid: int):
    part = model.parts.get(int(pid))
    return model.materials.get(part.get("mid")) if part is not None else None


def _elastic(mat) -> tuple[float, float] | None:
    if mat is None or mat.keyword.startswith("MAT_NULL"):
        return None
    e = float(mat.get("e", 0.0) or 0.0)
    return (e, float(mat.get("pr", 0.0) or 0.0)) if e > 0 else None


def _shell_thickness(model: Model, idx: np.ndarray) -> np.ndarray:
    s = model.shells
    t = s.thickness[idx]
    out = np.zeros(len(idx))
    for pid in np.unique(s.pid[idx]):
        part = model.parts.get(int(pid))
        sec = model.sections.get(part.get("secid")) if part is not None else None
        t1 = float(sec.get("t1", 0.0) or 0.0) if sec is not None else 0.0
        ts = [t1] + [float(sec.get(f"t{i}", 0.0) or 0.0) or t1 for i in (2, 3, 4)] if sec is not None else [0.0] * 4
        m = s.pid[idx] == pid
        out[m] = np.nanmean(np.where(np.isnan(t[m]), np.array(ts), t[m]), axis=1)
    return out


def _spring_k(model: Model, mat) -> float | None:
    """Static stiffness of a discrete material: k, or the slope of its curve at 0."""
    if mat is None:
        return None
    kw = mat.keyword
    if kw == "MAT_SPRING_ELASTIC":
        return float(mat["k"])
    if kw.startswith("MAT_DAMPER"):
        return 0.0
    lc = {
        "MAT_SPRING_NONLINEAR_ELASTIC": "lcd",
        "MAT_SPRING_INELASTIC": "lcfd",
        "MAT_SPRING_GENERAL_NONLINEAR": "lcdl",
    }.get(kw)
    if lc is None or int(mat.get(lc, 0) or 0) not in model.curves:
        return None
    rec = model.curves[int(mat[lc])]
    x = (np.asarray(rec.rows["a1"], float) + float(rec.get("offa", 0.0) or 0.0)) * float(rec.get("sfa", 1.0) or 1.0)
    y = (np.asarray(rec.rows["o1"], float) + float(rec.get("offo", 0.0) or 0.0)) * float(rec.get("sfo", 1.0) or 1.0)
    if len(x) < 2:
        return None
    h = 1e-6 * max(float(np.abs(x).max()), 1e-12)
    lo, hi = max(-h, x[0]), min(h, x[-1])
    return float((np.interp(hi, x, y) - np.interp(lo, x, y)) / (hi - lo)) if hi > lo else None


SHELL_STIFFNESS = ("static", "kernel")


def build_static(
    model: Model, select: dict | None = None, drill: float = 1e-3, shells: str = "static"
) -> tuple[LinearStatic, dict, list]:
    """A LinearStatic of the selected elements of ``model`` (table name ->
    bool mask or index array; None: every element) with its rigid links;
    ``shells``: "static" (QM6 membrane, MITC4 plate) or "kernel" (the time
    loop's own shell elements linearised, ``kernel_stiffness``).
    Returns (problem, element counts, notes)."""
    if shells not in SHELL_STIFFNESS:
        raise ValueError(f"shells={shells!r}: one of {SHELL_STIFFNESS}")
    from ...solver.beams import _frames, _properties

    notes: list = []
    sel = {}
    for t in ELEMENT_TABLES:
        n = len(getattr(model, t))
        m = np.ones(n, bool) if select is None or select.get(t) is None else np.asarray(select[t])
        if m.dtype != bool:
            b = np.zeros(n, bool)
            b[m] = True
            m = b
        sel[t] = m
    rigid = rigid_part_ids(model)
    xyz = model.nodes.xyz
    ls = LinearStatic(xyz)
    counts = {}
    in_structure = np.zeros(len(xyz), bool)
    skipped: dict = {}

    def usable(table, idx):
        tab = getattr(model, table)
        ok = np.zeros(len(idx), bool)
        props = np.zeros((len(idx), 2))
        for pid in np.unique(tab.pid[idx]):
            m = tab.pid[idx] == pid
            if int(pid) in rigid:
                conn = tab.nodes[idx[m]]
                in_structure[conn[conn >= 0]] = True
                continue
            ev = _elastic(_material(model, pid))
            if ev is None:
                skipped[int(pid)] = skipped.get(int(pid), 0) + int(m.sum())
                continue
            ok[m] = True
            props[m] = ev
        return idx[ok], props[ok]

    idx, props = usable("shells", np.flatnonzero(sel["shells"]))
    if len(idx):
        conn = model.shells.nodes[idx].astype(np.int64)
        t = _shell_thickness(model, idx)
        if np.any(t <= 0):
            raise ValueError(f"{int((t <= 0).sum())} shells have no thickness")
        if shells == "kernel":
            from .kernel_stiffness import kernel_shell_stiffness

            ke = kernel_shell_stiffness(model, idx, drill=drill)
        else:
            ke = el.shell_stiffness(xyz[conn], t, props[:, 0], props[:, 1], drill=drill)
        ls.add_elements(conn, ke)
        in_structure[conn.ravel()] = True
        counts["shell"] = len(idx)
    idx, props = usable("solids", np.flatnonzero(sel["solids"]))
    if len(idx):
        conn = model.solids.nodes[idx].astype(np.int64)
        ls.add_elements(conn, el.hex_stiffness(xyz[conn], props[:, 0], props[:, 1]), dofs_per_node=3)
        in_structure[conn.ravel()] = True
        counts["solid"] = len(idx)
    idx, props = usable("beams", np.flatnonzero(sel["beams"]))
    if len(idx):
        b = model.beams
        conn = b.nodes[idx].astype(np.int64)
        sec = np.zeros((len(idx), 4))
        for pid in np.unique(b.pid[idx]):
            part = model.parts[int(pid)]
            s = model.sections.get(part.get("secid"))
            if s is None or s.keyword != "SECTION_BEAM":
                raise ValueError(f"beams of part {int(pid)} have no *SECTION_BEAM")
            sec[b.pid[idx] == pid] = _properties(s, None)
        frames = _frames(xyz, conn[:, 0], conn[:, 1], conn[:, 2])
        e, nu = props[:, 0], props[:, 1]
        g = e / (2 * (1 + nu))
        ls.add_elements(
            conn[:, :2],
            el.beam_stiffness(
                xyz[conn[:, 0]], xyz[conn[:, 1]], frames, e * sec[:, 0], g * sec[:, 3], e * sec[:, 1], e * sec[:, 2]
            ),
        )
        in_structure[conn[:, :2].ravel()] = True
        counts["beam"] = len(idx)
    d = model.discretes
    didx = np.flatnonzero(sel["discretes"])
    if len(didx):
        ks = np.zeros(len(didx))
        for pid in np.unique(d.pid[didx]):
            m = d.pid[didx] == pid
            k = _spring_k(model, _material(model, pid))
            if k is None:
                skipped[int(pid)] = skipped.get(int(pid), 0) + int(m.sum())
            else:
                ks[m] = k * d.scale[didx[m]]
        if np.any(d.vid[didx] > 0):
            notes.append("discrete orientation vectors (VID) ignored: springs act along their nodes")
        conn = d.nodes[didx].astype(np.int64)
        two = (conn[:, 1] >= 0) & (ks != 0)
        vec = xyz[np.maximum(conn[:, 1], 0)] - xyz[conn[:, 0]]
        ln = np.linalg.norm(vec, axis=1)
        if np.any(two & (ln == 0)):
            notes.append("springs of zero length ignored (no direction)")
            two &= ln > 0
        if two.any():
            kk = el.spring_stiffness(vec[two] / ln[two, None], ks[two])
            ls.add_elements(conn[two], kk, dofs_per_node=3)
            in_structure[conn[two].ravel()] = True
            counts["discrete"] = int(two.sum())
        if np.any(conn[:, 1] < 0):
            notes.append("grounded springs ignored")
    for pid, k in skipped.items():
        mat = _material(model, pid)
        notes.append(f"part {pid}: {k} element(s) without static stiffness ({mat.keyword if mat else 'no material'})")
    from .cut import rigid_groups

    for g in rigid_groups(model):
        nodes = g.nodes[in_structure[g.nodes]]
        if len(nodes) >= 2:
            ls.add_rigid(nodes)
    for kw in ("CONTACT_TIED", "CONTACT_SPOTWELD", "CONSTRAINED_JOINT", "CONSTRAINED_TIE", "CONSTRAINED_INTERPOLATION"):
        if model.find(kw):
            notes.append(f"*{kw}... is not modelled in the static solve")
    ls.in_structure = in_structure
    return ls, counts, notes


def borne_structure(
    model: Model,
    support: NodeSelection,
    load_nodes: NodeSelection,
    select: dict | None = None,
    support_dofs: ArrayLike = (0, 1, 2, 3, 4, 5),
    load_point: ArrayLike | None = None,
    drill: float = 1e-3,
) -> tuple[LinearStatic, int, dict, list]:
    """The static model of the selected elements held at ``support`` with a
    rigid body (its master returned) over ``load_nodes``:
    (LinearStatic, master, element counts, notes)."""
    ls, counts, notes = build_static(model, select, drill)
    sup = node_indices(model, support)
    ld = node_indices(model, load_nodes)
    outside = ~ls.in_structure[sup]
    if outside.all():
        raise ValueError("no support node is a node of the structure")
    if outside.any():
        notes.append(f"{int(outside.sum())} support node(s) outside the structure ignored")
    ld = ld[ls.in_structure[ld]]
    if not len(ld):
        raise ValueError("no load node is a node of the structure")
    ls.fix(sup[~outside], support_dofs)
    return ls, ls.add_rigid(ld, load_point), counts, notes


def solve_named(ls: LinearStatic, model: Model, cases: list) -> list:
    """``ls.solve_cases`` with a mechanism's nodes named by their deck IDs."""
    try:
        return ls.solve_cases(cases)
    except MechanismError as e:
        ids = model.nodes.ids[e.nodes[e.nodes < len(model.nodes)]]
        if not len(ids):
            raise
        raise MechanismError(f"{e} (deck node IDs {ids[:10].tolist()})", e.nodes) from None


def vehicle_axes(axis: ArrayLike) -> np.ndarray:
    """(3, 3) rows: the unit ``axis``, the lateral and the vertical direction
    (lateral = z × axis unless the axis is near z)."""
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    ref = np.array([0.0, 0.0, 1.0]) if abs(a[2]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e_lat = np.cross(ref, a)
    e_lat /= np.linalg.norm(e_lat)
    return np.array([a, e_lat, np.cross(a, e_lat)])


def transverse_loads(axis: np.ndarray, force: float, moment: float) -> dict:
    """The rigid interface's transverse load cases: name -> (force (3,), moment (3,))."""
    a, e_lat, e_ver = vehicle_axes(axis)
    return {
        "lateral": (e_lat * force, np.zeros(3)),
        "vertical": (e_ver * force, np.zeros(3)),
        "roll": (np.zeros(3), a * moment),
    }


def transverse_stiffnesses(across: dict, motions: Iterable[tuple[np.ndarray, np.ndarray]]) -> dict:
    """Lateral, vertical and roll stiffness from the ``transverse_loads``
    cases and the interface's (displacement (3,), rotation (3,)) in each;
    shear is the softer of lateral and vertical."""
    out = {}
    for (key, (f, m)), (du, dth) in zip(across.items(), motions):
        out[key] = float(m @ m) / float(dth @ m) if key == "roll" else float(f @ f) / float(du @ f)
    out["shear"] = min(out["lateral"], out["vertical"])
    return out


def structure_stiffness(
    model: Model,
    support: NodeSelection,
    load_nodes: NodeSelection,
    force: float = 1000.0,
    direction: ArrayLike = (-1.0, 0.0, 0.0),
    select: dict | None = None,
    support_dofs: ArrayLike = (0, 1, 2, 3, 4, 5),
    load_point: ArrayLike | None = None,
    drill: float = 1e-3,
    transverse: tuple | None = None,
) -> StiffnessResult:
    """Stiffness of the selected elements of ``model`` borne at ``support``
    (node indices, ("set", SID) or a *SET_NODE title; ``support_dofs`` held)
    and loaded by a rigid body tying ``load_nodes`` to a master at their
    centroid (or ``load_point``) with ``force`` along ``direction``.
    ``transverse`` = (force, moment): also load it across ``direction``
    (both ways, the softer is the shear stiffness) and about it, on the same
    factorisation (``StiffnessResult.transverse``)."""
    ls, master, counts, notes = borne_structure(model, support, load_nodes, select, support_dofs, load_point, drill)
    dvec = np.asarray(direction, float).reshape(3)
    dvec = dvec / np.linalg.norm(dvec)
    across = {} if transverse is None else transverse_loads(dvec, *transverse)
    cases = [{master: np.concatenate([force * dvec, np.zeros(3)])}] + [
        {master: np.concatenate(fm)} for fm in across.values()
    ]
    sol, *others = solve_named(ls, model, cases)
    u = float(sol.u[master, :3] @ dvec)
    if not u > 0:
        raise ValueError(f"the load point moves {u:.3g} along the load: the structure is not stable under it")
    trans = transverse_stiffnesses(across, [(o.u[master, :3], o.u[master, 3:]) for o in others]) if across else None
    return StiffnessResult(
        force / u,
        float(force),
        u,
        dvec,
        ls.position(master),
        sol.u[master].copy(),
        sol.reaction_force,
        counts,
        sol.n_dofs,
        notes + sol.notes,
        sol,
        np.flatnonzero(ls.in_structure),
        trans,
    )


def longitudinal_stiffness(
    cut: Cut,
    support: NodeSelection,
    force: float = 1000.0,
    direction: ArrayLike | None = None,
    support_dofs: ArrayLike = (0, 1, 2, 3, 4, 5),
    interface_nodes: NodeSelection | None = None,
    drill: float = 1e-3,
    transverse: tuple | None = None,
) -> StiffnessResult:
    """Step 3: K of the structure ``cut`` replaces, borne at ``support``
    (the rear-axle attachment points: indices, ("set", SID) or a *SET_NODE
    title), loaded through its interface nodes (default: all of the cut)
    with ``force`` along ``direction`` (default −axis, rearwards);
    ``transverse`` = (force, moment) adds ``transverse_stiffness``'s cases
    on the same factorisation."""
    d = -cut.axis if direction is None else direction
    nodes = cut.interface_nodes if interface_nodes is None else node_indices(cut.model, interface_nodes)
    res = structure_stiffness(
        cut.model,
        support,
        nodes,
        force,
        d,
        select=cut.replaced,
        support_dofs=support_dofs,
        drill=drill,
        transverse=transverse,
    )
    res.notes = list(cut.notes) + res.notes
    return res


def transverse_stiffness(
    cut: Cut,
    support: NodeSelection,
    interface_nodes: NodeSelection | None = None,
    force: float = 1000.0,
    moment: float = 1.0e6,
) -> dict:
    """Shear and roll stiffness of the replaced structure at the interface,
    borne at ``support`` like step 3: the rigid interface loaded across the
    axis (both transverse directions, the softer taken) and about it.
    Returns {"shear": k_t [force/length], "roll": k_r [force·length/rad], "lateral", "vertical"}."""
    return longitudinal_stiffness(
        cut, support, force=force, interface_nodes=interface_nodes, transverse=(force, moment)
    ).transverse
