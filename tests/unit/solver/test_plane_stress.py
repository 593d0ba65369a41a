"""Plane-stress J2 return mapping (kernels.plane_stress): elastic law,
MAT_024 curve and MAT_003 bilinear hardening in uniaxial tension, mixed
kinematic/isotropic reverse yield, exactness against a 3D radial return
with the returned thickness strain, strain-rate scaling, failure."""

import numpy as np
import pytest

from crashlite.solver.kernels import plane_stress as ps

E, NU, RHO = 210000.0, 0.3, 7.85e-9
G = E / (2 * (1 + NU))
CURVE_EP = np.array([0.0, 0.02, 0.05, 0.1, 0.3])
CURVE_SY = np.array([250.0, 300.0, 340.0, 370.0, 420.0])


def _row(kind=ps.PIECEWISE, sigy=250.0, etan=0.0, beta=1.0, c=0.0, p=0.0, fail=1e21):
    r = np.zeros(ps.N_PROPS)
    r[ps.P_RO], r[ps.P_E], r[ps.P_PR], r[ps.P_G], r[ps.P_C1] = RHO, E, NU, G, E / (1 - NU**2)
    r[ps.P_SIGY], r[ps.P_EP] = sigy, E * etan / (E - etan)
    r[ps.P_BETA], r[ps.P_CS_C], r[ps.P_CS_P], r[ps.P_FAIL] = beta, c, p, fail
    r[ps.P_WAVE] = E / (RHO * (1 - NU**2))
    return r


class Point:
    """One integration point driven through kernels.plane_stress.update_points."""

    def __init__(self, kind, row, curves=(), slots=(-1, -1)):
        self.mtype = np.array([kind], np.int64)
        self.props = row[None, :].copy()
        self.mcurve = np.array([slots], np.int64)
        xs = [np.asarray(c[0], float) for c in curves] or [np.zeros(0)]
        ys = [np.asarray(c[1], float) for c in curves] or [np.zeros(0)]
        sizes = np.array([len(a) for a in xs], np.int64)
        self.cs, self.ce = np.cumsum(sizes) - sizes, np.cumsum(sizes)
        self.cx, self.cy = np.concatenate(xs), np.concatenate(ys)
        self.sig, self.back, self.ep = np.zeros((1, 5)), np.zeros((1, 5)), np.zeros(1)
        self.dez, self.failed = np.zeros(1), np.zeros(1, np.int8)

    def state(self):
        return self.sig.copy(), self.back.copy(), self.ep.copy()

    def set_state(self, st):
        self.sig[:], self.back[:], self.ep[:] = st

    def step(self, de, dt=1.0):
        ps.update_points(
            self.mtype,
            self.props,
            self.mcurve,
            self.cs,
            self.ce,
            self.cx,
            self.cy,
            np.zeros(1, np.int64),
            self.sig,
            self.back,
            self.ep,
            np.asarray(de, float)[None, :],
            dt,
            self.dez,
            self.failed,
        )
        return self.dez[0]

    def uniaxial(self, dex, dt=1.0):
        """Step Δεx with the lateral strain that keeps σy = 0 (secant)."""
        st = self.state()

        def sy(dey):
            self.set_state(st)
            self.step([dex, dey, 0, 0, 0], dt)
            return self.sig[0, 1]

        a, b = -NU * dex, -0.5 * dex
        fa, fb = sy(a), sy(b)
        for _ in range(50):
            if fb == fa or abs(fb) < 1e-11 * max(abs(self.sig[0, 0]), 1.0):
                break
            a, b, fa = b, b - fb * (b - a) / (fb - fa), fb
            fb = sy(b)
        return b


