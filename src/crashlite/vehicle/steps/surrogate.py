"""Step 4 of the simplified vehicle: the spring–mass surrogate of the replaced structure.

``build_surrogate`` turns a ``Cut`` and the figures of steps 1–3 into a
deck that keeps the front FE structure up to the interface and replaces
what lies behind it (the paper's figure 15):

- the kept structure (``truncate``), every reference to the deleted
  elements mended;
- the *interface*: a nodal rigid body over the cut (one over the whole
  interface, as the rigid load introduction of step 3, by default; or one
  per assembly, ``interface="assembly"``), holding for every assembly a
  node at the centre of its cut;
- one linear spring per assembly (*MAT_SPRING_ELASTIC, k_i = share_i · K)
  from that node rearwards along the *profile direction* of the assembly
  (the mean in-plane direction of its replaced shells across the cut, the
  axis of its beams), optionally with a viscous damper beside it;
- the *rear body*: a nodal rigid body with the mass, CoG and inertia tensor
  of the replaced structure (*CONSTRAINED_NODAL_RIGID_BODY_INERTIA) holding
  the springs' rear ends, a node at the CoG, the node between the rear-axle
  attachment points, and the history nodes of the replaced structure (so
  nodout of the full and the simplified run compare node by node);
- the rear-suspension / anti-rotation beam (*SECTION_BEAM ELFORM 2,
  *MAT_ELASTIC) from the rear-axle node to the interface centre. The
  springs carry the longitudinal stiffness and, through their spread over
  the cut, pitch and yaw; the beam adds what axial springs cannot: shear
  across the cut and roll. Its bending stiffness EI = k_t·L³/3 and
  torsion GJ = k_r·L come from the replaced structure's own transverse and
  roll stiffness at the interface (``stiffness.transverse_stiffness``: the step-3
  static model loaded across instead of along); its axial stiffness is a
  small fraction ``beam_axial`` of K, taken from the springs so that the
  longitudinal stiffness stays K.

The total mass is the full model's: kept elements and point masses stay,
everything replaced is the rear body's (less the beam's own small mass),
or, with ``mass_split="axle"``, shared between the rear body and the
interface body as a bar lumps it; with one body per assembly each of them
carries its own parts' share and the body nearest the interface centre
the rest (point masses, parts of no assembly).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from ...model.mesh import Beams, Discretes, Inertias, Nodes
from ...model.model import Model
from ...model.sets import history_nodes
from ..car.records import id_list, record
from .cut import ELEMENT_TABLES, Cut
from .massprops import ReplacedMass, element_moments, split_replaced
from .truncate import Truncated, truncate

STEEL_E, STEEL_NU, STEEL_RHO = 210000.0, 0.3, 7.85e-9  # MPa, -, t/mm³ (mm–t–s)


@dataclass
class Spring:
    """One load-path spring of the surrogate."""

    assembly: str
    share: float  # load-path share (fraction)
    k: float  # stiffness [force/length]
    damping: float  # viscous constant of the damper beside it (0: none) [force·time/length]
    front: np.ndarray  # (3,) node on the interface [length]
    rear: np.ndarray  # (3,) node on the rear body [length]
    direction: np.ndarray  # (3,) unit profile direction (rearwards)
    interface_nodes: int  # cut nodes of the assembly
    element_id: int = 0
    part_id: int = 0


@dataclass
class Surrogate:
    """The simplified vehicle (step 4) and what it was built from."""

    model: Model
    springs: list
    stiffness: float  # K of step 3 [force/length]
    mass: ReplacedMass
    truncated: Truncated
    node_ids: dict  # "cog", "axle", "interface centre" -> deck node ID
    part_ids: dict  # "rear body", "interface", "beam", spring parts -> ID
    beam: dict  # length, EA, EI, GJ of the anti-rotation beam
    interface: str = "rigid"
    notes: list = field(default_factory=list)
    mass_shares: dict = field(default_factory=dict)  # "interface", "rear body" -> MassProperties

    def write(self, path: Path | str, fmt: str = "fixed") -> Path:
        from ...keyword.writer import write_deck

        return write_deck(self.model, path, fmt=fmt)[0]

    def summary(self) -> dict:
        """Every figure of the surrogate, JSON-ready."""
        full = self.truncated
        return {
            "interface": self.interface,
            "longitudinal_stiffness": self.stiffness,
            "springs": [
                {
                    "assembly": s.assembly,
                    "share_percent": 100.0 * s.share,
                    "stiffness": s.k,
                    "damping": s.damping,
                    "direction": s.direction.tolist(),
                    "front": s.front.tolist(),
                    "rear": s.rear.tolist(),
                    "interface_nodes": s.interface_nodes,
                }
                for s in self.springs
            ],
            "mass_shares": {
                k: {"mass": v.mass, "cog": v.cog.tolist(), "inertia": v.inertia.tolist()}
                for k, v in self.mass_shares.items()
            },
            "rear_axle_point": None if self.mass.axle_points is None else self.mass.axle_points.tolist(),
            "beam": dict(self.beam),
            "kept": {
                "nodes": len(self.model.nodes),
                "shells": len(self.model.shells),
                "solids": len(self.model.solids),
                "parts": len(full.kept_parts),
            },
            "deleted": {"parts": len(full.dropped_parts), "nodes": int((full.node_map < 0).sum())},
            "node_ids": dict(self.node_ids),
            "part_ids": dict(self.part_ids),
            "notes": list(self.notes),
        }


def profile_direction(cut: Cut, pids: Iterable[int], nodes: np.ndarray, rows: int = 2) -> tuple[np.ndarray, float]:
    """Unit direction (rearwards) in which the replaced elements of parts
    ``pids`` leave the cut at ``nodes``, and how much of it is along the
    vehicle axis (|d·axis|): from the centre of the cut nodes to the centre
    of the nodes ``rows`` element rows behind them (the member's centre
    line, whatever its section or the angle the cut makes with it). No
    element behind the cut: −axis."""
    m = cut.model
    a = cut.axis
    xyz = m.nodes.xyz
    conns = []
    for table in ELEMENT_TABLES:
        tab = getattr(m, table)
        if len(tab):
            conn = tab.nodes[cut.replaced[table] & np.isin(tab.pid, list(pids))]
            conns.append(conn[:, :2] if table in ("beams", "discretes") else conn)
    front = np.zeros(len(m.nodes), bool)
    front[nodes] = True
    seen = front.copy()
    ring = front
    for _ in range(rows):
        nxt = np.zeros(len(m.nodes), bool)
        for conn in conns:
            touch = (ring[np.maximum(conn, 0)] & (conn >= 0)).any(axis=1)
            c = conn[touch]
            nxt[c[c >= 0]] = True
        nxt &= ~seen
        if not nxt.any():
            break
        seen |= nxt
        ring = nxt
    if ring is front:
        return -a, 1.0
    d = xyz[ring].mean(axis=0) - xyz[nodes].mean(axis=0)
    if not np.linalg.norm(d) > 0 or d @ a >= 0:
        return -a, 1.0
    d = d / np.linalg.norm(d)
    return d, float(abs(d @ a))


def _next(ids) -> int:
    ids = [int(i) for i in ids]
    return max(ids, default=0) + 1


class _Ids:
    """Fresh IDs above every ID the model has, per kind."""

    def __init__(self, m: Model):
        el = [getattr(m, t).ids for t in ELEMENT_TABLES + ("masses", "inertias")]
        self.node = _next(m.nodes.ids)
        self.element = _next(np.concatenate(el)) if el else 1
        self.part = _next(list(m.parts) + [int(r.get("pid", 0) or 0) for r in m.find("CONSTRAINED_NODAL_RIGID_BODY")])
        self.section = _next(m.sections)
        self.material = _next(m.materials)
        self.set = _next([sid for (kind, sid) in m.sets if kind == "NODE"])

    def take(self, kind: str, n: int = 1) -> int:
        first = getattr(self, kind)
        setattr(self, kind, first + n)
        return first


def retitle(m: Model, kind: str) -> None:
    """The deck's *TITLE marked as the simplified model of ``kind`` (80 characters)."""
    title = next((r for r in m.keywords if getattr(r, "keyword", "") == "TITLE"), None)
    if title is not None:
        title["title"] = (str(title.get("title", "")) + f" - simplified ({kind})").strip(" -")[:80]


