"""Initial conditions of the nodes: translational and angular velocities
from *INITIAL_VELOCITY, _NODE and _GENERATION, with the check that no card
sets a node faster than sound travels in the deck's stiffest material."""

from __future__ import annotations

import numpy as np

from ..model.model import Model
from .records import _node_set, _problem


def _fastest_wave(model: Model) -> float:
    """The largest bar wave speed sqrt(E/RO) of the deck's materials (0
    without any: springs and masses only) [length/time]."""
    c = 0.0
    for mat in model.materials.values():
        try:
            e, ro = float(mat.get("e", 0.0) or 0.0), float(mat.get("ro", 0.0) or 0.0)
        except (TypeError, ValueError):
            continue
        if e > 0 and ro > 0:
            c = max(c, float(np.sqrt(e / ro)))
    return c


def _initial_velocity(model: Model, v: np.ndarray, problems: list) -> None:
    """Initial velocities of the nodes from every *INITIAL_VELOCITY card;
    a card that sets a node faster than sound travels in the stiffest
    material of the deck is refused (no crash is, and the first steps
    would turn the elements inside out)."""
    n = len(v)
    c_max = _fastest_wave(model)
    for rec in model.find("INITIAL_VELOCITY"):  # typed cards only: unread variants are refused
        name = rec.keyword
        before = v.copy() if c_max > 0 else None
        _one_initial_velocity(model, rec, name, v, n)
        if before is not None:
            speed = np.linalg.norm(v - before, axis=1)
            changed = np.flatnonzero(speed > 0)
            fastest = np.linalg.norm(v[changed], axis=1) if len(changed) else np.zeros(0)
            if len(fastest) and fastest.max() > c_max:
                i = int(changed[np.argmax(fastest)])
                field = "vx" if name != "INITIAL_VELOCITY_NODE" else None
                problems.append(
                    _problem(
                        rec,
                        field,
                        f"node {int(model.nodes.ids[i])} starts at {fastest.max():.4g}, "
                        f"faster than sound in any material of the deck "
                        f"(sqrt(E/RO) at most {c_max:.4g})",
                    )
                )


def _one_initial_velocity(model: Model, rec, name: str, v: np.ndarray, n: int) -> None:
    """The velocities one *INITIAL_VELOCITY card sets, into ``v``."""
    if name == "INITIAL_VELOCITY":
        nodes = np.arange(n) if not rec.get("nsid") else _node_set(model, rec["nsid"])
        v[nodes] = [rec.get("vx", 0.0), rec.get("vy", 0.0), rec.get("vz", 0.0)]
        if rec.get("nsidex"):
            ex = _node_set(model, rec["nsidex"])
            v[ex] = [rec.get("vxe", 0.0), rec.get("vye", 0.0), rec.get("vze", 0.0)]
    elif name == "INITIAL_VELOCITY_NODE":
        idx = model.node_index(rec.rows["nid"])
        v[idx] = np.stack([rec.rows["vx"], rec.rows["vy"], rec.rows["vz"]], axis=1)
    elif name == "INITIAL_VELOCITY_GENERATION":
        styp = int(rec.get("styp", 2))
        if styp == 3:
            nodes = _node_set(model, rec["id"])
        else:
            pids = [rec["id"]] if styp == 2 else model.set_members("PART", rec["id"])
            nodes = _part_nodes(model, pids)
        axis = np.array([rec.get("nx", 0.0), rec.get("ny", 0.0), rec.get("nz", 0.0)], float)
        omega = float(rec.get("omega", 0.0))
        vt = np.array([rec.get("vx", 0.0), rec.get("vy", 0.0), rec.get("vz", 0.0)], float)
        v[nodes] = vt
        if omega and np.linalg.norm(axis) > 0:
            w = omega * axis / np.linalg.norm(axis)
            c = np.array([rec.get("xc", 0.0), rec.get("yc", 0.0), rec.get("zc", 0.0)], float)
            v[nodes] += np.cross(w, model.nodes.xyz[nodes] - c)


def _part_nodes(model: Model, pids) -> np.ndarray:
    out = []
    for t in (model.shells, model.solids, model.beams, model.discretes):
        sel = np.isin(t.pid, pids)
        out.append(t.nodes[sel].ravel())
    nodes = np.unique(np.concatenate(out)) if out else np.zeros(0, np.int64)
    return nodes[nodes >= 0]


def _initial_rotation(model: Model, n: int) -> np.ndarray:
    """(n, 3) initial angular velocities: VXR.. of *INITIAL_VELOCITY(_NODE)
    and OMEGA of *INITIAL_VELOCITY_GENERATION."""
    w = np.zeros((n, 3))
    for rec in model.keywords:
        name = getattr(rec, "keyword", "")
        if name == "INITIAL_VELOCITY":
            nodes = np.arange(n) if not rec.get("nsid") else _node_set(model, rec["nsid"])
            w[nodes] = [rec.get("vxr", 0.0), rec.get("vyr", 0.0), rec.get("vzr", 0.0)]
        elif name == "INITIAL_VELOCITY_NODE":
            idx = model.node_index(rec.rows["nid"])
            w[idx] = np.stack([rec.rows["vxr"], rec.rows["vyr"], rec.rows["vzr"]], axis=1)
        elif name == "INITIAL_VELOCITY_GENERATION" and rec.get("omega"):
            styp = int(rec.get("styp", 2))
            nodes = (
                _node_set(model, rec["id"])
                if styp == 3
                else _part_nodes(model, [rec["id"]] if styp == 2 else model.set_members("PART", rec["id"]))
            )
            axis = np.array([rec.get("nx", 0.0), rec.get("ny", 0.0), rec.get("nz", 0.0)], float)
            if np.linalg.norm(axis) > 0:
                w[nodes] = float(rec["omega"]) * axis / np.linalg.norm(axis)
    return w
