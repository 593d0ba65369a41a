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
def body_kick(f, x, moment, nodes, cog, use_moment, mass, dt_v, vel, mom, prev_vel, prev_mom, sums):
    """The kick of a body in one call: prev_* = the momenta before it,
    sums = the force and moment sums (``force_sums``), vel += dt_v Σf / mass,
    mom += dt_v Σ(moment)."""
    force_sums(f, x, moment, nodes, cog, use_moment, sums)
    for a in range(3):
        prev_vel[a] = vel[a]
        prev_mom[a] = mom[a]
        vel[a] += dt_v * sums[a] / mass
        mom[a] += dt_v * sums[3 + a]


@njit(cache=True)
def place_body(x, v, rot_n, w_n, nodes, r_body, cog, rot, vel, inv_i, mom, with_rotations, omega):
    """``place_nodes`` (and ``place_rotations`` if ``with_rotations``) with
    ω = R I⁻¹ Rᵀ L formed here (into ``omega`` (3,)): one call a placement."""
    body_omega(rot, inv_i, mom, omega)
    place_nodes(x, v, nodes, r_body, cog, rot, vel, omega)
    if with_rotations:
        place_rotations(rot_n, w_n, nodes, rot, omega)


@njit(cache=True)
def out_of_reach(x, nodes, cog, point, normal, velocity, momentum, spin_per_momentum, wall_speed, dt):
    """True when no node of a rigid body can land on the plane through
    ``point`` along ``normal`` over the next step: its smallest distance to
    the plane exceeds twice the largest speed a node can have, |v| + |ω|·r
    (|ω| ≤ ``spin_per_momentum``·|L|, r the largest distance of a node from
    the CoG) + |the wall's speed|, times ``dt``."""
    gap = math.inf
    arm2 = 0.0
    for k in range(nodes.shape[0]):
        i = nodes[k]
        g = (x[i, 0] - point[0]) * normal[0] + (x[i, 1] - point[1]) * normal[1] + (x[i, 2] - point[2]) * normal[2]
        gap = min(gap, g)
        a0, a1, a2 = x[i, 0] - cog[0], x[i, 1] - cog[1], x[i, 2] - cog[2]
        arm2 = max(arm2, a0 * a0 + a1 * a1 + a2 * a2)
    v = math.sqrt(velocity[0] ** 2 + velocity[1] ** 2 + velocity[2] ** 2)
    spin = spin_per_momentum * math.sqrt(momentum[0] ** 2 + momentum[1] ** 2 + momentum[2] ** 2)
    return gap > 2.0 * (v + spin * math.sqrt(arm2) + abs(wall_speed)) * dt


@njit(cache=True)
def body_omega(rot, inv_i, mom, out):
    """out = R I⁻¹ Rᵀ L: the angular velocity [1/time] of a body turned by
    ``rot`` (3, 3) with inverse body-frame inertia ``inv_i`` (3, 3) and
    world angular momentum ``mom`` (3,)."""
    a0 = rot[0, 0] * mom[0] + rot[1, 0] * mom[1] + rot[2, 0] * mom[2]  # Rᵀ L
    a1 = rot[0, 1] * mom[0] + rot[1, 1] * mom[1] + rot[2, 1] * mom[2]
    a2 = rot[0, 2] * mom[0] + rot[1, 2] * mom[1] + rot[2, 2] * mom[2]
    b0 = inv_i[0, 0] * a0 + inv_i[0, 1] * a1 + inv_i[0, 2] * a2
    b1 = inv_i[1, 0] * a0 + inv_i[1, 1] * a1 + inv_i[1, 2] * a2
    b2 = inv_i[2, 0] * a0 + inv_i[2, 1] * a1 + inv_i[2, 2] * a2
    for i in range(3):
        out[i] = rot[i, 0] * b0 + rot[i, 1] * b1 + rot[i, 2] * b2


@njit(cache=True, inline="always")
def rotation_entries(p0, p1, p2):
    """The nine entries (row by row) of the rotation matrix of the rotation
    vector (p0, p1, p2): I + sin·K + (1 − cos)·K², K the cross-product
    matrix of the unit axis, 1 − cos as 2 sin²(½θ) (no cancellation at small
    angles). Scalars only: kernels apply it without temporary arrays."""
    angle = math.sqrt(p0 * p0 + p1 * p1 + p2 * p2)
    if angle < 1e-300:
        return 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0
    k0, k1, k2 = p0 / angle, p1 / angle, p2 / angle
    s = math.sin(angle)
    sh = math.sin(0.5 * angle)
    c = 2.0 * sh * sh
    return (
        1.0 - c * (k1 * k1 + k2 * k2),
        -s * k2 + c * k0 * k1,
        s * k1 + c * k0 * k2,
        s * k2 + c * k0 * k1,
        1.0 - c * (k0 * k0 + k2 * k2),
        -s * k0 + c * k1 * k2,
        -s * k1 + c * k0 * k2,
        s * k0 + c * k1 * k2,
        1.0 - c * (k0 * k0 + k1 * k1),
    )


@njit(cache=True)
def rodrigues(p0, p1, p2, out):
    """out (3, 3) = the rotation matrix of the rotation vector (p0, p1, p2)."""
    r = rotation_entries(p0, p1, p2)
    for i in range(3):
        for j in range(3):
            out[i, j] = r[3 * i + j]


@njit(cache=True)
def _turn(a, rot, out):
    """out = a @ rot (3 x 3)."""
    for i in range(3):
        for j in range(3):
            out[i, j] = a[i, 0] * rot[0, j] + a[i, 1] * rot[1, j] + a[i, 2] * rot[2, j]


@njit(cache=True)
def body_drift(cog, vel, mom, rot, inv_i, dt, scratch):
    """Move and turn a body over dt in place: cog += dt·v, and rot turned by
    dt·ω with ω taken at mid-rotation (two fixed-point passes), so a
    torque-free body keeps its energy to second order. scratch (3, 3, 3)."""
    for i in range(3):
        cog[i] += dt * vel[i]
    w = scratch[0, 0]
    body_omega(rot, inv_i, mom, w)
    half, turned = scratch[1], scratch[2]
    for _ in range(2):  # ω at mid-rotation
        rodrigues(0.5 * dt * w[0], 0.5 * dt * w[1], 0.5 * dt * w[2], half)
        _turn(half, rot, turned)
        body_omega(turned, inv_i, mom, w)
    rodrigues(dt * w[0], dt * w[1], dt * w[2], half)
    _turn(half, rot, turned)
    for i in range(3):
        for j in range(3):
            rot[i, j] = turned[i, j]
