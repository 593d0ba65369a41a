"""The shell time step as LS-DYNA's rule gives it (*CONTROL_TIMESTEP ISDO,
TSSFAC), on single elements against the manual's formulas:

  Δt = L / c,  c = sqrt(E / (ρ(1 − ν²)))  (ISDO 2: the bar's sqrt(E/ρ))
  ISDO 0: L = (1 + β)·A / max(L1, L2, L3, (1 − β)·L4)
  ISDO 1: L = (1 + β)·A / max(D1, D2)
  ISDO 2: L = max[(1 + β)·A / max(L1, L2, L3, (1 − β)·L4), min(L1, L2, L3, L4 + β·1e20)]

β = 0 for quadrilaterals, 1 for triangles (n3 = n4).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.solver import run
from crashlite.solver.shells import build_shell_set, element_dt

E, NU, RHO = 210000.0, 0.3, 7.85e-9
C_PLATE = math.sqrt(E / (RHO * (1 - NU * NU)))
C_BAR = math.sqrt(E / RHO)


def _deck(tmp_path, nodes, elems, timestep="", end=1e-6):
    lines = ["*KEYWORD", "*NODE"] + [f"{i + 1},{x},{y},0" for i, (x, y) in enumerate(nodes)]
    lines += ["*ELEMENT_SHELL"] + [f"{k + 1},1," + ",".join(str(n) for n in e) for k, e in enumerate(elems)]
    lines += [
        "*PART",
        "p",
        "1,1,1",
        "*SECTION_SHELL",
        "1,2",
        "1.0,1.0,1.0,1.0",
        "*MAT_ELASTIC",
        f"1,{RHO},{E},{NU}",
        "*CONTROL_TERMINATION",
        f"{end}",
    ]
    if timestep:
        lines += ["*CONTROL_TIMESTEP", timestep]
    lines.append("*END")
    path = tmp_path / "deck.k"
    path.write_text("\n".join(lines) + "\n")
    return read_deck(path)


RECT = ([(0, 0), (10, 0), (10, 4), (0, 4)], [(1, 2, 3, 4)])  # A = 40, sides 10 and 4, diagonals √116
SKEW = ([(0, 0), (12, 0), (15, 5), (2, 6)], [(1, 2, 3, 4)])
TRI = ([(0, 0), (8, 0), (0, 6)], [(1, 2, 3, 3)])  # legs 8 and 6, hypotenuse 10, A = 24


def _quad_lengths(p):
    p = np.asarray(p, float)
    sides = [np.linalg.norm(p[(i + 1) % 4] - p[i]) for i in range(4)]
    diags = [np.linalg.norm(p[2] - p[0]), np.linalg.norm(p[3] - p[1])]
    d1, d2 = p[2] - p[0], p[3] - p[1]
    area = 0.5 * abs(d1[0] * d2[1] - d1[1] * d2[0])
    return area, sides, diags


@pytest.mark.parametrize("isdo", [0, 1, 2])
@pytest.mark.parametrize("mesh", [RECT, SKEW, TRI], ids=["rectangle", "skewed", "triangle"])
def test_shell_step_follows_the_manuals_rule(tmp_path, isdo, mesh):
    nodes, elems = mesh
    model = _deck(tmp_path, nodes, elems, f"0.0,0.0,{isdo}")
    s = build_shell_set(model, np.zeros(0, np.int64), problems := [])
    assert not problems
    (dt,) = element_dt(s, model.nodes.xyz)
    if len(nodes) == 3:  # β = 1: the quadrilateral 1, 2, 3, 3
        p = np.asarray(nodes, float)
        area = 0.5 * abs((p[1] - p[0])[0] * (p[2] - p[0])[1] - (p[1] - p[0])[1] * (p[2] - p[0])[0])
        sides = [np.linalg.norm(p[1] - p[0]), np.linalg.norm(p[2] - p[1]), np.linalg.norm(p[0] - p[2])]
        diags = [np.linalg.norm(p[2] - p[0]), np.linalg.norm(p[2] - p[1])]
        beta = 1
    else:
        area, sides, diags = _quad_lengths(nodes)
        beta = 0
    if isdo == 1:
        want = (1 + beta) * area / max(diags) / C_PLATE
    else:
        length = (1 + beta) * area / max(sides)
        want = length / C_PLATE
        if isdo == 2:
            want = max(length, min(sides)) / C_BAR
    assert dt == pytest.approx(want, rel=1e-12)


def test_rectangle_figures_by_hand(tmp_path):
    """The 10 × 4 rectangle: L = 4 (ISDO 0), 40/√116 (1), 4 with the bar speed (2)."""
    got = []
    for isdo in (0, 1, 2):
        model = _deck(tmp_path, *RECT, f"0.0,0.0,{isdo}")
        (dt,) = element_dt(build_shell_set(model, np.zeros(0, np.int64), []), model.nodes.xyz)
        got.append(dt)
    assert got == pytest.approx([4.0 / C_PLATE, 40.0 / math.sqrt(116.0) / C_PLATE, 4.0 / C_BAR], rel=1e-12)


@pytest.mark.parametrize("tssfac,factor", [("0.0", 0.9), ("", 0.9), ("0.5", 0.5)])
def test_the_run_steps_at_tssfac_times_the_smallest_element_step(tmp_path, tssfac, factor):
    """TSSFAC 0 or blank is LS-DYNA's 0.9; the first step of a free element."""
    model = _deck(tmp_path, *RECT, f"0.0,{tssfac},0", end=2e-6)
    r = run(model, output_dt=1e-6)
    assert r.time_step[1] == pytest.approx(factor * 4.0 / C_PLATE, rel=1e-9)  # [0] is t = 0