def test_elastic_plane_stress_law_and_thickness_strain():
    pt = Point(ps.ELASTIC, _row(ps.ELASTIC))
    de = np.array([1e-4, -3e-5, 2e-5, 4e-5, -1e-5])
    dez = pt.step(de)
    c1 = E / (1 - NU**2)
    expect = [c1 * (de[0] + NU * de[1]), c1 * (de[1] + NU * de[0]), G * de[2], G * de[3], G * de[4]]
    np.testing.assert_allclose(pt.sig[0], expect, rtol=1e-14)
    assert dez == pytest.approx(-NU / (1 - NU) * (de[0] + de[1]), rel=1e-12)


def test_mat024_uniaxial_follows_the_curve():
    """σx = σy(ε̄p) on the curve and εx = σx/E + ε̄p (uniaxial flow) at every
    step, far inside the 1 % asked of the element."""
    pt = Point(ps.PIECEWISE, _row(), [(CURVE_EP, CURVE_SY)], (0, -1))
    ex = 0.0
    for _ in range(250):
        pt.uniaxial(1e-3)
        ex += 1e-3
        sx, ep = pt.sig[0, 0], pt.ep[0]
        if ep > 0:
            assert sx == pytest.approx(np.interp(ep, CURVE_EP, CURVE_SY), rel=1e-9)
            assert ex == pytest.approx(sx / E + ep, rel=1e-9)
        else:
            assert sx == pytest.approx(E * ex, rel=1e-9)
    assert pt.ep[0] > 0.2  # the path crossed several curve segments


@pytest.mark.parametrize("beta", [0.0, 0.5, 1.0])
def test_mat003_bilinear_hardening_and_reverse_yield(beta):
    """Monotonic: σ = σ0 + Et (ε − σ0/E). Reversal: yield again at
    α − R, α = (1−β)Ep ε̄p the back stress, R = σ0 + βEp ε̄p the radius
    (β = 0 kinematic: Bauschinger σmax − 2σ0; β = 1 isotropic: −σmax)."""
    s0, et = 250.0, 2000.0
    ep_mod = E * et / (E - et)
    pt = Point(ps.KINEMATIC, _row(ps.KINEMATIC, s0, et, beta))
    ex = 0.0
    for _ in range(100):
        pt.uniaxial(5e-4)
        ex += 5e-4
    expect = s0 + et * (ex - s0 / E)
    assert pt.sig[0, 0] == pytest.approx(expect, rel=1e-9)
    epbar = pt.ep[0]
    alpha, radius = (1 - beta) * ep_mod * epbar, s0 + beta * ep_mod * epbar
    assert pt.sig[0, 0] == pytest.approx(alpha + radius, rel=1e-9)
    # unload and reload in compression in small steps: the first plastic step sits on α − R
    first = None
    for _ in range(4000):
        before = pt.ep[0]
        pt.uniaxial(-2e-5)
        if pt.ep[0] > before + 1e-12:
            first = pt.sig[0, 0]
            break
    assert first is not None
    assert first == pytest.approx(alpha - radius, abs=2e-3 * radius + 2e-5 * et)


def _radial_return_3d(sig, alpha, ep, deps, sy_fun, h_iso, h_kin):
    """Reference 3D J2 return (combined linear kinematic, any isotropic
    law), full tensors; deps (3, 3) tensor strain increment."""
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), G
    tr = sig + lam * np.trace(deps) * np.eye(3) + 2 * mu * deps
    xi = tr - np.trace(tr) / 3 * np.eye(3) - alpha
    q = np.sqrt(1.5 * np.sum(xi * xi))
    if q <= sy_fun(ep):
        return tr, alpha, ep
    dl = 0.0
    for _ in range(100):  # q − (3G + H_k) Δλ = σy(ε̄p + Δλ)
        f = q - (3 * mu + h_kin) * dl - sy_fun(ep + dl)
        dl += f / (3 * mu + h_kin + h_iso(ep + dl))
        if abs(f) < 1e-12 * q:
            break
    n = xi / q * 1.5
    return tr - 2 * mu * dl * n, alpha + 2.0 / 3.0 * h_kin * dl * n, ep + dl


