"""*INITIAL_VELOCITY_RIGID_BODY: the initial motion of a rigid part's body.

The body gets the translational velocity (VX, VY, VZ) of its centre of mass
and the angular velocity (VXR, VYR, VZR) about it, given in the system LCID
when it is not 0; its nodes start at v = v_c + ω × (x − x_c). The card
overrides what *INITIAL_VELOCITY cards or *PART_INERTIA gave the same body,
and the body's CMO constraints still hold. A part merged into another by
*CONSTRAINED_RIGID_BODIES gives the merged body its velocity. LS-DYNA reads
the card for rigid bodies only: naming a deformable part is refused (its
nodes take a velocity from *INITIAL_VELOCITY_GENERATION).
"""

from __future__ import annotations

import numpy as np

from ..model.model import Model
from .frames import axes
from .records import _problem
from .rigid import RigidBody, cross


def _lead_of(model: Model) -> dict[int, int]:
    """Part ID -> the lead part of the body it is merged into."""
    lead: dict[int, int] = {}
    for rec in model.find("CONSTRAINED_RIGID_BODIES"):
        for pl, pc in zip(rec.rows["pidl"], rec.rows["pidc"]):
            lead[int(pc)] = int(pl)
    return lead


def start_rigid_bodies(model: Model, bodies: list[RigidBody], x: np.ndarray, v: np.ndarray, problems: list) -> None:
    """Give the rigid-part ``bodies`` the velocities of the deck's
    *INITIAL_VELOCITY_RIGID_BODY cards, and their nodes the matching
    velocities in ``v`` (n, 3)."""
    cards = model.find("INITIAL_VELOCITY_RIGID_BODY")
    if not cards:
        return
    by_id = {b.body_id: b for b in bodies}
    lead = _lead_of(model)
    for rec in cards:
        rows = rec.rows or {}
        for k in range(len(rows.get("pid", []))):
            pid = int(rows["pid"][k])
            body = by_id.get(lead.get(pid, pid))
            if body is None:
                why = (
                    "is not defined"
                    if pid not in model.parts
                    else "is not a rigid part (*MAT_RIGID with elements): the card sets the velocity of a rigid "
                    "body; give a deformable part its velocity with *INITIAL_VELOCITY_GENERATION"
                )
                problems.append(_problem(rec, "pid", f"part {pid} {why}"))
                continue
            vel = np.array([rows["vx"][k], rows["vy"][k], rows["vz"][k]], float)
            w = np.array([rows["vxr"][k], rows["vyr"][k], rows["vzr"][k]], float)
            lcid = int(rows["lcid"][k])
            if lcid:
                try:
                    r = axes(model, lcid)
                except (KeyError, ValueError) as e:
                    problems.append(_problem(rec, "lcid", str(e).strip("'\"")))
                    continue
                vel, w = r.T @ vel, r.T @ w  # local components -> global
            body.velocity[:] = vel
            body.momentum[:] = (
                body.rot @ body.inertia_body @ body.rot.T @ w
            )  # L = I ω (the body frame is global at t = 0)
            body.constrain()
            v[body.nodes] = body.velocity + cross(body.omega(), x[body.nodes] - body.cog)
