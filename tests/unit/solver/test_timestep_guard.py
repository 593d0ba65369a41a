"""A zero, tiny or non-finite stable time step stops with a diagnosis that
names the element and node, never a run that hangs.

The case reported: a *CONSTRAINED_NODAL_RIGID_BODY with all its mass on
one node and a spring on a massless member. The body has no rotational
inertia, so the spring's nodal-rule step was 1.8e-22 s and the run never
ended. A SIGALRM turns a hang back into a failure.
"""

import signal

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.solver import run
from crashlite.solver.setup import SetupError, build
from crashlite.solver.timestep import MAX_CYCLES, stable_dt, step_problem

K = 10.0  # N/mm


@pytest.fixture(autouse=True)
def no_hang():
    def fail(*_):
        raise TimeoutError("the run hung")

    old = signal.signal(signal.SIGALRM, fail)
    signal.alarm(120)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, old)


def _deck(
    tmp_path,
    nodes: list[str],
    masses: list[str],
    body_nodes: str,
    spring: str,
    body: list[str] | None = None,
    name: str = "d.k",
    end: float = 0.01,
) -> str:
    body = body or ["*CONSTRAINED_NODAL_RIGID_BODY", "50,0,1"]
    lines = [
        "*KEYWORD",
        "*NODE",
        *nodes,
        "*ELEMENT_MASS",
        *masses,
        "*ELEMENT_DISCRETE",
        spring,
        "*PART",
        "s",
        "1,1,1",
        "*SECTION_DISCRETE",
        "1,0",
        "*MAT_SPRING_ELASTIC",
        f"1,{K!r}",
        "*SET_NODE_LIST",
        "1",
        body_nodes,
        *body,
        "*INITIAL_VELOCITY_NODE",
        "4,100.0,0,0",
        "*CONTROL_TERMINATION",
        repr(end),
        "*END",
    ]
    p = tmp_path / name
    p.write_text("\n".join(lines) + "\n")
    return str(p)


POINT = ["1,0,0,0", "2,100,0,0", "3,0,100,0", "4,200,0,0"]


def test_point_mass_body_with_a_spring_on_a_massless_member_is_refused(tmp_path):
    """All the body's mass on node 1, spring 7 from member node 2 to node 4."""
    deck = _deck(tmp_path, POINT, ["1,1,1.0", "4,4,0.1"], "1,2,3", "7,1,2,4")
    with pytest.raises(SetupError) as e:
        build(read_deck(deck))
    (p,) = e.value.problems
    assert p.keyword == "CONSTRAINED_NODAL_RIGID_BODY" and p.line == 23 and p.field == "NSID"
    for part in (
        "nodal rigid body 50",
        "sits at node 1",
        "no rotational inertia about any axis",
        "node 2 carries *ELEMENT_DISCRETE 7 at 100 from it",
        "_INERTIA",
    ):
        assert part in p.message, part
    with pytest.raises(SetupError, match="ELEMENT_DISCRETE 7"):
        run(deck)  # the run stops before its first cycle


def test_a_tiny_given_inertia_stops_before_the_first_cycle_naming_the_spring(tmp_path):
    """_INERTIA of 1e-30 t·mm²: the body exists, but its spring's step
    (2/√(k/m_eff), m_eff = I/r² = 1e-34 t) is 5.7e-18 s, 1.8e15 cycles to
    the end: refused at t = 0 with the element, its nodes and the body."""
    body = ["*CONSTRAINED_NODAL_RIGID_BODY_INERTIA", "50,0,1", "0,0,0,1.0", "1e-30,0,0,1e-30,0,1e-30", "0,0,0,0,0,0"]
    deck = _deck(tmp_path, POINT, ["1,1,1.0", "4,4,0.1"], "1,2,3", "7,1,2,4", body)
    s = build(read_deck(deck))
    m_eff = 1.0 / (1.0 / 1.0 + 100.0**2 / 1e-30)
    assert stable_dt(s) == pytest.approx(0.9 * 2.0 / np.sqrt(K * (1 / m_eff + 1 / 0.1)), rel=1e-9)
    with pytest.raises(SetupError) as e:
        run(deck)
    (p,) = e.value.problems
    assert p.keyword == "ELEMENT_DISCRETE" and p.file == deck
    assert "the run would not end" in p.message
    assert (
        "*ELEMENT_DISCRETE 7 on node 2 (of rigid body 50, effective mass 1e-34 there), node 4 (mass 0.1)" in p.message
    )