def _tensor(v, zz=0.0, shear_scale=1.0):
    x, y, xy, yz, zx = v
    return np.array(
        [
            [x, shear_scale * xy, shear_scale * zx],
            [shear_scale * xy, y, shear_scale * yz],
            [shear_scale * zx, shear_scale * yz, zz],
        ]
    )


@pytest.mark.parametrize("case", ["mat024_curve", "mat003_kinematic"])
def test_exact_plane_stress_against_3d_return_with_the_thickness_strain(case):
    """Random multiaxial increments (transverse shears included): the 3D
    radial return fed with (Δεx, Δεy, Δε_zz returned, shears) from the same
    3D state gives σzz = 0 to 1e-8 of the stress and the same in-plane
    stresses, back stress and ε̄p."""
    rng = np.random.default_rng(4)
    if case == "mat024_curve":
        pt = Point(ps.PIECEWISE, _row(), [(CURVE_EP, CURVE_SY)], (0, -1))

        def sy_fun(e):
            return np.interp(e, CURVE_EP, CURVE_SY) if e <= CURVE_EP[-1] else CURVE_SY[-1] + (e - CURVE_EP[-1]) * 250.0

        slopes = np.diff(CURVE_SY) / np.diff(CURVE_EP)
        h_iso = lambda e: slopes[min(max(np.searchsorted(CURVE_EP, e, side="right") - 1, 0), len(slopes) - 1)]  # noqa: E731
        h_kin = 0.0
    else:
        et, beta = 5000.0, 0.3
        hp = E * et / (E - et)
        pt = Point(ps.KINEMATIC, _row(ps.KINEMATIC, 250.0, et, beta))
        sy_fun, h_iso, h_kin = (lambda e: 250.0 + beta * hp * e), (lambda e: beta * hp), (1 - beta) * hp
    sig3, alpha3, ep3 = np.zeros((3, 3)), np.zeros((3, 3)), 0.0
    plastic_steps = 0
    for k in range(60):
        de = rng.normal(size=5) * 8e-4
        de[:2] += 6e-4 * np.array([np.cos(k / 9), np.sin(k / 7)])
        before = pt.ep[0]
        dez = pt.step(de)
        plastic_steps += pt.ep[0] > before
        deps = _tensor([de[0], de[1], 0.5 * de[2], 0.5 * de[3], 0.5 * de[4]], zz=dez)
        sig3, alpha3, ep3 = _radial_return_3d(sig3, alpha3, ep3, deps, sy_fun, h_iso, h_kin)
        scale = np.abs(sig3).max()
        assert abs(sig3[2, 2]) < 1e-8 * scale
        got = _tensor(pt.sig[0], zz=0.0)
        np.testing.assert_allclose(got, sig3, atol=1e-8 * scale)
        beta_ps = _tensor(pt.back[0])
        alpha_ps = beta_ps - np.trace(beta_ps) / 3 * np.eye(3)  # deviatoric back stress of the plane form
        np.testing.assert_allclose(alpha_ps, alpha3, atol=1e-8 * scale)
        assert pt.ep[0] == pytest.approx(ep3, rel=1e-8, abs=1e-14)
    assert plastic_steps > 20


@pytest.mark.parametrize("kind", [ps.PIECEWISE, ps.KINEMATIC])
def test_cowper_symonds_scales_the_yield_stress(kind):
    """At an axial strain rate ε̇ the flow stress at a given ε̄p is the
    static one times 1 + (ε̇/C)^(1/P) (within 1 %)."""
    c, p = 40.0, 5.0
    s0, et = 250.0, 1000.0
    static = Point(kind, _row(kind, s0, et, 1.0))
    dynamic = Point(kind, _row(kind, s0, et, 1.0, c=c, p=p))
    rate, dex = 200.0, 2e-4
    dt = dex / rate
    for _ in range(200):
        static.uniaxial(dex, dt)
        dynamic.uniaxial(dex, dt)
    factor = 1.0 + (rate / c) ** (1.0 / p)
    sy_static_at = s0 + et * E / (E - et) * dynamic.ep[0]
    assert dynamic.sig[0, 0] == pytest.approx(factor * sy_static_at, rel=0.01)
    assert dynamic.sig[0, 0] / static.sig[0, 0] > 1.5  # the rate effect is large here, not a rounding


