"""Plane-stress J2 plasticity at a shell integration point.

Materials: MAT_001 (elastic), MAT_003 (PLASTIC_KINEMATIC: bilinear with
mixed kinematic/isotropic hardening BETA, Cowper–Symonds SRC/SRP, failure
strain FS), MAT_024 (PIECEWISE_LINEAR_PLASTICITY: SIGY + ETAN or a curve
LCSS of yield stress vs effective plastic strain, Cowper–Symonds C/P or a
rate-scaling curve LCSR, failure strain FAIL) and MAT_081
(PLASTICITY_WITH_DAMAGE: MAT_024's plasticity with damage, below).

LCSS may name a *DEFINE_TABLE (slot C_TABLE): a yield curve per strain rate,
the yield stress and its slope interpolated linearly between the two curves
whose rates bracket the point's effective strain rate, the first or last
curve outside them (LS-DYNA does not extrapolate); rates in ln(ε̇) where the
first value is negative. C, P and LCSR do not apply then.

MAT_081: the stored stress is σ = (1 − D)·σ̃, σ̃ the plasticity's effective
stress, with D(ε̄p) = (ε̄p − EPPF)/(EPPFR − EPPF) between EPPF and EPPFR
(or the curve LCDM of D vs ε̄p − EPPF); D is a function of ε̄p, so σ̃ is
recovered from σ and ε̄p and no other history is kept. A point ruptures
(stress zero, failed) at ε̄p = EPPFR (P_FAIL) or D = 1. The work ½(σn + σn+1)·Δε
the shell kernels integrate is that of the damaged stress: the elastic
energy of the stress removed by D stays in the internal energy (dissipated,
never returned). The back stress is not used by the isotropic MAT_081:
back[e, k, 0] is 1 once point k ruptured, back[e, k, 1] the in-plane point
its layer belongs to (0 for the one-point shells; 0-3 for ELFORM 16, set
by the caller); with NUMINT > 0 a point fails once NUMINT points of its
in-plane point have, so that the shell kernels' rule (all points failed:
deleted) deletes the element one step later at most.

The return mapping is the Simo–Taylor projected algorithm: with the
elastic plane-stress trial state σ* and ξ = σ − β (β the back stress in its
plane-stress form β = α − α_zz I, so that dev(σ − β) = s − α exactly) the
update is ξ = (I + Δγ(C·P + ⅔H_k I))⁻¹ ξ*, diagonal in the basis
(ξx + ξy, ξy − ξx, shears). The plastic multiplier Δγ solves
ξ_eq(Δγ) = R·σ_y(ε̄p + ⅔Δγ ξ_eq(Δγ)) by Halley's iteration (third order,
from the function's first and second derivatives; Newton's where Halley's
denominator is not positive) kept inside its bracket, started from the root
for equal eigenvalues and converged to 1e-10 of the yield stress (mostly
one step: 1.04 iterations a plastic step against Newton's 1.73, on
MAT_024 steps of Δε = 4e-5): the plane-stress condition σ_zz = 0 is exact
and the normal strain increment Δε_zz (elastic + plastic) is returned for
the thickness update.

Components (the shell's local frame, Voigt): σx, σy, τxy, τyz, τzx;
strain increments with engineering shears Δγ = 2Δε. The transverse shears
are updated elastically with G and take part in the yield function (3D J2
with σ_zz = 0).

update_point updates one point; update_block the points of a block of
shell elements of one material at once, in loops that LLVM vectorises
(see the comment above it); the points it declines the caller redoes
with update_point.

Material parameters are rows of ``props`` (n_mat, N_PROPS) float64 laid out
by the P_* indices; curves by per-material slots ``mcurve`` (n_mat,
N_CURVES) int64 into the CSR curve store (curve_start, curve_stop,
curve_x, curve_y), -1 for none. Units: stresses and moduli [stress],
density [mass/length³], strain rates [1/time].
"""

import math

from numba import njit, prange

from .discrete import curve_value

# material kinds (LS-DYNA numbers)
ELASTIC, KINEMATIC, PIECEWISE, DAMAGE = 1, 3, 24, 81

N_PROPS = 15
P_RO, P_E, P_PR, P_G, P_C1 = 0, 1, 2, 3, 4  # P_C1 = E/(1 − ν²), plane-stress modulus
P_SIGY = 5  # initial yield stress
P_EP = 6  # plastic hardening modulus E·Et/(E − Et)
P_BETA = 7  # share of isotropic hardening (MAT_003 BETA; 1 for MAT_024)
P_CS_C, P_CS_P = 8, 9  # Cowper–Symonds C [1/time] and P (0: no rate effect)
P_FAIL = 10  # effective plastic strain at failure (1e21: none)
P_WAVE = 11  # plate wave speed² E/(ρ(1 − ν²)) [length²/time²]
P_EPPF, P_EPPFR = 12, 13  # MAT_081: ε̄p where softening begins, where the material ruptures (also P_FAIL)
P_NUMINT = 14  # MAT_081: failed points of an in-plane point that fail it (0: all)

