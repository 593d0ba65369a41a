"""Time accounting: the paper's table 1 figures and run facts from files."""

import pytest

from crashlite.verify.timing import RunInfo, format_duration, parse_d3hsp, run_info, timing_table

D3HSP_TAIL = """
 number of shell elements  . . . . . . . . . . .   1498722
 number of beam elements . . . . . . . . . . . .      1080

 Problem time       =    1.5000E-01
 Problem cycle      =    187432
 Total CPU time     =     20875 seconds (   5 hours 47 minutes 55 seconds)
 CPU time per zone cycle  =         74 nanoseconds

 Normal termination                                   07/14/21 08:46:26
 Elapsed time   20880 seconds for  187432 cycles using  8 SMP threads
             (   5 hours 48 minutes  0 seconds)
"""


def test_table_1_reduction_of_the_barrier():
    # paper, table 1: detailed ODB barrier 5 h 48 min, simplified 40 s, 0.13 % of the elements
    detailed = RunInfo("detailed", {"shell": 1_498_722}, wall_time=5 * 3600 + 48 * 60)
    simple = RunInfo("simplified", {"beam": 1080, "shell": 868}, wall_time=40.0)
    ref, row = timing_table([detailed, simple])
    assert ref["wall_reduction_percent"] == 0.0
    assert row["wall_reduction_percent"] == pytest.approx(100 * (1 - 40 / 20880), rel=1e-12)
    assert round(row["wall_reduction_percent"], 2) == 99.81
    assert row["element_share_percent"] == pytest.approx(0.13, abs=0.005)
    assert row["speedup"] == pytest.approx(522.0)
    assert row["cpu_reduction_percent"] is None  # no CPU times given: no figure, not NaN


def test_d3hsp_timing_lines():
    ri = parse_d3hsp(D3HSP_TAIL, "detailed")
    assert (ri.cpu_time, ri.wall_time, ri.cycles, ri.end_time) == (20875.0, 20880.0, 187432, 0.15)
    assert ri.elements == {"shell": 1498722, "beam": 1080}
    with pytest.raises(ValueError, match="Elapsed time"):
        parse_d3hsp("no timing here")


@pytest.mark.parametrize(
    "s, text", [(20880, "5 h 48 min"), (200, "3 min 20 s"), (40, "40 s"), (0.842, "0.842 s"), (None, "–")]
)
def test_durations(s, text):
    assert format_duration(s) == text


def test_run_info_of_a_crashlite_run(tmp_path):
    """results.npz carries what time accounting needs without the deck:
    elements by type, time step, cycles, CPU and wall time of the time
    loop, and the start-up apart."""
    from crashlite.solver import run

    deck = "src/crashlite/examples/pulse/pulse.k"
    res = run(deck, out=tmp_path)
    live = run_info(res, "pulse")
    assert live.elements == {"discrete": 1, "mass": 1}  # the deck's elements, as a d3hsp counts them
    assert live.cycles == res.cycles and live.time_step == res.dt
    assert live.wall_time == res.loop_time and live.cpu_time == res.cpu_time  # the time loop is compared
    assert res.loop_time + res.setup_time == pytest.approx(res.wall_time, rel=1e-12)
    assert 0.0 <= res.compile_time <= res.setup_time and res.loop_time > 0.0
    folder = run_info(tmp_path)  # no deck needed
    assert folder.elements == {"discrete": 1, "mass": 1}
    assert folder.cycles == res.cycles and folder.time_step == res.dt
    assert (folder.wall_time, folder.cpu_time, folder.setup_time, folder.compile_time, folder.total_wall_time) == (
        res.loop_time,
        res.cpu_time,
        res.setup_time,
        res.compile_time,
        res.wall_time,
    )
    assert folder.end_time == pytest.approx(res.time[-1]) and folder.end_time >= 0.12
    row = timing_table([folder])[0]
    assert row["setup_time"] == res.setup_time and row["total_wall_time"] == res.wall_time
    with pytest.raises(FileNotFoundError, match="d3hsp"):
        run_info(tmp_path / "nowhere")


def test_results_of_older_versions_give_their_whole_wall_time(tmp_path):
    """A results.npz without the loop time (written before it was
    recorded): the whole wall time is the run time, start-up unknown."""
    import numpy as np

    np.savez(tmp_path / "results.npz", time=np.array([0.0, 0.1]), cycles=40, dt=2.5e-3, wall_time=3.5)
    ri = run_info(tmp_path, "old")
    assert (ri.wall_time, ri.cpu_time, ri.setup_time, ri.cycles, ri.time_step, ri.elements) == (
        3.5,
        None,
        None,
        40,
        2.5e-3,
        {},
    )


def test_compilation_in_the_time_loop_is_start_up_not_run_time(tmp_path):
    """A kernel compiled inside the time loop (here by the progress
    callback, at its first call) is counted in setup_time and
    compile_time, not in the loop time compared."""
    import time

    from numba import njit

    from crashlite import read_deck
    from crashlite.solver.loop import CompileClock, integrate
    from crashlite.solver.setup import build

    spent = []

    def progress(t, cycle, dt, ratio):
        if not spent:
            t0 = time.perf_counter()
            njit(lambda a, b: a * b + 1.0)(2.0, 3.0)  # a fresh function: compiled now
            spent.append(time.perf_counter() - t0)

    res = integrate(build(read_deck("src/crashlite/examples/pulse/pulse.k")), progress=progress)
    assert spent and spent[0] > 0.0
    assert res.compile_time >= 0.9 * spent[0] and res.setup_time >= 0.9 * spent[0]
    assert res.loop_time + res.setup_time == pytest.approx(res.wall_time, rel=1e-12)
    with CompileClock() as clock:
        f = njit(lambda a: a + 1)
        f(1)
        first = clock.seconds
        f(2)  # compiled already: nothing more
        assert first > 0.0 and clock.seconds == first
    njit(lambda a: a - 1)(1)  # after the clock is taken off
    assert clock.seconds == first