def test_lcsr_curve_scales_the_yield_stress():
    rows = _row(ps.PIECEWISE, 250.0, 0.0)
    pt = Point(ps.PIECEWISE, rows, [([0.0, 100.0, 1000.0], [1.0, 1.4, 2.0])], (-1, 0))
    rate, dex = 550.0, 2e-4
    for _ in range(50):
        pt.uniaxial(dex, dex / rate)
    assert pt.sig[0, 0] == pytest.approx(250.0 * np.interp(rate, [0, 100, 1000], [1.0, 1.4, 2.0]), rel=0.01)


def test_failure_strain_zeroes_the_stress():
    pt = Point(ps.PIECEWISE, _row(ps.PIECEWISE, 250.0, 1000.0, fail=0.05))
    for k in range(200):  # noqa: B007 (k is read after the loop)
        pt.uniaxial(1e-3)
        if pt.failed[0]:
            break
    assert pt.failed[0] == 1
    assert pt.ep[0] >= 0.05
    assert np.all(pt.sig[0] == 0.0)
    assert 0.05 < k * 1e-3 < 0.06


def test_elastic_unloading_inside_the_surface():
    pt = Point(ps.PIECEWISE, _row(ps.PIECEWISE, 250.0, 1000.0))
    for _ in range(10):
        pt.uniaxial(1e-3)
    ep = pt.ep[0]
    sx = pt.sig[0, 0]
    pt.uniaxial(-1e-4)
    assert pt.ep[0] == ep
    assert pt.sig[0, 0] == pytest.approx(sx - E * 1e-4, rel=1e-9)


def _block_case(kind, row, n_el, nip, rng, scale):
    """Random states and increments of n_el elements of nip points, as the
    shell kernel lays them out for update_block."""
    n = n_el * nip
    sig = rng.normal(size=(n_el, nip, 5)) * 120.0
    back = rng.normal(size=(n_el, nip, 5)) * 30.0 if kind == ps.KINEMATIC else np.zeros((n_el, nip, 5))
    ep = np.abs(rng.normal(size=(n_el, nip))) * 0.02
    ipfail = np.zeros((n_el, nip), np.int8)
    ipfail[0, 1] = 1  # a failed point: left alone
    de = rng.normal(size=(n, 5)) * scale
    return sig, back, ep, ipfail, de


RATE_CURVE = ([0.0, 10.0, 1000.0], [1.0, 1.2, 1.6])
BLOCK_CASES = {  # kind, material row, curves (ε̄p or rate, value), slots (LCSS, LCSR)
    "elastic": (ps.ELASTIC, _row(ps.ELASTIC), (), (-1, -1)),
    "mat024": (ps.PIECEWISE, _row(sigy=250.0, etan=1000.0), (), (-1, -1)),
    "mat003": (ps.KINEMATIC, _row(ps.KINEMATIC, sigy=200.0, etan=2000.0, beta=0.4), (), (-1, -1)),
    "failure": (ps.PIECEWISE, _row(sigy=250.0, etan=500.0, fail=0.03), (), (-1, -1)),
    "curve": (ps.PIECEWISE, _row(), ((CURVE_EP, CURVE_SY),), (0, -1)),
    "cowper-symonds": (ps.PIECEWISE, _row(c=40.0, p=5.0), ((CURVE_EP, CURVE_SY),), (0, -1)),
    "mat003 rates": (ps.KINEMATIC, _row(ps.KINEMATIC, sigy=200.0, etan=2000.0, beta=0.4, c=40.0, p=5.0), (), (-1, -1)),
    "lcsr": (ps.PIECEWISE, _row(), ((CURVE_EP, CURVE_SY), RATE_CURVE), (0, 1)),
}


