"""The parametric generic compact car as a keyword Model.

``generic_vehicle`` meshes the layout of ``body`` at a chosen element size
(same geometry at every size: ≈ 20 k shells at 38 mm, ≈ 1.1 M at 5 mm),
assigns sheet grades and thicknesses (MAT_024 steels, glass, MAT_020 rigid
engine and rear axle), trims the mass with *ELEMENT_MASS to the target
mass and centre of gravity, and adds what the method needs, all by name:

- part sets per assembly (``assembly <name>``) and of the whole vehicle,
  node sets of the crash boxes, the firewall and the rear-axle attachment
  points;
- *DATABASE_CROSS_SECTION_PLANE_ID at the interface x for every assembly
  the plane cuts (the paper's eleven at the default x = −600 mm);
- *DATABASE_HISTORY_NODE_ID: engine top, vehicle CoG, rear seats, B-pillar
  sills;
- one *CONTACT_AUTOMATIC_SINGLE_SURFACE over the vehicle; door hinges and
  latches as patches of *CONSTRAINED_SPOTWELD pairs across the door gap.

Units mm–t–s–N–MPa. No controls, walls or initial velocity: the load cases
(``vehicle.car.loadcases``) include the car deck and add those.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...model.mesh import Masses, Nodes, Shells
from ...model.model import Model
from . import body, trim
from .build import build_mesh
from .materials import GRADES
from .records import id_list, record

KG = 1e-3  # t per kg


@dataclass
class GenericVehicle:
    """A generated car: the Model and where to find things in it."""

    model: Model
    mesh_size: float  # [mm]
    part_ids: dict = field(default_factory=dict)  # part name -> PID
    assemblies: dict = field(default_factory=dict)  # assembly -> [PID]
    set_ids: dict = field(default_factory=dict)  # set title -> (kind, SID)
    sections: dict = field(default_factory=dict)  # assembly -> cross-section ID (at the interface)
    history: dict = field(default_factory=dict)  # sensor name -> node ID
    trim_masses: dict = field(default_factory=dict)  # mass group -> [kg]
    structure_mass: float = 0.0  # [kg] shells (rigid parts included), before the trim
    mass: float = 0.0  # [kg] total
    cog: np.ndarray = field(default_factory=lambda: np.zeros(3))  # [mm]
    interface_x: float = 0.0  # [mm]

    @property
    def shells(self) -> int:
        return len(self.model.shells)

    def write(self, path: Path | str, fmt: str = "fixed") -> Path:
        from ...keyword.writer import write_deck

        return write_deck(self.model, path, fmt=fmt)[0]


def generic_vehicle(
    mesh_size: float = 25.0,
    mass: float = 1263.0,
    cog_x: float = -1100.0,
    cog_z: float = 500.0,
    interface_x: float = -600.0,
    engine_mass: float = 170.0,
    axle_mass: float = 73.0,
    trigger: float = 1.0,
    friction: float = 0.2,
    front: str = "generic",
) -> GenericVehicle:
    """The generic compact car with elements of about ``mesh_size`` mm,
    total ``mass`` [kg] with its CoG at (``cog_x``, 0, ``cog_z``) [mm]
    (front axle at x = 0, ground at z = 0), cross sections at
    ``interface_x`` [mm] (moved to the middle of the element row behind it
    where it falls on a row of nodes: ``GenericVehicle.interface_x``);
    rigid engine-gearbox and rear-axle masses [kg];
    crash-box bead depth ``trigger`` [mm]; contact friction; ``front``:
    "generic" or "stiff", a second front with a thicker, shallower bumper
    beam (``body.FRONTS``)."""
    parts = body.parts(engine_mass, axle_mass, front)
    mesh = build_mesh(parts, mesh_size, trigger)
    xyz = np.round(mesh.xyz, 5)  # short, exact texts in the deck; moves nodes < 1e-5 mm
    interface_x = _between_rows(xyz[:, 0], float(interface_x))
    m = Model()
    n_nodes, n_el = len(xyz), len(mesh.quads)
    m.nodes = Nodes(
        np.arange(1, n_nodes + 1, dtype=np.int64), xyz, np.zeros(n_nodes, np.int8), np.zeros(n_nodes, np.int8)
    )
    sh = Shells.zeros(n_el)
    sh.ids = np.arange(1, n_el + 1, dtype=np.int64)
    sh.pid = mesh.part + 1
    sh.nodes = mesh.quads.astype(np.int32)
    m.shells = sh
    v = GenericVehicle(m, float(mesh_size), interface_x=float(interface_x))
    v.part_ids = {p.name: k + 1 for k, p in enumerate(parts)}
    for p in parts:
        v.assemblies.setdefault(p.assembly, []).append(v.part_ids[p.name])
    _materials_parts(m, parts, mesh)
    m.keywords.append(record("TITLE", title=f"crashlite generic compact car ({mesh_size:g} mm shells)"))
    _trim(v, mesh, xyz, mass, cog_x, cog_z)
    _sets(v, parts, mesh)
    _outputs(v, mesh, xyz, parts, cog_x, cog_z, friction)
    return v


def _between_rows(x: np.ndarray, at: float) -> float:
    """``at``, or where it lies on a row of nodes (a section there would cut
    none of the elements that end on it), the middle of the element row
    behind it."""
    rows = np.unique(x)
    k = int(np.argmin(np.abs(rows - at)))
    if abs(rows[k] - at) > 1e-6 * max(1.0, abs(at)) or k == 0:
        return at
    return float(0.5 * (rows[k] + rows[k - 1]))


def _materials_parts(m: Model, parts, mesh) -> None:
    used = []
    for p in parts:
        if p.grade not in used and GRADES[p.grade].kind != "rigid":
            used.append(p.grade)
    mid = {g: i + 1 for i, g in enumerate(used)}
    for g, i in mid.items():
        gr = GRADES[g]
        if gr.kind == "glass":
            m.materials[i] = record(
                "MAT_PLASTIC_KINEMATIC_TITLE",
                card_title=g,
                mid=i,
                ro=gr.density,
                e=gr.e,
                pr=gr.pr,
                sigy=gr.sigy,
                etan=0.0,
                beta=0.0,
            )
            continue
        eps, sig = gr.curve()
        m.materials[i] = record(
            "MAT_PIECEWISE_LINEAR_PLASTICITY_TITLE",
            card_title=g,
            mid=i,
            ro=gr.density,
            e=gr.e,
            pr=gr.pr,
            sigy=gr.sigy,
            etan=0.0,
            c=gr.c,
            p=gr.p,
            lcss=i,
        )
        m.curves[i] = record("DEFINE_CURVE_TITLE", card_title=f"{g} hardening", rows={"a1": eps, "o1": sig}, lcid=i)
    m.hourglasses[1] = record("HOURGLASS_TITLE", card_title="stiffness form", hgid=1, ihq=4, qm=0.05, qb=0.05, qw=0.05)
    area = np.bincount(mesh.part, weights=mesh.areas(), minlength=len(parts))
    next_mid = len(mid) + 1
    for k, p in enumerate(parts):
        pid = k + 1
        gr = GRADES[p.grade]
        if gr.kind == "rigid":
            ro = p.mass * KG / (p.thickness * area[k])
            m.materials[next_mid] = record(
                "MAT_RIGID_TITLE", card_title=f"{p.name} rigid", mid=next_mid, ro=ro, e=gr.e, pr=gr.pr
            )
            mat, hg = next_mid, 0
            next_mid += 1
        else:
            mat, hg = mid[p.grade], 1
        m.sections[pid] = record(
            "SECTION_SHELL_TITLE",
            card_title=p.name,
            secid=pid,
            elform=2,
            shrf=0.833,
            nip=3,
            t1=p.thickness,
            t2=p.thickness,
            t3=p.thickness,
            t4=p.thickness,
        )
        m.parts[pid] = record("PART", heading=p.name, pid=pid, secid=pid, mid=mat, hgid=hg)


def _select(mesh, xyz, names, lo, hi) -> np.ndarray:
    nodes = mesh.nodes_of(names)
    p = xyz[nodes]
    inside = np.all((p >= np.asarray(lo)) & (p <= np.asarray(hi)), axis=1)
    return nodes[inside]


def _structure(m: Model, mesh, xyz) -> tuple[float, np.ndarray]:
    """Mass [t] and CoG of the shells: ρ·t·A at the element centres (the
    elements are flat parallelograms up to the crash-box beads)."""
    pids = np.arange(1, len(m.parts) + 1)
    rho = np.array([float(m.materials[m.parts[p]["mid"]]["ro"]) for p in pids])
    t = np.array([float(m.sections[p]["t1"]) for p in pids])
    me = (rho * t)[mesh.part] * mesh.areas()
    total = float(me.sum())
    return total, (me @ xyz[mesh.quads].mean(axis=1)) / total


def _trim(v: GenericVehicle, mesh, xyz, mass: float, cog_x: float, cog_z: float) -> None:
    m = v.model
    s_mass, s_cog = _structure(m, mesh, xyz)
    v.structure_mass = s_mass / KG
    groups = body.mass_groups()
    members = [_select(mesh, xyz, g.parts, g.lo, g.hi) for g in groups]
    for g, nodes in zip(groups, members):
        if not len(nodes):
            raise ValueError(f"mass group {g.name!r} has no nodes")
    centres = np.array([xyz[n].mean(axis=0) for n in members])
    target = np.array([cog_x, 0.0, cog_z])
    gm = trim.solve(s_mass, s_cog, centres, [g.nominal * KG for g in groups], mass * KG, target)
    node = np.concatenate(members)
    per = np.concatenate([np.full(len(n), float(f"{mi / len(n):.10g}")) for n, mi in zip(members, gm)])
    v.trim_masses = {g.name: float(mi / KG) for g, mi in zip(groups, gm)}
    ms = Masses.zeros(len(node))
    ms.ids = len(m.shells) + 1 + np.arange(len(node), dtype=np.int64)
    ms.node = node.astype(np.int32)
    ms.mass = per
    m.masses = ms
    total = s_mass + float(per.sum())
    v.mass, v.cog = total / KG, (s_mass * s_cog + per @ xyz[node]) / total


def _sets(v: GenericVehicle, parts, mesh) -> None:
    m = v.model
    sid = iter(range(1, 10**6))

    def part_set(title, pids):
        s = next(sid)
        m.sets[("PART", s)] = id_list("SET_PART_LIST_TITLE", s, sorted(pids), title=title)
        v.set_ids[title] = ("PART", s)

    def node_set(title, idx):
        s = next(sid)
        m.sets[("NODE", s)] = id_list("SET_NODE_LIST_TITLE", s, m.nodes.ids[np.unique(idx)], title=title)
        v.set_ids[title] = ("NODE", s)

    part_set("vehicle", v.part_ids.values())
    for name, pids in v.assemblies.items():
        part_set(f"assembly {name}", pids)
    for side in ("left", "right"):
        node_set(f"crash box {side} nodes", mesh.nodes_of([f"crash box {side}"]))
    node_set("firewall nodes", mesh.nodes_of(["firewall"]))
    axle = mesh.nodes_of(["rear axle"])
    node_set("rear axle attachment", np.intersect1d(axle, mesh.nodes_of(["rear rail left", "rear rail right"])))


def _nearest(xyz, nodes, point) -> int:
    d = np.linalg.norm(xyz[nodes] - np.asarray(point, float), axis=1)
    return int(nodes[np.argmin(d)])


def _outputs(v: GenericVehicle, mesh, xyz, parts, cog_x, cog_z, friction) -> None:
    m = v.model
    ids = m.nodes.ids
    vehicle = v.set_ids["vehicle"][1]
    m.keywords.append(
        record(
            "CONTACT_AUTOMATIC_SINGLE_SURFACE_ID",
            cid=1,
            heading="vehicle self contact",
            ssid=vehicle,
            sstyp=2,
            fs=friction,
            fd=friction,
        )
    )
    welds = []
    for j in body.door_joints():
        # a hinge or latch is a patch: every door node within HINGE_REACH of it welded to the body
        # node opposite (one welded node pair would concentrate the door's load in two elements)
        door = mesh.nodes_of([j.door_part])
        bodyn = mesh.nodes_of([j.body_part])
        shift = np.asarray(parts[mesh.part_index(j.door_part)].shift, float)
        a0 = _nearest(xyz, door, np.asarray(j.door) + shift)
        near = door[np.linalg.norm(xyz[door] - xyz[a0], axis=1) <= body.HINGE_REACH]
        gap = shift / np.linalg.norm(shift) * body.DOOR_GAP
        pairs = [(a, _nearest(xyz, bodyn, xyz[a] - gap)) for a in near]
        pairs = [(a, b) for a, b in pairs if abs(np.linalg.norm(xyz[a] - xyz[b]) - body.DOOR_GAP) <= 1e-6]
        if not any(a == a0 for a, _ in pairs):
            raise ValueError(f"{j.name}: door and body nodes are not opposite each other")
        welds += [(len(welds) + 1 + k, ids[a], ids[b]) for k, (a, b) in enumerate(pairs)]
    w = np.array(welds, np.int64)
    m.keywords.append(record("CONSTRAINED_SPOTWELD_ID", rows={"wid": w[:, 0], "n1": w[:, 1], "n2": w[:, 2]}))
    hist = []
    for s in body.sensors(cog_x, cog_z):
        nodes = mesh.nodes_of(s.parts) if s.parts else np.arange(len(xyz))
        nid = int(ids[_nearest(xyz, nodes, s.at)])
        v.history[s.name] = nid
        hist.append((nid, s.name))
    m.keywords.append(
        record(
            "DATABASE_HISTORY_NODE_ID",
            rows={"id": np.array([h[0] for h in hist], np.int64), "heading": np.array([h[1] for h in hist], object)},
        )
    )
    x = v.interface_x
    csid = 0
    for name, pids in v.assemblies.items():
        sel = np.isin(m.shells.pid, pids)
        px = xyz[mesh.quads[sel], 0]
        if not ((px.min(axis=1) < x) & (px.max(axis=1) > x)).any():
            continue
        csid += 1
        v.sections[name] = csid
        m.keywords.append(
            record(
                "DATABASE_CROSS_SECTION_PLANE_ID",
                csid=csid,
                title=name,
                psid=v.set_ids[f"assembly {name}"][1],
                xct=x,
                yct=0.0,
                zct=0.0,
                xch=x + 1.0,
                ych=0.0,
                zch=0.0,
            )
        )
