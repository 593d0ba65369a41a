"""Responses of a run against the closed form of the single-mass crash
pulse (1263 kg at 56 km/h on a linear spring, 600 mm dynamic crush):
crush C = v0/ω, peak deceleration v0·ω, peak spring force k·C,
initial kinetic energy ½·m·v0²."""

import math
from pathlib import Path

import pytest

from crashlite import read_deck
from crashlite.solver import run
from crashlite.study.responses import ResponseError, evaluate_responses, parse_response

PULSE = Path(__file__).parents[3] / "src" / "crashlite" / "examples" / "pulse" / "pulse.k"
M, V0, CRUSH = 1.263, 15555.6, 600.0
OMEGA = V0 / CRUSH
K = M * OMEGA**2


@pytest.fixture(scope="module")
def pulse():
    model = read_deck(PULSE)
    return run(model, quiet=True), model


def _eval(pulse, **tables):
    res, model = pulse
    specs = {name: parse_response(name, t) for name, t in tables.items()}
    return evaluate_responses(specs, res, model, {"x": 2.0})


def test_closed_form_responses(pulse):
    r = _eval(
        pulse,
        mass={"type": "mass", "scale": 1000.0},
        crush={"type": "node_displacement", "node": 2, "stat": "min", "scale": -1.0},
        crush_pulse={"type": "pulse", "node": 2, "figure": "dynamic_crush"},
        decel={"type": "deceleration", "node": 2, "cfc": 60},
        force={"type": "discrete_force", "id": 1, "stat": "absmax"},
        ke={"type": "energy", "quantity": "kinetic", "stat": "max"},
        intrusion={"type": "intrusion", "nodes": [2], "component": "x", "over": "history"},
        ratio={"type": "expression", "expression": "crush / crush_pulse * x"},
    )
    assert r["mass"] == pytest.approx(1263.0, rel=1e-12)
    assert r["crush"] == pytest.approx(CRUSH, rel=0.01)
    assert r["crush_pulse"] == pytest.approx(CRUSH, rel=0.01)
    assert r["decel"] == pytest.approx(V0 * OMEGA / 9806.65, rel=0.03)
    assert r["force"] == pytest.approx(K * CRUSH, rel=0.01)
    assert r["ke"] == pytest.approx(0.5 * M * V0**2, rel=1e-9)
    assert r["intrusion"] == pytest.approx(CRUSH, rel=0.01)
    assert r["ratio"] == pytest.approx(2.0 * r["crush"] / r["crush_pulse"], rel=1e-12)


def test_final_displacement_of_any_node(pulse):
    """final displacements come from the final state, so any node works;
    the mass is back near its start after the half period of 0.121 s."""
    res, model = pulse
    r = _eval(
        pulse,
        d={"type": "node_displacement", "node": 2},
        fixed={"type": "intrusion", "nodes": [1], "component": "magnitude"},
    )
    expected = -V0 / OMEGA * math.sin(OMEGA * res.time[-1])
    assert r["d"] == pytest.approx(expected, abs=0.02 * CRUSH)
    assert r["fixed"] == 0.0


def test_missing_entity_is_a_response_error(pulse):
    with pytest.raises(ResponseError, match="rigid wall"):
        _eval(pulse, w={"type": "wall_force"})
    with pytest.raises(ResponseError, match="history node 1 not recorded"):
        _eval(pulse, i={"type": "intrusion", "nodes": [2], "reference": 1, "over": "history"})
    with pytest.raises(ResponseError, match="history node 7"):
        _eval(pulse, v={"type": "node_velocity", "node": 7, "stat": "max"})


@pytest.mark.parametrize(
    "table, match",
    [
        ({"type": "energy", "quantity": "potential"}, "quantity"),
        ({"type": "wall_force", "stat": "peak"}, "stat"),
        ({"type": "node_displacement"}, "node"),
        ({"type": "intrusion", "nodes": [1], "set": 2}, "nodes"),
        ({"type": "section_force", "component": "normal"}, "normal"),
        ({"type": "pulse", "node": 2, "figure": "hic"}, "figure"),
        ({"type": "mass", "scale": 0}, "scale"),
        ({"type": "expression", "expression": "a +* b"}, "expression"),
    ],
)
def test_bad_response_tables(table, match):
    with pytest.raises(ValueError, match=match):
        parse_response("r", table)


def test_a_discrete_left_out_of_deforc_is_refused_before_the_run():
    """A response on a spring with PF 1 (*ELEMENT_DISCRETE: not printed to
    DEFORC) would find no history after the run: refused when checked."""
    from crashlite.study.responses import check_response

    model = read_deck(PULSE)
    spec = parse_response("force", {"type": "discrete_force", "id": 1, "stat": "absmax"})
    check_response(spec, model, [], [])
    model.discretes.pf[0] = 1
    with pytest.raises(ValueError, match=r"discrete element 1 has PF 1 \(\*ELEMENT_DISCRETE\)"):
        check_response(spec, model, [], [])
