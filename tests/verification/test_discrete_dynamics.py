"""Spring-mass systems against closed-form answers, with energy balance."""

import math

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.solver import SetupError, run

M, K = 0.1, 50.0  # t, N/mm -> ω = sqrt(K/M) = 22.36 rad/s (period 0.281 s)


def _deck(tmp_path, springs, extra="", v0=1000.0, end=0.6, mass=M):
    text = "\n".join(
        [
            "*KEYWORD",
            "*NODE",
            "1,0,0,0,7,7",
            "2,100,0,0",
            "3,200,0,0",
            "*ELEMENT_MASS",
            f"10,2,{mass}",
            "*ELEMENT_DISCRETE",
            *springs,
            "*INITIAL_VELOCITY_NODE",
            f"2,{v0},0,0",
            "*CONTROL_TERMINATION",
            f"{end}",
            # small steps: the tests check accuracy, not stability
            "" if "*CONTROL_TIMESTEP" in extra else "*CONTROL_TIMESTEP\n,0.02",
            "*DATABASE_HISTORY_NODE",
            "2",
            extra,
            "*END",
        ]
    )
    p = tmp_path / "sm.k"
    p.write_text(text)
    return read_deck(p)


def _parts(mat_lines):
    return ["*PART", "spring", "1,1,1", "*SECTION_DISCRETE", "1,0", *mat_lines]


def test_linear_spring_mass_oscillates_at_analytic_frequency(tmp_path):
    m = _deck(tmp_path, ["1,1,1,2"], "\n".join(_parts(["*MAT_SPRING_ELASTIC", f"1,{K}"])))
    r = run(m, output_dt=1e-4)
    w = math.sqrt(K / M)
    ux = r.node_displacement[:, 0, 0]
    exact = 1000.0 / w * np.sin(w * r.time)
    # central difference: phase error O((ω dt)²); dt is 0.9 of critical here
    assert np.max(np.abs(ux - exact)) < 0.01 * np.max(np.abs(exact))
    # energy: kinetic + spring energy constant
    e0 = 0.5 * M * 1000.0**2
    assert np.max(np.abs(r.kinetic + r.internal - e0)) < 2e-3 * e0
    # amplitude v0·sqrt(m/k) and period 2π·sqrt(m/k) within 0.5 %
    assert np.max(ux) == pytest.approx(1000.0 / w, rel=5e-3)
    ups = r.time[1:][(ux[:-1] < 0) & (ux[1:] >= 0)]
    assert np.diff(ups).mean() == pytest.approx(2 * math.pi / w, rel=5e-3)
    # spring force = -K x at every state (tension positive, node 2 moves away)
    np.testing.assert_allclose(r.discrete_force[:, 0], K * ux, rtol=1e-12, atol=1e-9)


def test_viscous_damper_decays_exponentially(tmp_path):
    c = 0.5  # N s/mm: v = v0 exp(-c t / m)
    m = _deck(tmp_path, ["1,1,1,2"], "\n".join(_parts(["*MAT_DAMPER_VISCOUS", f"1,{c}"])), end=0.4)
    r = run(m, output_dt=1e-3)
    vx = r.node_velocity[:, 0, 0]
    exact = 1000.0 * np.exp(-c * r.time / M)
    # the damper force uses the half-step velocity (as in LS-DYNA): first order in c·dt/m
    assert np.max(np.abs(vx - exact)) < 1e-2 * 1000.0
    # dissipated energy = lost kinetic energy
    e0 = 0.5 * M * 1000.0**2
    assert abs(r.kinetic[-1] + r.internal[-1] - e0) < 2e-3 * e0


