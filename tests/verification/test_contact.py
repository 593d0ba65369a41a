"""Penalty contact (*CONTACT_AUTOMATIC_...): rebound of a mass from a shell
plate, head-on impact of two elastic bars, Coulomb friction, single surface,
thread independence, the bucket-sort search and bad input."""

import math
from types import SimpleNamespace

import numba
import numpy as np
import pytest
from _contact_decks import STEEL, Deck, momentum, run

from crashlite import read_deck
from crashlite.solver.contact_build import build_surface
from crashlite.solver.kernels.contact import CAP, find_candidates
from crashlite.solver.results import Results
from crashlite.solver.setup import SetupError, build

RHO, E, NU = STEEL
K_BULK = E / (3 * (1 - 2 * NU))


def _shell_k(h, k_bulk=K_BULK, slsfac=0.1):
    """LS-DYNA SOFT = 0 penalty of a square shell segment of side h:
    SLSFAC·K·A/min(diagonal)."""
    return slsfac * k_bulk * h * h / (h * math.sqrt(2.0))


def _drop_deck(tmp_path, fixed=True, v=-1000.0, m=1e-4, gap=0.1, end=None, card_a=None):
    d = Deck()
    plate = d.plate(1, 4, 4, 20.0, 20.0)
    (node,) = d.nodes([[10.0, 10.0, 0.5 + gap]])  # above the plate's centre node, thickness 1
    d.mass(node, m)
    d.node_set(1, [node])
    if fixed:
        d.fix(plate)
    d.velocity([node], (0.0, 0.0, v))
    d.contact("NODES_TO_SURFACE", "1,1,4,3", "", "", card_a)
    k = _shell_k(5.0)
    t_contact = math.pi * math.sqrt(m / k)
    end = end or gap / abs(v) + 1.5 * t_contact
    return d.write(tmp_path / "drop.k", end), node - 1, k


def test_mass_rebounds_elastically_from_a_fixed_plate(tmp_path):
    path, node, k = _drop_deck(tmp_path)
    res, (g,), s = run(path, output_dt=2e-6)
    m, v0 = 1e-4, 1000.0
    assert res.final_v[node, 2] == pytest.approx(v0, rel=0.02)  # restitution 1
    # largest penetration: V·√(m/k) of the penalty spring, a small fraction of the thickness
    assert g.max_gap == pytest.approx(v0 * math.sqrt(m / k), rel=0.03)
    assert g.max_gap < 0.05 * 1.0
    total = res.kinetic + res.internal + res.sliding
    assert np.max(np.abs(total - total[0])) < 0.01 * total[0]
    assert res.sliding.max() > 0.9 * total[0]  # the spring took (nearly) all the energy ...
    assert abs(res.sliding[-1]) < 1e-3 * total[0]  # ... and gave it back after separation
    # rcforc: peak force on the slave node k·δmax, pointing up
    assert res.contact_ids.tolist() == [1]
    fz = res.contact_force[:, 0, 2]
    assert fz.max() == pytest.approx(k * g.max_gap, rel=0.03)
    res.save(tmp_path / "out")
    back = Results.load(tmp_path / "out")
    assert np.array_equal(back.contact_force, res.contact_force) and back.contact_ids.tolist() == [1]


def test_momentum_is_conserved_with_a_free_plate(tmp_path):
    path, node, _ = _drop_deck(tmp_path, fixed=False)
    res, (g,), s = run(path)
    p0 = momentum(s, s.v0)
    p1 = momentum(s, res.final_v)
    assert np.allclose(p1, p0, rtol=0, atol=1e-9 * abs(p0[2]))
    assert g.max_gap > 0  # they did meet
    assert res.final_v[node, 2] > -1000.0 * 0.99  # the mass was slowed down
    total = res.kinetic + res.internal + res.hourglass + res.sliding
    assert np.max(np.abs(total - total[0])) < 0.01 * total[0]


