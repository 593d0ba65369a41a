"""Stress updates of the solid materials at one integration point.

Each update takes the stress already rotated to t(n+1) (objective rate,
see kernels.solid) and the strain increment Δε = D·Δt of the step, and
returns the new Cauchy stress in place. All work in one element's row of
the state arrays; no allocation (scratch space comes from the caller).

Voigt order (LS-DYNA's): xx, yy, zz, xy, yz, zx. Strain increments are
tensor components (Δε_xy, not the engineering shear 2Δε_xy).

Material parameters are rows of a table ``props`` (n_mat, N_PROPS) float64
laid out by the P_* indices below, and curves (stress vs strain) are given
by per-material curve slots ``mcurve`` (n_mat, N_CURVES) int64 indexing the
CSR curve store (curve_start, curve_stop, curve_x, curve_y), -1 for none.

Units: stresses and moduli [stress], densities [mass/length³], strains [-].
"""

import math

from numba import njit

from .discrete import curve_value
from .plane_stress import table_yield

# material kinds
ELASTIC, PLASTIC, HONEYCOMB, FOAM = 1, 24, 26, 63

N_PROPS = 24
N_CURVES = 8
# common
P_RO, P_E, P_PR, P_K, P_G, P_WAVE = 0, 1, 2, 3, 4, 5  # P_WAVE: modulus for the time step
P_DAMP = 6  # viscous stress factor: MU (honeycomb), DAMP (foam); 0 otherwise
P_BULKQ = 7  # 1: artificial bulk viscosity applies, 0: not (honeycomb with BULK = 0)
# MAT_024
P_SIGY, P_HARD, P_FAIL, P_CS_C, P_CS_P = 8, 9, 10, 11, 12
# MAT_026 (P_SIGY shared)
P_VF, P_EAAU, P_EBBU, P_ECCU, P_GABU, P_GBCU, P_GCAU, P_TSEF, P_SSEF = 9, 10, 11, 12, 13, 14, 15, 16, 17
# MAT_126: P_FORM 2 = the transversely isotropic yield surface (LCA < 0), else MAT_026's; its SHDFLG
P_FORM, P_SHDFLG = 18, 19
# MAT_063
P_TSC = 8
# curve slots: MAT_024 yield curve, or a *DEFINE_TABLE of them by strain rate (x: rates, y: curve slots);
# MAT_026 a, b, c, ab, bc, ca; MAT_063 yield curve
C_LCSS, C_TABLE = 0, 1
C_A, C_B, C_C, C_AB, C_BC, C_CA = 0, 1, 2, 3, 4, 5
C_FOAM = 0

# history per element (per point for ELFORM 2). Honeycomb: [0:3] normal strains summed over the steps
# (TSEF), [3:6] half the total engineering shears (SSEF), [6:15] H = F·A0, the images of the initial
# material axes (columns, row major), [15:24] A0 itself (set on the first step); MAT_126's transversely
# isotropic form: [24:27] the damage of the shear planes ab, bc, ca (never falls)
H_LINES, H_AXES0, H_DAMAGE = 6, 15, 24
N_HIST = 27
N_SCRATCH = 24  # scratch values a material update may use


@njit(cache=True)
def curve_slope(xs, ys, start, stop, x):
    """Slope of the piecewise-linear curve segment used at x (extrapolated)."""
    if stop - start < 2:
        return 0.0
    i = start
    while i < stop - 2 and xs[i + 1] <= x:
        i += 1
    dx = xs[i + 1] - xs[i]
    return (ys[i + 1] - ys[i]) / dx if dx != 0.0 else 0.0


@njit(cache=True)
def _elastic_trial(s, w, do, k, g):
    """s += λ tr(Δε) I + 2G Δε."""
    tr = w[do] + w[do + 1] + w[do + 2]
    lam = k - 2.0 * g / 3.0
    for i in range(3):
        s[i] += lam * tr + 2.0 * g * w[do + i]
        s[i + 3] += 2.0 * g * w[do + i + 3]


@njit(cache=True)
def _mises(s):
    p = (s[0] + s[1] + s[2]) / 3.0
    a, b, c = s[0] - p, s[1] - p, s[2] - p
    return p, math.sqrt(1.5 * (a * a + b * b + c * c + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])))


