"""Prescribed motions (*BOUNDARY_PRESCRIBED_MOTION) applied to the
half-step velocities: on nodes, node sets and rigid parts."""

from __future__ import annotations

import numpy as np


class Motions:
    def __init__(self, motions, bodies, x0: np.ndarray):
        self.motions = motions
        self.x0 = x0
        self.bodies = {b.body_id: b for b in bodies}
        self.cog0 = {b.body_id: b.cog.copy() for b in bodies}

    def apply(self, st, t: float, dt_v: float, dt: float, place) -> float:
        """Prescribed velocities for the half step t .. t + dt (dt_v: time
        since the previous half step); returns the kinetic energy they put
        in (the work of the prescribed motion)."""
        work = 0.0
        for mo in self.motions:
            if not (mo.birth <= t <= mo.death):
                continue
            if mo.body_pid:
                work += self._body(mo, st, t, dt_v, dt, place)
                continue
            v = st.v
            vn = v[mo.nodes] @ mo.direction
            if mo.vad == 0:
                target = mo.scale * np.interp(t + 0.5 * dt, *mo.curve)
            elif mo.vad == 1:
                # replace the acceleration of the forces by the prescribed one
                vn_before = vn - dt_v * (st.f[mo.nodes] @ mo.direction) * st.inv_mass[mo.nodes]
                target = vn_before + dt_v * mo.scale * np.interp(t, *mo.curve)
            else:
                u = (st.x[mo.nodes] - self.x0[mo.nodes]) @ mo.direction
                target = (mo.scale * np.interp(t + dt, *mo.curve) - u) / dt
            m = st.mass[mo.nodes]
            before = 0.5 * float(np.sum(m * np.einsum("ij,ij->i", v[mo.nodes], v[mo.nodes])))
            v[mo.nodes] += np.outer(target - vn, mo.direction)
            after = 0.5 * float(np.sum(m * np.einsum("ij,ij->i", v[mo.nodes], v[mo.nodes])))
            work += after - before
        return work

    def _body(self, mo, st, t, dt_v, dt, place) -> float:
        """A rigid part's CoG velocity along the direction is set (the force
        along it is taken by the prescription)."""
        b = self.bodies[mo.body_pid]
        vn = float(b.velocity @ mo.direction)
        if mo.vad == 0:
            target = mo.scale * np.interp(t + 0.5 * dt, *mo.curve)
        elif mo.vad == 1:
            force = float(st.f[b.nodes].sum(axis=0) @ mo.direction)
            target = vn - dt_v * force / b.mass + dt_v * mo.scale * np.interp(t, *mo.curve)
        else:
            u = float((b.cog - self.cog0[b.body_id]) @ mo.direction)
            target = (mo.scale * np.interp(t + dt, *mo.curve) - u) / dt
        before = 0.5 * b.mass * float(b.velocity @ b.velocity)
        b.velocity += (target - vn) * mo.direction
        place(b)
        return 0.5 * b.mass * float(b.velocity @ b.velocity) - before