def test_nonlinear_curve_spring_stops_mass_at_energy_balance(tmp_path):
    """Force = 2000 N after 1 mm (then flat): the mass stops after
    x = E0 / F (energy absorbed by a constant force)."""
    curve = ["*DEFINE_CURVE", "5", "-1000.0,-2000.0", "-1.0,-2000.0", "0.0,0.0", "1.0,2000.0", "1000.0,2000.0"]
    parts = _parts(["*MAT_SPRING_NONLINEAR_ELASTIC", "1,5"]) + curve
    # compressive: node 2 is moved towards node 1 (velocity -1000)
    m = _deck(tmp_path, ["1,1,1,2"], "\n".join(parts), v0=-1000.0, end=0.08)
    r = run(m, output_dt=1e-4)
    e0 = 0.5 * M * 1000.0**2  # 50 000 N mm
    stop = np.argmin(r.node_displacement[:, 0, 0])
    x_max = -r.node_displacement[stop, 0, 0]
    # F(x) = 2000 x for x < 1 then 2000: E0 = 1000 + 2000 (x - 1)
    assert x_max == pytest.approx(1 + (e0 - 1000.0) / 2000.0, rel=5e-3)
    assert np.max(np.abs(r.kinetic + r.internal - e0)) < 5e-3 * e0


def test_mass_stops_on_rigid_wall_and_wall_takes_its_energy(tmp_path):
    m = _wall_deck(tmp_path, ["*RIGIDWALL_PLANAR", "0", "150,0,0,149,0,0"], (1000.0, 0.0, 0.0), end=0.1)
    r = run(m, output_dt=1e-3)
    x = r.node_displacement[:, 0, 0]
    assert x.max() == pytest.approx(50.0, abs=1e-9)  # stopped at the wall at x = 150
    assert r.final_v[1, 0] == pytest.approx(0.0, abs=1e-3)
    e0 = 0.5 * M * 1000.0**2
    assert r.wall[-1] == pytest.approx(e0, rel=1e-6)
    assert r.wall_force[:, 0, 0].max() > 0  # the node pushes the wall along +x


def test_unsupported_content_is_refused_with_the_keyword(tmp_path):
    text = "\n".join(
        [
            "*KEYWORD",
            "*NODE",
            "1,0,0,0",
            "2,1,0,0",
            "3,1,1,0",
            "*ELEMENT_SHELL",
            "1,1,1,2,3",
            "*PART",
            "p",
            "1,1,1",
            "*SECTION_SHELL",
            "1,2",
            "1.0",
            "*MAT_ELASTIC",
            "1,1e-9,1.0,0.3",
            "*DAMPING_GLOBAL",
            "0,0.1",
            "*END",
        ]
    )
    p = tmp_path / "shell.k"
    p.write_text(text)
    with pytest.raises(SetupError) as e:
        run(p)
    assert "DAMPING_GLOBAL" in str(e.value) and "ENDTIM" in str(e.value)


def test_results_identical_on_one_and_two_threads(tmp_path, two_threads):
    import numba

    springs = [f"{i},1,{a},{b}" for i, (a, b) in enumerate([(1, 2), (2, 3), (1, 3)], start=1)]
    text = "\n".join(
        [
            "*KEYWORD",
            "*NODE",
            "1,0,0,0,7,7",
            "2,100,0,0",
            "3,200,30,0",
            "*ELEMENT_MASS",
            "10,2,0.1",
            "11,3,0.2",
            "*ELEMENT_DISCRETE",
            *springs,
            "*INITIAL_VELOCITY_NODE",
            "2,1000,200,0",
            "3,-300,0,500",
            "*CONTROL_TERMINATION",
            "0.05",
            "*DATABASE_HISTORY_NODE",
            "2,3",
            *_parts(["*MAT_SPRING_ELASTIC", "1,50.0"]),
            "*END",
        ]
    )
    p = tmp_path / "three.k"
    p.write_text(text)
    model = read_deck(p)
    default = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        one = run(model)
        numba.set_num_threads(min(2, numba.config.NUMBA_NUM_THREADS))
        two = run(model)
    finally:
        numba.set_num_threads(default)
    assert np.array_equal(one.node_displacement, two.node_displacement)
    assert np.array_equal(one.discrete_force, two.discrete_force)