@pytest.mark.parametrize("case", list(BLOCK_CASES))
@pytest.mark.parametrize("scale", [1e-5, 3e-3], ids=["small", "large"])
def test_vectorised_block_equals_update_point(case, scale):
    """update_block (the shell kernel's SIMD pass over a block of points)
    gives update_point's stresses, back stresses, ε̄p, Δε_zz and failures
    (to 1e-9 of the stresses: both converge to 1e-10 of the yield stress),
    the work ½(σn + σn+1)·Δε, with linear hardening, curves and rate
    effects, and leaves failed points, points past NIP and the points it
    declines (ε̄p past its curve segment) exactly as they were."""
    kind, row, curves, slots = BLOCK_CASES[case]
    pt = Point(kind, row, curves, slots)  # the material and curve store
    rng = np.random.default_rng(7)
    n_el, nip, nk = 6, 4, 3  # the last point of each element is past this section's NIP
    sig, back, ep, ipfail, de = _block_case(kind, row, n_el, nip, rng, scale)
    dt = 1e-4
    ks = 0.8333
    P = np.zeros(ps.N_ROWS * ps.W)
    n = n_el * nip
    for i in range(5):
        P[(ps.R_D + i) * ps.W : (ps.R_D + i) * ps.W + n] = de[:, i]
    kk = np.arange(ps.W) % nip
    s1, b1, e1, f1 = sig.copy(), back.copy(), ep.copy(), ipfail.copy()
    ps.update_block(
        n,
        P,
        kk,
        nk,
        s1.reshape(-1),
        b1.reshape(-1),
        e1.reshape(-1),
        f1.reshape(-1),
        0,
        pt.mtype,
        pt.props,
        0,
        pt.mcurve,
        pt.cs,
        pt.ce,
        pt.cx,
        pt.cy,
        ks,
        dt,
    )
    row_of = lambda r: P[r * ps.W : r * ps.W + n]  # noqa: E731
    ok, failed = row_of(ps.R_OK), row_of(ps.R_FAILED)
    live = (kk[:n] < nk) & (ipfail.reshape(-1) == 0)
    assert ok[live].mean() > (0.5 if curves else 0.9)  # the pass declines few points
    if curves and scale > 1e-4:
        assert (ok[live] == 0.0).any()  # and here some: past their segment
    ref_sig, ref_back, ref_ep = sig.reshape(-1, 5).copy(), back.reshape(-1, 5).copy(), ep.reshape(-1).copy()
    dez, fl = np.zeros(n), np.zeros(n, np.int8)
    ps.update_points(
        pt.mtype,
        pt.props,
        pt.mcurve,
        pt.cs,
        pt.ce,
        pt.cx,
        pt.cy,
        np.zeros(n, np.int64),
        ref_sig,
        ref_back,
        ref_ep,
        de,
        dt,
        dez,
        fl,
    )
    tol = 1e-9 * np.abs(ref_sig).max()
    done = live & (ok == 1.0)
    np.testing.assert_allclose(s1.reshape(-1, 5)[done], ref_sig[done], atol=tol)
    np.testing.assert_allclose(b1.reshape(-1, 5)[done], ref_back[done], atol=tol)
    np.testing.assert_allclose(e1.reshape(-1)[done], ref_ep[done], rtol=1e-9, atol=1e-14)
    np.testing.assert_allclose(row_of(ps.R_DEZ)[done], dez[done], rtol=1e-8, atol=1e-14)
    np.testing.assert_array_equal(failed[done] == 1.0, fl[done] == 1)
    if kind != ps.ELASTIC and scale > 1e-4:
        assert (e1.reshape(-1) > ep.reshape(-1))[done].sum() > n // 2  # the case yields
    if kind == ps.PIECEWISE and row[ps.P_FAIL] < 1.0 and scale > 1e-4:
        assert failed[done].sum() > 0  # the case exercises failure
    o, s = sig.reshape(-1, 5), ref_sig
    work = 0.5 * ((o + s) * de)[:, :3].sum(axis=1) + 0.5 * ks * ((o + s) * de)[:, 3:].sum(axis=1)
    np.testing.assert_allclose(row_of(ps.R_WK)[done], work[done], rtol=1e-8, atol=1e-9 * np.abs(work).max())
    untouched = ~done
    np.testing.assert_array_equal(s1.reshape(-1, 5)[untouched], sig.reshape(-1, 5)[untouched])
    np.testing.assert_array_equal(e1.reshape(-1)[untouched], ep.reshape(-1)[untouched])
    np.testing.assert_array_equal(f1, ipfail)  # the caller marks failures


