"""Elastic beams against closed-form answers: stress wave in a bar hitting
a wall, cantilever bending frequency, strain-free rigid motion."""

import math

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.solver import run

E, RO, A, I = 210000.0, 7.85e-9, 100.0, 100.0 * 100.0 / 12.0  # 10 x 10 mm square
C = math.sqrt(E / RO)  # bar wave speed, mm/s


def _bar(tmp_path, n_el=20, length=1000.0, extra=(), end=2e-3, tc="0", rc="0", name="bar.k"):
    nodes = [f"{i + 1},{length * i / n_el},0,0,{tc if i == 0 else 0},{rc if i == 0 else 0}" for i in range(n_el + 1)]
    beams = [f"{i + 1},1,{i + 1},{i + 2}" for i in range(n_el)]
    text = "\n".join(
        [
            "*KEYWORD",
            "*NODE",
            *nodes,
            "*ELEMENT_BEAM",
            *beams,
            "*PART",
            "bar",
            "1,1,1",
            "*SECTION_BEAM",
            "1,2",
            f"{A},{I},{I},{2 * I}",
            "*MAT_ELASTIC",
            f"1,{RO},{E},0.3",
            "*CONTROL_TERMINATION",
            f"{end}",
            "*DATABASE_HISTORY_NODE",
            f"1,{n_el + 1}",
            *extra,
            "*END",
        ]
    )
    p = tmp_path / name
    p.write_text(text)
    return read_deck(p)


def test_bar_hits_wall_with_rho_c_v_stress_for_2L_over_c(tmp_path):
    """A free bar at v0 = 1000 mm/s hits a rigid wall with its front end:
    contact force ρ·c·v0·A for 2L/c, then it leaves at v0."""
    v0 = 1000.0
    m = _bar(
        tmp_path,
        n_el=50,
        extra=["*INITIAL_VELOCITY", "0", f"{-v0},0,0", "*RIGIDWALL_PLANAR", "0", "0,0,0,1,0,0"],
        end=3e-3,
    )
    r = run(m, output_dt=2e-6)
    fx = r.wall_force[:, 0, 0]
    contact = np.flatnonzero(np.abs(fx) > 0.5 * RO * C * v0 * A)
    duration = r.time[contact[-1]] - r.time[contact[0]]
    assert duration == pytest.approx(2 * 1000.0 / C, rel=0.05)
    mean = np.abs(fx[contact[0] : contact[-1] + 1]).mean()
    assert mean == pytest.approx(RO * C * v0 * A, rel=0.05)
    assert r.final_v[:, 0].mean() == pytest.approx(v0, rel=0.02)  # elastic rebound


def test_cantilever_first_bending_frequency(tmp_path):
    """Clamped at x = 0: f1 = 1.8751² / (2π) · sqrt(E I / (ρ A L⁴))."""
    n_el, length = 20, 1000.0
    vel = [f"{i + 1},0,0,{50.0 * (i / n_el) ** 2}" for i in range(1, n_el + 1)]
    m = _bar(tmp_path, n_el, length, ["*INITIAL_VELOCITY_NODE", *vel], end=0.2, tc="7", rc="7")
    r = run(m, output_dt=1e-4)
    uz = r.node_displacement[:, 1, 2]
    crossings = r.time[1:][(uz[:-1] > 0) & (uz[1:] <= 0)]
    period = np.diff(crossings).mean() if len(crossings) > 1 else None
    f1 = 1.8751**2 / (2 * math.pi) * math.sqrt(E * I / (RO * A * length**4))
    assert period is not None
    assert 1.0 / period == pytest.approx(f1, rel=0.02)
    assert np.max(np.abs(r.energy_ratio - 1.0)) < 1e-2


def test_rigid_spin_about_the_axis_makes_no_strain(tmp_path):
    """The whole bar spinning about its own axis: twist stays uniform, so no
    internal energy appears and the kinetic energy stays."""
    m = _bar(tmp_path, extra=["*INITIAL_VELOCITY", "0", "0,0,0,50.0,0,0"], end=1e-3)
    r = run(m, output_dt=1e-5)
    assert np.max(np.abs(r.internal)) < 1e-9 * r.kinetic[0]
    np.testing.assert_allclose(r.kinetic, r.kinetic[0], rtol=1e-9)


def test_field_states_written_as_vtk(tmp_path):
    """States at the *DATABASE_BINARY_D3PLOT interval become VTK files with
    the deformed points and their displacement."""
    from crashlite.results.vtk import read_points

    m = _bar(tmp_path, extra=["*INITIAL_VELOCITY", "0", "0,0,100.0", "*DATABASE_BINARY_D3PLOT", "2.5e-4"], end=1e-3)
    r = run(m, out=tmp_path / "out")
    assert len(r.states_time) == 5  # t = 0, 0.25, 0.5, 0.75, 1.0 ms
    files = sorted((tmp_path / "out" / "states").glob("state_*.vtk"))
    assert len(files) == 5 and (tmp_path / "out" / "states" / "states.pvd").is_file()
    pts, disp = read_points(files[-1])
    np.testing.assert_allclose(pts, r.states_x[-1], rtol=1e-8)
    np.testing.assert_allclose(disp[:, 2], 100.0 * r.states_time[-1], rtol=1e-6)
    assert "CELLS 20 60" in files[0].read_text()


def test_mass_scaling_of_beams(tmp_path):
    """DT2MS = -1e-5: the 50 mm steel beams (L/c = 9.7e-6 s) get mass so the
    step becomes TSSFAC·1e-5, and the added mass (a few %) is reported."""
    m = _bar(tmp_path, extra=["*CONTROL_TIMESTEP", "0.0,0.9,0,0.0,-1.0e-5"], end=1e-4)
    r = run(m)
    assert r.dt == pytest.approx(0.9e-5, rel=1e-6)
    added = r.info["added_mass"][1]
    total = RO * A * 1000.0
    assert 0.0 < added < 0.2 * total