N_CURVES = 4
C_LCSS, C_LCSR = 0, 1  # yield stress vs ε̄p; yield scale factor vs strain rate
# a table of yield curves by strain rate (x: rates, y: slots of the curves); MAT_081's damage vs ε̄p − EPPF.
# A narrower mcurve (callers with two slots) has neither.
C_TABLE, C_LCDM = 2, 3

_TOL = 1e-10  # relative tolerance of the consistency condition
# a Halley step that changes the stress by less than this fraction (|ΔΔγ|·k2) is the last: what is left
# of the error is of the order of its cube
_STEP = 1e-4


@njit(cache=True)
def curve_slope(xs, ys, start, stop, x):
    """Slope of the piecewise-linear segment used at x (end segments extend)."""
    if stop - start < 2:
        return 0.0
    i = start
    while i < stop - 2 and xs[i + 1] <= x:
        i += 1
    dx = xs[i + 1] - xs[i]
    return (ys[i + 1] - ys[i]) / dx if dx != 0.0 else 0.0


@njit(cache=True, inline="always")
def slot(mc, m, c):
    """Curve slot c of material row m, -1 where mcurve has no such column."""
    return mc[m, c] if c < mc.shape[1] else -1


@njit(cache=True)
def table_yield(cs, ce, cx, cy, t, rate, ep):
    """Yield stress and slope at ε̄p of the table in slot t at the strain
    rate: linear between the curves whose rates bracket it, the first or
    the last curve outside them; the rates are ln(ε̇) if the first is < 0."""
    a, b = cs[t], ce[t]
    r = rate
    if cx[a] < 0.0:
        r = math.log(rate) if rate > 0.0 else -math.inf
    i, w = a, 0.0
    if r >= cx[b - 1]:
        i = b - 1
    elif r > cx[a]:
        while cx[i + 1] <= r:
            i += 1
        w = (r - cx[i]) / (cx[i + 1] - cx[i])
    c0 = int(cy[i])
    y = curve_value(cx, cy, cs[c0], ce[c0], ep)
    h = curve_slope(cx, cy, cs[c0], ce[c0], ep)
    if w > 0.0:
        c1 = int(cy[i + 1])
        y += w * (curve_value(cx, cy, cs[c1], ce[c1], ep) - y)
        h += w * (curve_slope(cx, cy, cs[c1], ce[c1], ep) - h)
    return y, h


@njit(cache=True)
def damage(props, m, mc, cs, ce, cx, cy, ep):
    """MAT_081's damage D in [0, 1] at ε̄p (0 for the other materials)."""
    f = props[m, P_EPPF]
    if ep <= f:
        return 0.0
    c = slot(mc, m, C_LCDM)
    if c >= 0:
        d = curve_value(cx, cy, cs[c], ce[c], ep - f)
    else:
        span = props[m, P_EPPFR] - f
        d = (ep - f) / span if span > 0.0 else 1.0
    return min(max(d, 0.0), 1.0)


@njit(cache=True)
def _yield(props, m, mc, cs, ce, cx, cy, ep, rate):
    """Static yield stress and its isotropic hardening slope at ε̄p
    (material row m), at the strain rate where LCSS is a table."""
    t = slot(mc, m, C_TABLE)
    if t >= 0:
        return table_yield(cs, ce, cx, cy, t, rate, ep)
    c = mc[m, C_LCSS]
    if c >= 0:
        return curve_value(cx, cy, cs[c], ce[c], ep), curve_slope(cx, cy, cs[c], ce[c], ep)
    h = props[m, P_BETA] * props[m, P_EP]
    return props[m, P_SIGY] + h * ep, h


@njit(cache=True)
def effective_rate(d0, d1, d2, d3, d4, dt):
    """Von Mises strain rate sqrt(⅔ ė':ė') [1/time] of the increment, with
    ε̇zz = −(ε̇x + ε̇y) (incompressible flow), so uniaxial plastic flow gives
    its axial rate."""
    if dt <= 0.0:
        return 0.0
    dz = -(d0 + d1)
    dd = d0 * d0 + d1 * d1 + dz * dz + 0.5 * (d2 * d2 + d3 * d3 + d4 * d4)
    return math.sqrt(2.0 / 3.0 * dd) / dt


@njit(cache=True)
def rate_factor(props, m, mc, cs, ce, cx, cy, rate):
    """Scale factor of the yield stress of material row m at the strain
    rate: the curve LCSR if given, else Cowper–Symonds 1 + (ε̇/C)^(1/P),
    else 1."""
    c = mc[m, C_LCSR]
    if c >= 0:
        return curve_value(cx, cy, cs[c], ce[c], rate)
    cc, pp = props[m, P_CS_C], props[m, P_CS_P]
    if cc > 0.0 and pp > 0.0 and rate > 0.0:
        return 1.0 + (rate / cc) ** (1.0 / pp)
    return 1.0


