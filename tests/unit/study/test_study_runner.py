"""Running studies in this process (serial executor): every design stored,
resumption, failed designs, designs a killed session left running,
optuna and metamodel optimisation, the report."""

import json
import shutil
import sqlite3
from pathlib import Path

import pytest

from crashlite.study import build_report, load_study, run_study
from crashlite.study.executor import SerialExecutor
from crashlite.study.runner import Progress
from crashlite.study.storage import StudyStore

PULSE = Path(__file__).parents[3] / "src" / "crashlite" / "examples" / "pulse" / "pulse.k"

STUDY = """
[study]
name = "pulse"
deck = "pulse.k"

[variables.m]
parameter = "m"
bounds = [{lo}, 2.0]

[variables.crush]
parameter = "crush"
bounds = [400.0, 800.0]

[responses.peak]
type = "deceleration"
node = 2
cfc = 60

[responses.stroke]
type = "node_displacement"
node = 2
stat = "min"
scale = -1.0

[responses.mass]
type = "mass"
scale = 1000.0

[objectives]
peak = "minimize"

[constraints]
stroke = {{ upper = 700.0 }}

[doe]
method = "sobol"
designs = {n}
{extra}
"""


def _write(tmp_path, n=6, lo=1.0, extra=""):
    shutil.copy(PULSE, tmp_path / "pulse.k")
    p = tmp_path / "study.toml"
    p.write_text(STUDY.format(n=n, lo=lo, extra=extra))
    return load_study(p)


def _run(cfg, **kw):
    return run_study(cfg, executor=SerialExecutor(), progress=Progress(cfg, quiet=True), **kw)


def _trials(cfg):
    db = cfg.storage[len("sqlite:///") :]
    with sqlite3.connect(db) as c:
        return c.execute("select number, state from trials order by number").fetchall()


def test_doe_is_stored_and_resumes(tmp_path):
    cfg = _write(tmp_path)
    s = _run(cfg)
    assert (s.ran, s.complete, s.failed) == (6, 6, 0)
    trials = _trials(cfg)
    assert [st for _, st in trials] == ["COMPLETE"] * 6
    designs = StudyStore(cfg, readonly=True).designs()
    for d in designs:  # the closed form: stroke = v0·√(m/k) with k = m·v0²/crush², so stroke = crush
        assert d.responses["stroke"] == pytest.approx(d.values["crush"], rel=0.01)
        assert d.responses["mass"] == pytest.approx(1000 * d.values["m"])
        assert d.feasible == (d.responses["stroke"] <= 700.0)
        assert (cfg.directory / d.info["directory"] / "results" / "results.npz").is_file()
    s = _run(cfg)  # again: nothing to do
    assert (s.ran, s.skipped) == (0, 6)
    assert _trials(cfg) == trials


def test_failed_design_is_recorded_and_the_study_goes_on(tmp_path):
    """m < 0 is a negative *ELEMENT_MASS: the solver refuses the design
    naming the card, its message is stored, the other designs complete."""
    cfg = _write(tmp_path, n=8, lo=-2.0)
    s = _run(cfg)
    designs = StudyStore(cfg, readonly=True).designs()
    bad = [d for d in designs if d.values["m"] <= 0]
    assert bad and s.failed == len(bad) and s.complete == 8 - len(bad)
    for d in bad:
        assert d.status == "failed"
        assert "running: SetupError" in d.message and "*ELEMENT_MASS, field MASS" in d.message
        assert f"has mass {d.values['m']:g} < 0" in d.message
    assert _run(cfg).ran == 0  # failed designs are not run again


