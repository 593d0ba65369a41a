"""Boundary conditions from the Model: nodal constraints (*NODE TC/RC,
*BOUNDARY_SPC_NODE/SET, also in local systems and as _BIRTH_DEATH cards
that hold the whole run), planar and cylindrical rigid walls
(*RIGIDWALL_PLANAR, _GEOMETRIC_CYLINDER) and prescribed motions
(*BOUNDARY_PRESCRIBED_MOTION_NODE/SET/RIGID), and the run's end time.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..model.model import Model
from .records import _curve, _node_set, _problem

# constraint code of *NODE TC (and RC, same numbering) -> held (x, y, z)
_TC = {0: (0, 0, 0), 1: (1, 0, 0), 2: (0, 1, 0), 3: (0, 0, 1), 4: (1, 1, 0), 5: (0, 1, 1), 6: (1, 0, 1), 7: (1, 1, 1)}


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


def build_constraints(model: Model, problems: list) -> tuple[np.ndarray, np.ndarray, dict]:
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


def end_time(model: Model) -> float:
    """*CONTROL_TERMINATION ENDTIM (0 without the card)."""
    term = model.find("CONTROL_TERMINATION")
    return float(term[0].get("endtim", 0.0) or 0.0) if term else 0.0


def _spc_whole_run(model: Model, rec, problems: list) -> bool:
    """Whether every constraint of a *BOUNDARY_SPC_..._BIRTH_DEATH card holds
    from the start to the end time (then it is a plain SPC); constraints
    that start or end inside the run are refused, not held throughout."""
    end = end_time(model)
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


def build_walls(model: Model, problems: list) -> list[Wall]:
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


def build_motions(model: Model, problems: list) -> list[Motion]:
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
