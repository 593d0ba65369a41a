"""Penalty node-to-segment contact: bucket-sort search, closest-point
projection, normal penalty with viscous damping, Coulomb friction.

Each slave entry (a node facing the segments of the other side, or of its
own surface in single-surface contact) keeps a conservative list of
candidate segments from the last bucket sort; every cycle it picks its
nearest penetrated segment and writes the forces of that pair as five rows
(the node and the four segment nodes, weights of the closest point), so the
parallel loop over slave entries never writes shared memory. ``scatter``
then adds the rows to the nodal forces serially in slave order: the sums do
not depend on the number of threads.

Segments are quadrilaterals or triangles (n3 = n4), split into the
triangles (n1 n2 n3) and (n1 n3 n4) for the closest point, which is
continuous across the diagonal; the weights of the closest point sum to one
and reproduce it, so forces and moments balance exactly. Shell segments are
two-sided: the contact direction is from the closest point to the node, and
the gap is the half thicknesses minus the distance (edges are rounded).
Solid faces are one-sided (outward normal): a node behind the face is in
contact up to ``depth`` (measured along the normal) when its closest point
is its normal projection; such a contact wins over one in front of a face,
and a node keeps the face it is behind while it stays there, so a node at
a corner is not handed to the side face it grazes. A node found in a
segment it was not on (behind a solid face, or within a shell's contact
thickness), deeper than its approach over the step and the penetration it
had on the segment it slides over from, came through the solid (a deleted
element, round an edge) or a fold of a shell closed over it: it takes no
contact there (pushed out, it would gain energy no contact ever stored;
LS-DYNA releases such nodes by its PENMAX depth). The set-up search for
initial penetrations (dt = 0) takes every penetration. Otherwise the
nearest penetrated segment is taken.

Arrays (ns slave entries, nm segments, nc candidates; model units):
  x, v (n_nodes, 3) float64 coordinates at t(n+1), velocities at t(n+½)
  snode (ns,) int64 node; sthick (ns,) contact thickness [length];
  sk (ns,) node penalty stiffness (inf: none) [force/length];
  smass (ns,) node mass [mass]
  seg (nm, 4) int64 nodes; mthick (nm,) thickness [length]; mk (nm,)
  penalty stiffness [force/length]; mmass (nm,) mean node mass [mass];
  onesided (nm,) int8 1: solid face; depth (nm,) deepest penetration
  accepted behind a solid face [length]; msize (nm,) √area [length];
  alive (nm,) int8 0: the segment's element is eroded; box (nm, 6) the
  segments' bounding boxes at x grown by their reach, ½ thickness plus, for
  a solid face, the depth and 1 % of its size (segment_boxes) [length]
  cptr (ns + 1,), cand (nc,) int64 CSR slave entry -> candidate segments
  prm (N_PRM,) float64 interface parameters (P_*)
  ft (ns, 3) friction force on the node, kept between cycles [force];
  prev (ns,) int64 segment of the last cycle (-1: none); side (ns,) int8
  the side of that shell segment the node is on (0: none)
  rows (ns, 5, 3) forces ON the node and the segment nodes [force];
  rnode (ns, 5) int64 their node indices (-1: none); gap (ns,) penetration,
  > 0 exactly for the entries that have rows (the others' rows are zero
  and their rnode -1, as allocated)
"""

import math

import numpy as np
from numba import njit, prange

# interface parameters
P_FS, P_FD, P_DC, P_VDC, P_FSF, P_SOFT_K, P_ACTIVE, N_PRM = 0, 1, 2, 3, 4, 5, 6, 7
_BEHIND, _OUTSIDE = 0, 1


