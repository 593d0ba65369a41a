"""The fully integrated shell, LS-DYNA ELFORM 16 (kernels.shell_full):
membrane and bending patch tests on a distorted mesh, the zero-energy
modes of a free element, a coarse and a thin cantilever (no shear
locking), a dynamic cantilever (first frequency, deflection, energy
balance), a plastic bending strip against the one-point element, and the
section set-up."""

import math
from types import SimpleNamespace

import numpy as np
import pytest
from _shell_driver import deck_text, grid, run_deck

from crashlite import read_deck
from crashlite.solver.shells import build_shells

E, NU, RHO = 210000.0, 0.3, 7.85e-9
ELASTIC = f"*MAT_ELASTIC\n1,{RHO},{E},{NU}"
DISTORTED = np.array(
    [[0, 0, 0], [4.0, 0, 0], [10, 0, 0], [0, 5, 0], [6.5, 4.2, 0], [10, 6, 0], [0, 10, 0], [3.5, 10, 0], [10, 10, 0]],
    float,
)
PATCH = np.array([[1, 2, 5, 4], [2, 3, 6, 5], [4, 5, 8, 7], [5, 6, 9, 8]])


def _group(tmp_path, xyz, quads, section="1,16,0.8333,2\n1.0", material=ELASTIC, extra="", warnings=None):
    p = tmp_path / "shells.k"
    p.write_text(deck_text(xyz, quads, section, material, extra + "*CONTROL_TERMINATION\n1.0\n"))
    model = read_deck(p)
    problems = []
    g = build_shells(model, [], problems, warnings)
    assert not problems, problems
    return g, model


def _step(g, x, v, w, dt):
    st = SimpleNamespace(x=x, v=v, w=w, dt=dt, f=np.zeros_like(x), moment=np.zeros_like(x))
    g.forces(st)
    return st.f, st.moment


def _cmat(nu=NU):
    c1 = E / (1 - nu**2)
    return np.array([[c1, c1 * nu, 0], [c1 * nu, c1, 0], [0, 0, E / (2 * (1 + nu))]])


def _frames(x, conn):
    """(n, 3, 3) columns e1 e2 e3 of each flat (z = 0) element's frame: e1 along side 1-2."""
    out = []
    for q in conn - 1:
        e1 = x[q[1]] - x[q[0]]
        e1 /= np.linalg.norm(e1)
        out.append(np.stack([e1, np.cross([0.0, 0.0, 1.0], e1), [0.0, 0.0, 1.0]], axis=1))
    return out


def _voigt(t):
    return np.array([t[0, 0], t[1, 1], 2 * t[0, 1]])