def test_designs_left_running_by_a_killed_session_run_again(tmp_path):
    """A session that dies leaves RUNNING trials: the next session closes
    them as interrupted and runs just those designs again."""
    cfg = _write(tmp_path)
    _run(cfg)
    store = StudyStore(cfg)
    trial, _ = store.start_fixed("doe-0099", "doe", {"m": 1.5, "crush": 500.0})  # a foreign design
    store.study.enqueue_trial({"m": 1.5, "crush": 500.0}, user_attrs={"design": "doe-0098", "phase": "doe"})
    # pretend doe-0002 never finished: its trial RUNNING in the database
    with sqlite3.connect(cfg.storage[len("sqlite:///") :]) as c:
        c.execute("update trials set state = 'RUNNING', datetime_complete = NULL where number = 2")
    s = _run(cfg)
    assert s.rerun >= 1 and s.ran == 1
    designs = StudyStore(cfg, readonly=True).designs()
    runs = [d for d in designs if d.key == "doe-0002"]
    assert [d.status for d in runs] == ["interrupted", "complete"]
    assert runs[1].info["attempt"] == 2
    assert {d.status for d in designs if d.key in ("doe-0099", "doe-0098")} == {"interrupted"}
    assert trial.number not in [d.number for d in designs if d.status == "complete"]


def test_second_session_is_refused_while_the_first_is_alive(tmp_path):
    cfg = _write(tmp_path)
    store = StudyStore(cfg)
    store.claim()
    with pytest.raises(ValueError, match="is being run by process"):
        _run(cfg)
    store.release()
    assert _run(cfg).ran == 6


def test_changed_study_file_is_refused(tmp_path):
    cfg = _write(tmp_path)
    _run(cfg)
    cfg2 = _write(tmp_path, lo=1.1)
    with pytest.raises(ValueError, match=r"no longer matches .*variables"):
        _run(cfg2)


def test_optuna_optimisation_and_report(tmp_path):
    """TPE after the DOE: the budget of trials is run once; the report
    writes its figures, summary.json and the best design's deck."""
    cfg = _write(tmp_path, n=6, extra='[optimization]\nmethod = "tpe"\ntrials = 4\nseed = 3\n')
    s = _run(cfg)
    assert s.phases["opt"]["complete"] == 4 and s.ran == 10
    assert _run(cfg).ran == 0
    summary = build_report(cfg)
    out = cfg.directory / "report"
    assert json.loads((out / "summary.json").read_text())["counts"]["complete"] == 10
    for f in summary["figures"]:
        assert (out / f["file"]).stat().st_size > 1000
    names = {f["file"] for f in summary["figures"]}
    assert {
        "parallel_coordinates.png",
        "responses_vs_variables.png",
        "history.png",
        "metamodels.png",
        "sensitivity.png",
        "scatter.png",
    } <= names
    best = summary["best"]
    ok = [d for d in summary["designs"] if d["status"] == "complete" and d["feasible"]]
    assert best["responses"]["peak"] == min(d["responses"]["peak"] for d in ok)
    from crashlite import read_deck

    m = read_deck(out / summary["best_deck"])
    assert m.masses.mass[0] == pytest.approx(best["values"]["m"])


def test_metamodel_optimisation_finds_the_constrained_optimum(tmp_path):
    """Peak deceleration v0²/crush falls with the crush distance, and the
    stroke equals the crush distance: the optimum sits on the constraint,
    crush = 700 mm, peak = 15555.6²/700/9806.65 = 35.2 g."""
    cfg = _write(tmp_path, n=8, extra='[optimization]\nmethod = "metamodel"\niterations = 2\npoints = 2\n')
    _run(cfg)
    designs = StudyStore(cfg, readonly=True).designs()
    assert sorted(d.key for d in designs if d.phase == "mm") == ["mm-00-00", "mm-00-01", "mm-01-00", "mm-01-01"]
    best = min((d for d in designs if d.status == "complete" and d.feasible), key=lambda d: d.responses["peak"])
    assert best.key.startswith("mm-")
    assert best.values["crush"] == pytest.approx(700.0, rel=0.02)
    assert best.responses["peak"] == pytest.approx(15555.6**2 / 700.0 / 9806.65, rel=0.03)
