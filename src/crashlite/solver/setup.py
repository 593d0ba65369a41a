"""From a Model to the arrays the time loop works on.

This first solver stage runs models made of lumped masses and discrete
springs and dampers, with nodal constraints, initial velocities and
stationary planar rigid walls. Anything else in a deck that would change the
motion is refused with a message naming the keyword, so a run never silently
leaves part of the model out.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..keyword.errors import DeckError, Problem
from ..model.model import Model
from ..model.sets import history_nodes
from .initial import _initial_rotation, _initial_velocity
from .kernels.discrete import CURVE, DAMPER, GENERAL, INELASTIC, LINEAR
from .loads import build_nodal_loads
from .records import _curve, _node_set, _problem

# constraint code of *NODE TC (and RC, same numbering) -> held (x, y, z)
_TC = {0: (0, 0, 0), 1: (1, 0, 0), 2: (0, 1, 0), 3: (0, 0, 1), 4: (1, 1, 0), 5: (0, 1, 1), 6: (1, 0, 1), 7: (1, 1, 1)}


@dataclass
class Discrete:
    """Struct-of-arrays of discrete elements (see kernels.discrete)."""

    ids: np.ndarray  # (n,) int64 element IDs
    n1: np.ndarray  # (n,) int64 node index
    n2: np.ndarray  # (n,) int64 node index (-1: grounded)
    kind: np.ndarray  # (n,) int64 LINEAR, DAMPER or CURVE
    k: np.ndarray  # (n,) float64 stiffness [force/length] or damping [force·time/length]
    scale: np.ndarray  # (n,) float64
    offset: np.ndarray  # (n,) float64 [length]
    length0: np.ndarray  # (n,) float64 initial length (or projection) [length]
    direction: np.ndarray  # (n, 3) float64 fixed unit direction, zeros: along the axis
    ground: np.ndarray  # (n, 3) float64 ground point of grounded elements
    curve_start: np.ndarray  # (n,) int64
    curve_stop: np.ndarray  # (n,) int64
    curve_x: np.ndarray  # (m,) float64 deflection [length]
    curve_y: np.ndarray  # (m,) float64 force [force]
    ctf: np.ndarray  # (n,) int64 S08 sign restriction (1 compression only, -1 tension only)
    ucurve_start: np.ndarray | None = None  # (n,) int64 S06 unloading curve in curve_x/y (None: none)
    ucurve_stop: np.ndarray | None = None  # (n,) int64
    yield_t: np.ndarray | None = None  # (n,) S06 initial yield force in tension (> 0) [force]
    yield_c: np.ndarray | None = None  # (n,) S06 initial yield force in compression (< 0) [force]


@dataclass
class Wall:
    wall_id: int
    nodes: np.ndarray  # (k,) int64 slave node indices
    point: np.ndarray  # (3,) a point of the plane
    normal: np.ndarray  # (3,) unit normal towards the allowed side
    birth: float
    death: float
    fric: float = 0.0
    mass: float = 0.0  # _MOVING: wall mass (0: stationary)
    velocity: float = 0.0  # _MOVING: velocity along the normal
    edge_l: np.ndarray = field(default_factory=lambda: np.zeros(3))  # _FINITE: unit edge l
    edge_m: np.ndarray = field(default_factory=lambda: np.zeros(3))  # _FINITE: unit edge m = n x l
    len_l: float = 0.0  # _FINITE: edge lengths (0: infinite wall)
    len_m: float = 0.0
    watch: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))  # rigid-body nodes
    radius: float = 0.0  # cylinder: radius (0: planar wall)
    length: float = 0.0  # cylinder: length along the axis (0: infinite)


@dataclass
class Motion:
    """*BOUNDARY_PRESCRIBED_MOTION on nodes: velocity (VAD 0), acceleration
    (1) or displacement (2) along a global axis or a vector."""

    nodes: np.ndarray  # (k,) int64
    direction: np.ndarray  # (3,) unit vector
    vad: int
    curve: tuple  # (time, value) arrays
    scale: float
    birth: float
    death: float
    body_pid: int = 0  # _RIGID: the rigid part moved (its body), 0 for nodes


@dataclass
class Setup:
    x0: np.ndarray  # (n, 3) float64 initial coordinates
    v0: np.ndarray  # (n, 3) float64 initial velocities
    mass: np.ndarray  # (n,) float64 lumped nodal mass
    fixed: np.ndarray  # (n, 3) bool constrained DOFs
    discrete: Discrete
    walls: list[Wall] = field(default_factory=list)
    end_time: float = 0.0
    end_cycle: int = 0
    tssfac: float = 0.9
    history_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    dt_max: tuple | None = None  # *CONTROL_TIMESTEP LCTM: (time, largest step) curve
    motions: list[Motion] = field(default_factory=list)
    bodies: list = field(default_factory=list)  # rigid.RigidBody
    body_loads: list = field(default_factory=list)  # (unit axis (3,), (time, value) curve, scale)
    nodal_loads: object = None  # loads.NodalLoads or None
    dt2ms: float = 0.0  # *CONTROL_TIMESTEP DT2MS: mass scaling target step (0: none)
    beams: object = None  # beams.BeamSet of the elastic beams (None: none)
    rot_inertia: np.ndarray | None = None  # (n,) isotropic nodal rotational inertia (0: no rotation DOF)
    fixed_rot: np.ndarray | None = None  # (n, 3) bool constrained rotations
    w0: np.ndarray | None = None  # (n, 3) initial angular velocities
    state_dt: float = 0.0  # *DATABASE_BINARY_D3PLOT DT: field states interval (0: none)
    discrete_pid: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))  # (n_discrete,) part IDs
    beam_pid: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))  # (n_beams,) part IDs
    sections: list = field(default_factory=list)  # sections.Section (secforc)
    dt_min: float = 0.0  # *CONTROL_TERMINATION DTMIN: stop below this factor of the first step
    end_energy: float = 0.0  # *CONTROL_TERMINATION ENDENG: stop when the energy ratio moves this %
    groups: list = field(default_factory=list)  # further element groups (groups.ElementGroup)
    constraints: list = field(default_factory=list)  # tied contacts, spot welds: forces(st), velocities(st)
    node_ids: np.ndarray | None = None  # (n,) deck node IDs, for messages (None: indices)
    source: str = ""  # the deck, for messages
    skew_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))  # (k,) SPC in local systems
    skew_held: np.ndarray = field(default_factory=lambda: np.zeros((0, 3, 3)))  # (k, 3, 3) held directions
    skew_held_rot: np.ndarray = field(default_factory=lambda: np.zeros((0, 3, 3)))  # (k, 3, 3) held axes
    warnings: list = field(default_factory=list)  # Problem: cards passed over, options run approximately
    moved: list = field(default_factory=list)  # penetrations.Moved: slave nodes moved out at set-up


class SetupError(DeckError):
    """The model uses something this solver stage cannot run."""


# spring and damper constants that must not be negative, by field
_SPRING_CONSTANTS = {"k": ("MAT_SPRING_ELASTIC",), "dc": ("MAT_DAMPER_VISCOUS",), "ku": ("MAT_SPRING_INELASTIC",)}


def _discrete(model: Model, problems: list) -> Discrete:
    d = model.discretes
    n = len(d)
    kind = np.zeros(n, np.int64)
    k = np.zeros(n)
    starts, stops = np.zeros(n, np.int64), np.zeros(n, np.int64)
    ctf = np.zeros(n, np.int64)
    ustart, ustop = np.zeros(n, np.int64), np.zeros(n, np.int64)
    yield_t, yield_c = np.zeros(n), np.zeros(n)
    cx, cy = [np.zeros(0)], [np.zeros(0)]
    used = 0

    def add_curve(lcid):
        nonlocal used
        a, o = _curve(model, lcid)
        cx.append(a)
        cy.append(o)
        used += len(a)
        return used - len(a), used

    for pid in np.unique(d.pid):
        sel = d.pid == pid
        part = model.parts.get(int(pid))
        mat = model.materials.get(part.get("mid")) if part is not None else None
        sec = model.sections.get(part.get("secid")) if part is not None else None
        if sec is not None and int(sec.get("dro", 0)) != 0:
            problems.append(_problem(sec, "dro", "rotational discrete elements are not supported yet"))
        if mat is None:
            problems.append(_problem(part, "mid", "discrete elements need a *MAT_SPRING/_DAMPER material"))
            continue
        for fld, what in (("k", "stiffness K"), ("dc", "damping constant DC"), ("ku", "unloading stiffness KU")):
            if mat.keyword in _SPRING_CONSTANTS.get(fld, ()) and float(mat.get(fld, 0.0) or 0.0) < 0:
                problems.append(
                    _problem(
                        mat,
                        fld,
                        f"material {mat.get('mid')}: {what} = {float(mat[fld]):g} < 0 "
                        "gives energy instead of storing it: it must be >= 0",
                    )
                )
        if mat.keyword == "MAT_SPRING_ELASTIC":
            kind[sel], k[sel] = LINEAR, float(mat["k"])
        elif mat.keyword == "MAT_DAMPER_VISCOUS":
            kind[sel], k[sel] = DAMPER, float(mat["dc"])
        elif mat.keyword in ("MAT_SPRING_NONLINEAR_ELASTIC", "MAT_SPRING_INELASTIC"):
            lc = "lcd" if mat.keyword == "MAT_SPRING_NONLINEAR_ELASTIC" else "lcfd"
            if int(mat.get(lc, 0)) not in model.curves:
                problems.append(_problem(mat, lc, f"curve {mat.get(lc)} is not defined"))
                continue
            if lc == "lcd":
                kind[sel] = CURVE
            else:
                kind[sel], k[sel], ctf[sel] = INELASTIC, float(mat["ku"]), int(mat.get("ctf", 0))
            starts[sel], stops[sel] = add_curve(int(mat[lc]))
        elif mat.keyword == "MAT_SPRING_GENERAL_NONLINEAR":
            bad = [f for f in ("lcdl", "lcdu") if mat.get(f) and int(mat[f]) not in model.curves]
            if not mat.get("lcdl") or bad:
                problems.append(
                    _problem(mat, (bad or ["lcdl"])[0], f"curve {mat.get((bad or ['lcdl'])[0])} is not defined")
                )
                continue
            if float(mat.get("beta", 0.0) or 0.0) != 0.0:
                problems.append(_problem(mat, "beta", "BETA other than 0 (coupled hardening) is not supported yet"))
                continue
            kind[sel] = GENERAL
            starts[sel], stops[sel] = add_curve(int(mat["lcdl"]))
            if mat.get("lcdu"):
                ustart[sel], ustop[sel] = add_curve(int(mat["lcdu"]))
            yield_t[sel] = abs(float(mat.get("tyi", 0.0) or 0.0))
            yield_c[sel] = -abs(float(mat.get("cyi", 0.0) or 0.0))
        else:
            problems.append(
                _problem(
                    mat,
                    None,
                    f"*{mat.keyword} is not supported by the solver yet "
                    "(supported: MAT_S01, MAT_S02, MAT_S04, MAT_S06, MAT_S08)",
                )
            )
    x = model.nodes.xyz
    n1 = d.nodes[:, 0].astype(np.int64)
    n2 = d.nodes[:, 1].astype(np.int64)
    direction = np.zeros((n, 3))
    orient = {int(r["vid"]): r for r in model.find("DEFINE_SD_ORIENTATION")}
    for vid in np.unique(d.vid[d.vid > 0]):
        rec = orient.get(int(vid))
        if rec is None:
            problems.append(
                Problem(
                    model.source or "",
                    0,
                    "ELEMENT_DISCRETE",
                    "VID",
                    f"*DEFINE_SD_ORIENTATION {int(vid)} is not defined",
                )
            )
            continue
        if int(rec.get("iop", 0)) != 0:
            problems.append(_problem(rec, "iop", "only IOP = 0 (a fixed vector) is supported yet"))
            continue
        u = np.array([rec.get("xt", 0.0), rec.get("yt", 0.0), rec.get("zt", 0.0)], float)
        if not np.linalg.norm(u):
            problems.append(_problem(rec, "xt", "the orientation vector has zero length"))
            continue
        direction[d.vid == vid] = u / np.linalg.norm(u)
    ground = x[n1].copy()
    other = np.where(n2[:, None] >= 0, x[np.maximum(n2, 0)], ground)
    rel = other - x[n1]
    fixed_dir = np.any(direction != 0, axis=1)
    length0 = np.where(fixed_dir, np.einsum("ij,ij->i", rel, direction), np.linalg.norm(rel, axis=1))
    # two nodes at one point and no orientation: the element has no direction to act along
    for e in np.flatnonzero((n2 >= 0) & ~fixed_dir & (np.linalg.norm(rel, axis=1) == 0))[:10]:
        problems.append(
            Problem(
                model.source or "",
                0,
                "ELEMENT_DISCRETE",
                "VID",
                f"discrete element {int(d.ids[e])}: nodes {int(model.nodes.ids[n1[e]])} and "
                f"{int(model.nodes.ids[n2[e]])} lie at one point and no orientation (VID, "
                "*DEFINE_SD_ORIENTATION) gives its direction",
            )
        )
    return Discrete(
        d.ids,
        n1,
        n2,
        kind,
        k,
        d.scale.astype(float),
        d.offset.astype(float),
        length0,
        direction,
        ground,
        starts,
        stops,
        np.concatenate(cx),
        np.concatenate(cy),
        ctf,
        ustart,
        ustop,
        yield_t,
        yield_c,
    )


def _constraints(model: Model, problems: list) -> tuple[np.ndarray, np.ndarray, dict]:
    """(n, 3) held translations and (n, 3) held rotations: node TC/RC codes
    and *BOUNDARY_SPC_NODE/SET; and the constraints in local systems:
    node index -> ((3, 3) held translation directions, (3, 3) held
    rotation axes), zero rows for free directions."""
    from .frames import axes

    fixed = np.array([_TC.get(int(t), (0, 0, 0)) for t in model.nodes.tc], dtype=bool).reshape(-1, 3)
    fixed_rot = np.array([_TC.get(int(r), (0, 0, 0)) for r in model.nodes.rc], dtype=bool).reshape(-1, 3)
    skew: dict[int, tuple[np.ndarray, np.ndarray]] = {}
    for rec in model.keywords:
        name = getattr(rec, "keyword", "")
        if name not in ("BOUNDARY_SPC_NODE", "BOUNDARY_SPC_SET"):
            continue
        rows = rec.rows
        if "birth" in rows and not _spc_whole_run(model, rec, problems):
            continue
        for i in range(len(rows["cid"])):
            nodes = (
                model.node_index([rows["nid"][i]]) if name.endswith("NODE") else _node_set(model, int(rows["nsid"][i]))
            )
            held = np.array([rows["dofx"][i], rows["dofy"][i], rows["dofz"][i]], bool)
            held_rot = np.array([rows["dofrx"][i], rows["dofry"][i], rows["dofrz"][i]], bool)
            if rows["cid"][i]:
                try:
                    r = axes(model, int(rows["cid"][i]))
                except (KeyError, ValueError) as e:
                    problems.append(_problem(rec, "cid", str(e)))
                    continue
                for nd in nodes.tolist():
                    t, w = skew.get(nd, (np.zeros((3, 3)), np.zeros((3, 3))))
                    skew[nd] = (np.where(held[:, None], r, t), np.where(held_rot[:, None], r, w))
                continue
            fixed[nodes] |= held
            fixed_rot[nodes] |= held_rot
    return fixed, fixed_rot, skew


def _end_time(model: Model) -> float:
    """*CONTROL_TERMINATION ENDTIM (0 without the card)."""
    term = model.find("CONTROL_TERMINATION")
    return float(term[0].get("endtim", 0.0) or 0.0) if term else 0.0


def _spc_whole_run(model: Model, rec, problems: list) -> bool:
    """Whether every constraint of a *BOUNDARY_SPC_..._BIRTH_DEATH card holds
    from the start to the end time (then it is a plain SPC); constraints
    that start or end inside the run are refused, not held throughout."""
    end = _end_time(model)
    rows = rec.rows
    for fld, inside in (("birth", rows["birth"] > 0.0), ("death", rows["death"] < end)):
        if inside.any():
            when = float(rows[fld][np.flatnonzero(inside)[0]])
            problems.append(
                _problem(
                    rec,
                    fld,
                    f"{fld.upper()} = {when:g} lies inside the run (end time {end:g}): constraints that "
                    "start or end during the run are not supported yet",
                )
            )
            return False
    return True


def _walls(model: Model, problems: list) -> list[Wall]:
    walls = []
    n = len(model.nodes)
    for rec in model.keywords:
        kw = getattr(rec, "keyword", "")
        if kw not in ("RIGIDWALL_PLANAR", "RIGIDWALL_GEOMETRIC_CYLINDER"):
            continue
        if rec.get("wvel", 0.0) or "MOTION" in rec.options:
            problems.append(_problem(rec, None, "WVEL and moving cylinders are not supported yet"))
            continue
        nodes = np.arange(n) if not rec.get("nsid") else _node_set(model, rec["nsid"])
        if rec.get("nsidex"):
            nodes = np.setdiff1d(nodes, _node_set(model, rec["nsidex"]))
        tail = np.array([rec.get("xt", 0.0), rec.get("yt", 0.0), rec.get("zt", 0.0)], float)
        head = np.array([rec.get("xh", 0.0), rec.get("yh", 0.0), rec.get("zh", 0.0)], float)
        normal = head - tail
        if not np.linalg.norm(normal):
            problems.append(_problem(rec, "xh", "wall normal (head - tail) has zero length"))
            continue
        normal /= np.linalg.norm(normal)
        if kw == "RIGIDWALL_GEOMETRIC_CYLINDER":
            walls.append(
                Wall(
                    int(rec.get("rwid") or len(walls) + 1),
                    nodes.astype(np.int64),
                    tail,
                    normal,
                    float(rec.get("birth", 0.0)),
                    float(rec.get("death", 1e20)),
                    float(rec.get("fric", 0.0)),
                    radius=float(rec.get("radcyl") or 0.0),
                    length=float(rec.get("lencyl") or 0.0),
                )
            )
            if walls[-1].radius <= 0:
                problems.append(_problem(rec, "radcyl", "the cylinder needs a radius > 0"))
            continue
        point = tail + float(rec.get("offset", 0.0)) * normal
        moving = "MOVING" in rec.options
        if moving and not rec.get("mass", 0.0) > 0:
            problems.append(_problem(rec, "mass", "a moving rigid wall needs a mass > 0"))
            continue
        wall = Wall(
            int(rec.get("rwid") or len(walls) + 1),
            nodes.astype(np.int64),
            point,
            normal,
            float(rec.get("birth", 0.0)),
            float(rec.get("death", 1e20)),
            float(rec.get("fric", 0.0)),
            float(rec.get("mass", 0.0)) if moving else 0.0,
            float(rec.get("v0", 0.0)) if moving else 0.0,
        )
        if "FINITE" in rec.options:
            edge = np.array([rec.get("xhev", 0.0), rec.get("yhev", 0.0), rec.get("zhev", 0.0)], float) - tail
            edge -= (edge @ normal) * normal
            if not np.linalg.norm(edge) or not rec.get("lenl") or not rec.get("lenm"):
                problems.append(
                    _problem(rec, "xhev", "a finite wall needs an edge vector not along the normal and LENL, LENM > 0")
                )
                continue
            wall.edge_l = edge / np.linalg.norm(edge)
            wall.edge_m = np.cross(normal, wall.edge_l)
            wall.len_l, wall.len_m = float(rec["lenl"]), float(rec["lenm"])
        walls.append(wall)
    return walls


def _motions(model: Model, problems: list) -> list[Motion]:
    out = []
    for rec in model.find("BOUNDARY_PRESCRIBED_MOTION"):  # typed cards only: unread variants are refused
        name = rec.keyword
        rows = rec.rows
        for i in range(len(rows["dof"])):
            dof, vad = int(rows["dof"][i]), int(rows["vad"][i])
            if dof in (1, 2, 3):
                direction = np.eye(3)[dof - 1]
            elif dof == 4 and int(rows["vid"][i]) in model.vectors:
                vec = model.vectors[int(rows["vid"][i])]
                direction = np.array([vec["xh"] - vec["xt"], vec["yh"] - vec["yt"], vec["zh"] - vec["zt"]], float)
                direction /= np.linalg.norm(direction)
            else:
                problems.append(
                    _problem(rec, "dof", f"DOF {dof} is not supported yet (1, 2, 3 and 4 with a vector are)")
                )
                continue
            if vad not in (0, 1, 2):
                problems.append(_problem(rec, "vad", f"VAD {vad} is not supported (0, 1, 2 are)"))
                continue
            lcid = int(rows["lcid"][i])
            if lcid not in model.curves:
                problems.append(_problem(rec, "lcid", f"curve {lcid} is not defined"))
                continue
            if name.endswith("RIGID"):
                nodes, body_pid = np.zeros(0, np.int64), int(rows["pid"][i])
            else:
                nodes, body_pid = (
                    (
                        model.node_index([rows["nid"][i]])
                        if name.endswith("NODE")
                        else _node_set(model, int(rows["nsid"][i]))
                    ),
                    0,
                )
            out.append(
                Motion(
                    nodes.astype(np.int64),
                    direction,
                    vad,
                    _curve(model, lcid),
                    float(rows["sf"][i]),
                    float(rows["birth"][i]),
                    float(rows["death"][i]),
                    body_pid,
                )
            )
    return out


def node_inertia(model: Model, problems: list) -> np.ndarray:
    """(n, 3, 3) *ELEMENT_INERTIA tensors summed per node (global system)."""
    out = np.zeros((len(model.nodes), 3, 3))
    it = model.inertias
    if np.any(it.csid != 0):
        problems.append(
            Problem(
                model.source or "",
                0,
                "ELEMENT_INERTIA",
                "CSID",
                "inertia tensors in a local system are not supported yet",
            )
        )
    t = it.tensor
    tensor = np.stack(
        [
            np.stack([t[:, 0], t[:, 1], t[:, 2]], 1),
            np.stack([t[:, 1], t[:, 3], t[:, 4]], 1),
            np.stack([t[:, 2], t[:, 4], t[:, 5]], 1),
        ],
        1,
    )
    np.add.at(out, it.node, tensor)
    return out


def element_on(model: Model, node: int) -> str:
    """'*ELEMENT_DISCRETE 7'-style name of the first element on a node
    (index), for messages; '' when none."""
    for name, table in (
        ("DISCRETE", model.discretes),
        ("BEAM", model.beams),
        ("SHELL", model.shells),
        ("SOLID", model.solids),
    ):
        nodes = table.nodes[:, :2] if name == "BEAM" else table.nodes
        rows = np.flatnonzero((nodes == node).any(axis=1))
        if len(rows):
            return f"*ELEMENT_{name} {int(table.ids[rows[0]])}"
    return ""


def _no_inertia_problem(model: Model, rec, body, used, mass) -> Problem | None:
    """A body with no inertia about some axis (its mass on one node or on a
    line) whose nodes carry elements off that axis: the forces of those
    elements turn it about the axis with no inertia, so their stable time
    step is 0 and the run would never end."""
    if body.no_inertia is None:
        return None
    ids = model.nodes.ids
    size = float(np.abs(body.r_body).max()) or 1.0
    for k, i in enumerate(body.nodes):
        lever = np.linalg.norm(np.cross(body.no_inertia, body.r_body[k]), axis=1)
        if not used[i] or lever.max() <= 1e-9 * size:
            continue
        heavy = [int(ids[j]) for j in body.nodes if mass[j] > 0]
        where = (
            f"at node {heavy[0]}"
            if len(body.no_inertia) == 3 and len(heavy) == 1
            else "at one point"
            if len(body.no_inertia) == 3
            else "on one line"
        )
        axis = (
            "any axis"
            if len(body.no_inertia) == 3
            else "the axis (" + ", ".join(f"{c:.3g}" for c in body.no_inertia[0]) + ")"
        )
        what = element_on(model, int(i)) or "elements"
        return _problem(
            rec,
            "nsid",
            f"nodal rigid body {body.body_id}: its mass ({body.mass:g}) sits {where}, so "
            f"it has no rotational inertia about {axis}; node {int(ids[i])} carries {what} "
            f"at {float(lever.max()):.4g} from it, whose stable time step would be 0 (the run "
            "would never end). Give the body its inertia (_INERTIA), or mass (*ELEMENT_MASS, "
            "*ELEMENT_INERTIA) on its other nodes",
        )
    return None


def _bodies(
    model: Model, x, v, mass, problems: list, used: np.ndarray | None = None, rot_inertia: np.ndarray | None = None
) -> list:
    from .rigid import build_body

    bodies = []
    owner = np.full(len(x), -1)
    inertia = node_inertia(model, problems) if len(model.inertias) else None
    for rec in model.keywords:
        if getattr(rec, "keyword", "") != "CONSTRAINED_NODAL_RIGID_BODY":
            continue
        nodes = _node_set(model, int(rec["nsid"]))
        if np.any(owner[nodes] >= 0):
            problems.append(
                _problem(rec, "nsid", "a node belongs to two nodal rigid bodies; merge them (one set) instead")
            )
            continue
        if "SPC" in rec.options or int(rec.get("cid", 0) or 0):
            problems.append(_problem(rec, None, "SPC and CID of nodal rigid bodies are not supported yet"))
            continue
        given = None
        if "INERTIA" in rec.options:
            if int(rec.get("ircs", 0) or 0):
                problems.append(_problem(rec, "ircs", "inertia in a local system is not supported yet"))
                continue
            g = {k: float(rec.get(k, 0.0)) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
            given = {
                "tm": float(rec.get("tm", 0.0)),
                "cog": [rec.get("xc", 0.0), rec.get("yc", 0.0), rec.get("zc", 0.0)],
                "inertia": [
                    [g["ixx"], g["ixy"], g["ixz"]],
                    [g["ixy"], g["iyy"], g["iyz"]],
                    [g["ixz"], g["iyz"], g["izz"]],
                ],
                "v": [rec.get("vtx", 0.0), rec.get("vty", 0.0), rec.get("vtz", 0.0)],
                "w": [rec.get("vrx", 0.0), rec.get("vry", 0.0), rec.get("vrz", 0.0)],
            }
        try:
            bodies.append(build_body(int(rec["pid"]), nodes, x, v, mass, given, inertia, rot_inertia))
        except ValueError as e:
            problems.append(_problem(rec, "nsid", str(e)))
            continue
        bad = _no_inertia_problem(model, rec, bodies[-1], used, mass) if used is not None else None
        if bad is not None:
            problems.append(bad)
        owner[nodes] = len(bodies) - 1
    return bodies


def row_line(model: Model, keyword: str, eid: int) -> tuple[str, int]:
    """(file, line) of the row of element ``eid`` under a ``*keyword`` card
    (any of its options) in the files of the model, for messages; (source, 0)
    when not found. Only called when there is something to report."""
    from pathlib import Path

    for f in model.files or [model.source or ""]:
        try:
            lines = Path(f).read_text(errors="replace").splitlines()
        except OSError:
            continue
        inside = False
        for k, ln in enumerate(lines, 1):
            if ln.startswith("*"):
                inside = ln[1:].strip().upper().startswith(keyword)
                continue
            if not inside or ln.startswith("$") or not ln.strip():
                continue
            first = ln.replace(",", " ").split()[0] if "," in ln else ln[:8].strip()
            for cand in (first, ln[:10].strip(), ln[:20].strip()):
                try:
                    if int(cand) == eid:
                        return str(f), k
                except ValueError:
                    pass
    return str(model.source or ""), 0


def _massless_cards(model: Model, rigid: np.ndarray) -> list[Problem]:
    """Cards that give nodes a negative or no mass, named where they are
    (negative *ELEMENT_MASS, shell thickness <= 0, beam area <= 0, an
    inverted solid); checked before the elements are built, so the run is
    refused naming the card, not a node left without mass."""
    out: list[Problem] = []
    str(model.source or "")
    m = model.masses
    for i in np.flatnonzero(m.mass < 0)[:10]:
        eid, nid = int(m.ids[i]), int(model.nodes.ids[m.node[i]]) if m.node[i] >= 0 else -1
        out.append(
            Problem(
                *row_line(model, "ELEMENT_MASS", eid),
                "ELEMENT_MASS",
                "MASS",
                f"element {eid} on node {nid} has mass {float(m.mass[i]):g} < 0: a mass must be >= 0",
            )
        )
    sh = model.shells
    for p in np.unique(sh.pid[~np.isin(sh.pid, rigid)]):
        part = model.parts.get(int(p))
        sec = model.sections.get(part.get("secid")) if part is not None else None
        if sec is None or sec.keyword != "SECTION_SHELL":
            continue  # the shell builder names it
        t1 = float(sec.get("t1", 0.0) or 0.0)
        t = np.array([float(sec.get(f"t{k}", 0.0) or 0.0) for k in range(1, 5)])
        t = np.where(t > 0, t, t1)
        rows = np.flatnonzero(sh.pid == p)
        given = sh.thickness[rows]
        tn = np.where(np.isfinite(given) & (given > 0), given, t)
        bad = rows[tn.mean(axis=1) <= 0]
        if len(bad):
            ids = ", ".join(str(int(e)) for e in sh.ids[bad[:5]]) + (", ..." if len(bad) > 5 else "")
            out.append(
                Problem(
                    *sec.where("t1"),
                    sec.name,
                    "T1",
                    f"section {sec.get('secid')} (part {int(p)}): shell thickness T1 = {t1:g} <= 0 and "
                    f"{len(bad)} shell(s) give none of their own ({ids}): a shell needs a thickness > 0",
                )
            )
    bm = model.beams
    for p in np.unique(bm.pid[~np.isin(bm.pid, rigid)]):
        part = model.parts.get(int(p))
        sec = model.sections.get(part.get("secid")) if part is not None else None
        if sec is None or sec.keyword != "SECTION_BEAM" or int(sec.get("elform", 1) or 1) in (3, 6, 9):
            continue  # the beam builder names it; trusses of ELFORM 3, discrete beams: not here
        from ..model.properties import section_area

        a = section_area(sec)
        if not a > 0:
            given = int(sec.get("elform", 1) or 1) in (2, 12, 13) or sec.get("ts1") is None
            fld = "A" if given else "TS1"
            n = int((bm.pid == p).sum())
            out.append(
                Problem(
                    *sec.where(fld.lower()),
                    sec.name,
                    fld,
                    f"section {sec.get('secid')} (part {int(p)}, {n} beam(s)): cross-section area "
                    f"{a:g} <= 0: a beam needs an area > 0" + ("" if given else " (from TS1, TT1 and CST)"),
                )
            )
    so = model.solids
    deformable = np.flatnonzero(~np.isin(so.pid, rigid) & np.all(so.nodes[:, :4] >= 0, axis=1))
    if len(deformable):
        from .kernels.solid import N_CHUNKS, N_WORK, solid_volumes

        conn = so.nodes[deformable].astype(np.int64)
        conn = np.where(conn >= 0, conn, conn[:, 3:4])  # unset N5-N8: a tetrahedron's repeated N4
        vol = np.empty(len(conn))
        solid_volumes(model.nodes.xyz.astype(float), conn, np.zeros((N_CHUNKS, N_WORK)), vol)
        for i in np.flatnonzero(vol <= 0)[:10]:
            eid = int(so.ids[deformable[i]])
            out.append(
                Problem(
                    *row_line(model, "ELEMENT_SOLID", eid),
                    "ELEMENT_SOLID",
                    "N1",
                    f"solid {eid} has volume {vol[i]:.4g} <= 0: its nodes N1-N4 and N5-N8 are "
                    "in inverted order (or the element is flat)",
                )
            )
    return out


_UNSUPPORTED_TABLES: tuple[str, ...] = ()


def _element_groups(model: Model, rigid: np.ndarray, n: int, problems: list, warnings: list) -> list:
    """Element families beyond discretes and beams (solids, shells) as groups."""
    from .shells import build_shells
    from .solids import SolidGroup, build_solids

    groups = []
    solids = build_solids(model, rigid, problems, warnings)
    if solids is not None and len(solids):
        groups.append(SolidGroup(solids, n))
    shells = build_shells(model, rigid, problems, warnings)
    if shells is not None and len(shells.ids):
        groups.append(shells)
    from .superelement import build_superelements

    matrices = build_superelements(model, problems)
    if matrices is not None:
        groups.append(matrices)
    from .contact_build import build_contacts

    return groups + build_contacts(model, groups, problems)  # after the elements: they add to their forces


def _constraint_objects(model: Model, mass, rot_inertia, v0, w0, in_body, problems: list) -> list:
    """Tied contacts and spot welds (Setup.constraints): the tied slaves'
    masses (and rotary inertias) go to their masters and the initial
    velocities are made consistent with the ties, momentum kept."""
    from .spotwelds import build_spotwelds
    from .tied import build_tied

    ties = build_tied(model, problems)
    welds = build_spotwelds(model, problems)
    x = model.nodes.xyz
    for t in ties:
        slave_mass = mass[t.slave].copy()
        t.lump(mass, rot_inertia, x)
        t.start(v0, mass, slave_mass, x, w0)
    linked = [(t.keyword, np.concatenate([t.slave, t.seg.ravel()])) for t in ties]
    if welds is not None:
        welds.start(v0, w0, mass, rot_inertia, x)
        linked.append(("CONSTRAINED_SPOTWELD", welds.nodes))
    for kw, nodes in linked:
        if in_body[nodes].any():
            problems.append(
                Problem(
                    model.source or "",
                    0,
                    kw,
                    None,
                    "tied contacts and welds on nodal rigid body or rigid part nodes are not supported yet",
                )
            )
    return ties + ([welds] if welds is not None else [])


def build(model: Model) -> Setup:
    """Arrays for the time loop; raises SetupError listing everything the
    solver cannot run yet."""
    try:
        return _build(model)
    except KeyError as e:  # an undefined set or ID met while building
        raise SetupError([Problem(model.source or "", 0, "", None, str(e).strip("'\""))]) from None


def _build(model: Model) -> Setup:
    from .rigid_parts import part_bodies, rigid_part_ids
    from .sections import build_sections
    from .support import unsupported_cards

    warnings: list[Problem] = []
    problems: list[Problem] = unsupported_cards(model, warnings=warnings)
    rigid = np.array(sorted(rigid_part_ids(model)), np.int64)
    massless = _massless_cards(model, rigid)
    if massless:  # nodes without mass follow from these: name the cards, not the nodes
        raise SetupError(problems + massless)
    for t in _UNSUPPORTED_TABLES:
        deformable = ~np.isin(getattr(model, t).pid, rigid)
        if deformable.any():
            problems.append(
                Problem(
                    model.source or "",
                    0,
                    f"ELEMENT_{t[:-1].upper()}",
                    None,
                    f"{int(deformable.sum())} deformable {t}: this solver stage runs "
                    "masses, springs, dampers and rigid parts only",
                )
            )
    n = len(model.nodes)
    mass = np.zeros(n)
    np.add.at(mass, model.masses.node, model.masses.mass)
    np.add.at(mass, model.inertias.node, model.inertias.mass)
    disc = _discrete(model, problems)
    from .beams import build_beams, lumped

    beams = build_beams(model, rigid, problems)
    rot_inertia = np.zeros(n)
    if beams is not None:
        beam_mass, rot_inertia = lumped(beams, n)
        mass += beam_mass
    groups = _element_groups(model, rigid, n, problems, warnings)
    for g in groups:
        m_g, j_g = g.lumped(n)
        mass += m_g
        rot_inertia += j_g
    v0 = np.zeros((n, 3))
    _initial_velocity(model, v0, problems)
    fixed, fixed_rot, skew = _constraints(model, problems)
    walls = _walls(model, problems)
    motions = _motions(model, problems)
    used = np.zeros(n, bool)
    if beams is not None:
        used[beams.n1] = used[beams.n2] = True
    used[disc.n1] = True
    used[disc.n2[disc.n2 >= 0]] = True
    for g in groups:
        used[g.conn[g.conn >= 0]] = True
    bodies = _bodies(model, model.nodes.xyz, v0, mass, problems, used, rot_inertia)
    bodies += part_bodies(model, model.nodes.xyz, v0, mass, problems)
    body_of = {b.body_id: b for b in bodies}
    for mo in motions:
        if mo.body_pid and mo.body_pid not in body_of:
            problems.append(
                Problem(
                    model.source or "",
                    0,
                    "BOUNDARY_PRESCRIBED_MOTION_RIGID",
                    "PID",
                    f"part {mo.body_pid} is not a rigid part (or not the lead of a merged body)",
                )
            )
    count = np.zeros(n, np.int64)
    for b in bodies:
        count[b.nodes] += 1
    for i in np.flatnonzero(count > 1)[:10]:
        problems.append(
            Problem(
                model.source or "",
                0,
                "CONSTRAINED_NODAL_RIGID_BODY",
                None,
                f"node {int(model.nodes.ids[i])} belongs to two rigid bodies",
            )
        )
    in_body = np.zeros(n, bool)
    for b in bodies:
        in_body[b.nodes] = True
    driven = in_body.copy()
    for mo in motions:
        if in_body[mo.nodes].any():
            problems.append(
                Problem(
                    model.source or "",
                    0,
                    "BOUNDARY_PRESCRIBED_MOTION",
                    None,
                    "prescribed motion of nodal rigid body nodes is not supported yet",
                )
            )
        driven[mo.nodes] = True
    for w in walls:  # rigid-body nodes: the wall pushes their body (walls.Walls)
        w.watch = w.nodes[in_body[w.nodes]]
        w.nodes = w.nodes[~in_body[w.nodes]]
    skew_nodes = np.array(sorted(skew), np.int64)
    if (fixed & in_body[:, None]).any() or in_body[skew_nodes].any():
        problems.append(
            Problem(
                model.source or "",
                0,
                "BOUNDARY_SPC",
                None,
                "constraints on nodal rigid body nodes are not supported yet",
            )
        )
    massless = np.flatnonzero(used & (mass <= 0) & ~fixed.all(axis=1) & ~driven)
    for i in massless[:10]:
        problems.append(
            Problem(
                model.source or "",
                0,
                "ELEMENT_MASS",
                None,
                f"node {int(model.nodes.ids[i])} carries elements but has no mass",
            )
        )
    x0 = model.nodes.xyz.copy()
    from .contact import ContactGroup
    from .penetrations import remove_initial_penetrations, report

    contacts = [g for g in groups if isinstance(g, ContactGroup)]
    moved = remove_initial_penetrations(contacts, x0, ~fixed.all(axis=1) & ~driven) if contacts else []
    warnings += report(moved, {g.cid: g.name for g in contacts}, model.nodes.ids, model.source or "")
    w0 = _initial_rotation(model, n)
    constraints = _constraint_objects(model, mass, rot_inertia, v0, w0, in_body, problems)
    term = model.find("CONTROL_TERMINATION")
    ts = model.find("CONTROL_TIMESTEP")
    end_time = _end_time(model)
    if end_time <= 0:
        problems.append(Problem(model.source or "", 0, "CONTROL_TERMINATION", "ENDTIM", "an end time > 0 is needed"))
    end_cycle = int(term[0].get("endcyc", 0) or 0) if term else 0
    if end_cycle < 0:  # as LS-DYNA: the cycle limit applies only when ENDCYC > 0
        warnings.append(
            _problem(
                term[0], "endcyc", f"ENDCYC = {end_cycle} < 0 is read as 0: no cycle limit, the run ends at ENDTIM"
            )
        )
        end_cycle = 0
    tssfac = float(ts[0].get("tssfac", 0.9) or 0.9) if ts else 0.9
    if not 0 < tssfac <= 1:
        problems.append(
            _problem(
                ts[0],
                "tssfac",
                f"TSSFAC = {tssfac:g}: the time step scale factor must lie in "
                "(0, 1]; above 1 the steps exceed the stable step and the "
                "run goes unstable (0.9 is LS-DYNA's default)",
            )
        )
    hist_idx = history_nodes(model)  # IDs, _ID rows and _SET members
    dt_max = None
    if ts and ts[0].get("lctm"):
        if int(ts[0]["lctm"]) in model.curves:
            dt_max = _curve(model, int(ts[0]["lctm"]))
        else:
            problems.append(_problem(ts[0], "lctm", f"curve {ts[0]['lctm']} is not defined"))
    loads = []
    for rec in model.find("LOAD_BODY_"):  # typed cards only: unread variants are refused
        name = rec.keyword
        if int(rec.get("lcid", 0)) not in model.curves:
            problems.append(_problem(rec, "lcid", f"curve {rec.get('lcid')} is not defined"))
            continue
        if int(rec.get("cid", 0) or 0) or int(rec.get("lciddr", 0) or 0):
            problems.append(
                _problem(rec, "cid", "body loads in a local system or with dynamic relaxation are not supported yet")
            )
            continue
        axis = np.eye(3)["XYZ".index(name[-1])]
        loads.append((axis, _curve(model, int(rec["lcid"])), float(rec.get("sf", 1.0))))

    nodal_loads = build_nodal_loads(model, rot_inertia > 0, problems)
    sections = build_sections(model, beams.ids if beams is not None else np.zeros(0, np.int64), problems, groups)
    if ts and float(ts[0].get("dt2ms", 0.0) or 0.0) != 0.0 and groups:
        problems.append(
            _problem(
                ts[0],
                "dt2ms",
                "mass scaling (DT2MS) of "
                + ", ".join(sorted({g.kind + "s" for g in groups}))
                + " is not supported yet",
            )
        )
    if problems:
        raise SetupError(problems)
    return Setup(
        x0=x0,
        v0=v0,
        mass=mass,
        fixed=fixed,
        discrete=disc,
        walls=walls,
        end_time=end_time,
        end_cycle=end_cycle,
        tssfac=tssfac,
        history_nodes=hist_idx[hist_idx >= 0],
        dt_max=dt_max,
        motions=motions,
        bodies=bodies,
        body_loads=loads,
        nodal_loads=nodal_loads,
        dt2ms=float(ts[0].get("dt2ms", 0.0) or 0.0) if ts else 0.0,
        beams=beams,
        rot_inertia=rot_inertia,
        fixed_rot=fixed_rot,
        w0=w0,
        constraints=constraints,
        discrete_pid=model.discretes.pid.astype(np.int64),
        sections=sections,
        beam_pid=model.beams.pid[~np.isin(model.beams.pid, rigid)].astype(np.int64),
        state_dt=float(model.find("DATABASE_BINARY_D3PLOT")[0].get("dt", 0.0) or 0.0)
        if model.find("DATABASE_BINARY_D3PLOT")
        else 0.0,
        dt_min=float(term[0].get("dtmin", 0.0) or 0.0) if term else 0.0,
        end_energy=float(term[0].get("endeng", 0.0) or 0.0) if term else 0.0,
        node_ids=model.nodes.ids.astype(np.int64),
        source=str(model.source or ""),
        skew_nodes=skew_nodes,
        skew_held=np.array([skew[i][0] for i in skew_nodes]).reshape(-1, 3, 3),
        skew_held_rot=np.array([skew[i][1] for i in skew_nodes]).reshape(-1, 3, 3),
        groups=groups,
        warnings=warnings,
        moved=moved,
    )
