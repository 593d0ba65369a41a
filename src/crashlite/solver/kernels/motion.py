"""Prescribed nodal motion on the half-step velocities (solver/motions.py
states the rule and its work); one kernel per motion so that a small model
driven by a prescribed face does not pay NumPy's call overhead per cycle."""

import numpy as np
from numba import njit


@njit(cache=True)
def prescribe_nodes(v, f, x, x0, mass, inv_mass, nodes, direction, vad, ct, cy, scale, t, dt_v, dt):
    """Set the velocity of ``nodes`` along ``direction`` for the half step
    t .. t + dt (VAD 0 velocity, 1 acceleration, 2 displacement from the
    curve (ct, cy) times ``scale``); returns the reaction's work over dt_v."""
    if vad == 0:
        value = scale * np.interp(t + 0.5 * dt, ct, cy)
    elif vad == 1:
        value = dt_v * scale * np.interp(t, ct, cy)
    else:
        value = scale * np.interp(t + dt, ct, cy)
    work = 0.0
    for k in range(nodes.shape[0]):
        i = nodes[k]
        vn = v[i, 0] * direction[0] + v[i, 1] * direction[1] + v[i, 2] * direction[2]
        fn = f[i, 0] * direction[0] + f[i, 1] * direction[1] + f[i, 2] * direction[2]
        vn_old = vn - dt_v * fn * inv_mass[i]  # before the kick of the forces
        if vad == 0:
            target = value
        elif vad == 1:
            target = vn_old + value  # the prescribed acceleration replaces the forces'
        else:
            u = (
                (x[i, 0] - x0[i, 0]) * direction[0]
                + (x[i, 1] - x0[i, 1]) * direction[1]
                + (x[i, 2] - x0[i, 2]) * direction[2]
            )
            target = (value - u) / dt
        for j in range(3):
            v[i, j] += (target - vn) * direction[j]
        impulse = mass[i] * (target - vn_old) - dt_v * fn
        work += impulse * 0.5 * (vn_old + target)
    return work