@njit(cache=True, inline="always")
def _shrunk(dg, k1, k2, a1, a2, sh):
    """ξ at the multiplier dg: the factors 1/(1 + dg·k) on ξx + ξy (r1) and
    on ξy − ξx and the shears (r2), the two scaled in-plane combinations
    and ξ_eq."""
    den = 1.0 / ((1.0 + dg * k1) * (1.0 + dg * k2))
    r1 = (1.0 + dg * k2) * den
    r2 = (1.0 + dg * k1) * den
    aa1 = a1 * r1
    aa2 = a2 * r2
    return r1, r2, aa1, aa2, math.sqrt(0.25 * aa1 * aa1 + 0.75 * aa2 * aa2 + 3.0 * sh * r2 * r2)


@njit(cache=True)
def _rupture(sig, back, e, k):
    """A MAT_081 point fails: no stress, marked for NUMINT (back[e, k, 0])."""
    for i in range(5):
        sig[e, k, i] = 0.0
    back[e, k, 0] = 1.0
    return True


@njit(cache=True)
def _numint_reached(props, m, back, e, k):
    """Whether NUMINT (> 0) points of point k's in-plane point (back[., ., 1])
    have ruptured."""
    need = props[m, P_NUMINT]
    if need <= 0.0:
        return False
    n = 0
    for j in range(back.shape[1]):
        if back[e, j, 1] == back[e, k, 1] and back[e, j, 0] != 0.0:
            n += 1
    return n >= need


