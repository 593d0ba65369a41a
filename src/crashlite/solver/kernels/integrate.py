"""Central-difference (leapfrog) update with lumped masses."""

from numba import njit, prange


@njit(cache=True, parallel=True)
def update_velocity(v, f, inv_mass, fixed, dt_v):
    """v += dt_v · f/m on free DOFs; fixed DOFs keep v = 0.

    dt_v is the time between the two velocity half steps.
    """
    for i in prange(v.shape[0]):
        for j in range(3):
            if fixed[i, j]:
                v[i, j] = 0.0
            else:
                v[i, j] += dt_v * f[i, j] * inv_mass[i]


@njit(cache=True, parallel=True)
def update_position(x, v, dt):
    for i in prange(x.shape[0]):
        for j in range(3):
            x[i, j] += dt * v[i, j]


@njit(cache=True, parallel=True)
def copy_rows(src, dst):
    """dst[:] = src for (n, 3) arrays, in parallel (a nodal array copied
    every cycle: a serial copy was a visible share of the loop)."""
    for i in prange(src.shape[0]):
        dst[i, 0] = src[i, 0]
        dst[i, 1] = src[i, 1]
        dst[i, 2] = src[i, 2]