def test_a_free_rigid_plate_takes_the_momentum(tmp_path):
    d = Deck()
    d.plate(1, 4, 4, 20.0, 20.0, rigid=True)
    (node,) = d.nodes([[10.0, 10.0, 0.6]])
    d.mass(node, 1e-4)
    d.node_set(1, [node])
    d.velocity([node], (0.0, 0.0, -1000.0))
    d.contact("NODES_TO_SURFACE", "1,1,4,3")
    res, (g,), s = run(d.write(tmp_path / "rigid.k", 4e-4))
    (body,) = s.bodies
    # elastic impact of the mass on the lighter rigid plate: v' = (m - M)/(m + M)·v, V' = 2m/(m + M)·v
    m, mb, v = 1e-4, body.mass, -1000.0
    assert res.final_v[node - 1, 2] == pytest.approx((m - mb) / (m + mb) * v, rel=0.02)
    assert res.info["bodies"][1]["velocity"][2] == pytest.approx(2 * m / (m + mb) * v, rel=0.02)
    p = m * res.final_v[node - 1, 2] + mb * res.info["bodies"][1]["velocity"][2]
    assert p == pytest.approx(m * v, rel=1e-9)
    total = res.kinetic + res.internal + res.sliding
    assert np.max(np.abs(total - total[0])) < 0.01 * total[0]


@pytest.mark.parametrize("kind, card1", [("SURFACE_TO_SURFACE", "1,2,3,3"), ("SINGLE_SURFACE", "0,0,5")])
def test_bars_meeting_head_on_exchange_velocities(tmp_path, kind, card1):
    """Two equal elastic bars at ±V: contact for 2L/c, then they part at ∓V
    (both ways of pairing them: slave and master parts, or one surface)."""
    n, length, side, v, gap = 40, 100.0, 10.0, 5000.0, 0.05
    mat = (RHO, E, 0.0)  # ν = 0: the bar wave speed √(E/ρ) exactly
    d = Deck()
    a = d.bar(1, n, length, side, x0=-length - gap / 2, mat=mat)
    b = d.bar(2, n, length, side, x0=gap / 2, mat=mat)
    d.velocity(a, (v, 0, 0))
    d.velocity(b, (-v, 0, 0))
    d.contact(kind, card1, cid=5)
    c = math.sqrt(E / RHO)
    t_hit, t_c = gap / (2 * v), 2 * length / c
    res, (g,), s = run(d.write(tmp_path / "bars.k", t_hit + 1.6 * t_c), output_dt=t_c / 200)
    ia, ib = a - 1, b - 1
    va = (s.mass[ia] * res.final_v[ia, 0]).sum() / s.mass[ia].sum()
    vb = (s.mass[ib] * res.final_v[ib, 0]).sum() / s.mass[ib].sum()
    assert va == pytest.approx(-v, rel=0.05) and vb == pytest.approx(v, rel=0.05)
    fx = res.contact_force[:, 0, 0]
    if kind == "SINGLE_SURFACE":  # every node is a slave: the forces on them cancel (as in LS-DYNA's rcforc)
        assert np.abs(fx).max() < 1e-9 * RHO * c * v * side**2
        return _energy_ok(res)
    on = res.time[np.abs(fx) > 0.02 * np.abs(fx).max()]
    assert on[-1] - on[0] == pytest.approx(t_c, rel=0.05)
    # force while in contact: σ·A with σ = ρ c V
    assert np.median(np.abs(fx[np.abs(fx) > 0.5 * np.abs(fx).max()])) == pytest.approx(RHO * c * v * side**2, rel=0.05)
    _energy_ok(res)


def _energy_ok(res, tol=0.01):
    total = res.kinetic + res.internal + res.hourglass + res.sliding
    assert np.max(np.abs(total - total[0])) < tol * total[0]