@njit(cache=True, inline="always")  # inlined: the shell loop keeps its registers
def update_point(mtype, props, m, mc, cs, ce, cx, cy, sig, back, e, k, ep, d0, d1, d2, d3, d4, dt):
    """Stress update of integration point k of element e.

    Material row m of props and mc (mtype its kind); sig, back (n, nip, 5)
    stress and plane-stress back stress, point (e, k) updated in place
    [stress]; ep effective plastic strain before the step; d0..d4 strain
    increments Δεx, Δεy, Δγxy, Δγyz, Δγzx; dt the step [time] (rates).
    Arrays are indexed, never sliced: a view per point would
    reference-count its parent (atomics shared by every thread).

    Returns (ε̄p after the step, Δε_zz, failed): failed when ε̄p reached
    the failure strain (the stresses are then zero), or a MAT_081 point
    ruptured or its in-plane point reached NUMINT failed points.
    """
    e_mod = props[m, P_E]
    nu = props[m, P_PR]
    g = props[m, P_G]
    c1 = props[m, P_C1]
    keep = 1.0  # 1 − D of MAT_081 at the step's start: the effective stress is sig/keep
    if mtype == DAMAGE:
        keep = 1.0 - damage(props, m, mc, cs, ce, cx, cy, ep)
        if keep <= 0.0 or back[e, k, 0] != 0.0 or _numint_reached(props, m, back, e, k):
            return ep, 0.0, _rupture(sig, back, e, k)
    o0, o1 = sig[e, k, 0] / keep, sig[e, k, 1] / keep
    t0 = o0 + c1 * (d0 + nu * d1)
    t1 = o1 + c1 * (d1 + nu * d0)
    t2 = sig[e, k, 2] / keep + g * d2
    t3 = sig[e, k, 3] / keep + g * d3
    t4 = sig[e, k, 4] / keep + g * d4
    if mtype == ELASTIC:
        sig[e, k, 0], sig[e, k, 1], sig[e, k, 2], sig[e, k, 3], sig[e, k, 4] = t0, t1, t2, t3, t4
        return ep, -nu / e_mod * (t0 - o0 + t1 - o1), False
    kinematic = mtype == KINEMATIC
    b0 = b1 = b2 = b3 = b4 = 0.0  # MAT_024 hardens isotropically: its back stress stays zero, unread
    if kinematic:
        b0, b1, b2, b3, b4 = back[e, k, 0], back[e, k, 1], back[e, k, 2], back[e, k, 3], back[e, k, 4]
    x0, x1, x2, x3, x4 = t0 - b0, t1 - b1, t2 - b2, t3 - b3, t4 - b4
    q_tr = math.sqrt(max(x0 * x0 - x0 * x1 + x1 * x1 + 3.0 * (x2 * x2 + x3 * x3 + x4 * x4), 0.0))
    rf = 1.0
    rate = 0.0
    table = slot(mc, m, C_TABLE) >= 0
    if table or mc[m, C_LCSR] >= 0 or (props[m, P_CS_C] > 0.0 and props[m, P_CS_P] > 0.0):
        rate = effective_rate(d0, d1, d2, d3, d4, dt)
        if not table:  # a table's curves hold the rate effect
            rf = rate_factor(props, m, mc, cs, ce, cx, cy, rate)
    y0, h0 = _yield(props, m, mc, cs, ce, cx, cy, ep, rate)
    if q_tr <= rf * y0 or q_tr == 0.0:
        sig[e, k, 0], sig[e, k, 1], sig[e, k, 2] = keep * t0, keep * t1, keep * t2
        sig[e, k, 3], sig[e, k, 4] = keep * t3, keep * t4
        return ep, -nu / e_mod * (t0 - o0 + t1 - o1), False
    hk = (1.0 - props[m, P_BETA]) * props[m, P_EP] if kinematic else 0.0
    k1 = e_mod / (3.0 * (1.0 - nu)) + 2.0 / 3.0 * hk  # eigenvalue of C·P + ⅔H_k on ξx + ξy
    k2 = 2.0 * g + 2.0 / 3.0 * hk  # on ξy − ξx and on the shears
    a1 = x0 + x1
    a2 = x1 - x0
    sh = x2 * x2 + x3 * x3 + x4 * x4
    # bracket [lo, hi]: ξ_eq(Δγ) ≤ q*/(1 + Δγ·k1) (k1 ≤ k2) falls below R·σy(ε̄p) at the first
    # guess of hi; it is only trusted once F(hi) < 0 was seen (softening curves)
    lo = 0.0
    hi = 1.01 * (q_tr / (rf * y0) - 1.0) / k1 if y0 > 0.0 else 1.0 / k1
    sure = False
    # start: the root where both eigenvalues are the mean k one at Δγ = 0 (exact for k1 = k2 and linear
    # hardening); Newton from there takes one or two steps instead of three or four from Δγ = 0
    k_mean = (0.25 * a1 * a1 * k1 + (0.75 * a2 * a2 + 3.0 * sh) * k2) / (q_tr * q_tr)
    slope0 = rf * y0 * k_mean + 2.0 / 3.0 * rf * max(h0, 0.0) * q_tr
    dg = (q_tr - rf * y0) / slope0 if slope0 > 0.0 else hi
    if not dg < hi:
        dg = 0.5 * hi
    at_dg = False  # r1, r2, aa1, aa2 and q are those of the final Δγ: no last evaluation needed
    r1 = r2 = aa1 = aa2 = q = 0.0
    for _it in range(200):
        r1, r2, aa1, aa2, q = _shrunk(dg, k1, k2, a1, a2, sh)
        y, h = _yield(props, m, mc, cs, ce, cx, cy, ep + 2.0 / 3.0 * dg * q, rate)
        f = q - rf * y
        if abs(f) <= _TOL * rf * max(y, y0):
            at_dg = True
            break
        if f > 0.0:
            lo = dg
        else:
            hi = dg
            sure = True
        if sure and hi - lo <= 1e-15 * hi:
            at_dg = True
            break
        # q(Δγ)² = ¼a1²r1² + (¾a2² + 3sh)r2², r = 1/(1 + Δγk): its first and second derivatives give
        # Halley's step (third order: one step from the start is mostly the last)
        g1 = 0.25 * aa1 * aa1 * k1 * r1
        g2 = (0.75 * aa2 * aa2 + 3.0 * sh * r2 * r2) * k2 * r2
        inv_q = 1.0 / q if q > 0.0 else 0.0
        dq = -(g1 + g2) * inv_q  # q' = (q²)'/(2q), (q²)' = −2(g1 + g2)
        ddq = (3.0 * (g1 * k1 * r1 + g2 * k2 * r2) - dq * dq) * inv_q  # q'' = ((q²)''/2 − q'²)/q
        hh = rf * h * 2.0 / 3.0
        slope = dq - hh * (q + dg * dq)
        curv = ddq - hh * (2.0 * dq + dg * ddq)
        den = 2.0 * slope * slope - f * curv
        if slope < 0.0 and den > 0.0:
            nxt = dg - 2.0 * f * slope / den
        else:
            nxt = dg - f / slope if slope < 0.0 else -1.0
        if nxt <= lo or (sure and nxt >= hi):
            if sure:
                nxt = 0.5 * (lo + hi)
            else:  # no root seen yet on the right: widen
                nxt = max(hi, 2.0 * lo)
                hi = 2.0 * nxt
        elif abs(nxt - dg) * k2 <= _STEP:
            dg = nxt
            break
        dg = nxt
    if not at_dg:
        r1, r2, aa1, aa2, q = _shrunk(dg, k1, k2, a1, a2, sh)
    dep = 2.0 / 3.0 * dg * q
    n0 = 0.5 * (aa1 - aa2)
    n1 = 0.5 * (aa1 + aa2)
    n2, n3, n4 = x2 * r2, x3 * r2, x4 * r2
    if kinematic:  # the back stress moves along ξ
        fb = 2.0 / 3.0 * hk * dg
        b0 += fb * n0
        b1 += fb * n1
        b2 += fb * n2
        b3 += fb * n3
        b4 += fb * n4
    s0, s1 = b0 + n0, b1 + n1
    ep_new = ep + dep
    # Δε_zz: elastic −ν/E (Δσx + Δσy), plastic −(Δεp_x + Δεp_y) = −Δγ (ξx + ξy)/3
    dez = -nu / e_mod * (s0 - o0 + s1 - o1) - dg * (n0 + n1) / 3.0
    if mtype == DAMAGE:
        keep = 1.0 - damage(props, m, mc, cs, ce, cx, cy, ep_new)
        if keep <= 0.0 or ep_new >= props[m, P_FAIL]:
            return ep_new, dez, _rupture(sig, back, e, k)
    if ep_new >= props[m, P_FAIL]:
        for i in range(5):
            sig[e, k, i] = 0.0
            if kinematic:
                back[e, k, i] = 0.0
        return ep_new, dez, True
    sig[e, k, 0], sig[e, k, 1], sig[e, k, 2] = keep * s0, keep * s1, keep * (b2 + n2)
    sig[e, k, 3], sig[e, k, 4] = keep * (b3 + n3), keep * (b4 + n4)
    if kinematic:
        back[e, k, 0], back[e, k, 1], back[e, k, 2], back[e, k, 3], back[e, k, 4] = b0, b1, b2, b3, b4
    return ep_new, dez, False