@pytest.mark.parametrize("peak", [1.2, 8.0], ids=["above-static-below-dynamic", "above-dynamic"])
def test_block_between_the_static_and_the_rate_scaled_yield(peak):
    """Cowper–Symonds only raises the yield stress, so update_block first
    tests a block against its static yield and scales by the rate only
    where some point passes it: a point whose trial stress lies above the
    static yield but below the rate-scaled one stays elastic (σ = the
    trial, ε̄p kept), one above both yields; both as update_point."""
    kind, row, curves, slots = BLOCK_CASES["cowper-symonds"]
    pt = Point(kind, row, curves, slots)
    dt = 1e-6
    dex = np.array([1.2, peak]) * 250.0 / E  # trial σx = 1.2 and `peak` times the static yield
    n = 2
    de = np.stack([dex, -NU * dex, 0 * dex, 0 * dex, 0 * dex], axis=1)
    rate = np.sqrt(2.0 / 3.0 * (1 + NU**2 + (1 - NU) ** 2)) * dex / dt
    dynamic = 250.0 * (1.0 + (rate / 40.0) ** 0.2)
    assert dynamic[0] > 2.0 * 300.0  # the first point is well inside the rate-scaled surface
    P = np.zeros(ps.N_ROWS * ps.W)
    for i in range(5):
        P[(ps.R_D + i) * ps.W : (ps.R_D + i) * ps.W + n] = de[:, i]
    sig, back, ep, ipf = np.zeros(5 * n), np.zeros(5 * n), np.zeros(n), np.zeros(n, np.int8)
    kk = np.zeros(ps.W, np.int64)
    ps.update_block(n, P, kk, 1, sig, back, ep, ipf, 0, pt.mtype, pt.props, 0, pt.mcurve, pt.cs, pt.ce, pt.cx, pt.cy,
                    0.8333, dt)  # fmt: skip
    assert P[ps.R_OK * ps.W] == 1.0 and P[ps.R_OK * ps.W + 1] == 1.0
    assert sig[0] == pytest.approx(1.2 * 250.0, rel=1e-12) and ep[0] == 0.0  # elastic: the rate holds it
    ref_sig, ref_back, ref_ep = np.zeros((n, 5)), np.zeros((n, 5)), np.zeros(n)
    ps.update_points(pt.mtype, pt.props, pt.mcurve, pt.cs, pt.ce, pt.cx, pt.cy, np.zeros(n, np.int64), ref_sig,
                     ref_back, ref_ep, de, dt, np.zeros(n), np.zeros(n, np.int8))  # fmt: skip
    np.testing.assert_allclose(sig.reshape(n, 5), ref_sig, atol=1e-9 * np.abs(ref_sig).max())
    np.testing.assert_allclose(ep, ref_ep, rtol=1e-9, atol=1e-14)
    if peak > 3.5:
        assert ep[1] > 0.0 and sig[5] < peak * 250.0  # the second point yields at its rate-scaled stress