@njit(cache=True)
def _scale_deviator(s, p, f):
    for i in range(3):
        s[i] = p + f * (s[i] - p)
        s[i + 3] *= f


@njit(cache=True)
def update_elastic(p, s, w, do):
    """MAT_001 (hypoelastic). Returns the wave modulus K + 4G/3."""
    _elastic_trial(s, w, do, p[P_K], p[P_G])
    return p[P_K] + 4.0 * p[P_G] / 3.0


@njit(cache=True)
def _yield(p, curve, table, cs, ce, cx, cy, ep, rate):
    """Yield stress and hardening slope at plastic strain ep (and, for a
    table, at the strain rate: kernels.plane_stress.table_yield)."""
    if table >= 0:
        return table_yield(cs, ce, cx, cy, table, rate, ep)
    if curve >= 0:
        return (curve_value(cx, cy, cs[curve], ce[curve], ep), curve_slope(cx, cy, cs[curve], ce[curve], ep))
    return p[P_SIGY] + p[P_HARD] * ep, p[P_HARD]


@njit(cache=True)
def update_plastic(p, mc, cs, ce, cx, cy, s, w, do, epsp, e, dt):
    """MAT_024: J2 plasticity, isotropic hardening (SIGY + ETAN or LCSS
    curve of yield stress vs effective plastic strain, or a table of such
    curves by strain rate), radial return, with Cowper–Symonds scaling of
    the yield stress (C, P) when given and LCSS is no table.

    Returns (wave modulus, failed): failed when the effective plastic
    strain reaches FAIL.
    """
    k, g = p[P_K], p[P_G]
    _elastic_trial(s, w, do, k, g)
    pm, q = _mises(s)
    ep = epsp[e]
    curve = mc[C_LCSS]
    table = mc[C_TABLE]
    factor = 1.0
    rate = 0.0
    cowper = p[P_CS_C] > 0.0 and p[P_CS_P] > 0.0 and table < 0
    if (cowper or table >= 0) and dt > 0.0:
        tr = (w[do] + w[do + 1] + w[do + 2]) / 3.0
        dd = 0.0
        for i in range(3):
            dd += (w[do + i] - tr) ** 2 + 2.0 * w[do + i + 3] ** 2
        rate = math.sqrt(2.0 / 3.0 * dd) / dt
        if cowper:
            factor = 1.0 + (rate / p[P_CS_C]) ** (1.0 / p[P_CS_P])
    y, h = _yield(p, curve, table, cs, ce, cx, cy, ep, rate)
    if q > factor * y:
        # q - 3G·Δλ = factor·σy(ep + Δλ): Newton, kept inside its bracket
        lo, hi = 0.0, q / (3.0 * g)
        dl = 0.0
        for _ in range(60):
            y, h = _yield(p, curve, table, cs, ce, cx, cy, ep + dl, rate)
            f = q - 3.0 * g * dl - factor * y
            if abs(f) <= 1e-12 * q:
                break
            if f > 0.0:
                lo = dl
            else:
                hi = dl
            slope = 3.0 * g + factor * h
            nxt = dl + f / slope if slope > 0.0 else 0.5 * (lo + hi)
            if not (lo < nxt < hi):
                nxt = 0.5 * (lo + hi)
            dl = nxt
        _scale_deviator(s, pm, (q - 3.0 * g * dl) / q)
        epsp[e] = ep + dl
    return k + 4.0 * g / 3.0, epsp[e] >= p[P_FAIL]


@njit(cache=True)
def _to_local(q, src, so, w, o):
    """w[o:o+6] = the symmetric tensor src[so:so+6] (Voigt) in the axes q
    (columns a, b, c): Qᵀ S Q."""
    m00, m11, m22, m01, m12, m20 = src[so], src[so + 1], src[so + 2], src[so + 3], src[so + 4], src[so + 5]
    idx_i = (0, 1, 2, 0, 1, 2)
    idx_j = (0, 1, 2, 1, 2, 0)
    for t in range(6):
        a = idx_i[t]
        b = idx_j[t]
        a0, a1, a2 = q[0, a], q[1, a], q[2, a]
        b0, b1, b2 = q[0, b], q[1, b], q[2, b]
        w[o + t] = (
            a0 * (m00 * b0 + m01 * b1 + m20 * b2)
            + a1 * (m01 * b0 + m11 * b1 + m12 * b2)
            + a2 * (m20 * b0 + m12 * b1 + m22 * b2)
        )