@njit(cache=True, parallel=True)
def update_points(
    mtype, props, mcurve, curve_start, curve_stop, curve_x, curve_y, mat_of, sig, back, epsp, deps, dt, dez, failed
):
    """Batch update of independent points (tests, material drivers).

    mat_of (n,) int64 material row; sig, back (n, 5) [stress] and epsp (n,)
    updated in place (the kernel sees them as (n, 1, 5)); deps (n, 5) strain increments (engineering shears);
    dt [time]; outputs dez (n,) Δε_zz and failed (n,) int8.
    """
    n = sig.shape[0]
    sig3 = sig.reshape((n, 1, 5))
    back3 = back.reshape((n, 1, 5))
    for i in prange(n):
        m = mat_of[i]
        ep, dz, fl = update_point(
            mtype[m],
            props,
            m,
            mcurve,
            curve_start,
            curve_stop,
            curve_x,
            curve_y,
            sig3,
            back3,
            i,
            0,
            epsp[i],
            deps[i, 0],
            deps[i, 1],
            deps[i, 2],
            deps[i, 3],
            deps[i, 4],
            dt,
        )
        epsp[i] = ep
        dez[i] = dz
        failed[i] = 1 if fl else 0


# --- a block of points at once --------------------------------------------------------------------------
# The shell kernel updates the points of a few elements of one material and section in one loop without
# calls or data-dependent branches, which LLVM turns into SIMD code (eight points per instruction with
# AVX-512): the same return mapping as update_point, two Halley steps from the same start, with the
# hardening linear over the step (the curve's segment at ε̄p, rate-scaled). A point whose result does not
# meet update_point's tolerance, or whose ε̄p left its segment, keeps its state and is marked; the caller
# redoes it with update_point.
# The block's scratch P is flat: row R_x of point p at R_x·W + p (W a constant, so LLVM sees that the
# rows never overlap and vectorises without run-time alias checks).
R_D = 0  # 5 rows, input: strain increments Δεx, Δεy, Δγxy, Δγyz, Δγzx
R_DEZ = 5  # output: Δε_zz
R_WK = 6  # output: work per unit volume ½(σ(n) + σ(n+1))·Δε (shears weighted by SHRF)
R_OK = 7  # output: 1 done, 0 state untouched (redo with update_point)
R_FAILED = 8  # output: 1 the point failed in this step
R_O, R_S, R_B = 9, 14, 19  # 5 rows each, inside: stress before and after, back stress
R_EP, R_EPN = 24, 25  # inside: ε̄p before and after
R_Y, R_H, R_TOP = 26, 27, 28  # inside: rate-scaled yield stress at ε̄p, its slope, the ε̄p where the slope ends
R_SEG = 29  # inside: the hardening curve's segment at ε̄p
N_ROWS = 30
W = 160  # columns: up to 16 elements of up to 10 points