def test_cli_run_writes_results(tmp_path, capsys):
    from crashlite.cli import main
    from crashlite.solver import Results

    _deck(tmp_path, ["1,1,1,2"], "\n".join(_parts(["*MAT_SPRING_ELASTIC", f"1,{K}"])), end=0.1)
    assert main(["run", str(tmp_path / "sm.k"), "-o", str(tmp_path / "out"), "--quiet"]) == 0
    assert "energy ratio" in capsys.readouterr().out
    r = Results.load(tmp_path / "out")
    assert r.time[-1] >= 0.1 and r.node_displacement.shape[1:] == (1, 3)


def test_inelastic_spring_crushes_then_releases_its_elastic_energy(tmp_path):
    """*MAT_S08, compression only: the mass crushes the spring along a 2 kN
    plateau (stop at 25.5 mm as for the elastic envelope), unloads with KU
    and leaves with the elastic energy F²/(2 KU); a permanent set remains."""
    curve = ["*DEFINE_CURVE", "5", "-1000.0,-2000.0", "-1.0,-2000.0", "0.0,0.0", "1000.0,0.0"]
    parts = _parts(["*MAT_SPRING_INELASTIC", "1,5,2000.0,1"]) + curve
    m = _deck(tmp_path, ["1,1,1,2"], "\n".join(parts), v0=-1000.0, end=0.1)
    r = run(m, output_dt=1e-4)
    x = r.node_displacement[:, 0, 0]
    assert -x.min() == pytest.approx(25.5, rel=5e-3)
    e_el = 2000.0**2 / (2 * 2000.0)
    assert r.final_v[1, 0] == pytest.approx(math.sqrt(2 * e_el / M), rel=1e-2)
    assert r.discrete_force[-1, 0] == 0.0  # separated: compression only
    e0 = 0.5 * M * 1000.0**2
    # crushing energy stays in the spring: internal = e0 - final kinetic
    assert r.internal[-1] == pytest.approx(e0 - e_el, rel=5e-3)


def _wall_deck(tmp_path, wall_lines, v, end=0.02):
    text = "\n".join(
        [
            "*KEYWORD",
            "*NODE",
            "1,0,0,0,7,7",
            "2,100,0,0",
            "*ELEMENT_MASS",
            f"10,2,{M}",
            "*ELEMENT_DISCRETE",
            "1,1,1,2",
            "*INITIAL_VELOCITY_NODE",
            f"2,{v[0]},{v[1]},{v[2]}",
            "*CONTROL_TERMINATION",
            f"{end}",
            "*DATABASE_HISTORY_NODE",
            "2",
            "*CONTROL_TIMESTEP",
            "0.0,0.9,0,0.0,0.0,9",
            "*DEFINE_CURVE",
            "9",
            "0.0,1e-5",
            "1.0,1e-5",
            *wall_lines,
            *_parts(["*MAT_SPRING_ELASTIC", "1,1e-9"]),
            "*END",
        ]
    )
    p = tmp_path / "wall.k"
    p.write_text(text)
    return read_deck(p)


def test_moving_wall_impact_conserves_momentum(tmp_path):
    """A 5 t wall at 1000 mm/s hits a 0.1 t free mass: plastic impact, common
    velocity M v0 / (M + m), energy loss M m v0² / (2 (M + m))."""
    wall = ["*RIGIDWALL_PLANAR_MOVING", "2", "90,0,0,91,0,0", "5.0,1000.0", "*SET_NODE_LIST", "2", "2"]
    r = run(_wall_deck(tmp_path, wall, (0.0, 0.0, 0.0)), output_dt=1e-4)
    common = 5.0 * 1000.0 / 5.1
    assert r.wall_velocity[-1, 0] == pytest.approx(common, rel=1e-9)
    assert r.final_v[1, 0] == pytest.approx(common, rel=1e-6)
    e0 = 0.5 * 5.0 * 1000.0**2
    assert r.wall[-1] == pytest.approx(e0 * M / 5.1, rel=1e-6)
    assert r.kinetic[-1] + r.wall[-1] == pytest.approx(e0, rel=1e-9)


