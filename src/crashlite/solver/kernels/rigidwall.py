"""Planar rigid walls, imposed kinematically as LS-DYNA does: a node that
would pass the wall in this step has its normal velocity changed so that it
lands on the wall; the wall force is the momentum change / dt.

A node further behind the plane than it or the wall can travel in one step
is not in contact (it is beside a finite wall, not struck by it).

A moving wall (*RIGIDWALL_PLANAR_MOVING) has a mass and a velocity along its
normal; the nodes it hits and the wall leave with the velocity that conserves
their momentum (perfectly plastic impact), as a rigid impactor does.
"""

import numpy as np
from numba import njit, prange


@njit(cache=True, inline="always")
def _contact_velocity(v, v_before, i, n0, n1, n2, vn, vn_new, fric, m, dt, force, wall_mid):
    """Set node i's normal velocity to vn_new; friction takes up to fric
    times the normal velocity change from the tangential velocity (fric ≥ 1:
    no sliding). The momentum change goes into the wall ``force`` (3,).

    force[3] gathers the energy the wall takes over the step: the node's
    impulse J does the work J·(v_before + v_after)/2 on it (v_before: its
    velocity before this step's velocity update), the wall's reaction
    -J·wall_mid (the wall's mean normal speed over the step): a node resting
    on a wall that a spring pushes into it costs nothing, a node struck by a
    wall loses what a plastic impact loses."""
    vt0, vt1, vt2 = v[i, 0] - vn * n0, v[i, 1] - vn * n1, v[i, 2] - vn * n2
    vt = np.sqrt(vt0 * vt0 + vt1 * vt1 + vt2 * vt2)
    keep = 1.0
    if fric >= 1.0:
        keep = 0.0
    elif fric > 0.0 and vt > 0.0:
        keep = max(0.0, 1.0 - fric * abs(vn_new - vn) / vt)
    old0, old1, old2 = v[i, 0], v[i, 1], v[i, 2]
    v[i, 0] = vn_new * n0 + keep * vt0
    v[i, 1] = vn_new * n1 + keep * vt1
    v[i, 2] = vn_new * n2 + keep * vt2
    j0, j1, j2 = m * (v[i, 0] - old0), m * (v[i, 1] - old1), m * (v[i, 2] - old2)
    force[0] -= j0 / dt
    force[1] -= j1 / dt
    force[2] -= j2 / dt
    force[3] += (
        j0 * (wall_mid * n0 - 0.5 * (v_before[i, 0] + v[i, 0]))
        + j1 * (wall_mid * n1 - 0.5 * (v_before[i, 1] + v[i, 1]))
        + j2 * (wall_mid * n2 - 0.5 * (v_before[i, 2] + v[i, 2]))
    )


N_CHUNKS = 64  # fixed node chunks of the hit test: sums in the same order on any number of threads