@njit(cache=True, error_model="numpy")
def _yield_rows(n, P, kind, props, m, mc, cs, ce, cx, cy, dt, rate):
    """R_Y, R_H, R_TOP of points 0 .. n-1 of P: the yield stress at ε̄p, its
    slope and the end of its segment (as _yield and curve_slope), scaled
    by the rate factor of the step's strain rate if ``rate`` (else
    ``_rate_rows`` may scale them after)."""
    c = mc[m, C_LCSS]
    if kind == ELASTIC:
        for p in range(n):
            P[R_Y * W + p], P[R_H * W + p], P[R_TOP * W + p] = math.inf, 0.0, math.inf
        return
    if c < 0 or ce[c] - cs[c] < 2:
        hs = props[m, P_BETA] * props[m, P_EP] if c < 0 else 0.0
        y0 = props[m, P_SIGY] if c < 0 else cy[cs[c]]
        for p in range(n):
            P[R_Y * W + p] = y0 + hs * P[R_EP * W + p]
            P[R_H * W + p], P[R_TOP * W + p] = hs, math.inf
    else:
        start, stop = cs[c], ce[c]
        for p in range(n):
            P[R_SEG * W + p] = start
        for j in range(start + 1, stop - 1):  # the last point at or below ε̄p (curve_slope's segment)
            xj = cx[j]
            for p in range(n):
                P[R_SEG * W + p] = j if xj <= P[R_EP * W + p] else P[R_SEG * W + p]
        for p in range(n):
            i = int(P[R_SEG * W + p])
            dx = cx[i + 1] - cx[i]
            h = (cy[i + 1] - cy[i]) / dx if dx != 0.0 else 0.0
            P[R_Y * W + p] = cy[i] + h * (P[R_EP * W + p] - cx[i])
            P[R_H * W + p] = h
            P[R_TOP * W + p] = cx[i + 1] if i < stop - 2 else math.inf
    if rate:
        _rate_rows(n, P, props, m, mc, cs, ce, cx, cy, dt)


@njit(cache=True, error_model="numpy")
def _rate_rows(n, P, props, m, mc, cs, ce, cx, cy, dt):
    """R_Y and R_H of points 0 .. n-1 of P scaled by the rate factor of the
    step's strain rate (rate_factor; 1 without rate effects)."""
    if mc[m, C_LCSR] >= 0 or (props[m, P_CS_C] > 0.0 and props[m, P_CS_P] > 0.0):
        for p in range(n):
            rf = rate_factor(
                props,
                m,
                mc,
                cs,
                ce,
                cx,
                cy,
                effective_rate(
                    P[R_D * W + p],
                    P[(R_D + 1) * W + p],
                    P[(R_D + 2) * W + p],
                    P[(R_D + 3) * W + p],
                    P[(R_D + 4) * W + p],
                    dt,
                ),
            )
            P[R_Y * W + p] *= rf
            P[R_H * W + p] *= rf


@njit(cache=True, error_model="numpy", inline="always")
def work_density(o0, o1, o2, o3, o4, s0, s1, s2, s3, s4, d0, d1, d2, d3, d4, ks):
    """Work per unit volume ½(σ(n) + σ(n+1))·Δε of a point, the transverse
    shears weighted by the shear factor ks."""
    return 0.5 * ((o0 + s0) * d0 + (o1 + s1) * d1 + (o2 + s2) * d2 + ks * ((o3 + s3) * d3 + (o4 + s4) * d4))


@njit(cache=True, error_model="numpy", inline="always")
def _trial(P, p, c1, nu, g):
    """Elastic trial stress of point p of P."""
    d0, d1, d2, d3, d4 = (
        P[R_D * W + p],
        P[(R_D + 1) * W + p],
        P[(R_D + 2) * W + p],
        P[(R_D + 3) * W + p],
        P[(R_D + 4) * W + p],
    )
    return (
        P[R_O * W + p] + c1 * (d0 + nu * d1),
        P[(R_O + 1) * W + p] + c1 * (d1 + nu * d0),
        P[(R_O + 2) * W + p] + g * d2,
        P[(R_O + 3) * W + p] + g * d3,
        P[(R_O + 4) * W + p] + g * d4,
    )


@njit(cache=True, error_model="numpy", inline="always")
def _trial_q(P, p, c1, nu, g):
    """Von Mises measure of point p's elastic trial stress less its back stress."""
    t0, t1, t2, t3, t4 = _trial(P, p, c1, nu, g)
    x0, x1 = t0 - P[R_B * W + p], t1 - P[(R_B + 1) * W + p]
    x2, x3, x4 = t2 - P[(R_B + 2) * W + p], t3 - P[(R_B + 3) * W + p], t4 - P[(R_B + 4) * W + p]
    return math.sqrt(max(x0 * x0 - x0 * x1 + x1 * x1 + 3.0 * (x2 * x2 + x3 * x3 + x4 * x4), 0.0))


@njit(cache=True, error_model="numpy")
def _any_yields(n, P, c1, nu, g):
    """Whether the trial stress of any of points 0 .. n-1 of P is above yield."""
    count = 0
    for p in range(n):
        count += 1 if _trial_q(P, p, c1, nu, g) > P[R_Y * W + p] else 0  # as _plastic_block's test
    return count > 0


@njit(cache=True, error_model="numpy")
def _first_yields(n, P, c1, nu, g):
    """``_any_yields`` stopping at the first point above yield: the test
    after the rate factors, on a block where most points yield."""
    for p in range(n):
        if _trial_q(P, p, c1, nu, g) > P[R_Y * W + p]:
            return True
    return False


