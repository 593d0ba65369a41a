"""From a Model to the arrays the time loop works on.

``build`` gathers into one Setup the lumped masses, the element groups
(discrete springs and dampers: ``discretes``; beams, solids, shells,
superelements, contacts), the boundary conditions (``boundary``: constraints,
rigid walls, prescribed motions), the rigid bodies (``nodal_bodies``,
``rigid_parts``), the initial velocities, the loads, the tied contacts and
spot welds and the run controls. Anything in a deck that would change the
motion and is not run is refused with a message naming the keyword (cards
that leave nodes without mass first: ``massless``), so a run never silently
leaves part of the model out.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..keyword.errors import DeckError, Problem
from ..model.model import Model
from ..model.sets import history_nodes
from .boundary import Motion, Wall, build_constraints, build_motions, build_walls, end_time
from .discretes import Discrete, build_discrete
from .initial import _initial_rotation, _initial_velocity
from .loads import build_nodal_loads
from .mass_parts import add_part_masses
from .massless import massless_cards
from .nodal_bodies import build_nodal_bodies
from .part_moves import moved_model
from .records import _curve, _problem


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
    discrete_printed: np.ndarray | None = None  # indices of the discretes DEFORC prints (PF 0); None: all
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


def _constraint_objects(model: Model, mass, rot_inertia, v0, w0, in_body, problems: list, warnings: list) -> list:
    """Tied contacts and spot welds (Setup.constraints): the tied slaves'
    masses (and rotary inertias) go to their masters and the initial
    velocities are made consistent with the ties, momentum kept."""
    from .spotwelds import build_spotwelds
    from .tied import build_tied

    ties = build_tied(model, problems, warnings)
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
    from .rigid_velocity import start_rigid_bodies
    from .sections import build_sections
    from .support import unsupported_cards

    warnings: list[Problem] = []
    problems: list[Problem] = unsupported_cards(model, warnings=warnings)
    model = moved_model(model, problems, warnings)  # *PART_MOVE: before anything reads a coordinate
    rigid = np.array(sorted(rigid_part_ids(model)), np.int64)
    massless = massless_cards(model, rigid)
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
    disc = build_discrete(model, problems)
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
    beam_pid = model.beams.pid[~np.isin(model.beams.pid, rigid)].astype(np.int64)
    add_part_masses(model, groups, beams, beam_pid, rigid, mass, problems)  # before bodies take the masses
    v0 = np.zeros((n, 3))
    _initial_velocity(model, v0, problems)
    fixed, fixed_rot, skew = build_constraints(model, problems)
    walls = build_walls(model, problems)
    motions = build_motions(model, problems)
    used = np.zeros(n, bool)
    if beams is not None:
        used[beams.n1] = used[beams.n2] = True
    used[disc.n1] = True
    used[disc.n2[disc.n2 >= 0]] = True
    for g in groups:  # a refused part's elements: its card is the problem, not their nodes' mass
        refused = getattr(g, "refused", None)
        conn = g.conn if refused is None else g.conn[~refused]
        used[conn[conn >= 0]] = True
    bodies = build_nodal_bodies(model, model.nodes.xyz, v0, mass, problems, used, rot_inertia)
    rigid_bodies = part_bodies(model, model.nodes.xyz, v0, mass, problems)
    start_rigid_bodies(model, rigid_bodies, model.nodes.xyz, v0, problems)
    bodies += rigid_bodies
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
    constraints = _constraint_objects(model, mass, rot_inertia, v0, w0, in_body, problems, warnings)
    term = model.find("CONTROL_TERMINATION")
    ts = model.find("CONTROL_TIMESTEP")
    t_end = end_time(model)
    if t_end <= 0:
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
        end_time=t_end,
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
        discrete_printed=_printed(model, disc),
        sections=sections,
        beam_pid=beam_pid,
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


def _printed(model: Model, disc) -> np.ndarray | None:
    """Indices of the discrete elements whose forces DEFORC prints:
    *ELEMENT_DISCRETE PF 1 leaves one out (a barrier's thousands of links
    would otherwise fill memory with histories nobody reads); None: all."""
    pf = np.asarray(model.discretes.pf)
    if len(pf) != len(disc.ids) or not np.any(pf == 1):
        return None
    return np.flatnonzero(pf != 1)
