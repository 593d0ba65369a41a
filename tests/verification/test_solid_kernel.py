"""8-node solid (ELFORM 1) against analytic answers: patch test, rigid
motions, time step and masses, uniaxial stress (E, ν; MAT_024 curve),
elastic wave in a bar, honeycomb crush to compaction, crushable foam
loading and unloading, hourglass energy, energy balance, thread-count
independence."""

import math
from types import SimpleNamespace

import numba
import numpy as np
import pytest

from crashlite.solver import run
from crashlite.solver.solids import lumped_mass

from _solid_driver import Driver, brick_mesh, deck_text, group_from_deck

E, NU, RHO = 210000.0, 0.3, 7.85e-9  # MPa, -, t/mm³
LAM, MU = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
STEEL = f"*MAT_ELASTIC\n1,{RHO},{E},{NU}"


def _sym(sig):
    """(6,) Voigt xx yy zz xy yz zx -> (3, 3)."""
    return np.array([[sig[0], sig[3], sig[5]], [sig[3], sig[1], sig[4]], [sig[5], sig[4], sig[2]]])


def _one_step(g, x_mid, v, dt):
    """One force evaluation with the mid-step shape x_mid and velocity v:
    x(n+1) = x_mid + ½Δt·v. Returns the nodal forces (n, 3)."""
    st = SimpleNamespace(x=x_mid + 0.5 * dt * v, v=v, dt=dt, t=dt, f=np.zeros_like(x_mid))
    g.forces(st)
    return st.f


def _distorted_block(seed=3):
    """2x2x2 block of 10 mm cubes with its interior node and the in-plane
    positions of the face nodes moved (outer faces stay planar)."""
    x, conn = brick_mesh(2, 2, 2, 10.0, 10.0, 10.0)
    rng = np.random.default_rng(seed)
    d = rng.uniform(-2.0, 2.0, x.shape)
    for k in range(3):  # nodes on a face of the block keep that coordinate
        d[np.isclose(x[:, k], 0.0) | np.isclose(x[:, k], 20.0), k] = 0.0
    return x + d, conn


GRAD = np.array([[1.0, 0.3, -0.2], [0.1, -0.5, 0.4], [0.2, 0.0, 0.7]])  # velocity gradient [1/s]


@pytest.mark.parametrize("ihq", [1, 2, 3, 4, 5])
def test_patch_linear_velocity_gives_uniform_stress_and_interior_equilibrium(tmp_path, ihq):
    """v = L·x on a distorted 2x2x2 patch: every element gets the same
    strain rate sym(L) and the stress C:sym(L)·Δt to round-off; the interior
    node and the in-face nodes are in equilibrium, the block face carries
    no hourglass force (IHQ 1 only on an undistorted patch, where its base
    vectors are orthogonal to linear fields), the forces' power in the
    velocity field is −V·σ:L, Σf = 0, Σx×f = 0."""
    x, conn = _distorted_block() if ihq != 1 else brick_mesh(2, 2, 2, 10.0, 10.0, 10.0)
    g, _, _ = group_from_deck(tmp_path, deck_text(x, conn, STEEL, hourglass=f"1,{ihq},0.1"))
    dt = 1e-7
    v = x @ GRAD.T
    f = _one_step(g, x, v, dt)
    d = 0.5 * (GRAD + GRAD.T) * dt
    expect = LAM * np.trace(d) * np.eye(3) + 2 * MU * d
    scale = np.abs(expect).max()
    for e in range(len(conn)):
        np.testing.assert_allclose(_sym(g.st.sig[e]), expect, rtol=0, atol=1e-9 * scale)
    fscale = np.abs(f).max()
    assert np.abs(g.st.hgq).max() < 1e-9 * fscale
    centre = np.flatnonzero(~np.any(np.isclose(x, 0.0) | np.isclose(x, 20.0), axis=1))
    assert len(centre) == 1
    assert np.abs(f[centre]).max() < 1e-9 * fscale
    xn = x + 0.5 * dt * v  # the forces act at t(n+1): Σ_a b_a ⊗ x_a = V·I there
    vol = g.st.vol.sum()
    sig_total = _sym(g.st.sig[0] + g.st.sv[0])
    assert np.einsum("ij,ij->", f, xn @ GRAD.T) == pytest.approx(-vol * np.einsum("ij,ij->", sig_total, GRAD),
                                                                 rel=1e-9)
    assert np.abs(f.sum(axis=0)).max() < 1e-9 * fscale
    assert np.abs(np.cross(xn, f).sum(axis=0)).max() < 1e-9 * fscale * 20.0