@pytest.mark.parametrize("fric,vt", [(0.0, 1000.0), (0.2, 1000.0 - 0.2 * 300.0), (1.0, 0.0)])
def test_stationary_wall_friction(tmp_path, fric, vt):
    """Normal velocity 300 into the wall is stopped; Coulomb friction takes
    μ·300 of the tangential 1000 (FRIC 1: no sliding)."""
    wall = ["*RIGIDWALL_PLANAR", "0", f"0,-5,0,0,-4,0,{fric}"]
    r = run(_wall_deck(tmp_path, wall, (0.0, -300.0, 1000.0)), output_dt=1e-3)
    assert r.final_v[1, 1] == pytest.approx(0.0, abs=1e-9)
    assert r.final_v[1, 2] == pytest.approx(vt, rel=1e-9, abs=1e-9)


@pytest.mark.parametrize(
    "vad,curve,expected",
    [
        (0, ["0.0,500.0", "1.0,500.0"], lambda t: 500.0 * t),  # constant velocity
        (1, ["0.0,2.0e4", "1.0,2.0e4"], lambda t: 0.5 * 2.0e4 * t**2),  # constant acceleration
        (2, ["0.0,0.0", "0.02,10.0", "1.0,10.0"], lambda t: np.minimum(10.0 * t / 0.02, 10.0)),  # ramp
    ],
)
def test_prescribed_motion(tmp_path, vad, curve, expected):
    """Node 2 driven along x against a spring to the fixed node 1: its
    displacement follows the prescription and the work put in equals the
    kinetic plus spring energy."""
    extra = [
        "*BOUNDARY_PRESCRIBED_MOTION_NODE",
        f"2,1,{vad},7",
        "*DEFINE_CURVE",
        "7",
        *curve,
        *_parts(["*MAT_SPRING_ELASTIC", f"1,{K}"]),
    ]
    m = _deck(tmp_path, ["1,1,1,2"], "\n".join(extra), v0=0.0, end=0.04)
    r = run(m, output_dt=4e-3)  # states every few cycles
    u = r.node_displacement[:, 0, 0]
    np.testing.assert_allclose(u, expected(r.time), rtol=2e-3, atol=2e-3 * np.abs(u).max())
    np.testing.assert_allclose(r.discrete_force[:, 0], K * u, rtol=1e-12, atol=1e-9)
    if vad == 0:  # steady drive: the work put in is the kinetic plus the spring energy
        assert np.all(np.abs(r.energy_ratio[1:] - 1.0) < 1e-2)