def test_solid_step_is_volume_over_largest_face_at_the_dilatational_wave_speed(tmp_path):
    """ELFORM 1 brick 10 × 20 × 5 at rest: L = V / A_max = 1000 / 200 = 5,
    c = sqrt(E(1 − ν) / ((1 + ν)(1 − 2ν)ρ)) (no bulk viscosity at rest)."""
    from crashlite.solver.solids import build_solids
    from crashlite.solver.solids import element_dt as solid_dt

    corners = [(0, 0, 0), (10, 0, 0), (10, 20, 0), (0, 20, 0), (0, 0, 5), (10, 0, 5), (10, 20, 5), (0, 20, 5)]
    lines = ["*KEYWORD", "*NODE"] + [f"{i + 1},{x},{y},{z}" for i, (x, y, z) in enumerate(corners)]
    lines += [
        "*ELEMENT_SOLID",
        "1,1,1,2,3,4,5,6,7,8",
        "*PART",
        "p",
        "1,1,1",
        "*SECTION_SOLID",
        "1,1",
        "*MAT_ELASTIC",
        f"1,{RHO},{E},{NU}",
        "*CONTROL_TERMINATION",
        "1e-6",
        "*END",
    ]
    path = tmp_path / "brick.k"
    path.write_text("\n".join(lines) + "\n")
    model = read_deck(path)
    (dt,) = solid_dt(build_solids(model, np.zeros(0, np.int64), []), model.nodes.xyz)
    c = math.sqrt(E * (1 - NU) / ((1 + NU) * (1 - 2 * NU) * RHO))
    assert dt == pytest.approx(5.0 / c, rel=1e-12)


def test_spring_step_is_the_two_mass_oscillators(tmp_path):
    """A linear spring k between masses m1, m2: Δt = 2·sqrt(m1·m2 / (k(m1 + m2))), × TSSFAC."""
    k, m1, m2 = 1.0e4, 2.0e-3, 5.0e-3
    lines = [
        "*KEYWORD",
        "*NODE",
        "1,0,0,0",
        "2,10,0,0",
        "*ELEMENT_DISCRETE",
        "1,1,1,2",
        "*PART",
        "s",
        "1,1,1",
        "*SECTION_DISCRETE",
        "1,0",
        "*MAT_SPRING_ELASTIC",
        f"1,{k}",
        "*ELEMENT_MASS",
        f"1,1,{m1}",
        f"2,2,{m2}",
        "*CONTROL_TERMINATION",
        "1e-4",
        "*END",
    ]
    path = tmp_path / "spring.k"
    path.write_text("\n".join(lines) + "\n")
    r = run(read_deck(path), output_dt=1e-5)
    assert r.time_step[1] == pytest.approx(0.9 * 2.0 * math.sqrt(m1 * m2 / (k * (m1 + m2))), rel=1e-12)


BEAM_A, BEAM_I = 100.0, 100.0 * 100.0 / 12.0  # a solid 10 mm x 10 mm square


def _one_beam(tmp_path, length, end):
    """Run one free ELFORM 2 beam of ``length`` (the square section) to ``end``."""
    lines = [
        "*KEYWORD",
        "*NODE",
        "1,0,0,0",
        f"2,{length},0,0",
        "*ELEMENT_BEAM",
        "1,1,1,2",
        "*PART",
        "b",
        "1,1,1",
        "*SECTION_BEAM",
        "1,2",
        f"{BEAM_A},{BEAM_I},{BEAM_I},{2 * BEAM_I}",
        "*MAT_ELASTIC",
        f"1,{RHO},{E},{NU}",
        "*CONTROL_TERMINATION",
        f"{end}",
        "*END",
    ]
    path = tmp_path / "beam.k"
    path.write_text("\n".join(lines) + "\n")
    return run(read_deck(path), output_dt=end / 10)


def _bs_step(length, area, inertia):
    """LS-DYNA's Belytschko–Schwer beam step: the bar wave L/c unless the
    bending rule 0.5·L / (c·sqrt(3I·(3/(12I + AL²) + 1/(AL²)))) is shorter
    (I the larger moment of inertia)."""
    al2 = area * length * length
    bend = 0.5 * length / (C_BAR * math.sqrt(3 * inertia * (3 / (12 * inertia + al2) + 1 / al2)))
    return min(length / C_BAR, bend)


@pytest.mark.parametrize("length", [25.0, 50.0, 200.0, 1000.0])
def test_beam_step_is_belytschko_schwers_where_it_is_the_bar_wave(tmp_path, length):
    """One free ELFORM 2 beam (solid 10 mm × 10 mm square: A = 100, I = 833):
    the run steps at 0.9 × LS-DYNA's Belytschko–Schwer rule for a beam 2.5
    times as long as it is deep or longer (the bar wave L/c governs both
    rules); a stubbier one steps shorter (next test)."""
    r = _one_beam(tmp_path, length, 1e-5)
    expected = 0.9 * _bs_step(length, BEAM_A, BEAM_I)
    assert r.time_step[1] == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize("length", [5.0, 10.0])
def test_stubby_beam_steps_shorter_than_belytschko_schwer(tmp_path, length):
    """Beams shorter than 2.5 depths (here 10 mm deep): crashlite's nodal
    rule of the rotation (rotary inertia m·L²/24 per end, ω² from the end
    stiffness 6EI/L) takes 0.5–1 of LS-DYNA's bending rule: more cycles,
    never a longer step than LS-DYNA's."""
    r = _one_beam(tmp_path, length, 1e-6)
    ratio = r.time_step[1] / (0.9 * _bs_step(length, BEAM_A, BEAM_I))
    assert 0.5 < ratio < 1.0
