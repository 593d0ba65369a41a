"""Central-difference (leapfrog) update with lumped masses."""

from numba import njit, prange


@njit(cache=True, parallel=True)
def kick_nodes(v, f, inv_mass, fixed, dt_v, before, w, moment, inv_j, fixed_rot):
    """v += dt_v · f/m on free DOFs (fixed DOFs keep v = 0), and for nodes
    with rotational inertia ω += dt_v · M/J (isotropic: no gyroscopic term)
    on free rotational DOFs; dt_v is the time between the two velocity half
    steps. ``before`` takes v first (the walls' energy reads it) unless it
    has no rows, and ``w`` has none where no node turns. One pass: each
    launch costs more than the arithmetic on a few thousand nodes."""
    keep = before.shape[0] > 0
    turns = w.shape[0] > 0
    for i in prange(v.shape[0]):
        for j in range(3):
            if keep:
                before[i, j] = v[i, j]
            if fixed[i, j]:
                v[i, j] = 0.0
            else:
                v[i, j] += dt_v * f[i, j] * inv_mass[i]
        if turns and inv_j[i] != 0.0:
            for j in range(3):
                if fixed_rot[i, j]:
                    w[i, j] = 0.0
                else:
                    w[i, j] += dt_v * moment[i, j] * inv_j[i]


@njit(cache=True, parallel=True)
def update_position(x, v, dt, f, moment):
    """x += dt · v, and the nodal forces and moments zeroed for the force
    pass that follows: one pass over the nodes instead of three."""
    for i in prange(x.shape[0]):
        for j in range(3):
            x[i, j] += dt * v[i, j]
            f[i, j] = 0.0
            moment[i, j] = 0.0