@njit(cache=True, parallel=True)
def _planar_hits(x, v, mass, nodes, point, normal, wall_v, dt, hit, edge_l, edge_m, len_l, len_m, part):
    """hit[k]: node k meets the plane this step (planar_wall); part (N_CHUNKS,
    2) the momentum the hit nodes of each chunk bring and their mass."""
    nk = nodes.shape[0]
    nc = part.shape[0]
    for ch in prange(nc):
        p_moved = 0.0
        m_hit = 0.0
        for k in range(ch * nk // nc, (ch + 1) * nk // nc):
            i = nodes[k]
            d = 0.0
            vn = 0.0
            gap = 0.0
            for j in range(3):
                d += (x[i, j] + dt * v[i, j] - point[j] - dt * wall_v * normal[j]) * normal[j]
                vn += v[i, j] * normal[j]
                gap += (x[i, j] - point[j]) * normal[j]
            # a node already further behind the plane than one step of relative motion never met the wall: it
            # came round a finite wall's edge (e.g. barrier cells beside an offset impactor), it is not struck
            hit[k] = d < 0.0 and gap >= -dt * (abs(wall_v) + abs(vn)) * 1.01
            if hit[k] and len_l > 0.0:  # finite wall: only nodes over the rectangle
                pl = 0.0
                pm = 0.0
                for j in range(3):
                    pl += (x[i, j] - point[j]) * edge_l[j]
                    pm += (x[i, j] - point[j]) * edge_m[j]
                hit[k] = 0.0 <= pl <= len_l and 0.0 <= pm <= len_m
            if hit[k]:
                # momentum the node brings, counting the approach it makes this step
                p_moved += mass[i] * (vn + gap / dt)
                m_hit += mass[i]
        part[ch, 0] = p_moved
        part[ch, 1] = m_hit


@njit(cache=True)
def planar_wall(
    x,
    v,
    v_before,
    mass,
    nodes,
    point,
    normal,
    wall_v,
    wall_mass,
    fric,
    dt,
    force,
    hit,
    edge_l,
    edge_m,
    len_l,
    len_m,
    part,
):
    """Correct v of ``nodes`` against the plane through ``point`` (moving at
    ``wall_v`` along the unit ``normal``, which points to the allowed side).

    wall_mass 0: the wall does not move. fric: 0 frictionless, 1 no sliding,
    between: Coulomb coefficient on the normal impulse. Adds the force of the
    nodes on the wall to ``force`` (3,) and the energy it takes to force[3]
    (``_contact_velocity``); ``hit`` (len(nodes),) bool and ``part``
    (N_CHUNKS, 2) are scratch.
    A finite wall (len_l > 0) is the rectangle [0, len_l] x [0, len_m] along
    the unit edges ``edge_l``, ``edge_m`` from ``point`` (its corner).
    Returns the wall's new normal velocity.
    """
    nk = nodes.shape[0]
    _planar_hits(x, v, mass, nodes, point, normal, wall_v, dt, hit, edge_l, edge_m, len_l, len_m, part)
    p_moved = 0.0
    m_hit = 0.0
    for ch in range(part.shape[0]):
        p_moved += part[ch, 0]
        m_hit += part[ch, 1]
    if m_hit == 0.0:
        return wall_v
    v_new = wall_v
    if wall_mass > 0.0:  # common normal velocity of the wall and the nodes it hits
        v_new = (wall_mass * wall_v + p_moved) / (wall_mass + m_hit)
    for k in range(nk):
        if not hit[k]:
            continue
        i = nodes[k]
        gap = 0.0
        vn = 0.0
        for j in range(3):
            gap += (x[i, j] - point[j]) * normal[j]
            vn += v[i, j] * normal[j]
        target = v_new - gap / dt  # lands on the wall at the end of the step
        _contact_velocity(
            v,
            v_before,
            i,
            normal[0],
            normal[1],
            normal[2],
            vn,
            target,
            fric,
            mass[i],
            dt,
            force,
            0.5 * (wall_v + v_new),
        )
    return v_new


@njit(cache=True)
def cylinder_wall(x, v, v_before, mass, nodes, tail, axis, radius, length, fric, dt, force):
    """Keep nodes outside a stationary cylinder (axis from ``tail`` along the
    unit ``axis``, ``length`` 0: infinite): a node that would enter it this
    step gets the radial velocity that puts it on the surface."""
    for k in range(nodes.shape[0]):
        i = nodes[k]
        p = np.empty(3)
        for j in range(3):
            p[j] = x[i, j] + dt * v[i, j] - tail[j]
        h = p[0] * axis[0] + p[1] * axis[1] + p[2] * axis[2]
        if length > 0.0 and (h < 0.0 or h > length):
            continue
        r = np.empty(3)
        for j in range(3):
            r[j] = p[j] - h * axis[j]
        dist = np.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2])
        if dist >= radius or dist == 0.0:
            continue
        n = r / dist  # outward normal at the predicted point
        vn = v[i, 0] * n[0] + v[i, 1] * n[1] + v[i, 2] * n[2]
        # the outward velocity increment that lands it on the surface
        _contact_velocity(
            v, v_before, i, n[0], n[1], n[2], vn, vn + (radius - dist) / dt, fric, mass[i], dt, force, 0.0
        )