def test_gravity_free_fall(tmp_path):
    """*LOAD_BODY_Z of 9810 mm/s² pulls the mass down: z = -g t²/2; the work
    of gravity is its kinetic energy."""
    extra = [
        "*LOAD_BODY_Z",
        "3",
        "*DEFINE_CURVE",
        "3",
        "0.0,9810.0",
        "1.0,9810.0",
        *_parts(["*MAT_SPRING_ELASTIC", "1,1e-9"]),
        "*CONTROL_TIMESTEP",
        "0.0,0.9,0,0.0,0.0,9",
        "*DEFINE_CURVE",
        "9",
        "0.0,1e-4",
        "1.0,1e-4",
    ]
    m = _deck(tmp_path, ["1,1,1,2"], "\n".join(extra), v0=0.0, end=0.1)
    r = run(m, output_dt=1e-3)
    z = r.node_displacement[:, 0, 2]
    np.testing.assert_allclose(z, -0.5 * 9810.0 * r.time**2, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(r.kinetic[1:], r.external[1:], rtol=1e-2)


def test_mass_scaling_reaches_the_requested_step(tmp_path):
    """DT2MS = -0.01 s: the 0.1 t mass on a 50 N/mm spring (critical step
    0.089 s) needs none; a 5e-4 t mass (0.0063 s) is raised to k·dt²/4."""
    extra = _parts(["*MAT_SPRING_ELASTIC", f"1,{K}"]) + ["*CONTROL_TIMESTEP", "0.0,0.9,0,0.0,-0.01"]
    light = _deck(tmp_path, ["1,1,1,2"], "\n".join(extra), end=0.05, mass=5e-4)
    r = run(light)
    assert r.dt == pytest.approx(0.9 * 0.01, rel=1e-12)
    assert r.info["added_mass"] == {1: pytest.approx(K * 0.01**2 / 4 - 5e-4, rel=1e-12)}
    heavy = _deck(tmp_path, ["1,1,1,2"], "\n".join(extra), end=0.05)
    assert run(heavy).info["added_mass"] == {}


def test_damped_oscillator_logarithmic_decrement(tmp_path):
    """Spring and damper in parallel: successive peaks fall by
    δ = 2π ζ / sqrt(1 - ζ²) with ζ = c / (2 sqrt(k m))."""
    c = 0.5
    extra = [
        "*PART",
        "damper",
        "2,2,2",
        "*SECTION_DISCRETE",
        "2,0",
        "*MAT_DAMPER_VISCOUS",
        f"2,{c}",
        *_parts(["*MAT_SPRING_ELASTIC", f"1,{K}"]),
    ]
    m = _deck(tmp_path, ["1,1,1,2", "2,2,1,2"], "\n".join(extra), end=1.2)
    r = run(m, output_dt=2e-4)
    u = r.node_displacement[:, 0, 0]
    peaks = [i for i in range(1, len(u) - 1) if u[i - 1] < u[i] >= u[i + 1] and u[i] > 0]
    assert len(peaks) >= 3
    zeta = c / (2 * math.sqrt(K * M))
    expected = 2 * math.pi * zeta / math.sqrt(1 - zeta**2)
    measured = np.log(u[peaks[0]] / u[peaks[2]]) / 2
    assert measured == pytest.approx(expected, rel=2e-2)


def test_results_load_back_with_binout_names(tmp_path):
    from crashlite.results import load

    m = _deck(tmp_path, ["1,1,1,2"], "\n".join(_parts(["*MAT_SPRING_ELASTIC", f"1,{K}"])), end=0.1)
    r = run(m, out=tmp_path / "out", output_dt=1e-3)
    h = load(tmp_path / "out")
    assert h.read("nodout", "ids").tolist() == [2]
    np.testing.assert_array_equal(h.read("nodout", "x_displacement"), r.node_displacement[:, :, 0])
    np.testing.assert_array_equal(h.read("glstat", "internal_energy"), r.internal)
    np.testing.assert_array_equal(h.read("deforc", "resultant_force"), r.discrete_force)
    assert "x_displacement" in h.read("nodout")
    with pytest.raises(KeyError, match="bndout"):
        h.read("bndout", "x_force")


def test_divergence_stops_the_run_and_keeps_the_states(tmp_path, monkeypatch):
    """A time step far above the critical one (TSSFAC 3) blows up: the run
    stops with a message naming time and cycle, the states so far are saved;
    ENDENG stops a run whose energy ratio drifts. (A deck's TSSFAC > 1 is
    refused at set-up: the factor is set on the Setup here.)"""
    from dataclasses import replace

    from crashlite.solver import RunError, loop
    from crashlite.solver.results import Results

    build = loop.build
    monkeypatch.setattr(loop, "build", lambda model: replace(build(model), tssfac=3.0))
    extra = _parts(["*MAT_SPRING_ELASTIC", f"1,{K}"])
    m = _deck(tmp_path, ["1,1,1,2"], "\n".join(extra), end=100.0)
    with pytest.raises(RunError, match=r"diverged|ENDENG") as e:
        run(m, out=tmp_path / "out", output_dt=0.05)
    assert "cycle" in str(e.value)
    assert "ENDENG" in str(e.value) or "at node 2," in str(e.value)  # the deck ID of the diverging node
    saved = Results.load(tmp_path / "out")
    assert len(saved.time) == len(e.value.results.time) > 1
    term = next(k for k in m.keywords if getattr(k, "keyword", "") == "CONTROL_TERMINATION")
    term["endeng"] = 5.0  # percent
    with pytest.raises(RunError, match="ENDENG"):
        run(m, output_dt=0.05)


@pytest.mark.parametrize("corner,stops", [("0,-50,-50", True), ("0,10,10", False)])
def test_finite_wall_only_over_its_rectangle(tmp_path, corner, stops):
    """A 100 x 100 finite wall at x = 150 catches the mass when its
    rectangle (corner at the tail point) lies in the mass's path."""
    c = [float(v) for v in corner.split(",")]
    wall = [
        "*RIGIDWALL_PLANAR_FINITE",
        "0",
        f"150,{c[1]},{c[2]},149,{c[1]},{c[2]}",
        f"150,{c[1]},{c[2] + 1},100,100",
    ]  # edge l along z, so m = n x l is +y
    r = run(_wall_deck(tmp_path, wall, (1000.0, 0.0, 0.0), end=0.1), output_dt=1e-3)
    x = r.node_displacement[:, 0, 0]
    if stops:
        assert x.max() == pytest.approx(50.0, abs=1e-9)
    else:
        assert x.max() > 90.0


def test_cylinder_wall_deflects_a_mass(tmp_path):
    """A mass moving along y at 1000 mm/s meets a cylinder (axis z, radius
    40) head-on: stopped on its surface at y = -40, it keeps x and z."""
    wall = ["*RIGIDWALL_GEOMETRIC_CYLINDER", "0", "100,0,-100,100,0,100", "40.0,0.0"]
    text = _wall_deck(tmp_path, wall, (0.0, 1000.0, 0.0), end=0.2)
    # put the mass below the cylinder on the y axis
    text.nodes.xyz[1] = [100.0, -100.0, 0.0]
    r = run(text, output_dt=1e-3)
    y = r.node_displacement[:, 0, 1] - 100.0
    assert y.max() == pytest.approx(-40.0, abs=1e-6)
    assert r.final_v[1, 1] == pytest.approx(0.0, abs=1e-3)


def test_spc_reaction_balances_the_spring_load(tmp_path):
    """Node 2 pulled at constant speed: the support of node 1 reacts with
    minus the spring force, at every state; spcforc reads back by name."""
    from crashlite.results import load

    extra = [
        "*BOUNDARY_PRESCRIBED_MOTION_NODE",
        "2,1,0,7",
        "*DEFINE_CURVE",
        "7",
        "0.0,500.0",
        "1.0,500.0",
        *_parts(["*MAT_SPRING_ELASTIC", f"1,{K}"]),
    ]
    m = _deck(tmp_path, ["1,1,1,2"], "\n".join(extra), v0=0.0, end=0.04)
    r = run(m, out=tmp_path / "out", output_dt=4e-3)
    assert r.spc_nodes.tolist() == [1]
    np.testing.assert_allclose(r.spc_force[:, 0, 0], -r.discrete_force[:, 0], rtol=1e-12, atol=1e-9)
    np.testing.assert_array_equal(load(tmp_path / "out").read("spcforc", "x_force"), r.spc_force[:, :, 0])


def test_glstat_ascii_written_and_read_back(tmp_path):
    from crashlite.results.ascii import read_glstat

    m = _deck(tmp_path, ["1,1,1,2"], "\n".join(_parts(["*MAT_SPRING_ELASTIC", f"1,{K}"])), end=0.1)
    r = run(m, out=tmp_path / "out", output_dt=1e-2)
    text = (tmp_path / "out" / "glstat").read_text()
    assert " kinetic energy................. " in text and "total energy / initial energy.. " in text
    g = read_glstat(tmp_path / "out" / "glstat")
    np.testing.assert_allclose(g["time"], r.time, rtol=1e-5)
    np.testing.assert_allclose(g["kinetic_energy"], r.kinetic, rtol=1e-5, atol=1e-5 * r.kinetic.max())
    np.testing.assert_allclose(g["energy_ratio"], r.energy_ratio, rtol=1e-5)
    # an LS-DYNA style block (labels with dots, E-format values) parses the same way
    (tmp_path / "dyna").mkdir()
    (tmp_path / "dyna" / "glstat").write_text(
        " dt of cycle     0 is controlled by shell    1 of part    1\n"
        " time...........................   0.00000E+00\n"
        " kinetic energy.................   2.50000E+06\n"
        " time...........................   1.00000E-03\n"
        " kinetic energy.................   2.40000E+06\n"
    )
    from crashlite.results import load

    h = load(tmp_path / "dyna")
    assert h.read("glstat", "kinetic_energy").tolist() == [2.5e6, 2.4e6]


def test_part_internal_energy_matsum(tmp_path):
    """Two springs in series in two parts: each part's internal energy is
    ½ k_i δ_i², and they add up to the global internal energy."""
    from crashlite.results import load

    extra = [
        "*PART",
        "soft",
        "2,2,2",
        "*SECTION_DISCRETE",
        "2,0",
        "*MAT_SPRING_ELASTIC",
        f"2,{2 * K}",
        *_parts(["*MAT_SPRING_ELASTIC", f"1,{K}"]),
        "*ELEMENT_MASS",
        "11,3,0.05",
    ]
    m = _deck(tmp_path, ["1,1,1,2", "2,2,2,3"], "\n".join(extra), end=0.05)
    r = run(m, out=tmp_path / "out", output_dt=1e-3)
    assert r.part_ids.tolist() == [1, 2]
    d1, d2 = r.discrete_elong[:, 0], r.discrete_elong[:, 1]
    np.testing.assert_allclose(r.part_internal[:, 0], 0.5 * K * d1**2, rtol=1e-9, atol=1e-6)
    np.testing.assert_allclose(r.part_internal[:, 1], 0.5 * 2 * K * d2**2, rtol=1e-9, atol=1e-6)
    np.testing.assert_allclose(r.part_internal.sum(axis=1), r.internal, rtol=1e-12)
    h = load(tmp_path / "out")
    np.testing.assert_array_equal(h.read("matsum", "internal_energy"), r.part_internal)


@pytest.mark.parametrize(
    "section",
    [
        ["*DATABASE_CROSS_SECTION_PLANE_ID", "7,plane", "0,150,0,0,151,0,0"],
        [
            "*DATABASE_CROSS_SECTION_SET_ID",
            "7,set",
            "8,0,0,0,0,9",
            "*SET_NODE_LIST",
            "8",
            "3",
            "*SET_DISCRETE_LIST",
            "9",
            "2",
        ],
    ],
)
def test_section_force_through_the_cut_spring(tmp_path, section):
    """A section between nodes 2 and 3 cuts the second spring: secforc is
    its axial force along +x (tension positive, as LS-DYNA), plane or set
    alike."""
    from crashlite.results import load

    extra = [
        "*PART",
        "second",
        "2,2,2",
        "*SECTION_DISCRETE",
        "2,0",
        "*MAT_SPRING_ELASTIC",
        f"2,{2 * K}",
        *_parts(["*MAT_SPRING_ELASTIC", f"1,{K}"]),
        "*ELEMENT_MASS",
        "11,3,0.05",
        *section,
    ]
    m = _deck(tmp_path, ["1,1,1,2", "2,2,2,3"], "\n".join(extra), end=0.05)
    r = run(m, out=tmp_path / "out", output_dt=1e-3)
    assert r.section_ids.tolist() == [7]
    np.testing.assert_allclose(r.section_force[:, 0, 0], r.discrete_force[:, 1], rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(r.section_force[:, 0, 1:], 0.0, atol=1e-9)
    h = load(tmp_path / "out")
    np.testing.assert_array_equal(h.read("secforc", "x_force"), r.section_force[:, :, 0])


def test_general_nonlinear_spring_unloads_on_its_shifted_curve(tmp_path):
    """*MAT_S06: loads along LCDL (100 N/mm to 200 N, then 10 N/mm), yields
    past TYI = 150 N, unloads on LCDU (500 N/mm) shifted through the point
    of largest deflection, reloads on it back to LCDL. Driven by a
    prescribed displacement 0 -> 10 -> 9.6 -> 12 mm; forces match the rule
    along the path and the stored energy is its integral (2700 N·mm)."""
    path = ["0.0,0.0", "0.4,10.0", "0.5,9.6", "0.7,12.0"]
    extra = [
        "*BOUNDARY_PRESCRIBED_MOTION_NODE",
        "2,1,2,7",
        "*DEFINE_CURVE",
        "7",
        *path,
        *_parts(["*MAT_SPRING_GENERAL_NONLINEAR", "1,5,6,0.0,150.0,-150.0"]),
        "*DEFINE_CURVE",
        "5",
        "-100.0,-10000.0",
        "0.0,0.0",
        "2.0,200.0",
        "100.0,1180.0",
        "*DEFINE_CURVE",
        "6",
        "-100.0,-50000.0",
        "100.0,50000.0",
    ]
    m = _deck(tmp_path, ["1,1,1,2"], "\n".join(extra), v0=0.0, end=0.7)
    r = run(m, output_dt=5e-3)
    delta, force = r.discrete_elong[:, 0], r.discrete_force[:, 0]
    load = np.where(delta < 2.0, 100.0 * delta, 200.0 + 10.0 * (delta - 2.0))
    shift = 10.0 - 280.0 / 500.0  # the unloading curve through (10, 280)
    after_peak = r.time > 0.4 + 1e-3
    expected = np.where(after_peak, np.minimum(load, 500.0 * (delta - shift)), load)
    # the steps straddle the peak: its deflection is known to ~1e-3 mm, the steep branch to ~1 N
    np.testing.assert_allclose(force, expected, rtol=1e-3, atol=1.0)
    i = np.argmin(np.abs(r.time - 0.5))
    assert delta[i] == pytest.approx(9.6, abs=0.01) and force[i] == pytest.approx(80.0, abs=3.0)  # unloaded
    assert force[-1] == pytest.approx(300.0, rel=1e-3)  # back on the loading curve
    assert r.internal[-1] == pytest.approx(2700.0, rel=5e-3)


def test_print_flag_leaves_a_spring_out_of_deforc_and_changes_nothing(tmp_path):
    """*ELEMENT_DISCRETE PF 1: LS-DYNA leaves the element out of DEFORC
    (a barrier writes its thousands of links so). Two equal springs in
    parallel oscillate at sqrt(2K/M) whether printed or not, to the last
    bit; with PF 1 on the second, only the first's history is kept."""
    mats = "\n".join(_parts(["*MAT_SPRING_ELASTIC", f"1,{K}"]))
    both = run(_deck(tmp_path, ["1,1,1,2", "2,1,1,2"], mats, end=0.2), output_dt=1e-3)
    one = run(_deck(tmp_path, ["1,1,1,2", "2,1,1,2,0,1.0,1"], mats, end=0.2), output_dt=1e-3)
    np.testing.assert_array_equal(one.final_x, both.final_x)
    np.testing.assert_array_equal(one.discrete_ids, [1])
    np.testing.assert_array_equal(one.discrete_force[:, 0], both.discrete_force[:, 0])
    ux = one.node_displacement[:, 0, 0]
    w = math.sqrt(2 * K / M)
    assert np.max(ux) == pytest.approx(1000.0 / w, rel=5e-3)
    np.testing.assert_allclose(one.discrete_force[:, 0], K * ux, rtol=1e-12, atol=1e-9)