def kept_front(cut: Cut, keep_nodes: ArrayLike | None = None) -> tuple[Truncated, np.ndarray]:
    """The kept structure (``truncate``) and the removed nodes that ride on
    the rear body with it: the replaced structure's history nodes (so
    nodout of the full and the simplified run compare node by node) and
    ``keep_nodes``."""
    hist = history_nodes(cut.model)
    ride = hist[cut.removed_nodes[hist]]
    if keep_nodes is not None:
        ride = np.union1d(ride, np.asarray(keep_nodes, np.int64))
    return truncate(cut, keep=ride), ride


def _whole_vehicle_sets(full: Model, cut: Cut, m: Model, new_ids: np.ndarray, notes: list) -> None:
    """Node sets that held the whole replaced structure (the vehicle's
    nodes for an initial velocity, a wall, gravity) take the surrogate's
    new nodes too, so the rear body moves and is treated as the structure
    it stands for."""
    removed = full.nodes.ids[cut.removed_nodes]
    if not len(removed):
        return
    for (kind, sid), rec in full.sets.items():
        if kind != "NODE" or ("NODE", sid) not in m.sets:
            continue
        members = full.set_members("NODE", sid)
        if np.isin(removed, members).all():
            now = m.set_members("NODE", sid)
            head = {k: v for k, v in rec.values.items() if k != "sid"}
            m.sets[("NODE", sid)] = id_list(
                "SET_NODE_LIST" + ("_TITLE" if rec.title is not None else ""),
                sid,
                np.union1d(now, new_ids),
                title=rec.title,
                **head,
            )
            notes.append(
                f"*SET_NODE {sid}{' (' + rec.title + ')' if rec.title else ''} held the whole replaced "
                "structure: it holds the surrogate's nodes too"
            )


