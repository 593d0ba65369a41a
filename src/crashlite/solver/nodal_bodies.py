"""Nodal rigid bodies from the Model: *CONSTRAINED_NODAL_RIGID_BODY (and
_INERTIA) as rigid.RigidBody objects, with the *ELEMENT_INERTIA tensors of
their nodes, and the check that a body without inertia about some axis
carries no element off that axis.
"""

from __future__ import annotations

import numpy as np

from ..keyword.errors import Problem
from ..model.model import Model
from .records import _node_set, _problem
from .rigid import RigidBody


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


def build_nodal_bodies(
    model: Model,
    x: np.ndarray,
    v: np.ndarray,
    mass: np.ndarray,
    problems: list,
    used: np.ndarray | None = None,
    rot_inertia: np.ndarray | None = None,
) -> list[RigidBody]:
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