@njit(cache=True, error_model="numpy")
def _elastic_block(n, P, c1, nu, g, e_mod, ks):
    """Points 0 .. n-1 of P, none of which yields (update_block)."""
    for p in range(n):
        t0, t1, t2, t3, t4 = _trial(P, p, c1, nu, g)
        o0, o1, o2, o3, o4 = (
            P[R_O * W + p],
            P[(R_O + 1) * W + p],
            P[(R_O + 2) * W + p],
            P[(R_O + 3) * W + p],
            P[(R_O + 4) * W + p],
        )
        d0, d1, d2, d3, d4 = (
            P[R_D * W + p],
            P[(R_D + 1) * W + p],
            P[(R_D + 2) * W + p],
            P[(R_D + 3) * W + p],
            P[(R_D + 4) * W + p],
        )
        P[R_S * W + p], P[(R_S + 1) * W + p], P[(R_S + 2) * W + p], P[(R_S + 3) * W + p], P[(R_S + 4) * W + p] = (
            t0,
            t1,
            t2,
            t3,
            t4,
        )
        P[R_EPN * W + p] = P[R_EP * W + p]
        P[R_DEZ * W + p] = -nu / e_mod * (t0 - o0 + t1 - o1)
        P[R_WK * W + p] = work_density(o0, o1, o2, o3, o4, t0, t1, t2, t3, t4, d0, d1, d2, d3, d4, ks)
        P[R_OK * W + p] = 1.0
        P[R_FAILED * W + p] = 0.0


@njit(cache=True, error_model="numpy")
def _plastic_block(n, P, c1, nu, g, e_mod, ks, hk, fail):
    """The return mapping of points 0 .. n-1 of P (update_block)."""
    k1 = e_mod / (3.0 * (1.0 - nu)) + 2.0 / 3.0 * hk
    k2 = 2.0 * g + 2.0 / 3.0 * hk
    for p in range(n):
        d0, d1, d2, d3, d4 = (
            P[R_D * W + p],
            P[(R_D + 1) * W + p],
            P[(R_D + 2) * W + p],
            P[(R_D + 3) * W + p],
            P[(R_D + 4) * W + p],
        )
        o0, o1, o2, o3, o4 = (
            P[R_O * W + p],
            P[(R_O + 1) * W + p],
            P[(R_O + 2) * W + p],
            P[(R_O + 3) * W + p],
            P[(R_O + 4) * W + p],
        )
        b0, b1, b2, b3, b4 = (
            P[R_B * W + p],
            P[(R_B + 1) * W + p],
            P[(R_B + 2) * W + p],
            P[(R_B + 3) * W + p],
            P[(R_B + 4) * W + p],
        )
        ep = P[R_EP * W + p]
        y_ep = P[R_Y * W + p]
        h = 2.0 / 3.0 * P[R_H * W + p]
        t0, t1, t2, t3, t4 = _trial(P, p, c1, nu, g)
        x0, x1, x2, x3, x4 = t0 - b0, t1 - b1, t2 - b2, t3 - b3, t4 - b4
        qq = max(x0 * x0 - x0 * x1 + x1 * x1 + 3.0 * (x2 * x2 + x3 * x3 + x4 * x4), 0.0)
        q_tr = math.sqrt(qq)
        plastic = (q_tr > y_ep) & (q_tr > 0.0)
        elastic = (q_tr <= y_ep) | (q_tr <= 0.0)
        y0 = y_ep if plastic else 0.0
        a1 = x0 + x1
        a2 = x1 - x0
        sh = x2 * x2 + x3 * x3 + x4 * x4
        # start as update_point: the root for equal eigenvalues
        k_mean = (0.25 * a1 * a1 * k1 + (0.75 * a2 * a2 + 3.0 * sh) * k2) / (qq if plastic else 1.0)
        slope0 = y0 * k_mean + max(h, 0.0) * q_tr
        good = slope0 > 0.0
        dg = (q_tr - y0) / slope0 if plastic & good else 0.0
        for _ in range(2):
            r1, r2, aa1, aa2, q = _shrunk(dg, k1, k2, a1, a2, sh)
            f = q - y0 - h * dg * q
            g1 = 0.25 * aa1 * aa1 * k1 * r1
            g2 = (0.75 * aa2 * aa2 + 3.0 * sh * r2 * r2) * k2 * r2
            iq = 1.0 / q if q > 0.0 else 0.0
            dq = -(g1 + g2) * iq
            ddq = (3.0 * (g1 * k1 * r1 + g2 * k2 * r2) - dq * dq) * iq
            slope = dq - h * (q + dg * dq)
            curv = ddq - h * (2.0 * dq + dg * ddq)
            den = 2.0 * slope * slope - f * curv
            step = (slope < 0.0) & (den > 0.0)
            good = good & step
            dg = dg - 2.0 * f * slope / den if plastic & step else dg
        r1, r2, aa1, aa2, q = _shrunk(dg, k1, k2, a1, a2, sh)
        y = y0 + h * dg * q
        f = q - y
        n0 = 0.5 * (aa1 - aa2)
        n1 = 0.5 * (aa1 + aa2)
        n2, n3, n4 = x2 * r2, x3 * r2, x4 * r2
        fb = 2.0 / 3.0 * hk * dg
        if plastic:
            b0 += fb * n0
            b1 += fb * n1
            b2 += fb * n2
            b3 += fb * n3
            b4 += fb * n4
            t0, t1, t2, t3, t4 = b0 + n0, b1 + n1, b2 + n2, b3 + n3, b4 + n4
        ep_new = ep + 2.0 / 3.0 * dg * q
        ok = elastic | (good & (abs(f) <= _TOL * max(y, y0)) & (dg >= 0.0) & (ep_new <= P[R_TOP * W + p]))
        P[R_DEZ * W + p] = -nu / e_mod * (t0 - o0 + t1 - o1) - (dg * (n0 + n1) / 3.0 if plastic else 0.0)
        failed = plastic & (ep_new >= fail)
        if failed:  # as update_point: stress and back stress zero
            t0 = t1 = t2 = t3 = t4 = 0.0
            b0 = b1 = b2 = b3 = b4 = 0.0
        P[R_WK * W + p] = work_density(o0, o1, o2, o3, o4, t0, t1, t2, t3, t4, d0, d1, d2, d3, d4, ks)
        P[R_OK * W + p] = 1.0 if ok else 0.0
        P[R_FAILED * W + p] = 1.0 if failed else 0.0
        P[R_S * W + p], P[(R_S + 1) * W + p], P[(R_S + 2) * W + p], P[(R_S + 3) * W + p], P[(R_S + 4) * W + p] = (
            t0,
            t1,
            t2,
            t3,
            t4,
        )
        P[R_B * W + p], P[(R_B + 1) * W + p], P[(R_B + 2) * W + p], P[(R_B + 3) * W + p], P[(R_B + 4) * W + p] = (
            b0,
            b1,
            b2,
            b3,
            b4,
        )
        P[R_EPN * W + p] = ep_new