def _slide(tmp_path, fs, fd, dc, v0=500.0, acc=1.0e5, m=1e-4):
    """A mass pressed on a fixed plate by a body load ``acc`` and launched
    along it at v0: (Results, displacement along the plate). It starts on
    the plate's contact surface (a start inside it would be moved out, as
    LS-DYNA does) and settles into its static penetration m·acc/k within a
    few periods of the penalty spring, damped by VDC = 40 % of critical."""
    soft = (RHO, E / 100, NU)  # a soft plate: a longer time step, the same physics
    k = _shell_k(5.0, soft[1] / (3 * (1 - 2 * NU)))
    d = Deck()
    plate = d.plate(1, 4, 2, 20.0, 10.0, mat=soft)
    (node,) = d.nodes([[3.0, 5.0, 0.5]])  # on the contact surface (the plate's half thickness)
    d.mass(node, m)
    d.node_set(1, [node])
    d.fix(plate)
    d.velocity([node], (v0, 0.0, 0.0))
    d.contact("NODES_TO_SURFACE", "1,1,4,3", f"{fs},{fd},{dc},0,40")
    d.extra += ["*LOAD_BODY_Z", f"1,{acc}", "*DEFINE_CURVE", "1", "0.0,1.0", "1.0,1.0"]  # gravity -z
    t_stop = 1.3 * v0 / (min(fs, fd) * acc)
    res, (g,), s = run(d.write(tmp_path / "slide.k", t_stop))
    return res, res.final_x[node - 1] - [3.0, 5.0, 0.5 - m * acc / k], res.final_v[node - 1]  # from rest


def test_friction_stops_a_sliding_mass_after_v0_squared_over_2_mu_g(tmp_path):
    mu, v0, acc, m = 0.3, 500.0, 1.0e5, 1e-4
    res, (dist, dy, _), v = _slide(tmp_path, mu, mu, 0.0, v0, acc, m)
    assert dist == pytest.approx(v0**2 / (2 * mu * acc), rel=0.03)
    # stopped: what is left is the stick oscillation on the tangential penalty spring, whose speed
    # is at most μ·acc/ω (the spring let go at μ·m·acc, ω² = k/m)
    k = _shell_k(5.0, E / 100 / (3 * (1 - 2 * NU)))
    assert abs(v[0]) <= 1.05 * mu * acc * math.sqrt(m / k) < 0.05 * v0 and abs(dy) < 1e-9
    # the energy taken by the interface is the friction work μ·m·g·d
    assert res.sliding[-1] == pytest.approx(mu * m * acc * dist, rel=0.03)
    assert res.energy_ratio[-1] == pytest.approx(1.0, abs=0.01)


def test_friction_decays_from_static_to_dynamic_with_the_sliding_speed(tmp_path):
    """μ(v) = FD + (FS − FD)·exp(−DC·v): the distance is ∫ v dv / (μ(v)·g)."""
    from scipy.integrate import quad

    fs, fd, dc, v0, acc, m = 0.5, 0.2, 0.005, 500.0, 1.0e5, 1e-4
    res, (dist, _, _), v = _slide(tmp_path, fs, fd, dc, v0, acc, m)
    ref = quad(lambda u: u / ((fd + (fs - fd) * math.exp(-dc * u)) * acc), 0.0, v0)[0]
    assert ref > 1.2 * v0**2 / (2 * fs * acc)  # well apart from the static-only answer
    assert dist == pytest.approx(ref, rel=0.03)
    assert res.sliding[-1] == pytest.approx(0.5 * m * v0**2, rel=0.03)  # all the motion dissipated


def test_single_surface_keeps_two_plates_apart(tmp_path):
    """Two plates of one surface driven into each other. The plates meet
    all at once, each light shell node on a penalty spring: SFS = 0.1 lets
    the step resolve the contact period (at SFS = 1 it lasts ~5 steps and
    the energy is off by several % while it lasts)."""
    t, v = 2.0, -2000.0
    d = Deck()
    d.plate(1, 4, 4, 20.0, 20.0, thick=t)
    top = d.plate(2, 3, 3, 15.0, 15.0, x0=2.5, y0=2.5, z=t + 0.5, thick=t)  # 0.5 mm between the surfaces
    d.velocity(top, (0.0, 0.0, v))
    d.contact("SINGLE_SURFACE", "0,0,0", "", "0.1")
    res, (g,), s = run(d.write(tmp_path / "ss.k", 1.2e-3))
    # the upper plate came down, was stopped by the lower one and moves apart from it
    assert g.max_gap > 0 and g.max_gap < 0.2 * t
    zt, zb = res.final_x[top - 1, 2].mean(), res.final_x[: top[0] - 1, 2].mean()
    assert zt - zb > t
    p0, p1 = momentum(s, s.v0), momentum(s, res.final_v)
    assert np.allclose(p1, p0, rtol=0, atol=1e-9 * abs(p0[2]))
    total = res.kinetic + res.internal + res.hourglass + res.sliding
    assert np.max(np.abs(total - total[0])) < 0.01 * total[0]