@pytest.mark.parametrize("mixed", [False, True], ids=["elform16", "beside-BT-and-triangles"])
def test_membrane_patch_constant_stress(tmp_path, mixed):
    """v = L·x in the plane on a distorted four-element patch: every one
    of the 4 × 3 points of every element gets the stress C·sym(∇v)Δt of
    the mid-step configuration (1e-8 relative), the interior node is in
    equilibrium and the forces and their moments sum to zero (1e-12).
    ``mixed``: the patch with two ELFORM 16 quadrilaterals, an ELFORM 2
    one and two triangles of the ELFORM 16 part in one model."""
    conn = PATCH.copy()
    extra = ""
    if mixed:
        conn = np.array([[1, 2, 5, 4], [2, 3, 6, 5], [4, 5, 8, 7], [5, 6, 9, 9], [5, 9, 8, 8]])
    g, model = _group(tmp_path, DISTORTED, conn, section="1,16,0.8333,3\n1.5", extra=extra)
    if mixed:  # the third element as ELFORM 2 through a second part
        p = tmp_path / "shells.k"
        text = p.read_text().replace("\n3,1,4,5,8,7\n", "\n3,2,4,5,8,7\n")
        text = text.replace("*END", "*PART\nbt\n2,2,1,0,1\n*SECTION_SHELL\n2,2,0.8333,3\n1.5\n*END")
        p.write_text(text)
        model = read_deck(p)
        problems = []
        g = build_shells(model, [], problems)
        assert not problems, problems
        assert g.s.full.tolist() == [1, 1, 0, 0, 0] and g.s.tri.tolist() == [0, 0, 0, 1, 1]
    lg = np.array([[1.0, 0.4, 0], [-0.2, -0.6, 0], [0, 0, 0]])
    dt = 1e-13  # the frames turn by O(Δt|∇v|) between mid-step and end: kept below round-off
    x0 = model.nodes.xyz
    v = x0 @ lg.T
    x = x0 + dt * v
    f, m = _step(g, x, v, np.zeros_like(x), dt)
    xm = x - 0.5 * dt * v
    grad = np.linalg.solve(np.eye(3) + 0.5 * dt * lg, lg)
    d = 0.5 * (grad + grad.T) * dt
    nipm = g.st.sig.shape[1]
    for e, frame in enumerate(_frames(xm, g.s.conn + 1)):
        expect = _cmat() @ _voigt(frame.T @ d @ frame)
        tol = dict(rtol=1e-8, atol=1e-8 * np.abs(expect).max())
        if g.s.full[e]:
            j = int(np.flatnonzero(g.st.full_idx == e)[0])
            for gp in range(4):
                for k in range(3):
                    np.testing.assert_allclose(g.st.sig4[j, gp * nipm + k, :3], expect, **tol)
                    assert np.abs(g.st.sig4[j, gp * nipm + k, 3:]).max() < 1e-8 * np.abs(expect).max()
        for k in range(3):  # the element-averaged layers (d3plot's), and the one-point elements
            np.testing.assert_allclose(g.st.sig[e, k, :3], expect, **tol)
    scale = np.abs(f).max()
    assert np.abs(f[4]).max() < 1e-12 * scale  # interior node
    assert np.abs(f.sum(axis=0)).max() < 1e-12 * scale
    assert np.abs(np.cross(x, f).sum(axis=0)).max() < 1e-11 * scale
    assert np.abs(m).max() == 0.0
    assert np.all(g.st.energy > 0) and np.abs(g.st.hg_energy[g.s.full == 1]).max() == 0.0


def test_plate_patch_constant_curvature_gives_constant_moment(tmp_path):
    """Kirchhoff field vz = −(a x² + b y²)/2, θy = a x, θx = −b y on the
    distorted patch: at all 16 Gauss points σ(z) = C z κΔt (κ in each
    element's frame), the moments t²/2·Σwζσ equal D κΔt and the transverse
    shears vanish (the assumed natural strain is exact for constant
    curvature: no shear locking), each to 1e-8; the interior node carries
    no resultant force or moment, and there are no membrane forces."""
    t = 0.8
    g, model = _group(tmp_path, DISTORTED, PATCH, section=f"1,16,0.8333,2\n{t}")
    a, b = 0.7, -0.4
    x0 = model.nodes.xyz
    v = np.zeros_like(x0)
    v[:, 2] = -0.5 * (a * x0[:, 0] ** 2 + b * x0[:, 1] ** 2)
    w = np.zeros_like(x0)
    w[:, 1] = a * x0[:, 0]
    w[:, 0] = -b * x0[:, 1]
    dt = 1e-13
    f, m = _step(g, x0 + dt * v, v, w, dt)
    c = _cmat()
    zg = 0.5 * t / math.sqrt(3.0)
    kappa = np.diag([a, b, 0.0])
    for e, frame in enumerate(_frames(x0, PATCH)):
        kl = _voigt(frame.T @ kappa @ frame) * dt
        moment = t**3 / 12.0 * (c @ kl)
        for gp in range(4):
            s = g.st.sig4[e, 2 * gp : 2 * gp + 2]
            for k, z in enumerate((-zg, zg)):
                np.testing.assert_allclose(s[k, :3], c @ (z * kl), rtol=1e-8, atol=1e-8 * np.abs(c @ (zg * kl)).max())
            m_gp = 0.5 * t * t * 0.5 * (-s[0, :3] / math.sqrt(3.0) + s[1, :3] / math.sqrt(3.0))
            np.testing.assert_allclose(m_gp, moment, rtol=1e-8, atol=1e-8 * np.abs(moment).max())
            assert np.abs(s[:, 3:]).max() < 1e-8 * np.abs(s[:, :3]).max()
    scale_m = np.abs(m).max()
    assert np.abs(m[4]).max() < 1e-9 * scale_m
    assert np.abs(f).max() < 1e-9 * scale_m