@njit(cache=True, inline="always")
def _tri_weights(x, a, b, c, px, py, pz):
    """Barycentric weights of the point of triangle (a, b, c) closest to p
    (Ericson, Real-Time Collision Detection, 5.1.5)."""
    abx, aby, abz = x[b, 0] - x[a, 0], x[b, 1] - x[a, 1], x[b, 2] - x[a, 2]
    acx, acy, acz = x[c, 0] - x[a, 0], x[c, 1] - x[a, 1], x[c, 2] - x[a, 2]
    apx, apy, apz = px - x[a, 0], py - x[a, 1], pz - x[a, 2]
    d1 = abx * apx + aby * apy + abz * apz
    d2 = acx * apx + acy * apy + acz * apz
    if d1 <= 0.0 and d2 <= 0.0:
        return 1.0, 0.0, 0.0
    bpx, bpy, bpz = px - x[b, 0], py - x[b, 1], pz - x[b, 2]
    d3 = abx * bpx + aby * bpy + abz * bpz
    d4 = acx * bpx + acy * bpy + acz * bpz
    if d3 >= 0.0 and d4 <= d3:
        return 0.0, 1.0, 0.0
    vc = d1 * d4 - d3 * d2
    if vc <= 0.0 and d1 >= 0.0 and d3 <= 0.0:
        t = d1 / (d1 - d3)
        return 1.0 - t, t, 0.0
    cpx, cpy, cpz = px - x[c, 0], py - x[c, 1], pz - x[c, 2]
    d5 = abx * cpx + aby * cpy + abz * cpz
    d6 = acx * cpx + acy * cpy + acz * cpz
    if d6 >= 0.0 and d5 <= d6:
        return 0.0, 0.0, 1.0
    vb = d5 * d2 - d1 * d6
    if vb <= 0.0 and d2 >= 0.0 and d6 <= 0.0:
        t = d2 / (d2 - d6)
        return 1.0 - t, 0.0, t
    va = d3 * d6 - d5 * d4
    if va <= 0.0 and (d4 - d3) >= 0.0 and (d5 - d6) >= 0.0:
        t = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        return 0.0, 1.0 - t, t
    den = 1.0 / (va + vb + vc)
    v_ = vb * den
    w_ = vc * den
    return 1.0 - v_ - w_, v_, w_


@njit(cache=True, inline="always")
def _closest(x, seg, s, px, py, pz):
    """Weights (w1..w4) of the closest point of segment s to p."""
    n0, n1, n2, n3 = seg[s, 0], seg[s, 1], seg[s, 2], seg[s, 3]
    a0, a1, a2 = _tri_weights(x, n0, n1, n2, px, py, pz)
    if n2 == n3:
        return a0, a1, a2, 0.0
    b0, b2, b3 = _tri_weights(x, n0, n2, n3, px, py, pz)
    da = 0.0
    db = 0.0
    for k in range(3):
        qa = a0 * x[n0, k] + a1 * x[n1, k] + a2 * x[n2, k]
        qb = b0 * x[n0, k] + b2 * x[n2, k] + b3 * x[n3, k]
        p = px if k == 0 else (py if k == 1 else pz)
        da += (p - qa) ** 2
        db += (p - qb) ** 2
    if db < da:
        return b0, 0.0, b2, b3
    return a0, a1, a2, 0.0


@njit(cache=True, inline="always")
def _normal(x, seg, s):
    """Unit normal of segment s (d13 × d24 for quads, right-hand rule)."""
    n0, n1, n2, n3 = seg[s, 0], seg[s, 1], seg[s, 2], seg[s, 3]
    if n2 == n3:
        ux, uy, uz = x[n1, 0] - x[n0, 0], x[n1, 1] - x[n0, 1], x[n1, 2] - x[n0, 2]
        wx, wy, wz = x[n2, 0] - x[n0, 0], x[n2, 1] - x[n0, 1], x[n2, 2] - x[n0, 2]
    else:
        ux, uy, uz = x[n2, 0] - x[n0, 0], x[n2, 1] - x[n0, 1], x[n2, 2] - x[n0, 2]
        wx, wy, wz = x[n3, 0] - x[n1, 0], x[n3, 1] - x[n1, 1], x[n3, 2] - x[n1, 2]
    nx = uy * wz - uz * wy
    ny = uz * wx - ux * wz
    nz = ux * wy - uy * wx
    ln = math.sqrt(nx * nx + ny * ny + nz * nz)
    if ln > 0.0:
        return nx / ln, ny / ln, nz / ln
    return 0.0, 0.0, 0.0


@njit(cache=True, inline="always")
def _far(box, s, px, py, pz, reach):
    """True when p lies farther than ``reach`` outside the bounding box of
    segment s (box (nm, 6): low and high corner): no point of the segment
    is within ``reach`` of it."""
    return (
        px < box[s, 0] - reach
        or px > box[s, 3] + reach
        or py < box[s, 1] - reach
        or py > box[s, 4] + reach
        or pz < box[s, 2] - reach
        or pz > box[s, 5] + reach
    )


