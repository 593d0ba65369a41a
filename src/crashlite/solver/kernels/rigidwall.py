"""Stationary planar rigid walls, imposed kinematically as LS-DYNA does:
a node that would pass the wall in this step has its normal velocity changed
so that it lands on the wall; the wall force is the momentum change / dt."""

from numba import njit


@njit(cache=True)
def planar_wall(x, v, mass, nodes, point, normal, dt, force):
    """Correct v of ``nodes`` against the wall through ``point`` with unit
    ``normal`` (pointing to the allowed side). Adds the force the nodes exert
    on the wall to ``force`` (3,); returns the number of nodes in contact."""
    n_contact = 0
    for k in range(nodes.shape[0]):
        i = nodes[k]
        d = 0.0
        for j in range(3):
            d += (x[i, j] + dt * v[i, j] - point[j]) * normal[j]
        if d < 0.0:
            dv = -d / dt  # normal velocity increment that puts the node on the wall
            for j in range(3):
                v[i, j] += dv * normal[j]
                force[j] -= mass[i] * dv / dt * normal[j]
            n_contact += 1
    return n_contact