def _stiffness(g, x0, dt=1e-9):
    """(6·n_nodes)² tangent stiffness at x0 from the kernel's forces after
    one step of each unit nodal velocity (fresh state each time): K = −f/Δt."""
    nn = len(x0)
    k = np.zeros((6 * nn, 6 * nn))
    for c in range(6 * nn):
        v, w = np.zeros((nn, 3)), np.zeros((nn, 3))
        (v if c % 6 < 3 else w)[c // 6, c % 3] = 1.0
        for a in (g.st.sig, g.st.sig4, g.st.epsp4, g.st.energy, g.st.hgq):
            a[:] = 0.0
        f, m = _step(g, x0 + dt * v, v, w, dt)
        k[:, c] = -np.concatenate([f, m], axis=1).ravel() / dt
    return k


def test_free_element_has_exactly_the_six_rigid_zero_energy_modes(tmp_path):
    """A free distorted quadrilateral (NIP 3): its stiffness over the 20
    degrees of freedom the element has (translations, rotations about the
    two in-plane axes; no drilling stiffness, as the one-point element) is
    symmetric (1e-8) and has exactly six zero eigenvalues (below 1e-10 of
    the largest, the next above 1e-5): the rigid motions, which it leaves
    strain free. No hourglass modes, and no hourglass energy."""
    xyz = np.array([[0, 0, 0], [10.0, 0, 0], [11, 8, 0], [1, 9, 0]])
    g, model = _group(tmp_path, xyz, np.array([[1, 2, 3, 4]]), section="1,16,0.8333,3\n0.5")
    x0 = model.nodes.xyz
    k = _stiffness(g, x0)
    assert np.abs(k[:, 5::6]).max() == 0.0  # drilling: no stiffness
    keep = [c for c in range(24) if c % 6 != 5]
    kr = k[np.ix_(keep, keep)]
    assert np.abs(kr - kr.T).max() < 1e-8 * np.abs(kr).max()
    ev = np.linalg.eigvalsh(0.5 * (kr + kr.T)) / np.abs(kr).max()
    assert np.sum(np.abs(ev) < 1e-10) == 6 and np.sort(np.abs(ev))[6] > 1e-5
    rigid = []
    c = x0.mean(axis=0)
    for i in range(3):
        u = np.zeros((4, 6))
        u[:, i] = 1.0
        rigid.append(u)
        r = np.zeros((4, 6))
        axis = np.eye(3)[i]
        r[:, :3] = np.cross(axis, x0 - c)
        r[:, 3:] = axis
        rigid.append(r)
    for u in rigid:
        assert np.abs(kr @ u.ravel()[keep]).max() < 1e-9 * np.abs(kr).max()
    assert np.abs(g.st.hg_energy).max() == 0.0


@pytest.mark.parametrize("t", [2.0, 0.1], ids=["t/L=1/50", "t/L=1/1000"])
def test_coarse_cantilever_static_deflection_without_shear_locking(tmp_path, t):
    """A 100 x 10 mm strip of 10 x 1 elements (ν = 0), clamped, a tip
    force: the static tip deflection from the kernel's stiffness is
    PL³/(3EI) within 2 %, for a thick strip and a thin one (t/L = 1/1000,
    where an element with the plain transverse shear would lock: its
    deflection a small fraction of the beam's)."""
    L, b, p = 100.0, 10.0, 10.0
    xyz, quads = grid(10, 1, L, b)
    g, model = _group(tmp_path, xyz, quads, section=f"1,16,0.8333,2\n{t}", material=f"*MAT_ELASTIC\n1,{RHO},{E},0.0")
    k = _stiffness(g, model.nodes.xyz)
    clamp, tip = (0, 11), (10, 21)
    keep = [c for c in range(k.shape[0]) if c % 6 != 5 and c // 6 not in clamp]
    f = np.zeros(k.shape[0])
    for n in tip:
        f[6 * n + 2] = -0.5 * p
    u = np.linalg.solve(k[np.ix_(keep, keep)], f[keep])
    deflection = -np.mean([u[keep.index(6 * n + 2)] for n in tip])
    assert deflection == pytest.approx(p * L**3 / (3 * E * b * t**3 / 12.0), rel=0.02)


def test_cantilever_frequency_deflection_and_energy_balance(tmp_path):
    """Plate strip 100 x 10 x 2 mm (ν = 0) of 20 x 2 ELFORM 16 shells,
    clamped, tip force P = 10 N applied at once: through the time loop the
    tip swings about the static deflection PL³/(3EI) (its mean over whole
    periods, within 2 %) at the first bending frequency
    1.8751²/(2πL²)·sqrt(EI/(ρA)) (within 2 %); the load's work balances
    kinetic and internal energy within 1 %; no hourglass energy."""
    L, b, t, p = 100.0, 10.0, 2.0, 10.0
    nx, ny = 20, 2
    ei = E * b * t**3 / 12.0
    delta = p * L**3 / (3 * ei)
    per = 2 * math.pi * L**2 / 1.8751**2 / math.sqrt(ei / (RHO * b * t))
    xyz, quads = grid(nx, ny, L, b)
    clamp = [j * (nx + 1) + 1 for j in range(ny + 1)]
    tip = [j * (nx + 1) + nx + 1 for j in range(ny + 1)]
    extra = (
        "*BOUNDARY_SPC_NODE\n"
        + "".join(f"{n},0,1,1,1,1,1,1\n" for n in clamp)
        + "*LOAD_NODE_POINT\n"
        + "".join(f"{n},3,1,{-p * s}\n" for n, s in zip(tip, (0.25, 0.5, 0.25)))
        + "*DEFINE_CURVE\n1\n0,0\n1e-6,1\n1,1\n"
        + f"*DATABASE_HISTORY_NODE\n{tip[1]}\n"
        + f"*CONTROL_TERMINATION\n{3.2 * per!r},\n"
    )
    path = tmp_path / "cantilever.k"
    path.write_text(deck_text(xyz, quads, f"1,16,0.8333,2\n{t},{t},{t},{t}", f"*MAT_ELASTIC\n1,{RHO},{E},0.0", extra))
    res, g, _, _ = run_deck(path, output_dt=2e-5)
    assert g.s.full.all()
    tt, z = res.time, -res.node_displacement[:, 0, 2]
    up = np.flatnonzero((z[:-1] < delta) & (z[1:] >= delta))
    tc = tt[up] + (delta - z[up]) / (z[up + 1] - z[up]) * (tt[up + 1] - tt[up])
    assert len(tc) >= 3
    assert np.diff(tc).mean() == pytest.approx(per, rel=0.02)
    whole = (tt >= tc[0]) & (tt < tc[-1])
    assert z[whole].mean() == pytest.approx(delta, rel=0.02)
    assert np.abs(res.kinetic + res.internal + res.hourglass - res.external).max() < 0.01 * res.external.max()
    assert res.hourglass.max() == 0.0


def _plastic_strip(tmp_path, elform):
    """A 50 x 10 x 2 mm MAT_024 strip (σy 250 MPa, Et 1000 MPa, NIP 5) of
    10 x 2 shells, clamped, bent by an end moment of 1.25 times the elastic
    limit σy·b·t²/6 (the plastic limit is 1.5 times it) raised smoothly over
    three periods of its first mode and held for one: a uniform moment, so
    every section yields alike (no hinge whose size the mesh would set)."""
    L, b, t = 50.0, 10.0, 2.0
    nx, ny = 10, 2
    xyz, quads = grid(nx, ny, L, b)
    clamp = [j * (nx + 1) + 1 for j in range(ny + 1)]
    tip = [j * (nx + 1) + nx + 1 for j in range(ny + 1)]
    ei = E * b * t**3 / 12.0
    per = 2 * math.pi * L**2 / 1.8751**2 / math.sqrt(ei / (RHO * b * t))
    moment = 1.25 * 250.0 * b * t**2 / 6.0
    s = np.linspace(0.0, 1.0, 41)
    curve = (
        "*DEFINE_CURVE\n1\n"
        + "".join(f"{float(a * 3 * per)!r},{float(0.5 * (1 - math.cos(math.pi * a)))!r}\n" for a in s)
        + f"{8 * per!r},1.0\n"
    )
    extra = (
        "*BOUNDARY_SPC_NODE\n"
        + "".join(f"{n},0,1,1,1,1,1,1\n" for n in clamp)
        + "*LOAD_NODE_POINT\n"
        + "".join(f"{n},6,1,{-moment * w!r}\n" for n, w in zip(tip, (0.25, 0.5, 0.25)))
        + curve
        + f"*CONTROL_TERMINATION\n{4 * per!r},\n"
    )
    mat = f"*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,{RHO},{E},0.3,250.0,1000.0\n0.0,0.0"
    path = tmp_path / f"plastic{elform}.k"
    path.write_text(deck_text(xyz, quads, f"1,{elform},0.8333,5\n{t},{t},{t},{t}", mat, extra))
    return run_deck(path, output_dt=per / 20)


def test_plastic_bending_strip_matches_the_one_point_element(tmp_path):
    """The plastic strip (``_plastic_strip``) as ELFORM 16 and as ELFORM 2:
    both yield, and their internal energies at the end agree within 5 %;
    ELFORM 16 has no hourglass energy and balances the moment's work
    within 1 %."""
    r16, g16, _, _ = _plastic_strip(tmp_path, 16)
    r2, g2, _, _ = _plastic_strip(tmp_path, 2)
    assert g16.st.epsp4.max() > 1e-4 and g2.st.epsp.max() > 1e-4
    assert r16.internal[-1] == pytest.approx(r2.internal[-1] + r2.hourglass[-1], rel=0.05)
    assert r16.hourglass.max() == 0.0
    assert abs(r16.kinetic[-1] + r16.internal[-1] - r16.external[-1]) < 0.01 * r16.external[-1]


@pytest.mark.parametrize("elform", [16, -16])
def test_elform_16_runs_as_itself(tmp_path, elform):
    """ELFORM 16 and -16 build fully integrated quadrilaterals without a
    warning, their triangles (N3 = N4) as C0 triangles; other formulations
    keep their mapping to ELFORM 2 with its warning."""
    xyz, quads = grid(2, 1, 20.0, 10.0)
    quads[1, 3] = quads[1, 2]
    warns = []
    g, _ = _group(tmp_path, xyz, quads, section=f"1,{elform},0.8333,2\n1.0", warnings=warns)
    assert not warns
    assert g.s.full.tolist() == [1, 0] and g.st.sig4.shape == (1, 8, 5)
    warns = []
    g, _ = _group(tmp_path, xyz, quads, section="1,10,0.8333,2\n1.0", warnings=warns)
    assert g.s.full.tolist() == [0, 0] and any("ELFORM 10 of part 1 runs as ELFORM 2" in str(w) for w in warns)