@pytest.mark.parametrize("shape", ["wedge", "tetrahedron"])
def test_patch_degenerate_wedge_and_tetrahedron(tmp_path, shape):
    """Repeated-node wedges (N1 N2 N3 N4 N5 N5 N6 N6) and tetrahedra
    (N1 N2 N3 N4 N4 N4 N4 N4, LS-DYNA's input): exact volume, uniform
    strain rate under a linear velocity field, forces in balance, row-sum
    lumped masses (ρV/6, ρV/4 per node)."""
    if shape == "wedge":
        x = np.array([[0, 0, 0], [10, 0, 0], [10, 8, 0], [0, 8, 0], [1, 0, 9], [2, 8, 9]], float)
        conn = np.array([[0, 1, 2, 3, 4, 4, 5, 5]])
        vol = 0.5 * 10 * 9 * 8  # prism: triangle (x, z) × depth y (top edge sheared: same volume)
        k = 6
    else:
        x = np.array([[0, 0, 0], [10, 0, 0], [1, 9, 0], [2, 3, 8]], float)
        conn = np.array([[0, 1, 2, 3, 3, 3, 3, 3]])
        vol = abs(np.linalg.det(x[1:] - x[0])) / 6.0
        k = 4
    g, _, _ = group_from_deck(tmp_path, deck_text(x, conn, STEEL, hourglass="1,4,0.1"))
    assert g.s.vol0[0] == pytest.approx(vol, rel=1e-12)
    np.testing.assert_allclose(lumped_mass(g.s, len(x)), RHO * vol / k, rtol=1e-12)
    dt = 1e-7
    f = _one_step(g, x, x @ GRAD.T, dt)
    d = 0.5 * (GRAD + GRAD.T) * dt
    expect = LAM * np.trace(d) * np.eye(3) + 2 * MU * d
    np.testing.assert_allclose(_sym(g.st.sig[0]), expect, rtol=0, atol=1e-9 * np.abs(expect).max())
    assert np.abs(f.sum(axis=0)).max() < 1e-9 * np.abs(f).max()


def _rotation(axis, angle):
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * k @ k


@pytest.mark.parametrize("ihq", [1, 4])
def test_rigid_translation_and_large_rotation_give_no_stress(tmp_path, ihq):
    """A distorted block moved rigidly (translation, then 120° about a
    skew axis in 12 steps of 10°): no stress, no strain energy, no
    hourglass energy, no nodal force; a prestress turns with the body."""
    x, conn = _distorted_block()
    g, _, _ = group_from_deck(tmp_path, deck_text(x, conn, STEEL, hourglass=f"1,{ihq},0.1"))
    dt = 1e-6
    f = _one_step(g, x, np.tile([3000.0, -1000.0, 500.0], (len(x), 1)), dt)
    assert np.abs(g.st.sig).max() < 1e-9 and np.abs(f).max() < 1e-9
    c = x.mean(axis=0)
    pre = np.array([100.0, -50.0, 30.0, 20.0, -10.0, 5.0])
    g.st.sig[:] = pre
    axis, n, total = [1.0, 2.0, 2.0], 12, math.radians(120.0)
    xa = x.copy()
    for k in range(1, n + 1):  # exact rigid motion between the step ends: v = (x(n+1) − x(n)) / Δt
        xb = c + (x - c) @ _rotation(axis, total * k / n).T
        st = SimpleNamespace(x=xb, v=(xb - xa) / dt, dt=dt, t=k * dt, f=np.zeros_like(x))
        g.forces(st)
        xa = xb
    r = _rotation(axis, total)
    for e in range(len(conn)):
        np.testing.assert_allclose(_sym(g.st.sig[e]), r @ _sym(pre) @ r.T, atol=1e-9 * 100.0)
    assert np.abs(g.energy).max() < 1e-12 * 100.0 * g.s.vol0.sum()
    if ihq == 4:  # stiffness hourglass: no hourglass displacement in a rigid motion
        assert np.abs(g.st.hgq).max() < 1e-9 and np.abs(g.hourglass).max() < 1e-12