@njit(cache=True, error_model="numpy")
def update_block(n, P, kk, nk, sig, back, epsp, ipfail, base, mtype, props, m, mc, cs, ce, cx, cy, ks, dt):
    """Points p = 0 .. n-1 of the block P: point kk[p] of the base + p // len
    element's row of sig, back, epsp, ipfail seen flat (sig (n·nip·5,),
    epsp (n·nip,), the point's row at base + p); points with kk[p] ≥ nk
    or failed are skipped. Material row m (mc and the curve store as
    update_point), shear factor ks, the step dt (rates)."""
    kind = mtype[m]
    if kind == DAMAGE or slot(mc, m, C_TABLE) >= 0:  # the rate table and the damage: update_point's
        for p in range(n):
            P[R_OK * W + p] = 0.0
        return
    kinematic = kind == KINEMATIC
    e_mod, nu, g, c1 = props[m, P_E], props[m, P_PR], props[m, P_G], props[m, P_C1]
    hk = (1.0 - props[m, P_BETA]) * props[m, P_EP] if kinematic else 0.0
    fail = props[m, P_FAIL]
    for p in range(n):  # in: the state (loops of their own, so that the update below reads and writes P alone)
        q5 = 5 * (base + p)
        for i in range(5):
            P[(R_O + i) * W + p] = sig[q5 + i]
        P[R_EP * W + p] = epsp[base + p]
    for p in range(n):
        q5 = 5 * (base + p)
        for i in range(5):
            P[(R_B + i) * W + p] = back[q5 + i] if kinematic else 0.0
    # Cowper–Symonds only raises the yield stress (1 + (ε̇/C)^(1/P) ≥ 1): a block that stays below its static
    # yield is elastic whatever the rate, and skips a power a point (most of an elastic part's cost)
    cowper = mc[m, C_LCSR] < 0 and props[m, P_CS_C] > 0.0 and props[m, P_CS_P] > 0.0
    _yield_rows(n, P, kind, props, m, mc, cs, ce, cx, cy, dt, not cowper)
    plastic = _any_yields(n, P, c1, nu, g)
    if plastic and cowper:
        _rate_rows(n, P, props, m, mc, cs, ce, cx, cy, dt)
        plastic = _first_yields(n, P, c1, nu, g)
    if not plastic:
        _elastic_block(n, P, c1, nu, g, e_mod, ks)
    else:
        _plastic_block(n, P, c1, nu, g, e_mod, ks, hk, fail)
    for p in range(n):  # out: the points done
        if kk[p] < nk and ipfail[base + p] == 0 and P[R_OK * W + p] == 1.0:
            q5 = 5 * (base + p)
            for i in range(5):
                sig[q5 + i] = P[(R_S + i) * W + p]
            epsp[base + p] = P[R_EPN * W + p]
            if kinematic:
                for i in range(5):
                    back[q5 + i] = P[(R_B + i) * W + p]