def test_masses_on_a_line_turn_about_the_others_only(tmp_path):
    """Body of nodes 1 and 2 (0.5 t each at x = ∓100) and member node 3 at
    x = 200 on their line: no inertia about x, I = 10⁴ t·mm² about y and z.
    Spring 7 (node 3 – node 4, 0.1 t) is fine: the effective inverse mass
    at node 3 is 1/M + r²/I = 1 + 4, so dt = 0.9·2/√(k·(5 + 10)). A spring
    on member node 5, 100 off the line, turns the body about x: refused."""
    nodes = ["1,-100,0,0", "2,100,0,0", "3,200,0,0", "4,300,0,0", "5,0,100,0"]
    deck = _deck(tmp_path, nodes, ["1,1,0.5", "2,2,0.5", "4,4,0.1"], "1,2,3,5", "7,1,3,4", end=3.0)
    s = build(read_deck(deck))
    (b,) = s.bodies
    np.testing.assert_allclose(np.abs(b.no_inertia), [[1.0, 0.0, 0.0]], atol=1e-12)
    assert stable_dt(s) == pytest.approx(0.9 * 2.0 / np.sqrt(K * (1.0 + 4.0 + 10.0)), rel=1e-8)
    r = run(deck)
    assert r.cycles == pytest.approx(3.0 / stable_dt(s), abs=1)  # steps of the closed form to the end
    assert np.isfinite(r.final_x).all() and np.abs(r.final_x[3] - [300.0, 0.0, 0.0]).max() < 100.0
    off = _deck(tmp_path, nodes, ["1,1,0.5", "2,2,0.5", "4,4,0.1"], "1,2,3,5", "7,1,5,4", name="off.k")
    with pytest.raises(
        SetupError,
        match=r"on one line, so it has no rotational inertia about the axis \(-?1, "
        r"-?0, -?0\); node 5 carries \*ELEMENT_DISCRETE 7 at 100 from it",
    ):
        build(read_deck(off))


def test_step_problems():
    assert step_problem(1e-6, 0.0, 0.1, 0) is None
    assert "not a number" in step_problem(float("nan"), 0.02, 0.1, 0)
    assert "is 0" in step_problem(0.0, 0.0, 0.1, 0)
    assert "is -1e-06" in step_problem(-1e-6, 0.0, 0.1, 0)
    tiny = 0.1 / (10 * MAX_CYCLES)
    assert "the run would not end" in step_problem(tiny, 0.0, 0.1, 0)
    assert step_problem(tiny, 0.0, 0.1, 1000) is None  # ENDCYC ends it
    assert step_problem(tiny, 0.1 - 5 * tiny, 0.1, 0) is None  # a few cycles from the end


SOLID = """*KEYWORD
*NODE
11,0,0,0
12,10,0,0
13,10,10,0
14,0,10,0
15,0,0,10
16,10,0,10
17,10,10,10
18,0,10,10
*ELEMENT_SOLID
5,2,11,12,13,14,15,16,17,18
*PART
block
2,2,2
*SECTION_SOLID
2,1
*MAT_ELASTIC
2,7.85e-9,210000.0,0.3
*CONTROL_TERMINATION
1e-4
*END
"""


def test_a_step_that_turns_nan_in_the_loop_stops_the_run_naming_the_element(tmp_path):
    """The solid's element step becomes NaN after 2e-5 s (as a collapsed
    element's would): the run stops there with the element named and
    keeps the states so far, instead of stepping on with a made-up step."""
    from crashlite.solver.loop import integrate

    p = tmp_path / "solid.k"
    p.write_text(SOLID)
    s = build(read_deck(p))
    (g,) = s.groups
    original = g.critical_dt

    def broken(st):
        dt = original(st)
        if st.t > 2e-5:
            g._dt[0] = np.nan
            return float("nan")
        return dt

    g.critical_dt = broken
    res = integrate(s)
    stop = res.info["stopped"]
    assert stop.startswith("the stable time step at t = ") and "is not a number" in stop
    assert "*ELEMENT_SOLID 5 on node 11 (mass" in stop and stop.endswith("the run is stopped")
    assert 2e-5 - 2e-6 < res.time[-1] <= 2e-5 and np.isfinite(res.final_x).all()  # the states before it
