"""Discrete springs and dampers (*ELEMENT_DISCRETE with *MAT_S01/S02/S04).

Forces are computed per element into ``fe`` (n_elem, 3) in parallel, then
each node sums its elements' terms in a fixed order (``gather``): the result
does not depend on the number of threads.
"""

import numpy as np
from numba import njit, prange

LINEAR, DAMPER, CURVE, INELASTIC, GENERAL = 0, 1, 2, 3, 4


@njit(cache=True, inline="always")
def curve_value(xs, ys, start, stop, x):
    """Piecewise-linear curve points [start, stop), extrapolated linearly."""
    n = stop - start
    if n == 1:
        return ys[start]
    if x <= xs[start]:
        i = start
    elif x >= xs[stop - 1]:
        i = stop - 2
    else:
        lo, hi = start, stop - 1
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if xs[mid] <= x:
                lo = mid
            else:
                hi = mid
        i = lo
    dx = xs[i + 1] - xs[i]
    t = (x - xs[i]) / dx if dx != 0.0 else 0.0
    return ys[i] + t * (ys[i + 1] - ys[i])


@njit(cache=True, inline="always")
def curve_inverse(xs, ys, start, stop, y):
    """x where a rising piecewise-linear curve reaches y (linear beyond its ends)."""
    if stop - start == 1:
        return xs[start]
    i = start
    while i < stop - 2 and ys[i + 1] < y:
        i += 1
    dy = ys[i + 1] - ys[i]
    t = (y - ys[i]) / dy if dy != 0.0 else 0.0
    return xs[i] + t * (xs[i + 1] - xs[i])


@njit(cache=True, inline="always")
def _general(xs, ys, ls, le, us, ue, yt, yc, delta, h):
    """*MAT_S06 force: along the loading curve; once loaded past the yield
    force of a side (TYI > 0, CYI < 0), unloading and reloading on that side
    follow the unloading curve shifted through the point of the largest
    deflection (tension and compression independent, BETA = 0). h (4,):
    largest tensile deflection, its shift, largest compressive deflection,
    its shift."""
    f = curve_value(xs, ys, ls, le, delta)
    if ue <= us:  # no unloading curve: nonlinear elastic
        return f
    if h[0] > 0.0 and delta < h[0]:
        fu = curve_value(xs, ys, us, ue, delta - h[1])
        if fu < f:
            f = fu
    elif delta > 0.0 and f >= yt:
        h[0] = delta
        h[1] = delta - curve_inverse(xs, ys, us, ue, f)
    if h[2] < 0.0 and delta > h[2]:
        fu = curve_value(xs, ys, us, ue, delta - h[3])
        if fu > f:
            f = fu
    elif delta < 0.0 and f <= yc:
        h[2] = delta
        h[3] = delta - curve_inverse(xs, ys, us, ue, f)
    return f