def test_critical_time_step_is_volume_over_largest_face_and_wave_speed(tmp_path):
    """Δt = L/c with L = V / largest face area and c = √((K + 4G/3)/ρ) at
    rest; under compression the bulk viscosity shortens it to
    L / (Q + √(Q² + c²)), Q = Q2·c + Q1·L·|tr D|."""
    x, conn = brick_mesh(1, 1, 1, 10.0, 6.0, 4.0)
    g, _, _ = group_from_deck(tmp_path, deck_text(x, conn, STEEL))
    c = math.sqrt((LAM + 2 * MU) / RHO)
    st = SimpleNamespace(x=x, v=np.zeros_like(x), dt=0.0, t=0.0, f=np.zeros_like(x))
    g.forces(st)
    le = 240.0 / 60.0
    assert g.critical_dt(st) == pytest.approx(le / c, rel=1e-12)
    rate = -200.0  # uniform compression along x [1/s]
    v = np.zeros_like(x)
    v[:, 0] = rate * x[:, 0]
    dt = 1e-7
    xm = x.copy()
    st = SimpleNamespace(x=xm + 0.5 * dt * v, v=v, dt=dt, t=dt, f=np.zeros_like(x))
    g.forces(st)
    le = g.st.vol[0] / (60.0 * (1.0 + 0.5 * dt * rate))  # the largest face (x-y) shortens with x
    rho = RHO * 240.0 / g.st.vol[0]
    c = math.sqrt((LAM + 2 * MU) / rho)
    q = 0.06 * c + 1.5 * le * abs(rate)
    assert g.critical_dt(st) == pytest.approx(le / (q + math.sqrt(q * q + c * c)), rel=1e-9)


def _slab(nx, ny, nz, h):
    x, conn = brick_mesh(nx, ny, nz, h, h, h)
    return x, conn, [np.isclose(x[:, k], 0.0) for k in range(3)]


def _uniaxial_stress(tmp_path, material, strain, t_load, extra="", unload=False):
    """One 10 mm cube pulled (strain > 0) or pushed along x at a constant
    true strain rate on symmetry planes x = y = z = 0, sides free (uniaxial
    stress); optionally driven back to its length. Returns the group and
    records of (log strain x, log strain y, σ, face force / current area)."""
    x, conn, sym = _slab(1, 1, 1, 10.0)
    g, _, _ = group_from_deck(tmp_path, deck_text(x, conn, material, extra=extra))
    fixed = np.stack(sym, axis=1)
    far = np.flatnonzero(np.isclose(x[:, 0], 10.0))
    rate = math.log(1.0 + strain) / t_load
    ramp = 0.2 * t_load  # a smooth start: little lateral ringing in the undamped cube

    def vel(t):  # constant true strain rate after a short smooth start; reversed after t_load to unload
        if t < t_load or not unload:
            return rate * 10.0 * math.exp(rate * t) * min(t / ramp, 1.0) ** 2
        return -rate * 10.0 * math.exp(rate * (2.0 * t_load - t))

    dr = Driver(g, x, fixed=fixed, driven=[(far, 0, vel)])
    rows = []

    def rec(d, v_n):
        xs = d.st.x
        lx, ly = xs[far, 0].mean(), xs[np.isclose(x[:, 1], 10.0), 1].mean()
        area = ly * xs[np.isclose(x[:, 2], 10.0), 2].mean()
        rows.append((math.log(lx / 10.0), math.log(ly / 10.0), g.st.sig[0].copy(), d.reaction[far, 0].sum() / area,
                     d.balance(v_n)))

    dr.run(t_load * (2.0 if unload else 1.0), rec)
    return g, rows