# --- search -------------------------------------------------------------------------------------


@njit(cache=True, parallel=True)
def segment_boxes(x, seg, grow, box):
    """Bounding boxes of the segments grown by ``grow`` (nm,) [length]: box
    (nm, 6) lower corner, upper corner (one cache line per segment: the
    search's test, and every cycle contact_forces' first test of each
    candidate, with the segment's reach)."""
    for s in prange(seg.shape[0]):
        for k in range(3):
            a = x[seg[s, 0], k]
            b = a
            for j in range(1, 4):
                c = x[seg[s, j], k]
                a = min(a, c)
                b = max(b, c)
            box[s, k] = a - grow[s]
            box[s, 3 + k] = b + grow[s]


@njit(cache=True)
def _grid(x, snode, box, h):
    """Origin and cell counts of a grid of cell size h over the boxes and
    the slave nodes, the number of (segment, cell) entries, and whether all
    of them are finite."""
    org = np.empty(3)
    top = np.empty(3)
    for k in range(3):
        org[k] = np.inf
        top[k] = -np.inf
    finite = True
    for s in range(box.shape[0]):
        for k in range(3):
            org[k] = min(org[k], box[s, k])
            top[k] = max(top[k], box[s, 3 + k])
            finite = finite and math.isfinite(box[s, k]) and math.isfinite(box[s, 3 + k])
    for i in range(snode.shape[0]):
        for k in range(3):
            org[k] = min(org[k], x[snode[i], k])
            top[k] = max(top[k], x[snode[i], k])
            finite = finite and math.isfinite(x[snode[i], k])
    # counted in floating point: a node flung far away must coarsen the grid, not overflow the keys
    ncell = np.empty(3)
    for k in range(3):
        ncell[k] = np.floor((top[k] - org[k]) / h) + 1.0
    total = 0.0
    for s in range(box.shape[0]):
        c = 1.0
        for k in range(3):
            c *= np.floor((box[s, 3 + k] - org[k]) / h) - np.floor((box[s, k] - org[k]) / h) + 1.0
        total += c
    return org, ncell, total, finite


_HASH = np.uint64(0x9E3779B97F4A7C15)  # Fibonacci hashing: 2^64 / golden ratio


@njit(cache=True, inline="always")
def _bucket(key, shift):
    """Bucket of a cell key: the top bits of key × _HASH (cells of a regular
    grid spread evenly over any power-of-two number of buckets)."""
    return np.int64((np.uint64(key) * _HASH) >> np.uint64(shift))


@njit(cache=True, inline="always")
def _cells(box, h, org, s):
    """Range of grid cells (a0, a1, b0, b1, c0, c1) of segment s's box."""
    return (
        int((box[s, 0] - org[0]) / h),
        int((box[s, 3] - org[0]) / h),
        int((box[s, 1] - org[1]) / h),
        int((box[s, 4] - org[1]) / h),
        int((box[s, 2] - org[2]) / h),
        int((box[s, 5] - org[2]) / h),
    )


@njit(cache=True)
def _register(box, h, org, ncell, total):
    """Every (segment, cell) entry, for each cell that a segment's box
    overlaps, grouped by bucket (a hash of the cell): bucket b's entries at
    start[b] .. start[b + 1] - 1 of keys (their cell) and owner (their
    segment), in segment order. A counting sort in two passes: cells of
    several buckets never need comparing (an argsort of the keys was 40 % of
    the search on a 100 k-shell model); distinct cells sharing a bucket are
    told apart by the key. Returns (start, keys, owner, shift)."""
    bits = 1
    while (1 << bits) < total:
        bits += 1
    shift = 64 - bits
    start = np.zeros((1 << bits) + 1, np.int64)
    for s in range(box.shape[0]):
        a0, a1, b0, b1, c0, c1 = _cells(box, h, org, s)
        for a in range(a0, a1 + 1):
            for b in range(b0, b1 + 1):
                for c in range(c0, c1 + 1):
                    start[_bucket((a * ncell[1] + b) * ncell[2] + c, shift) + 1] += 1
    for b in range(1 << bits):
        start[b + 1] += start[b]
    fill = start[:-1].copy()
    keys = np.empty(total, np.int64)
    owner = np.empty(total, np.int64)
    for s in range(box.shape[0]):
        a0, a1, b0, b1, c0, c1 = _cells(box, h, org, s)
        for a in range(a0, a1 + 1):
            for b in range(b0, b1 + 1):
                for c in range(c0, c1 + 1):
                    key = (a * ncell[1] + b) * ncell[2] + c
                    bk = _bucket(key, shift)
                    keys[fill[bk]] = key
                    owner[fill[bk]] = s
                    fill[bk] += 1
    return start, keys, owner, shift