def test_one_flat_plate_does_not_touch_itself(tmp_path):
    d = Deck()
    plate = d.plate(1, 4, 4, 20.0, 20.0)
    d.velocity(plate, (100.0, 0.0, 0.0))
    d.contact("SINGLE_SURFACE", "1,0,3")
    res, (g,), s = run(d.write(tmp_path / "one.k", 2e-5))
    assert g.max_gap == 0.0 and res.sliding[-1] == 0.0


def test_thread_count_does_not_change_the_result(tmp_path, two_threads):
    d = Deck()
    d.plate(1, 4, 4, 20.0, 20.0)
    top = d.plate(2, 3, 3, 15.0, 15.0, x0=2.0, y0=3.0, z=1.3)
    d.velocity(top, (300.0, 0.0, -3000.0))
    d.contact("SINGLE_SURFACE", "0,0,0", "0.2,0.1,0.01")
    model = read_deck(d.write(tmp_path / "thr.k", 2e-4))
    from crashlite.solver.loop import integrate

    default = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        one = integrate(build(model))
        numba.set_num_threads(min(2, numba.config.NUMBA_NUM_THREADS))
        two = integrate(build(model))
    finally:
        numba.set_num_threads(default)
    assert one.sliding.max() > 0
    assert np.array_equal(one.final_x, two.final_x) and np.array_equal(one.contact_force, two.contact_force)


@pytest.mark.parametrize(
    "far,large",
    [(0.0, 50), (1e12, 50), (1e30, 50), (0.0, 1)],
    ids=["compact", "node 1e12 away", "node 1e30 away", "crowded"],
)
def test_bucket_search_finds_every_pair_within_reach(far, large):
    """Every (node, segment) pair whose grown box holds the node, and no
    other, in segment order; a node flung far away (a diverging or escaping
    node) coarsens the grid instead of overflowing its cell keys; nodes
    within reach of more segments than the first scan keeps (crowded:
    every segment large) get all of them."""
    rng = np.random.default_rng(3)
    n_seg = 200
    base = rng.uniform(0, 50, (n_seg, 3))
    size = np.where(np.arange(n_seg) % large == 0, 40.0, 3.0)[:, None, None]  # some large segments
    x = (base[:, None, :] + size * rng.uniform(0, 1, (n_seg, 4, 3))).reshape(-1, 3)
    nodes = rng.uniform(-2, 52, (300, 3))
    nodes[17] += far
    x = np.concatenate([x, nodes])
    seg = np.arange(4 * n_seg).reshape(n_seg, 4)
    seg[::7, 3] = seg[::7, 2]  # some triangles
    snode = np.arange(4 * n_seg, 4 * n_seg + 300)
    grow = rng.uniform(0.1, 2.0, n_seg)
    cptr, cand = find_candidates(x, snode, np.full(300, -1), seg, np.zeros(n_seg, np.int64), grow)
    lo = np.min(x[seg], axis=1) - grow[:, None]
    hi = np.max(x[seg], axis=1) + grow[:, None]
    for i, nd in enumerate(snode):
        inside = np.flatnonzero(np.all((x[nd] >= lo) & (x[nd] <= hi), axis=1))
        assert cand[cptr[i] : cptr[i + 1]].tolist() == inside.tolist()
    assert cptr[18] == cptr[17] or far == 0.0  # the far node has none
    assert (np.diff(cptr).max() > CAP) == (large == 1)


def test_bucket_search_stops_a_diverged_run_with_a_diagnosis():
    x = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, np.nan]], float)
    seg = np.array([[0, 1, 2, 3]])
    with pytest.raises(FloatingPointError, match="diverged"):
        find_candidates(x, np.array([4]), np.array([-1]), seg, np.zeros(1, np.int64), np.ones(1))


