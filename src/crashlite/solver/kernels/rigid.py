"""Node loops of nodal rigid bodies: placing the member nodes from the
body's motion, summing the nodal forces on the body, and how close its
nodes are to a plane. NumPy on the few thousand nodes of an engine body
costs tens of µs a call in temporaries and fancy indexing, several calls a
cycle; these loops cost a few.

Arrays: x, v (n, 3) node coordinates [length] and velocities
[length/time]; nodes (k,) int64 member indices; r_body (k, 3) member
positions about the CoG in the body frame [length]; rot (3, 3)
body-to-world rotation; rot_n (n, 3, 3) and w_n (n, 3) nodal
orientations and angular velocities [1/time] (nodes with rotations).
"""

import math

from numba import njit


@njit(cache=True)
def place_nodes(x, v, nodes, r_body, cog, rot, vel, omega):
    """x = cog + R r, v = vel + ω × (R r) of every member node."""
    for k in range(nodes.shape[0]):
        i = nodes[k]
        r0, r1, r2 = r_body[k, 0], r_body[k, 1], r_body[k, 2]
        a0 = rot[0, 0] * r0 + rot[0, 1] * r1 + rot[0, 2] * r2
        a1 = rot[1, 0] * r0 + rot[1, 1] * r1 + rot[1, 2] * r2
        a2 = rot[2, 0] * r0 + rot[2, 1] * r1 + rot[2, 2] * r2
        x[i, 0], x[i, 1], x[i, 2] = cog[0] + a0, cog[1] + a1, cog[2] + a2
        v[i, 0] = vel[0] + omega[1] * a2 - omega[2] * a1
        v[i, 1] = vel[1] + omega[2] * a0 - omega[0] * a2
        v[i, 2] = vel[2] + omega[0] * a1 - omega[1] * a0


@njit(cache=True)
def place_rotations(rot_n, w_n, nodes, rot, omega):
    """Member nodes with rotations take the body's orientation and ω."""
    for k in range(nodes.shape[0]):
        i = nodes[k]
        for a in range(3):
            w_n[i, a] = omega[a]
            for b in range(3):
                rot_n[i, a, b] = rot[a, b]


@njit(cache=True)
def force_sums(f, x, moment, nodes, cog, use_moment, out):
    """out[:3] = Σ f, out[3:] = Σ (x − cog) × f (+ Σ nodal moments if
    ``use_moment``) over the member nodes [force, force·length]."""
    for j in range(6):
        out[j] = 0.0
    for k in range(nodes.shape[0]):
        i = nodes[k]
        f0, f1, f2 = f[i, 0], f[i, 1], f[i, 2]
        a0, a1, a2 = x[i, 0] - cog[0], x[i, 1] - cog[1], x[i, 2] - cog[2]
        out[0] += f0
        out[1] += f1
        out[2] += f2
        out[3] += a1 * f2 - a2 * f1
        out[4] += a2 * f0 - a0 * f2
        out[5] += a0 * f1 - a1 * f0
        if use_moment:
            out[3] += moment[i, 0]
            out[4] += moment[i, 1]
            out[5] += moment[i, 2]


@njit(cache=True)
def plane_reach(x, nodes, cog, point, normal):
    """(smallest signed distance of the nodes to the plane through
    ``point`` along ``normal``, largest distance of a node to the CoG)."""
    gap = math.inf
    arm2 = 0.0
    for k in range(nodes.shape[0]):
        i = nodes[k]
        g = ((x[i, 0] - point[0]) * normal[0] + (x[i, 1] - point[1]) * normal[1]
             + (x[i, 2] - point[2]) * normal[2])
        gap = min(gap, g)
        a0, a1, a2 = x[i, 0] - cog[0], x[i, 1] - cog[1], x[i, 2] - cog[2]
        arm2 = max(arm2, a0 * a0 + a1 * a1 + a2 * a2)
    return gap, math.sqrt(arm2)
