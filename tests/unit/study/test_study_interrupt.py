"""Ctrl-C stops a study within seconds and keeps its database consistent
(issue 35): the designs that finished stay stored, the ones that were
running are closed as interrupted (they run again on resume), the Dask
LocalCluster is closed, the CLI exits 130 saying how many designs finished.

On the pulse example (one mass on a spring, a tenth of a second a design
once compiled: the Dask study has 256 designs, so that it is still running
when the signal arrives on a loaded machine).
"""

import os
import signal
import sqlite3
import subprocess
import sys
import threading
import time
from pathlib import Path

import psutil
import pytest

from crashlite.study import load_study, run_study
from crashlite.study.evaluate import evaluate
from crashlite.study.executor import SerialExecutor
from crashlite.study.runner import Progress, StudyInterrupted
from crashlite.study.storage import StudyStore

PULSE = Path(__file__).parents[3] / "src" / "crashlite" / "examples" / "pulse" / "pulse.k"

STUDY = """
[study]
name = "pulse"
deck = "pulse.k"

[variables.m]
parameter = "m"
bounds = [1.0, 2.0]

[variables.crush]
parameter = "crush"
bounds = [400.0, 800.0]

[responses.mass]
type = "mass"
scale = 1000.0

[doe]
method = "sobol"
designs = 16

[execution]
workers = 1
"""


def _study(tmp_path, designs: int = 16) -> Path:
    (tmp_path / "pulse.k").write_text(PULSE.read_text())
    p = tmp_path / "study.toml"
    p.write_text(STUDY.replace("designs = 16", f"designs = {designs}"))
    return p


def _states(cfg) -> list[tuple[int, str]]:
    with sqlite3.connect(cfg.storage[len("sqlite:///") :], timeout=30) as c:
        return c.execute("select number, state from trials order by number").fetchall()


def _check_store(cfg, finished: int) -> list:
    """Every trial closed: the finished designs complete, the others
    interrupted (optuna FAIL), none left running; the session's claim is
    released."""
    states = _states(cfg)
    assert states and all(st in ("COMPLETE", "FAIL") for _, st in states), states
    store = StudyStore(cfg, readonly=True)
    designs = store.designs()
    complete = [d for d in designs if d.status == "complete"]
    assert len(complete) == finished
    assert {d.status for d in designs} <= {"complete", "interrupted"}
    for d in designs:
        if d.status == "interrupted":
            assert "interrupted" in d.message and "Ctrl-C" in d.message
    assert store.study.user_attrs.get("driver") is None
    return designs


def test_ctrl_c_stops_a_dask_study_within_seconds_and_keeps_the_finished_designs(tmp_path):
    study = _study(tmp_path, designs=256)
    cfg = load_study(study)
    proc = subprocess.Popen(
        [sys.executable, "-m", "crashlite.cli", "study", "run", str(study)],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
        start_new_session=True,
        # SIGINT as a shell gives it (a disposition of SIG_IGN in the test process would be inherited)
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
        text=True,
    )
    lines: list[str] = []
    reader = threading.Thread(target=lambda: lines.extend(proc.stdout), daemon=True)
    reader.start()
    try:
        deadline = time.time() + 120
        while not any("complete in" in line for line in lines) and proc.poll() is None and time.time() < deadline:
            time.sleep(0.02)
        assert proc.poll() is None, "".join(lines)
        sent = time.time()
        os.killpg(proc.pid, signal.SIGINT)  # as a terminal does: the driver and every worker process
        rc = proc.wait(timeout=30)
        took = time.time() - sent
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    reader.join(timeout=5)
    out = "".join(lines)
    assert rc == 130, out
    assert took < 15.0, out  # the stop itself: about a second
    assert "Traceback" not in out
    finished = sum("complete in" in line for line in lines)
    assert f"interrupted: {finished} design(s) finished in this session ({finished} complete, 0 failed)" in out
    assert "they run again when the study is resumed" in out
    designs = _check_store(cfg, finished)
    assert len(designs) > finished  # the Ctrl-C caught designs on their way
    time.sleep(0.5)
    assert not _alive_in_group(proc.pid)  # the cluster is gone with the driver: no worker or nanny left


def _alive_in_group(pgid: int) -> list[int]:
    """Processes of the process group, less zombies (exited, waiting for
    a parent that is gone)."""
    alive = []
    for p in psutil.process_iter(["pid", "status"]):
        try:
            if os.getpgid(p.info["pid"]) == pgid and p.info["status"] != psutil.STATUS_ZOMBIE:
                alive.append(p.info["pid"])
        except (ProcessLookupError, psutil.Error):
            pass
    return alive


def test_ctrl_c_in_a_serial_study_leaves_no_design_half_stored(tmp_path):
    """The second design's run is interrupted: the first stays complete,
    the second is interrupted (not stored as a result of its truncated
    run), StudyInterrupted says what this session did."""
    cfg = load_study(_study(tmp_path))
    calls = []

    def second_interrupted(task):
        calls.append(task.key)
        if len(calls) == 2:
            raise KeyboardInterrupt
        return evaluate(task)

    with pytest.raises(StudyInterrupted) as e:
        run_study(cfg, executor=SerialExecutor(), progress=Progress(cfg, quiet=True), fn=second_interrupted)
    s = e.value.summary
    assert (s.ran, s.complete, s.failed, s.stopped) == (1, 1, 0, 1)
    designs = _check_store(cfg, 1)
    assert [d.status for d in designs] == ["complete", "interrupted"]


def test_a_run_stopped_by_ctrl_c_is_not_a_design_result(tmp_path, monkeypatch):
    """The solver keeps what a Ctrl-C'd run computed ("interrupted at t =
    ..."); in a study that run is no result: evaluate stops the study."""
    from crashlite.solver import loop

    calls = {"n": 0}
    check = loop._Recorder._check_sliding

    def check_then_interrupt(self, *a):
        calls["n"] += 1
        if calls["n"] == 40:
            raise KeyboardInterrupt
        return check(self, *a)

    monkeypatch.setattr(loop._Recorder, "_check_sliding", check_then_interrupt)
    cfg = load_study(_study(tmp_path))
    with pytest.raises(StudyInterrupted) as e:
        run_study(cfg, executor=SerialExecutor(), progress=Progress(cfg, quiet=True))
    assert (e.value.summary.ran, e.value.summary.stopped) == (0, 1)
    assert [d.status for d in _check_store(cfg, 0)] == ["interrupted"]