def test_solid_surface_is_the_exterior_faces(tmp_path):
    d = Deck()
    d.bar(1, 3, 30.0, 10.0)
    model = read_deck(d.write(tmp_path / "bar.k", 1.0))
    problems = []
    surf = build_surface(model, [1], 0.1, 1.0, 0.0, 1.0, problems, None)
    assert not problems
    assert len(surf.seg) == 2 + 3 * 4  # two ends, four sides of three elements
    # outward normals (the bar is convex: away from its centre)
    x = model.nodes.xyz
    c = x[surf.seg].mean(axis=1)
    nrm = np.cross(x[surf.seg[:, 2]] - x[surf.seg[:, 0]], x[surf.seg[:, 3]] - x[surf.seg[:, 1]])
    assert np.all(np.einsum("ij,ij->i", nrm, c - [15.0, 5.0, 5.0]) > 0)
    # K·A²/V, depth half the element length normal to the face
    assert np.allclose(surf.k[:2], 0.1 * K_BULK * 100.0**2 / 1000.0)
    assert np.allclose(np.sort(surf.depth)[-2:], 5.0)


def test_undefined_part_set_names_the_card_and_field(tmp_path):
    d = Deck()
    d.plate(1, 2, 2, 10.0, 10.0)
    d.contact("SINGLE_SURFACE", "99,0,2")
    with pytest.raises(SetupError) as e:
        build(read_deck(d.write(tmp_path / "bad.k", 1e-4)))
    msg = str(e.value)
    assert "CONTACT_AUTOMATIC_SINGLE_SURFACE" in msg and "SSID" in msg and "99" in msg


@pytest.mark.parametrize(
    "card_a, extra, field",
    [
        ("2", [], "SOFT"),
        ("0,0.1,0,0,0,0,0,0\n0,0,0,0,0,0,0,0\n0,3", [], "IGNORE"),  # 0, 1, 2 run
        (None, ["*CONTROL_CONTACT", "0.1,0,1,0,4"], "PENOPT"),
    ],
)
def test_options_not_run_are_refused(tmp_path, card_a, extra, field):
    d = Deck()
    d.plate(1, 2, 2, 10.0, 10.0)
    d.contact("SINGLE_SURFACE", "1,0,3", "", "", card_a)
    d.extra += extra
    with pytest.raises(SetupError) as e:
        build(read_deck(d.write(tmp_path / "opt.k", 1e-4)))
    assert field in str(e.value)


def test_soft_constraint_stiffness_from_the_masses_and_the_initial_step(tmp_path):
    """SOFT = 1: k = max(SOFT 0 penalty, 0.5·SOFSCL·m*/Δt0²), m* the reduced
    mass of the node and its segment; the mass rebounds on that spring."""
    m, v0 = 1e-4, 1000.0
    path, node, k0 = _drop_deck(tmp_path, card_a="1,2.0")
    s = build(read_deck(path))
    (g,) = [c for c in s.groups if c.kind == "contact"]
    dt0 = 0.9 * s.groups[0].critical_dt(SimpleNamespace(x=s.x0))  # the shells' initial step × TSSFAC
    assert g.c.soft == 1 and g.c.dt0 == pytest.approx(dt0, rel=1e-12)
    m_seg = s.mass[0:25].reshape(5, 5)[1:4, 1:4].mean()  # the plate nodes round the centre
    k = 0.5 * 2.0 * (m * m_seg / (m + m_seg)) / dt0**2
    assert k > 2 * k0  # the soft constraint governs here
    from crashlite.solver.loop import integrate

    res = integrate(s)
    assert g.max_gap == pytest.approx(v0 * math.sqrt(m / k), rel=0.03)
    assert res.final_v[node, 2] == pytest.approx(v0, rel=0.02)


def test_segments_of_eroded_shells_drop_out(tmp_path):
    path, node, _ = _drop_deck(tmp_path)
    s = build(read_deck(path))
    shells, contact = s.groups[0], s.groups[1]
    assert len(contact.links) == 1
    shells.st.alive[:] = 0  # every shell failed
    from crashlite.solver.loop import integrate

    res = integrate(s)
    assert contact.max_gap == 0.0 and res.final_v[node, 2] == pytest.approx(-1000.0, rel=1e-12)