def build_surrogate(
    cut: Cut,
    assemblies: dict,
    shares: dict,
    stiffness: float,
    mass: ReplacedMass,
    transverse: dict | None = None,
    interface: str = "rigid",
    spring_length: float = 100.0,
    damping_ratio: float = 0.0,
    beam_axial: float = 1e-3,
    keep_nodes: ArrayLike | None = None,
    mass_split: str = "axle",
) -> Surrogate:
    """The surrogate deck (module docstring).

    assemblies     name -> part IDs of the full model (the interface groups)
    shares         name -> load-path share (step 1); assemblies without a share get no spring
    stiffness      K of step 3 [force/length]
    mass           step 2 (its ``axle_points`` anchor the anti-rotation beam; without them, the CoG)
    transverse     {"shear": k_t [force/length], "roll": k_r [force·length/rad]} of the replaced
                   structure at the interface (``stiffness.transverse_stiffness``); None: the beam gets
                   the stiffness of a steel tube carrying K axially
    interface      "rigid" (one nodal rigid body over the cut) or "assembly" (one per assembly)
    spring_length  length of each spring along its profile direction [length]
    damping_ratio  ζ of the dampers, c_i = share_i · 2ζ·√(K·M) (0: springs only, as the paper)
    beam_axial     the beam's axial stiffness as a fraction of K
    keep_nodes     more removed nodes (indices) to move with the rear body
    mass_split     "axle": the replaced mass shared between the interface body and the rear
                   body as a bar between the interface and the rear-axle point lumps it
                   (``massprops.split_replaced``), each share with its own CoG and inertia;
                   "cog": all of it on the rear body at the CoG (the paper)
    """
    if mass_split not in ("axle", "cog"):
        raise ValueError(f"mass_split must be 'axle' or 'cog', got {mass_split!r}")
    if interface not in ("rigid", "assembly"):
        raise ValueError(f"interface must be 'rigid' or 'assembly', got {interface!r}")
    if not stiffness > 0:
        raise ValueError(f"the longitudinal stiffness must be positive, got {stiffness}")
    full = cut.model
    notes = list(cut.notes)
    total = sum(float(shares.get(n, 0.0)) for n in assemblies)
    unknown = sorted(set(shares) - set(assemblies))
    if unknown:
        raise KeyError(f"shares for assemblies without parts: {unknown}")
    if not total > 0:
        raise ValueError("no assembly has a load-path share")
    groups = cut.assembly_interface(assemblies)
    tr, ride = kept_front(cut, keep_nodes)
    notes += tr.notes
    m = tr.model
    ids = _Ids(m)
    new_xyz, new_ids = [], []

    def node(p) -> int:
        nid = ids.take("node")
        new_xyz.append(np.asarray(p, float))
        new_ids.append(nid)
        return nid

    # rigid groups the cut keeps may not share nodes with the interface body
    bound = np.zeros(len(full.nodes), bool)
    for g in cut.groups:
        if not cut.removed_nodes[g.nodes].all():
            bound[g.nodes] = True
    cut_nodes = cut.interface_nodes[~bound[cut.interface_nodes]]
    if len(cut_nodes) < len(cut.interface_nodes):
        notes.append(
            f"{len(cut.interface_nodes) - len(cut_nodes)} interface node(s) of spot welds, nodal rigid "
            "bodies or rigid parts left out of the interface rigid body"
        )
    xyz = full.nodes.xyz
    centre = xyz[cut_nodes].mean(axis=0)
    axle = mass.axle_points
    if axle is None:
        axle = mass.structure.cog
        notes.append("no rear-axle attachment points: the anti-rotation beam starts at the CoG")
    near, far = None, mass.structure
    if mass_split == "axle" and mass.axle_points is not None:
        near, far = split_replaced(cut, mass.axle_points)
    g_id, a_id, i_id = node(far.cog), node(axle), node(centre)
    k_beam = beam_axial * stiffness
    k_springs = stiffness - k_beam
    total_m = float(far.mass)
    springs = []
    for name in assemblies:
        s = float(shares.get(name, 0.0)) / total
        nodes_i = groups[name]
        nodes_i = nodes_i[~bound[nodes_i]]
        if s <= 0:
            notes.append(f"assembly {name!r}: no load-path share, no spring")
            continue
        if not len(nodes_i):
            raise ValueError(f"assembly {name!r} has a share of {100 * s:.1f} % but no node on the interface")
        d, along = profile_direction(cut, assemblies[name], nodes_i)
        front = xyz[nodes_i].mean(axis=0)
        c = s * 2.0 * damping_ratio * np.sqrt(stiffness * total_m)
        springs.append(Spring(name, s, s * k_springs, c, front, front + spring_length * d, d, len(nodes_i)))
        if along < 0.9:
            notes.append(
                f"assembly {name!r}: profile {np.degrees(np.arccos(min(along, 1.0))):.0f}° off the vehicle axis"
            )
    # the interface share of the replaced mass: per assembly body its own parts' share (a body of a
    # few cut nodes alone would be light), the rest on the body nearest the interface centre
    own_near = {}
    near_total = near
    if near is not None and interface == "assembly":
        moments = element_moments(full)  # once for every split
        taken: set = set()
        for sp in springs:
            parts = [int(p) for p in assemblies[sp.assembly] if int(p) not in taken]
            taken.update(parts)
            share = split_replaced(cut, mass.axle_points, only=parts, moments=moments)[0]
            if share.mass > 0:
                own_near[sp.assembly] = (node(share.cog), share)
        near = split_replaced(cut, mass.axle_points, without=taken, moments=moments)[0]
    f_id = node(near.cog) if near is not None and near.mass > 0 else None
    front_ids = [node(s.front) for s in springs]
    rear_ids = [node(s.rear) for s in springs]
    nodes = Nodes.zeros(len(new_ids))
    nodes.ids = np.array(new_ids, np.int64)
    nodes.xyz = np.array(new_xyz)
    m.nodes = Nodes.concat([m.nodes, nodes])
    index = {int(n): k for k, n in enumerate(m.nodes.ids[-len(new_ids) :], start=len(m.nodes) - len(new_ids))}

    def node_set(title, deck_ids) -> int:
        sid = ids.take("set")
        m.sets[("NODE", sid)] = id_list(
            "SET_NODE_LIST_TITLE", sid, np.unique(np.asarray(deck_ids, np.int64)), title=title
        )
        return sid

    _whole_vehicle_sets(full, cut, m, np.array(new_ids, np.int64), notes)
    part_ids = {}
    # --- interface rigid bodies -------------------------------------------------------------------
    kept_ids = lambda idx: full.nodes.ids[idx]  # noqa: E731 (full and kept models share node IDs)
    if interface == "rigid":
        pid = ids.take("part")
        extra = [i_id] + ([f_id] if f_id is not None else [])
        sid = node_set("surrogate interface", np.concatenate([kept_ids(cut_nodes), front_ids, extra]))
        m.keywords.append(record("CONSTRAINED_NODAL_RIGID_BODY", pid=pid, nsid=sid))
        part_ids["interface"] = pid
    else:
        nearest = int(np.argmin([np.linalg.norm(s.front - centre) for s in springs]))
        for k, (s, f) in enumerate(zip(springs, front_ids)):
            own = groups[s.assembly][~bound[groups[s.assembly]]]
            extra = ([f, i_id] + ([f_id] if f_id is not None else [])) if k == nearest else [f]
            if s.assembly in own_near:
                extra = extra + [own_near[s.assembly][0]]
            pid = ids.take("part")
            sid = node_set(f"surrogate interface {s.assembly}", np.concatenate([kept_ids(own), extra]))
            m.keywords.append(record("CONSTRAINED_NODAL_RIGID_BODY", pid=pid, nsid=sid))
            part_ids[f"interface {s.assembly}"] = pid
        notes.append(
            f"interface per assembly: the anti-rotation beam ends on the rigid body of "
            f"{springs[nearest].assembly!r}, the one nearest the interface centre"
        )
    # --- springs and dampers ------------------------------------------------------------------------
    sec = ids.take("section")
    m.sections[sec] = record("SECTION_DISCRETE_TITLE", card_title="surrogate springs", secid=sec)
    disc = Discretes.zeros(0)
    rows = []
    for s, f, r in zip(springs, front_ids, rear_ids):
        for kind, value in (("spring", s.k), ("damper", s.damping)):
            if kind == "damper" and not value > 0:
                continue
            mid, pid, eid = ids.take("material"), ids.take("part"), ids.take("element")
            if kind == "spring":
                m.materials[mid] = record(
                    "MAT_SPRING_ELASTIC_TITLE", card_title=f"spring {s.assembly}", mid=mid, k=value
                )
                s.element_id, s.part_id = eid, pid
            else:
                m.materials[mid] = record(
                    "MAT_DAMPER_VISCOUS_TITLE", card_title=f"damper {s.assembly}", mid=mid, dc=value
                )
            m.parts[pid] = record("PART", heading=f"surrogate {kind} {s.assembly}", pid=pid, secid=sec, mid=mid)
            part_ids[f"{kind} {s.assembly}"] = pid
            rows.append((eid, pid, index[f], index[r]))
    if rows:
        r = np.array(rows, np.int64)
        disc = Discretes.zeros(len(r))
        disc.ids, disc.pid = r[:, 0], r[:, 1]
        disc.nodes = r[:, 2:4].astype(np.int32)
        m.discretes = Discretes.concat([m.discretes, disc])
    # --- anti-rotation / rear-suspension beam ---------------------------------------------------------
    length = float(np.linalg.norm(centre - axle))
    if not length > 0:
        raise ValueError("the rear-axle point lies on the interface centre: no anti-rotation beam")
    area = k_beam * length / STEEL_E
    if transverse is not None:
        ei = float(transverse["shear"]) * length**3 / 3.0
        gj = float(transverse["roll"]) * length
    else:  # a thin steel tube of the same axial stiffness as the springs together
        r_t = np.sqrt(stiffness * length / STEEL_E / (2 * np.pi * 2.0))  # 2 mm wall
        ei = STEEL_E * np.pi * r_t**3 * 2.0
        gj = ei / (1 + STEEL_NU)
        notes.append("no transverse stiffness given: the anti-rotation beam is a steel tube of stiffness K")
    iss = itt = ei / STEEL_E
    irr = gj * 2 * (1 + STEEL_NU) / STEEL_E
    sec_b, mid_b, pid_b, eid_b = ids.take("section"), ids.take("material"), ids.take("part"), ids.take("element")
    m.sections[sec_b] = record(
        "SECTION_BEAM_TITLE",
        card_title="surrogate anti-rotation beam",
        secid=sec_b,
        elform=2,
        a=area,
        iss=iss,
        itt=itt,
        irr=irr,
    )
    m.materials[mid_b] = record(
        "MAT_ELASTIC_TITLE", card_title="surrogate anti-rotation beam", mid=mid_b, ro=STEEL_RHO, e=STEEL_E, pr=STEEL_NU
    )
    m.parts[pid_b] = record("PART", heading="surrogate anti-rotation beam", pid=pid_b, secid=sec_b, mid=mid_b)
    part_ids["beam"] = pid_b
    bm = Beams.zeros(1)
    bm.ids[:] = eid_b
    bm.pid[:] = pid_b
    bm.nodes[0] = [index[a_id], index[i_id], -1]
    m.beams = Beams.concat([m.beams, bm])
    beam_mass = STEEL_RHO * area * length
    # --- rear body ----------------------------------------------------------------------------------
    pid = ids.take("part")
    rear_members = np.concatenate([[g_id, a_id], rear_ids, full.nodes.ids[ride]])
    sid = node_set("surrogate rear body", rear_members)
    c, t = far.cog, far.inertia
    # the interface's share: masses with their inertia on the interface body (bodies)
    lumps = ([(f_id, near)] if f_id is not None else []) + list(own_near.values())
    if lumps:
        it = Inertias.zeros(len(lumps))
        for r, (nid, share) in enumerate(lumps):
            it.ids[r] = ids.take("element")
            it.node[r] = index[nid]
            it.mass[r] = share.mass
            it.tensor[r] = share.inertia[[0, 0, 0, 1, 1, 2], [0, 1, 2, 1, 2, 2]]
        m.inertias = Inertias.concat([m.inertias, it])
        shared = sum(share.mass for _, share in lumps)
        notes.append(
            f"{100 * shared / mass.structure.mass:.1f} % of the replaced mass on the interface "
            f"bod{'ies' if len(own_near) else 'y'} (shared along the axis to the rear axle"
            f"{', per assembly' if own_near else ''}), the rest on the rear body"
        )
    m.keywords.append(
        record(
            "CONSTRAINED_NODAL_RIGID_BODY_INERTIA",
            pid=pid,
            nsid=sid,
            xc=float(c[0]),
            yc=float(c[1]),
            zc=float(c[2]),
            tm=total_m - beam_mass,
            nodeid=g_id,
            ixx=float(t[0, 0]),
            ixy=float(t[0, 1]),
            ixz=float(t[0, 2]),
            iyy=float(t[1, 1]),
            iyz=float(t[1, 2]),
            izz=float(t[2, 2]),
        )
    )
    part_ids["rear body"] = pid
    retitle(m, "surrogate")
    if len(ride):
        notes.append(f"{len(ride)} history node(s) of the replaced structure move with the rear body")
    beam = {"length": length, "axial_stiffness": k_beam, "EI": ei, "GJ": gj, "mass": beam_mass}
    node_ids = {"cog": g_id, "axle": a_id, "interface centre": i_id}
    if f_id is not None:
        node_ids["interface mass"] = f_id
    return Surrogate(
        m,
        springs,
        float(stiffness),
        mass,
        tr,
        node_ids,
        part_ids,
        beam,
        interface,
        notes,
        {"rear body": far, **({"interface": near_total} if near_total is not None else {})},
    )