@njit(cache=True)
def _to_global(q, w, o, s):
    """s (Voigt) = Q L Qᵀ for the local tensor w[o:o+6]."""
    l00, l11, l22, l01, l12, l20 = w[o], w[o + 1], w[o + 2], w[o + 3], w[o + 4], w[o + 5]
    idx_i = (0, 1, 2, 0, 1, 2)
    idx_j = (0, 1, 2, 1, 2, 0)
    for t in range(6):
        i = idx_i[t]
        j = idx_j[t]
        a0, a1, a2 = q[i, 0], q[i, 1], q[i, 2]
        b0, b1, b2 = q[j, 0], q[j, 1], q[j, 2]
        s[t] = (
            a0 * (l00 * b0 + l01 * b1 + l20 * b2)
            + a1 * (l01 * b0 + l11 * b1 + l12 * b2)
            + a2 * (l20 * b0 + l12 * b1 + l22 * b2)
        )


@njit(cache=True)
def _bound(v, y):
    if v > y:
        return y
    if v < -y:
        return -y
    return v


@njit(cache=True)
def carry_lines(h, q, g00, g01, g02, g10, g11, g12, g20, g21, g22):
    """H ← (I + L·Δt)·H (g = L·Δt) for the history h of a honeycomb: the
    initial material axes carried as material lines, H = F·A0. On the
    first step (A0 still zero) A0 = H = q, the axes before they move."""
    if h[H_AXES0] == 0.0 and h[H_AXES0 + 3] == 0.0 and h[H_AXES0 + 6] == 0.0:
        for t in range(9):
            h[H_AXES0 + t] = q[t // 3, t % 3]
            h[H_LINES + t] = q[t // 3, t % 3]
    for j in range(3):
        c0, c1, c2 = h[H_LINES + j], h[H_LINES + 3 + j], h[H_LINES + 6 + j]
        h[H_LINES + j] = c0 + g00 * c0 + g01 * c1 + g02 * c2
        h[H_LINES + 3 + j] = c1 + g10 * c0 + g11 * c1 + g12 * c2
        h[H_LINES + 6 + j] = c2 + g20 * c0 + g21 * c1 + g22 * c2


@njit(cache=True)
def _shear_of_cell(h, i, j):
    """G_ij + G_ji, G = A0ᵀ·H: the engineering shear of material axes i, j
    over the undeformed cell (zero before carry_lines has run)."""
    gij = 0.0
    gji = 0.0
    for k in range(3):
        gij += h[H_AXES0 + 3 * k + i] * h[H_LINES + 3 * k + j]
        gji += h[H_AXES0 + 3 * k + j] * h[H_LINES + 3 * k + i]
    return gij + gji


@njit(cache=True)
def update_honeycomb(p, mc, cs, ce, cx, cy, s, w, do, wo, hist, axes, relvol):
    """MAT_026. Uncompacted (relative volume V > VF): in the material axes
    each normal and shear component is updated on its own with the moduli
    E_ii = E_iiu + β(E − E_iiu), G_ij = G_iju + β(G − G_iju),
    β = max(min((1 − V)/(1 − VF), 1), 0), and bounded in magnitude by its
    curve (a, b, c, ab, bc, ca) of stress vs volumetric strain 1 − V.
    Fully compacted (V ≤ VF): isotropic elastic–perfectly plastic (E, PR,
    SIGY). hist[0:3] accumulates the normal strains in the material axes
    for TSEF (tension). SSEF bounds the engineering shear of the undeformed
    cell, γ_ab = ∂u_a/∂X_b + ∂u_b/∂X_a = G_ab + G_ba with G = A0ᵀ·F·A0, the
    deformation gradient in the initial material axes (``_shear_of_cell``):
    a band dragged along the cell axis beside an imprint tears at a slip of
    SSEF × its width however much it is crushed, and a crushed brick whose
    faces slide sideways fails at a slide of SSEF × its initial depth, not
    of its current one (summing the increments D·Δt, a brick crushed to a
    third fails at a third of the slide). Rigid rotations cancel exactly in
    a plane and to second order otherwise.

    Returns (wave modulus, failed).
    """
    if p[P_FORM] == 2.0:
        return _honeycomb_transverse(p, mc, cs, ce, cx, cy, s, w, do, wo, hist, axes, relvol)
    vf = p[P_VF]
    k, g = p[P_K], p[P_G]
    if relvol <= vf:
        _elastic_trial(s, w, do, k, g)
        pm, q = _mises(s)
        if q > p[P_SIGY]:
            _scale_deviator(s, pm, p[P_SIGY] / q)
        return k + 4.0 * g / 3.0, False
    beta = min(max((1.0 - relvol) / (1.0 - vf), 0.0), 1.0)
    ev = 1.0 - relvol
    e = p[P_E]
    _to_local(axes, s, 0, w, wo)  # stress in the material axes
    _to_local(axes, w, do, w, wo + 12)  # strain increment in the material axes
    wave = 0.0
    failed = False
    for i in range(3):
        mod = p[P_EAAU + i] + beta * (e - p[P_EAAU + i])
        wave = max(wave, mod)
        c = mc[C_A + i]
        y = max(curve_value(cx, cy, cs[c], ce[c], ev), 0.0)
        w[wo + i] = _bound(w[wo + i] + mod * w[wo + 12 + i], y)
        hist[i] += w[wo + 12 + i]
        if p[P_TSEF] > 0.0 and hist[i] > p[P_TSEF]:
            failed = True
    for i in range(3):
        mod = p[P_GABU + i] + beta * (g - p[P_GABU + i])
        wave = max(wave, mod)
        c = mc[C_AB + i]
        y = max(curve_value(cx, cy, cs[c], ce[c], ev), 0.0)
        w[wo + 3 + i] = _bound(w[wo + 3 + i] + 2.0 * mod * w[wo + 15 + i], y)
        gam = _shear_of_cell(hist, i, (i + 1) % 3)
        hist[3 + i] = 0.5 * gam
        if p[P_SSEF] > 0.0 and abs(gam) > p[P_SSEF]:
            failed = True
    _to_global(axes, w, wo, s)
    return wave, failed


@njit(cache=True)
def _honeycomb_transverse(p, mc, cs, ce, cx, cy, s, w, do, wo, hist, axes, relvol):
    """MAT_126 with LCA < 0: a transversely isotropic honeycomb about the
    cell axis a. Uncompacted, the trial stress (MAT_026's moduli, c taking
    b's) is bounded as a whole: each principal stress i, at an angle φ_i
    off a (cos² φ_i = c_i), yields at σ_i = |LCA|(φ_i) + c_i·LCB(ε_v) +
    (1 − c_i)·LCC(ε_v); the surface σ_y = Σ σ_i λ_i² / Σ λ_i², and the
    stress is scaled by min(1, σ_y/|λ|). A crushing cell therefore carries
    little shear on top of its crush, where MAT_026 bounds each component
    on its own. Compacted: as MAT_026. Then the shear damage: the curve of
    each plane (LCAB, LCBC, LCCA) gives the factor left at the half
    engineering shear of the undeformed cell; the damage never falls, the
    element is kept. SHDFLG 1: the factor scales the undamaged stress
    (kept by dividing the stored one back); 0: it scales the stored
    stress again every step. TSEF, SSEF erode as in MAT_026."""
    vf = p[P_VF]
    k, g, e = p[P_K], p[P_G], p[P_E]
    _to_local(axes, s, 0, w, wo)  # stress in the material axes
    _to_local(axes, w, do, w, wo + 12)  # strain increment in the material axes
    if p[P_SHDFLG] == 1.0:
        for i in range(3):
            w[wo + 3 + i] /= max(1.0 - hist[H_DAMAGE + i], 1e-20)
    failed = False
    for i in range(3):
        hist[i] += w[wo + 12 + i]
        if p[P_TSEF] > 0.0 and hist[i] > p[P_TSEF]:
            failed = True
    if relvol <= vf:
        _to_global(axes, w, wo, s)
        _elastic_trial(s, w, do, k, g)
        pm, q = _mises(s)
        if q > p[P_SIGY]:
            _scale_deviator(s, pm, p[P_SIGY] / q)
        _to_local(axes, s, 0, w, wo)
        wave = k + 4.0 * g / 3.0
    else:
        beta = min(max((1.0 - relvol) / (1.0 - vf), 0.0), 1.0)
        ev = 1.0 - relvol
        ea = p[P_EAAU] + beta * (e - p[P_EAAU])
        eb = p[P_EBBU] + beta * (e - p[P_EBBU])
        gab = p[P_GABU] + beta * (g - p[P_GABU])
        gbc = p[P_GBCU] + beta * (g - p[P_GBCU])
        w[wo] += ea * w[wo + 12]
        w[wo + 1] += eb * w[wo + 13]
        w[wo + 2] += eb * w[wo + 14]
        w[wo + 3] += 2.0 * gab * w[wo + 15]
        w[wo + 4] += 2.0 * gbc * w[wo + 16]
        w[wo + 5] += 2.0 * gab * w[wo + 17]
        wave = max(max(ea, eb), max(gab, gbc))
        a, v = wo + 6, wo + 15  # the strain increment is spent: its slots hold the eigenvectors
        w[a], w[a + 4], w[a + 8] = w[wo], w[wo + 1], w[wo + 2]
        w[a + 1] = w[a + 3] = w[wo + 3]
        w[a + 5] = w[a + 7] = w[wo + 4]
        w[a + 2] = w[a + 6] = w[wo + 5]
        _jacobi3(w, a, v)
        strong = max(curve_value(cx, cy, cs[mc[C_B]], ce[mc[C_B]], ev), 0.0)
        weak = max(curve_value(cx, cy, cs[mc[C_C]], ce[mc[C_C]], ev), 0.0)
        num = 0.0
        den = 0.0
        for i in range(3):
            lam = w[a + 4 * i]
            c2 = min(max(w[v + i] * w[v + i], 0.0), 1.0)  # (a · principal direction i)²
            phi = math.degrees(math.acos(math.sqrt(c2)))
            y = curve_value(cx, cy, cs[mc[C_A]], ce[mc[C_A]], phi) + c2 * strong + (1.0 - c2) * weak
            num += max(y, 0.0) * lam * lam
            den += lam * lam
        if den > 0.0:
            f = (num / den) / math.sqrt(den)
            if f < 1.0:  # every principal stress scaled alike: the tensor is
                for t in range(6):
                    w[wo + t] *= f
    for i in range(3):
        gam = _shear_of_cell(hist, i, (i + 1) % 3)
        hist[3 + i] = 0.5 * gam
        if p[P_SSEF] > 0.0 and abs(gam) > p[P_SSEF]:
            failed = True
        c = mc[C_AB + i]
        if c >= 0:
            left = min(max(curve_value(cx, cy, cs[c], ce[c], abs(0.5 * gam)), 0.0), 1.0 - hist[H_DAMAGE + i])
            hist[H_DAMAGE + i] = 1.0 - left
            w[wo + 3 + i] *= left
    _to_global(axes, w, wo, s)
    return wave, failed


@njit(cache=True)
def _jacobi3(w, a, v):
    """Eigen-decomposition of the symmetric 3x3 matrix w[a:a+9] (row major,
    destroyed: its diagonal ends as the eigenvalues) into eigenvectors as
    the columns of w[v:v+9], by cyclic Jacobi rotations."""
    for i in range(9):
        w[v + i] = 0.0
    w[v] = w[v + 4] = w[v + 8] = 1.0
    for _ in range(50):
        off = w[a + 1] ** 2 + w[a + 2] ** 2 + w[a + 5] ** 2
        diag = w[a] ** 2 + w[a + 4] ** 2 + w[a + 8] ** 2
        if off <= 1e-30 * diag or off == 0.0:
            return
        for pq in range(3):
            pi = 0 if pq < 2 else 1
            qi = 1 if pq == 0 else 2
            apq = w[a + 3 * pi + qi]
            if apq == 0.0:
                continue
            app = w[a + 4 * pi]
            aqq = w[a + 4 * qi]
            theta = 0.5 * (aqq - app) / apq
            t = (1.0 if theta >= 0.0 else -1.0) / (abs(theta) + math.sqrt(theta * theta + 1.0))
            c = 1.0 / math.sqrt(t * t + 1.0)
            sn = t * c
            for k in range(3):  # A ← Jᵀ A J: columns then rows
                akp = w[a + 3 * k + pi]
                akq = w[a + 3 * k + qi]
                w[a + 3 * k + pi] = c * akp - sn * akq
                w[a + 3 * k + qi] = sn * akp + c * akq
            for k in range(3):
                apk = w[a + 3 * pi + k]
                aqk = w[a + 3 * qi + k]
                w[a + 3 * pi + k] = c * apk - sn * aqk
                w[a + 3 * qi + k] = sn * apk + c * aqk
            for k in range(3):
                vkp = w[v + 3 * k + pi]
                vkq = w[v + 3 * k + qi]
                w[v + 3 * k + pi] = c * vkp - sn * vkq
                w[v + 3 * k + qi] = sn * vkp + c * vkq


@njit(cache=True)
def update_foam(p, mc, cs, ce, cx, cy, s, w, do, wo, relvol):
    """MAT_063: isotropic elastic trial (E, PR), then each principal stress
    is limited to [−σy(γ), TSC], σy from the curve of yield stress vs
    volumetric strain γ = 1 − V; below the curve the foam unloads
    elastically. Returns the wave modulus."""
    k, g = p[P_K], p[P_G]
    _elastic_trial(s, w, do, k, g)
    c = mc[C_FOAM]
    y = max(curve_value(cx, cy, cs[c], ce[c], 1.0 - relvol), 0.0)
    tsc = p[P_TSC]
    a, v = wo, wo + 9
    w[a], w[a + 4], w[a + 8] = s[0], s[1], s[2]
    w[a + 1] = w[a + 3] = s[3]
    w[a + 5] = w[a + 7] = s[4]
    w[a + 2] = w[a + 6] = s[5]
    _jacobi3(w, a, v)
    clipped = False
    for i in range(3):
        lam = w[a + 4 * i]
        if lam < -y:
            w[a + 4 * i] = -y
            clipped = True
        elif lam > tsc:
            w[a + 4 * i] = tsc
            clipped = True
    if clipped:
        l0, l1, l2 = w[a], w[a + 4], w[a + 8]
        idx_i = (0, 1, 2, 0, 1, 2)
        idx_j = (0, 1, 2, 1, 2, 0)
        for t in range(6):
            i = idx_i[t]
            j = idx_j[t]
            s[t] = (
                w[v + 3 * i] * l0 * w[v + 3 * j]
                + w[v + 3 * i + 1] * l1 * w[v + 3 * j + 1]
                + w[v + 3 * i + 2] * l2 * w[v + 3 * j + 2]
            )
    return k + 4.0 * g / 3.0


@njit(cache=True)
def update_stress(kind, p, mc, cs, ce, cx, cy, s, w, do, wo, epsp, e, hist, axes, relvol, dt):
    """Dispatch on the material kind. s (6,) stress rotated to t(n+1),
    updated in place; w[do:do+6] the strain increment; w[wo:wo+N_SCRATCH]
    scratch; epsp (n,) effective plastic strain; hist (N_HIST,) and axes
    (3, 3) this element's history and material axes; relvol V/V0.
    Returns (wave modulus [stress], failed)."""
    if kind == ELASTIC:
        return update_elastic(p, s, w, do), False
    if kind == PLASTIC:
        return update_plastic(p, mc, cs, ce, cx, cy, s, w, do, epsp, e, dt)
    if kind == HONEYCOMB:
        return update_honeycomb(p, mc, cs, ce, cx, cy, s, w, do, wo, hist, axes, relvol)
    return update_foam(p, mc, cs, ce, cx, cy, s, w, do, wo, relvol), False