def test_contact_damping_vdc_against_the_spring_dashpot_solution(tmp_path):
    """VDC = 20 % of critical (LS-DYNA: of 2·min(m)·ω, ω² = k/m*): the
    restitution of the mass equals that of a linear spring-dashpot
    without tension, integrated here with a fine ODE solver."""
    from scipy.integrate import solve_ivp

    m, v0, vdc, t = 1e-4, 1000.0, 20.0, 5.0
    rho = m / (t * 25.0)  # plate nodes as heavy as the mass: m* = m/2
    d = Deck()
    plate = d.plate(1, 4, 4, 20.0, 20.0, thick=t, mat=(rho, E, NU))
    (node,) = d.nodes([[10.0, 10.0, t / 2 + 0.05]])
    d.mass(node, m)
    d.node_set(1, [node])
    d.fix(plate)
    d.velocity([node], (0.0, 0.0, -v0))
    d.contact("NODES_TO_SURFACE", "1,1,4,3", f"0,0,0,0,{vdc}")
    d.extra += ["*CONTROL_TIMESTEP", "0.0,0.2"]  # the damper acts on half-step velocities: 1st order in Δt
    k = _shell_k(5.0)
    mstar = m / 2
    c = 0.01 * vdc * 2 * m * math.sqrt(k / mstar)
    end = 0.05 / v0 + 2 * math.pi * math.sqrt(m / k)
    res, (g,), s = run(d.write(tmp_path / "vdc.k", end))

    def rhs(_, y):  # y = (penetration, its rate); the force never pulls
        return [y[1], -max(k * y[0] + c * y[1], 0.0) / m]

    def released(_, y):
        return k * y[0] + c * y[1] if y[0] > 0 or y[1] < 0 else 1.0

    released.terminal, released.direction = True, -1
    sol = solve_ivp(rhs, (0, end), [0.0, v0], events=released, rtol=1e-10, atol=1e-12, max_step=1e-7)
    e_ref = -sol.y_events[0][0][1] / v0
    assert 0.3 < e_ref < 0.8  # damping matters
    assert res.final_v[node - 1, 2] / v0 == pytest.approx(e_ref, rel=0.03)
    # the energy lost is in the interface (positive sliding energy)
    assert res.sliding[-1] == pytest.approx(0.5 * m * v0**2 * (1 - e_ref**2), rel=0.05)


@pytest.mark.parametrize(
    "z, card2, card3, rebounds",
    [
        (1.6, "", "1.0,1.0,0.0,3.0", True),  # MST = 3: the plate acts 1.5 thick each side
        (1.6, "", "", False),  # its own 1 mm: not reached in the time
        (0.6, "0,0,0,0,0,0,0,5e-5", "", False),  # DT: dead before the mass arrives
        (0.6, "0,0,0,0,0,0,1e-3", "", False),  # BT: born after the end
    ],
)
def test_thickness_override_and_birth_death_times(tmp_path, z, card2, card3, rebounds):
    d = Deck()
    d.fix(d.plate(1, 4, 4, 20.0, 20.0))
    (node,) = d.nodes([[10.0, 10.0, z]])
    d.mass(node, 1e-4)
    d.node_set(1, [node])
    d.velocity([node], (0.0, 0.0, -1000.0))
    d.contact("NODES_TO_SURFACE", "1,1,4,3", card2, card3)
    res, (g,), s = run(d.write(tmp_path / "opt.k", 1e-4 + 1.5 * math.pi * math.sqrt(1e-4 / _shell_k(5.0))))
    assert (res.final_v[node - 1, 2] > 990.0) == rebounds
    assert (g.max_gap > 0) == rebounds


def test_slave_nodes_of_a_node_set_carry_their_shell_thickness(tmp_path):
    """A node set on a 2 mm shell meets a 1 mm plate at 1.5 mm between the
    mid-surfaces (SST 0: the shells' own thickness)."""
    d = Deck()
    d.fix(d.plate(1, 4, 4, 20.0, 20.0))
    chip = d.plate(2, 1, 1, 2.0, 2.0, x0=9.0, y0=9.0, z=1.6, thick=2.0)
    d.node_set(1, chip)
    d.velocity(chip, (0.0, 0.0, -1000.0))
    d.contact("NODES_TO_SURFACE", "1,1,4,3", "", "1.0,0.1")
    res, (g,), s = run(d.write(tmp_path / "chip.k", 4e-4))
    assert np.allclose(g.c.sthick, 2.0)
    z = res.final_x[chip - 1, 2]
    assert g.max_gap > 0 and np.all(res.final_v[chip - 1, 2] > 900.0)  # stopped at 1.5 and sent back
    assert np.all(z > 1.5)