def test_elastic_cube_in_uniaxial_stress_gives_young_modulus_and_poisson_ratio(tmp_path):
    """Slowly stretched cube (0.2 % in 200 wave transits): σxx / εxx = E,
    −εyy / εxx = ν (log strains, hypoelastic), lateral stresses ≈ 0, the
    reaction on the driven face equals σxx; energy balance within 1 %."""
    g, rows = _uniaxial_stress(tmp_path, STEEL, 0.002, 2e-4)
    ex, ey, sig, face, (err, scale) = rows[-1]
    assert sig[0] / ex == pytest.approx(E, rel=5e-3)
    assert -ey / ex == pytest.approx(NU, rel=5e-3)
    assert np.abs(sig[1:]).max() < 5e-3 * sig[0]
    assert face == pytest.approx(sig[0], rel=5e-3)
    assert abs(err) < 0.01 * scale
    assert g.energy.sum() == pytest.approx(0.5 * sig[0] * ex * 1000.0, rel=0.01)


def _curve_points():
    """MAT_024 yield curve: σy = 250 + 400·εp^0.4 MPa sampled to εp = 0.5."""
    ep = np.concatenate([[0.0], np.geomspace(1e-3, 0.5, 14)])
    return ep, 250.0 + 400.0 * ep ** 0.4


def test_mat024_uniaxial_stress_follows_its_curve(tmp_path):
    """MAT_024 (LCSS curve) cube pulled to 20 % log strain: the true stress
    is the curve at the plastic strain ε − σ/E within 1 % (from 1 % plastic
    strain on, once the lateral ringing set off by yielding has died out),
    the element's effective plastic strain is that value, lateral stresses
    stay ≈ 0, energy balance within 1 %."""
    ep, sy = _curve_points()
    curve = "*DEFINE_CURVE\n2\n" + "\n".join(f"{float(a)!r},{float(b)!r}" for a, b in zip(ep, sy))
    mat = f"*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,{RHO},{E},{NU},0.0,0.0,0.0\n0.0,0.0,2"
    g, rows = _uniaxial_stress(tmp_path, mat, math.exp(0.2) - 1.0, 1e-3, extra=curve)
    checked = 0
    for ex, ey, sig, face, (err, scale) in rows:
        p = ex - sig[0] / E
        if p < 0.01:
            continue
        assert sig[0] == pytest.approx(np.interp(p, ep, sy), rel=0.01)
        assert abs(face - sig[0]) < 0.01 * sig[0]
        assert abs(err) < 0.01 * scale
        checked += 1
    assert checked > 100
    assert g.st.epsp[0] == pytest.approx(rows[-1][0] - rows[-1][2][0] / E, rel=0.01)
    assert np.abs(rows[-1][2][1:]).max() < 0.01 * rows[-1][2][0]


def test_mat024_fail_erodes_the_element(tmp_path):
    """FAIL = 0.05: the element is deleted once its plastic strain reaches
    5 % and carries no force afterwards."""
    mat = f"*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,{RHO},{E},{NU},250.0,1000.0,0.05\n0.0,0.0"
    g, rows = _uniaxial_stress(tmp_path, mat, 0.1, 5e-4)
    assert g.st.alive[0] == 0 and g.eroded == 1
    faces = np.array([r[3] for r in rows])
    ex = np.array([r[0] for r in rows])
    assert faces.max() > 250.0
    assert np.all(np.abs(faces[ex > 0.056]) < 1e-3 * faces.max())  # the driven nodes' own m·a only
    assert np.all(ex[faces > 1.0] < 0.05 + 250.0 / E * 2)
