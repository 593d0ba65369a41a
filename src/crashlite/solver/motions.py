"""Prescribed motions (*BOUNDARY_PRESCRIBED_MOTION) applied to the
half-step velocities: on nodes, node sets and rigid parts.

The work of a prescribed motion is the work of the reaction it needs: the
impulse over the step from the old half-step velocity ``v_old`` (before
the kick of the nodal forces f) to the prescribed one ``v_new`` is
J = m·(v_new − v_old) − f·dt_v along the direction, and it does the work
J·(v_old + v_new)/2 (mid-point velocity over the step). For a node with
mass this is ΔKE − (work of f); for a massless driven node (the end of a
spring pulled by a prescribed displacement) it is −f·v·dt, so the energy
the spring takes up is supplied and the balance closes. (Booking the
kinetic-energy jump from the kicked velocity instead counts a spurious
½·(f·dt)²/m per step, huge for light nodes.)
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .kernels.motion import prescribe_nodes
from .rigid import RigidBody
from .state import State


class Motions:
    def __init__(self, motions, bodies, x0: np.ndarray):
        self.motions = motions
        self.x0 = x0
        self.bodies = {b.body_id: b for b in bodies}
        self.cog0 = {b.body_id: b.cog.copy() for b in bodies}

    def apply(self, st: State, t: float, dt_v: float, dt: float, place: Callable[[RigidBody], None]) -> float:
        """Prescribed velocities for the half step t .. t + dt (dt_v: time
        since the previous half step; the nodal forces st.f of time t have
        already been applied over dt_v); returns the work the prescriptions
        did over dt_v (see the module text)."""
        work = 0.0
        for mo in self.motions:
            if not (mo.birth <= t <= mo.death):
                continue
            if mo.body_pid:
                work += self._body(mo, st, t, dt_v, dt, place)
                continue
            ct, cy = mo.curve
            work += prescribe_nodes(
                st.v,
                st.f,
                st.x,
                self.x0,
                st.mass,
                st.inv_mass,
                mo.nodes,
                mo.direction,
                int(mo.vad),
                ct,
                cy,
                float(mo.scale),
                float(t),
                float(dt_v),
                float(dt),
            )
        return work

    def _body(self, mo, st, t, dt_v, dt, place) -> float:
        """A rigid part's CoG velocity along the direction is set (the force
        along it is taken by the prescription)."""
        b = self.bodies[mo.body_pid]
        vn = float(b.velocity @ mo.direction)
        force = float(st.f[b.nodes].sum(axis=0) @ mo.direction)
        vn_old = vn - dt_v * force / b.mass
        if mo.vad == 0:
            target = mo.scale * np.interp(t + 0.5 * dt, *mo.curve)
        elif mo.vad == 1:
            target = vn_old + dt_v * mo.scale * np.interp(t, *mo.curve)
        else:
            u = float((b.cog - self.cog0[b.body_id]) @ mo.direction)
            target = (mo.scale * np.interp(t + dt, *mo.curve) - u) / dt
        b.velocity += (target - vn) * mo.direction
        place(b)
        impulse = b.mass * (target - vn_old) - dt_v * force
        return float(impulse * 0.5 * (vn_old + target))