def test_a_fast_mass_pushed_past_the_mid_surface_still_rebounds(tmp_path):
    """At 20 m/s the penalty lets the mass 0.8 mm into the 1 mm plate, past
    its mid-surface: it keeps the side it came from and is sent back."""
    v0, m = 20000.0, 1e-4
    path, node, k = _drop_deck(tmp_path, v=-v0, gap=0.1)
    res, (g,), s = run(path)
    assert v0 * math.sqrt(m / k) > 0.5  # deeper than the half thickness
    assert g.max_gap == pytest.approx(v0 * math.sqrt(m / k), rel=0.03)
    assert res.final_v[node, 2] == pytest.approx(v0, rel=0.02)


def test_contact_options_not_run_are_refused_by_name(tmp_path):
    d = Deck()
    d.plate(1, 2, 2, 10.0, 10.0)
    d.lines += ["*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_TIEBREAK", "1,1,3,3", "", "", "0"]
    with pytest.raises(SetupError) as e:
        build(read_deck(d.write(tmp_path / "tie.k", 1e-4)))
    assert "CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_TIEBREAK is not run by the crashlite solver" in str(e.value)


@pytest.mark.parametrize(
    "start_z, vz, struck, card2",
    [
        (8.0, 1000.0, False, "0,0,0,0,0,0,1e-4"),  # born (BT) while the node is inside: not moved at set-up
        (8.0, 1000.0, False, ""),  # inside at t = 0: moved out at set-up (IGNORE 0), then leaves untouched
        (10.1, -1000.0, True, ""),
    ],
)
def test_a_node_inside_a_solid_is_not_pushed_out_through_its_face(tmp_path, start_z, vz, struck, card2):
    """A node that is already 2 mm behind the top face of a fixed solid bar
    when the contact is born (as if it came through the solid, through a
    deleted element) and moves out slowly takes no contact: pushed out
    from that depth it would gain energy no contact ever stored. Inside at
    t = 0, the set-up's initial-penetration check moves it out instead
    (LS-DYNA's IGNORE 0). The same node striking the face from above
    rebounds."""
    d = Deck()
    bar = d.bar(1, 4, 40.0, 10.0)
    (node,) = d.nodes([[15.0, 5.0, start_z]])
    d.mass(node, 1e-4)
    d.node_set(1, [node])
    d.fix(bar)
    d.velocity([node], (0.0, 0.0, vz))
    d.contact("NODES_TO_SURFACE", "1,1,4,3", card2)
    res, (g,), s = run(d.write(tmp_path / "inside.k", 4e-3), output_dt=1e-4)
    moved = [m.node for m in s.moved if m.moved]
    assert moved == ([node - 1] if start_z < 10.0 and not card2 else [])
    if struck:
        assert res.final_v[node - 1, 2] == pytest.approx(-vz, rel=0.02) and g.max_gap > 0.0
    else:
        assert res.final_v[node - 1, 2] == pytest.approx(vz, rel=1e-12) and g.max_gap == 0.0
        assert res.final_x[node - 1, 2] > 10.0  # it left through the face untouched
    total = res.kinetic + res.internal + res.sliding
    assert np.max(np.abs(total - total[0])) < 0.01 * total[0]