@njit(cache=True, parallel=True)
def discrete_forces(
    x,
    v,
    n1,
    n2,
    kind,
    k,
    scale,
    offset,
    length0,
    direction,
    curve_start,
    curve_stop,
    curve_x,
    curve_y,
    ground,
    ctf,
    ucurve_start,
    ucurve_stop,
    yield_t,
    yield_c,
    plastic,
    hist,
    fe,
    force,
    elong,
):
    """Axial force of each element (tension positive) and its force vector on n1.

    x, v (n_nodes, 3); n1, n2 (n,) node indices (n2 = -1: tied to ground at
    ``ground``); kind LINEAR (force = k·δ), DAMPER (force = k·δ̇) or CURVE
    (force = curve(δ)) or INELASTIC (*MAT_S08: force = k (δ - δp) bounded by
    the curve, δp the plastic deflection kept in ``plastic``; ``ctf`` 1 keeps
    compression only, -1 tension only); scale S; offset; length0 initial
    length; direction (n, 3): unit vector, or zeros to follow the element
    axis. GENERAL (*MAT_S06, see ``_general``): loading curve as CURVE,
    unloading curve [ucurve_start, ucurve_stop), yield forces yield_t > 0,
    yield_c < 0, history ``hist`` (n, 4). Outputs: fe (n, 3) force on n1
    (n2 gets -fe), force (n,), elong δ.
    """
    for e in prange(n1.shape[0]):
        a = n1[e]
        b = n2[e]
        d0 = (ground[e, 0] - x[a, 0]) if b < 0 else (x[b, 0] - x[a, 0])
        d1 = (ground[e, 1] - x[a, 1]) if b < 0 else (x[b, 1] - x[a, 1])
        d2 = (ground[e, 2] - x[a, 2]) if b < 0 else (x[b, 2] - x[a, 2])
        r0 = -v[a, 0] if b < 0 else v[b, 0] - v[a, 0]
        r1 = -v[a, 1] if b < 0 else v[b, 1] - v[a, 1]
        r2 = -v[a, 2] if b < 0 else v[b, 2] - v[a, 2]
        fixed_dir = direction[e, 0] != 0.0 or direction[e, 1] != 0.0 or direction[e, 2] != 0.0
        if fixed_dir:
            u0, u1, u2 = direction[e, 0], direction[e, 1], direction[e, 2]
            delta = d0 * u0 + d1 * u1 + d2 * u2 - length0[e]
        else:
            length = np.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
            if length > 0.0:
                u0, u1, u2 = d0 / length, d1 / length, d2 / length
            else:
                u0, u1, u2 = 0.0, 0.0, 0.0
            delta = length - length0[e]
        delta += offset[e]
        rate = r0 * u0 + r1 * u1 + r2 * u2
        if kind[e] == LINEAR:
            f = k[e] * delta
        elif kind[e] == DAMPER:
            f = k[e] * rate
        elif kind[e] == CURVE:
            f = curve_value(curve_x, curve_y, curve_start[e], curve_stop[e], delta)
        elif kind[e] == GENERAL:
            f = _general(
                curve_x,
                curve_y,
                curve_start[e],
                curve_stop[e],
                ucurve_start[e],
                ucurve_stop[e],
                yield_t[e],
                yield_c[e],
                delta,
                hist[e],
            )
        else:
            f = k[e] * (delta - plastic[e])
            env = curve_value(curve_x, curve_y, curve_start[e], curve_stop[e], delta)
            if (delta >= 0.0 and f > env > 0.0) or (delta < 0.0 and f < env < 0.0):
                f = env  # on the envelope: the deflection beyond it is permanent
                plastic[e] = delta - f / k[e]
            if (ctf[e] == 1 and f > 0.0) or (ctf[e] == -1 and f < 0.0):
                f = 0.0  # the spring does not carry this sign: a gap opens
        f *= scale[e]
        force[e] = f
        elong[e] = delta
        fe[e, 0] = f * u0
        fe[e, 1] = f * u1
        fe[e, 2] = f * u2


@njit(cache=True)
def gather(rows, row_ptr, elem_of, sign_of, fe, out):
    """out[rows[r]] += Σ sign · fe[e] over the elements of row r's node, in
    a fixed order.

    The node-to-element incidence (CSR over the nodes that have elements:
    rows, row_ptr, elem_of, sign_of) is built once. Serial: a few adds per
    node of an element, cheaper than starting the threads (which cost more
    than the sums on the hundreds of nodes of a model's springs and
    dampers); a loop over every node of the model was most of the cost.
    """
    for r in range(rows.shape[0]):
        a0 = 0.0
        a1 = 0.0
        a2 = 0.0
        for k in range(row_ptr[r], row_ptr[r + 1]):
            e = elem_of[k]
            s = sign_of[k]
            a0 += s * fe[e, 0]
            a1 += s * fe[e, 1]
            a2 += s * fe[e, 2]
        i = rows[r]
        out[i, 0] += a0
        out[i, 1] += a1
        out[i, 2] += a2


@njit(cache=True)
def energy_step(force_old, force, elong_old, elong, elem_energy):
    """Work of the element forces over the last step (trapezoid), added per
    element to ``elem_energy`` (totals are summed at output, in a fixed
    order); the new values become the old ones. Serial: three numbers an
    element, less than starting the threads costs."""
    for e in range(force.shape[0]):
        elem_energy[e] += 0.5 * (force_old[e] + force[e]) * (elong[e] - elong_old[e])
        force_old[e] = force[e]
        elong_old[e] = elong[e]


def incidence(n1: np.ndarray, n2: np.ndarray):
    """CSR over the nodes that have elements -> (element, sign): (rows,
    row_ptr, elem_of, sign_of), sign +1 where the node is n1, -1 where n2."""
    ne = len(n1)
    nodes = np.concatenate([n1, n2])
    elems = np.concatenate([np.arange(ne), np.arange(ne)])
    signs = np.concatenate([np.ones(ne), -np.ones(ne)])
    keep = nodes >= 0
    nodes, elems, signs = nodes[keep], elems[keep], signs[keep]
    order = np.lexsort((elems, nodes))
    rows, counts = np.unique(nodes, return_counts=True)
    ptr = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    return rows.astype(np.int64), ptr, elems[order].astype(np.int64), signs[order]