@njit(cache=True, inline="always")
def _accepts(i, s, x, snode, sside, seg, mside, box):
    nd = snode[i]
    for k in range(3):  # first: most entries of a cell fail it
        if x[nd, k] < box[s, k] or x[nd, k] > box[s, 3 + k]:
            return False
    if sside[i] >= 0 and sside[i] == mside[s]:
        return False
    for j in range(4):
        if seg[s, j] == nd:
            return False
    return True


@njit(cache=True, inline="always")
def _scan(i, x, snode, sside, seg, mside, box, h, org, ncell, start, skeys, sowner, shift, out, at, cap):
    """The candidates of slave entry i: the segments registered in its
    cell whose grown box holds the node, in segment order; the first
    ``cap`` into out[at:]. Returns how many there are."""
    nd = snode[i]
    key = (int((x[nd, 0] - org[0]) / h) * ncell[1] + int((x[nd, 1] - org[1]) / h)) * ncell[2] + int(
        (x[nd, 2] - org[2]) / h
    )
    m = 0
    b = _bucket(key, shift)
    for j in range(start[b], start[b + 1]):
        if skeys[j] != key:
            continue
        s = sowner[j]
        if _accepts(i, s, x, snode, sside, seg, mside, box):
            if m < cap:
                out[at + m] = s
            m += 1
    return m


CAP = 16  # candidates of a slave entry kept by the first scan (most have a few; more: scanned again)


@njit(cache=True, parallel=True)
def _candidates(x, snode, sside, seg, mside, box, h, org, ncell, start, skeys, sowner, shift):
    """(cptr, cand) of all slave entries (find_candidates): one scan into a
    buffer of CAP per entry, a second only for the entries with more."""
    ns = snode.shape[0]
    buf = np.empty(ns * CAP, np.int64)
    count = np.empty(ns, np.int64)
    for i in prange(ns):
        count[i] = _scan(
            i, x, snode, sside, seg, mside, box, h, org, ncell, start, skeys, sowner, shift, buf, i * CAP, CAP
        )
    cptr = np.zeros(ns + 1, np.int64)
    for i in range(ns):
        cptr[i + 1] = cptr[i] + count[i]
    cand = np.empty(cptr[ns], np.int64)
    for i in prange(ns):
        if count[i] <= CAP:
            for m in range(count[i]):
                cand[cptr[i] + m] = buf[i * CAP + m]
        else:
            _scan(
                i, x, snode, sside, seg, mside, box, h, org, ncell, start, skeys, sowner, shift, cand, cptr[i], count[i]
            )
    return cptr, cand