def _column(tmp_path, fail):
    """A rigid plate (6 x 6 mm, its nodes against the faces: nodes to
    surface) at 10 m/s on a column of three 10 mm hexahedra fixed at the
    bottom: the top one soft (yield 50 MPa) failing at ``fail`` plastic
    strain (0: never), the two below elastic steel; ν = 0, as a column one
    element across is unstable at TSSFAC 0.9 for ν ≥ 0.2 (known defect,
    README). (deck, plate node IDs)."""
    d = Deck()
    col = d.nodes([[x, y, z] for z in (0.0, 10.0, 20.0, 30.0) for (x, y) in ((0, 0), (10, 0), (10, 10), (0, 10))])
    col = col.reshape(4, 4)
    for k, pid in ((0, 2), (1, 2), (2, 1)):
        d.elem += 1
        a, b = col[k], col[k + 1]
        d.lines += ["*ELEMENT_SOLID", f"{d.elem},{pid},{a[0]},{a[1]},{a[2]},{a[3]},{b[0]},{b[1]},{b[2]},{b[3]}"]
    d.lines += [
        "*PART",
        "soft top",
        "1,1,1",
        "*SECTION_SOLID",
        "1,1",
        "*MAT_PIECEWISE_LINEAR_PLASTICITY",
        f"1,{RHO},{E},0.0,50.0,0.0,{fail}",
        "0,0,0,0",
        "*PART",
        "steel",
        "2,2,2",
        "*SECTION_SOLID",
        "2,1",
        "*MAT_ELASTIC",
        f"2,{RHO},{E},0.0",
    ]
    plate = d.plate(3, 1, 1, 6.0, 6.0, z=30.6, x0=2.0, y0=2.0, thick=1.0, mat=(4.9e-5, 210000.0, 0.3), rigid=True)
    d.fix(col[0])
    d.velocity(plate, (0.0, 0.0, -10000.0))
    d.node_set(1, plate)  # the plate's nodes on the column's faces: it rests on the solid, not the solid on it
    d.lines += ["*SET_PART_LIST", "2", "1,2"]
    d.contact("NODES_TO_SURFACE", "1,2,4,2")
    d.lines += ["*DATABASE_HISTORY_NODE", ",".join(str(int(n)) for n in plate)]
    return d.write(tmp_path / "column.k", 2e-3), plate


@pytest.mark.parametrize("fail", [0.3, 0.0])
def test_the_solid_behind_a_deleted_one_still_bears(tmp_path, fail):
    """The plate on the column (``_column``): once the top element is
    deleted, the face it shared with the one below is surface and the
    plate rebounds from it, above z = 20 mm; without failure the plate
    rebounds from the crushed top element. Energy balances within 2 %."""
    path, plate = _column(tmp_path, fail)
    res, (g,), s = run(path, output_dt=2e-6)
    lowest = res.node_coordinates[:, :, 2].mean(axis=1).min() - 0.5  # the plate's underside (1 mm thick)
    assert res.final_v[plate - 1, 2].mean() > 0.0  # rebounding
    (solids,) = [gr for gr in s.groups if gr.kind == "solid"]
    if fail:  # the top element gone, the plate rebounds from the steel, within 1 mm of its face at z = 20
        assert solids.eroded == 1 and 19.0 < lowest < 20.0
    else:
        assert solids.eroded == 0 and lowest > 20.0 + 10.0 * 0.3  # on the top element, crushed but there
    total = res.kinetic + res.internal + res.sliding + res.hourglass
    assert np.max(np.abs(total - total[0])) < 0.02 * total[0]


@pytest.mark.parametrize(
    "control, sst, kind, want",
    [
        ([], "", "SINGLE_SURFACE", 0.8),  # 40 % of the 2 mm edge, not the 2 mm shell
        (["*CONTROL_CONTACT", "0.1", "0,0,0,0,4,1"], "", "SINGLE_SURFACE", 2.0),  # SSTHK = 1: the shell's
        ([], "0,0,1.5", "SINGLE_SURFACE", 1.5),  # SST given: no limit
        ([], "", "SURFACE_TO_SURFACE", 2.0),  # the rule is single surface's only
    ],
)
def test_single_surface_shell_thickness_is_at_most_40_percent_of_the_shortest_edge(tmp_path, control, sst, kind, want):
    """LS-DYNA: for single-surface contact with SSTHK = 0 and no SST, a
    shell's contact thickness is limited to 40 % of its shortest edge."""
    d = Deck()
    d.plate(1, 5, 2, 10.0, 4.0, thick=2.0)  # 2 × 2 mm elements
    d.plate(2, 5, 2, 10.0, 4.0, z=5.0, thick=2.0)
    d.lines += ["*SET_PART_LIST", "1", "1,2"]
    c1 = "1,0,2" if kind == "SINGLE_SURFACE" else "1,2,3,3"
    d.contact(kind, c1, "", sst)
    d.extra += control
    s = build(read_deck(d.write(tmp_path / "t.k", 1e-5)))
    (g,) = [g for g in s.groups if g.kind == "contact"]
    np.testing.assert_allclose(g.c.mthick, want, rtol=1e-12)
    np.testing.assert_allclose(g.c.sthick, want, rtol=1e-12)
