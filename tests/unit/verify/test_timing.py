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


@pytest.mark.parametrize("s, text", [(20880, "5 h 48 min"), (200, "3 min 20 s"), (40, "40 s"),
                                     (0.842, "0.842 s"), (None, "–")])
def test_durations(s, text):
    assert format_duration(s) == text


def test_run_info_of_a_crashlite_run(tmp_path):
    from crashlite.solver import run

    deck = "src/crashlite/examples/pulse/pulse.k"
    res = run(deck, out=tmp_path)
    live = run_info(res, "pulse")
    assert live.elements == {"discrete": 1}
    assert live.cycles == res.cycles and live.time_step == res.dt
    folder = run_info(tmp_path, deck=deck)
    assert folder.cycles == res.cycles and folder.wall_time == pytest.approx(res.wall_time)
    assert folder.end_time == pytest.approx(res.time[-1]) and folder.end_time >= 0.12
    assert folder.elements == {"discrete": 1, "mass": 1}  # the deck counts mass elements too
    with pytest.raises(FileNotFoundError, match="d3hsp"):
        run_info(tmp_path / "nowhere")