def find_candidates(x, snode, sside, seg, mside, grow):
    """(cptr (ns+1,), cand (nc,)) int64: for each slave entry the segments
    whose box grown by ``grow`` (nm,) holds its node (own segments and
    segments of its own side excluded; sside -1: any side).

    Bucket sort: cells of about the median box size; a segment is entered
    in every cell its box overlaps (a few for most, many for a large one),
    so a node looks in its own cell only (``_register``: the entries
    grouped by a hash of their cell, so that the grid may be as large as
    the model's spread without an array per cell)."""
    ns, nm = len(snode), len(seg)
    if nm == 0 or ns == 0:
        return np.zeros(ns + 1, np.int64), np.zeros(0, np.int64)
    box = np.empty((nm, 6))
    segment_boxes(x, seg, grow, box)
    sample = box[:: max(nm // 4096, 1)]
    # cells of about the median box (of a sample: any size finds the same candidates, only faster or slower)
    h = max(float(np.median((sample[:, 3:] - sample[:, :3]).max(axis=1))), 1e-12 * float(np.abs(box).max()), 1e-300)
    while True:
        org, ncell_f, total, finite = _grid(x, snode, box, h)
        if not finite:
            raise FloatingPointError("non-finite coordinates in the contact search: the run diverged")
        # a few huge segments must not flood the grid, nor a far node overflow its cell keys
        if total <= 64 * nm and ncell_f[0] * ncell_f[1] * ncell_f[2] < 2.0**62:
            break
        h *= 2.0
    ncell = ncell_f.astype(np.int64)
    start, skeys, sowner, shift = _register(box, h, org, ncell, int(total))
    return _candidates(x, snode, sside, seg, mside, box, h, org, ncell, start, skeys, sowner, shift)


@njit(cache=True, parallel=True)
def max_displacement(x, xref, nodes):
    """Largest |x − xref| over ``nodes`` [length] (xref indexed like nodes)."""
    m = 0.0
    for j in prange(nodes.shape[0]):  # a max: the same on any number of threads
        nd = nodes[j]
        d = (x[nd, 0] - xref[j, 0]) ** 2 + (x[nd, 1] - xref[j, 1]) ** 2 + (x[nd, 2] - xref[j, 2]) ** 2
        m = max(m, d)
    return math.sqrt(m)


# --- forces -------------------------------------------------------------------------------------


@njit(cache=True, inline="always")
def _relative_velocity(v, nd, n0, n1, n2, n3, w0, w1, w2, w3):
    """Velocity of node nd relative to the segment point of weights w."""
    return (
        v[nd, 0] - (w0 * v[n0, 0] + w1 * v[n1, 0] + w2 * v[n2, 0] + w3 * v[n3, 0]),
        v[nd, 1] - (w0 * v[n0, 1] + w1 * v[n1, 1] + w2 * v[n2, 1] + w3 * v[n3, 1]),
        v[nd, 2] - (w0 * v[n0, 2] + w1 * v[n1, 2] + w2 * v[n2, 2] + w3 * v[n3, 2]),
    )


@njit(cache=True, parallel=True)
def contact_forces(
    x,
    v,
    dt,
    snode,
    sthick,
    sk,
    smass,
    seg,
    mthick,
    mk,
    mmass,
    onesided,
    depth,
    msize,
    alive,
    box,
    cptr,
    cand,
    prm,
    ft,
    prev,
    side,
    rows,
    rnode,
    gap,
    offset,
):
    """Rows of the pair forces of every slave entry (see the module doc).

    The segment of an entry is the nearest one it penetrates; a node behind
    a solid face keeps that face (prev (ns,) int64, -1: none) while it
    stays behind it, so that a node at a corner is not handed to the side
    face it grazes; a node on a shell keeps the side it came from (side
    (ns,) int8, ±1 along the segment normal) while it stays over the same
    segment, so a node pushed past the mid-surface is still pushed back.
    offset (ns,) float64: a tracked initial penetration (LS-DYNA's IGNORE
    1, 2): only the penetration beyond it pushes, and it shrinks to the
    penetration as the node moves out; 0 once the node is out of contact."""
    fs, fd, dc, vdc, fsf, soft_k = prm[P_FS], prm[P_FD], prm[P_DC], prm[P_VDC], prm[P_FSF], prm[P_SOFT_K]
    active = prm[P_ACTIVE] != 0.0
    friction = fs > 0.0 or fd > 0.0
    for i in prange(snode.shape[0]):
        g_prev = gap[i]  # the penetration of the last cycle
        g_last = g_prev + offset[i]  # the same, with a tracked initial penetration it did not push
        if g_prev > 0.0:  # in contact last cycle (otherwise its rows are zero still: most entries, and
            for a in range(5):  # not writing them halves this loop's memory traffic)
                rnode[i, a] = -1
                for k in range(3):
                    rows[i, a, k] = 0.0
        gap[i] = 0.0
        nd = snode[i]
        px, py, pz = x[nd, 0], x[nd, 1], x[nd, 2]
        best = -1
        best_cls = 2
        best_d = np.inf
        bg = 0.0
        bw0 = bw1 = bw2 = bw3 = 0.0
        bnx = bny = bnz = 0.0
        bsg = 0
        if active:
            hs = 0.5 * sthick[i]
            for c in range(cptr[i], cptr[i + 1]):
                s = cand[c]
                # box: grown by the segment's reach, so that most candidates are dropped on one cache line
                if s != prev[i] and _far(box, s, px, py, pz, hs):
                    continue
                if alive[s] == 0:
                    continue
                half = hs + 0.5 * mthick[s]
                sg = 0
                w0, w1, w2, w3 = _closest(x, seg, s, px, py, pz)
                n0, n1, n2, n3 = seg[s, 0], seg[s, 1], seg[s, 2], seg[s, 3]
                rx = px - (w0 * x[n0, 0] + w1 * x[n1, 0] + w2 * x[n2, 0] + w3 * x[n3, 0])
                ry = py - (w0 * x[n0, 1] + w1 * x[n1, 1] + w2 * x[n2, 1] + w3 * x[n3, 1])
                rz = pz - (w0 * x[n0, 2] + w1 * x[n1, 2] + w2 * x[n2, 2] + w3 * x[n3, 2])
                d = math.sqrt(rx * rx + ry * ry + rz * rz)
                nx, ny, nz = _normal(x, seg, s)
                tol = 1e-9 * msize[s]
                sd = rx * nx + ry * ny + rz * nz
                if onesided[s] != 0 and sd < 0.0:
                    # behind a solid face: only where the closest point is the normal projection
                    tx, ty, tz = rx - sd * nx, ry - sd * ny, rz - sd * nz
                    if math.sqrt(tx * tx + ty * ty + tz * tz) > 1e-2 * msize[s] or -sd > depth[s]:
                        continue
                    g = half - sd  # the depth along the normal (a node just past an edge has none)
                    cls = _BEHIND
                else:
                    cls = _OUTSIDE
                    sg = 1 if sd >= 0.0 else -1
                    tx, ty, tz = rx - sd * nx, ry - sd * ny, rz - sd * nz
                    if (
                        onesided[s] == 0
                        and s == prev[i]
                        and side[i] != 0
                        and math.sqrt(tx * tx + ty * ty + tz * tz) <= 1e-6 * msize[s]
                    ):
                        sg = side[i]  # over the same shell segment: the side it came from
                        g = half - sd * sg
                        nx, ny, nz = sg * nx, sg * ny, sg * nz
                        cls = _BEHIND  # held like a node behind a solid face
                    else:
                        g = half - d
                        if d > tol:
                            nx, ny, nz = rx / d, ry / d, rz / d
                if g <= tol:
                    continue
                if dt > 0.0 and s != prev[i] and g > g_last + tol:
                    # deeper in a segment it was not on than one step's approach brings it: the node came
                    # through a solid (a deleted element, round an edge) or a fold of a shell closed over it;
                    # it did not strike this segment, and pushed out it would gain energy no contact stored
                    ux, uy, uz = _relative_velocity(v, nd, n0, n1, n2, n3, w0, w1, w2, w3)
                    approach = -(ux * nx + uy * ny + uz * nz) * dt
                    if g > g_last + 2.0 * max(approach, 0.0) + tol:
                        continue
                keep = s == prev[i] and cls == _BEHIND
                if best_cls >= 0 and (keep or cls < best_cls or (cls == best_cls and d < best_d)):
                    best, best_cls, best_d, bg = s, cls, d, g
                    bw0, bw1, bw2, bw3 = w0, w1, w2, w3
                    bnx, bny, bnz = nx, ny, nz
                    bsg = sg if onesided[s] == 0 else 0
                    if keep:
                        best_cls = -1  # no other candidate replaces it
        prev[i] = best
        side[i] = bsg if best >= 0 else 0
        if best >= 0 and offset[i] > 0.0:  # a tracked initial penetration: only what goes beyond it
            if bg < offset[i]:
                offset[i] = bg
            bg -= offset[i]
            if bg <= 0.0:
                best = -1
        elif best < 0:
            offset[i] = 0.0
        if best < 0:
            ft[i, 0] = 0.0
            ft[i, 1] = 0.0
            ft[i, 2] = 0.0
            continue
        s = best
        n0, n1, n2, n3 = seg[s, 0], seg[s, 1], seg[s, 2], seg[s, 3]
        mstar = smass[i] * mmass[s] / (smass[i] + mmass[s]) if smass[i] + mmass[s] > 0.0 else 0.0
        k = min(mk[s], sk[i])
        if soft_k > 0.0:
            k = max(k, soft_k * mstar)
        vrx, vry, vrz = _relative_velocity(v, nd, n0, n1, n2, n3, bw0, bw1, bw2, bw3)
        vn = vrx * bnx + vry * bny + vrz * bnz
        fn = k * bg
        if vdc > 0.0 and mstar > 0.0:  # LS-DYNA: VDC % of 2·min(m)·ω, ω² = k/m*
            fn -= 0.01 * vdc * 2.0 * min(smass[i], mmass[s]) * math.sqrt(k / mstar) * vn
        fn = max(fn, 0.0)  # no adhesion
        fx, fy, fz = fn * bnx, fn * bny, fn * bnz
        if friction:
            vtx, vty, vtz = vrx - vn * bnx, vry - vn * bny, vrz - vn * bnz
            vt = math.sqrt(vtx * vtx + vty * vty + vtz * vtz)
            mu = fsf * (fd + (fs - fd) * math.exp(-dc * vt))
            # elastic-plastic tangential spring: the stored force turned into the tangent plane
            on = ft[i, 0] * bnx + ft[i, 1] * bny + ft[i, 2] * bnz
            tx = ft[i, 0] - on * bnx - k * dt * vtx
            ty = ft[i, 1] - on * bny - k * dt * vty
            tz = ft[i, 2] - on * bnz - k * dt * vtz
            tn = math.sqrt(tx * tx + ty * ty + tz * tz)
            cap = mu * fn
            if tn > cap:
                sc = cap / tn
                tx, ty, tz = tx * sc, ty * sc, tz * sc
            ft[i, 0], ft[i, 1], ft[i, 2] = tx, ty, tz
            fx += tx
            fy += ty
            fz += tz
        gap[i] = bg
        rows[i, 0, 0], rows[i, 0, 1], rows[i, 0, 2] = fx, fy, fz
        rnode[i, 0] = nd
        rnode[i, 1], rnode[i, 2], rnode[i, 3] = n0, n1, n2
        ws = (bw0, bw1, bw2, bw3)
        for a in range(4):
            w = ws[a]
            rows[i, 1 + a, 0] = -w * fx
            rows[i, 1 + a, 1] = -w * fy
            rows[i, 1 + a, 2] = -w * fz
        if n3 != n2:
            rnode[i, 4] = n3


@njit(cache=True)
def power(rows, rnode, gap, v):
    """Σ row · v over every row (the rate of work of the contact forces
    at the velocities v), summed in slave order. Only entries in contact
    have rows: gap > 0 (contact_forces accepts penetrations above a
    positive tolerance), a read of 8 bytes for the others."""
    p = 0.0
    for i in range(rows.shape[0]):
        if not gap[i] > 0.0:
            continue
        for a in range(5):
            nd = rnode[i, a]
            if nd >= 0:
                p += rows[i, a, 0] * v[nd, 0] + rows[i, a, 1] * v[nd, 1] + rows[i, a, 2] * v[nd, 2]
    return p


@njit(cache=True)
def scatter(rows, rnode, gap, v, node_side, f, resultant):
    """f += the rows, in slave order; resultant (3,) = the force on the
    slave side (row 0 where node_side is 1, else the segment rows).
    Returns the power of the rows at the velocities v (entries in contact
    only, as ``power``) and the largest gap (0 with none in contact)."""
    p = 0.0
    deepest = 0.0
    resultant[0] = resultant[1] = resultant[2] = 0.0
    for i in range(rows.shape[0]):
        if not gap[i] > 0.0:
            continue
        deepest = max(deepest, gap[i])
        for a in range(5):
            nd = rnode[i, a]
            if nd < 0:
                continue
            f[nd, 0] += rows[i, a, 0]
            f[nd, 1] += rows[i, a, 1]
            f[nd, 2] += rows[i, a, 2]
            p += rows[i, a, 0] * v[nd, 0] + rows[i, a, 1] * v[nd, 1] + rows[i, a, 2] * v[nd, 2]
            if (a == 0) == (node_side[i] == 1):
                resultant[0] += rows[i, a, 0]
                resultant[1] += rows[i, a, 1]
                resultant[2] += rows[i, a, 2]
    return p, deepest


@njit(cache=True)
def link_alive(rows, alive, el, across, seg_alive):
    """Segments follow their elements: seg_alive[rows[k]] = alive[el[k]] == 1
    (the element that owns the segment), or, ``across``, is cleared where
    alive[el[k]] == 1 (a segment between solids lives while a neighbour is
    deleted: ``_links``)."""
    for k in range(rows.shape[0]):
        a = alive[el[k]] == 1
        if across:
            if a:
                seg_alive[rows[k]] = 0
        else:
            seg_alive[rows[k]] = 1 if a else 0
