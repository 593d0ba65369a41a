"""Acceptance of issue 9: a study of 16 designs of a small shell model
(crash box and rail, thicknesses by part name, driving into a rigid wall)
on a Dask LocalCluster of 2 worker processes, every design in SQLite.

* A worker killed in the middle of a run loses nothing: its design runs
  again on the restarted worker and the study completes.
* A study whose whole session is killed (driver, scheduler and workers)
  resumes from the database: the designs that were running run again,
  none that had finished does.
* Running the finished study file again runs no design.
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
from crashlite.study.executor import DaskExecutor
from crashlite.study.models import front_structure
from crashlite.study.runner import Progress
from crashlite.study.storage import StudyStore

STUDY = """
[study]
name = "crash-box"
deck = "car.k"

[variables.t_box]
part = "crash box"
property = "thickness"
bounds = [0.8, 1.6]

[variables.t_rail]
part = "rail"
property = "thickness"
bounds = [1.5, 2.5]

[responses.mass]
type = "mass"
parts = ["crash box", "rail"]
scale = 1000.0

[responses.crush]
type = "node_displacement"
node = 900001
stat = "min"
scale = -1.0

[responses.peak]
type = "deceleration"
node = 900001
cfc = 60

[objectives]
mass = "minimize"

[constraints]
crush = { upper = 22.0 }

[doe]
method = "lhs"
designs = 16
seed = 5

[execution]
workers = 2
"""


@pytest.fixture
def study(tmp_path):
    front_structure(tmp_path / "car.k", "surrogate", element_size=25.0, end_time=0.008)
    p = tmp_path / "study.toml"
    p.write_text(STUDY)
    return p


def _states(cfg):
    with sqlite3.connect(cfg.storage[len("sqlite:///") :], timeout=30) as c:
        return c.execute("select number, state from trials order by number").fetchall()


def _starts(cfg):
    """(mtime, design key, pid) of every start of a design on a worker."""
    out = []
    for f in (cfg.directory / "designs").glob(".*.starts"):
        for line in f.read_text().splitlines():
            host, pid, t = line.split()
            out.append((float(t), f.name[1 : -len(".starts")], int(pid)))
    return sorted(out)


def _children():
    """Child processes of this one, less multiprocessing's resource
    tracker (it lives as long as this process)."""
    return [p for p in psutil.Process().children(recursive=True) if "resource_tracker" not in " ".join(p.cmdline())]


@pytest.mark.slow
def test_killed_worker_loses_nothing_and_rerun_runs_nothing(study):
    cfg = load_study(study)
    killed = {}

    def kill_a_running_worker():
        deadline = time.time() + 120
        while time.time() < deadline:
            starts = _starts(cfg) if (cfg.directory / "designs").is_dir() else []
            if len(starts) >= 4:
                t, key, pid = starts[-1]  # started just now: mid-run
                killed.update(key=key, pid=pid)
                os.kill(pid, signal.SIGKILL)
                return
            time.sleep(0.02)

    with DaskExecutor(workers=2) as ex:
        pids = set(ex.worker_pids().values())
        killer = threading.Thread(target=kill_a_running_worker)
        killer.start()
        s = run_study(cfg, executor=ex, progress=Progress(cfg, quiet=True))
        killer.join()
        assert killed and killed["pid"] in pids
    assert not _children()  # the cluster is gone
    assert (s.ran, s.complete, s.failed) == (16, 16, 0)
    states = _states(cfg)
    assert [st for _, st in states] == ["COMPLETE"] * 16
    designs = {d.key: d for d in StudyStore(cfg, readonly=True).designs()}
    assert sorted(designs) == [f"doe-{i:04d}" for i in range(16)]
    assert designs[killed["key"]].info["attempt"] == 2  # run again after its worker died
    assert designs[killed["key"]].info["pid"] != killed["pid"]
    for d in designs.values():
        # a crush, not noise, and shorter than the crash box and rail together (100 + 150 mm)
        assert d.responses["mass"] > 0 and 5.0 < d.responses["crush"] < 250.0
    # the same study file again: resumes, runs nothing, adds no trial
    s = run_study(load_study(study), executor=DaskExecutor(workers=2), progress=Progress(cfg, quiet=True))
    assert (s.ran, s.skipped) == (0, 16)
    assert _states(cfg) == states


@pytest.mark.slow
def test_killed_session_resumes_without_rerunning_finished_designs(study):
    cfg = load_study(study)
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    proc = subprocess.Popen(
        [sys.executable, "-m", "crashlite.cli", "study", "run", str(study), "--workers", "2"],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        env=env,
        start_new_session=True,
    )
    try:
        deadline = time.time() + 180
        done = []
        while time.time() < deadline and proc.poll() is None:
            if Path(cfg.storage[len("sqlite:///") :]).is_file():
                try:
                    done = [n for n, st in _states(cfg) if st == "COMPLETE"]
                except sqlite3.OperationalError:  # tables not made yet
                    done = []
                if len(done) >= 5:
                    break
            time.sleep(0.05)
        assert proc.poll() is None, proc.stdout.read().decode()
    finally:
        os.killpg(proc.pid, signal.SIGKILL)  # the whole session: driver, scheduler, nannies, workers
        proc.wait()
    for _ in range(100):  # the session's processes are gone
        try:
            os.killpg(proc.pid, 0)
        except ProcessLookupError:
            break
        time.sleep(0.05)
    else:
        pytest.fail("processes of the killed session are still alive")
    before = {d.key: d for d in StudyStore(cfg, readonly=True).designs() if d.status == "complete"}
    running = [n for n, st in _states(cfg) if st == "RUNNING"]
    assert len(before) >= 5 and running
    s = run_study(load_study(study), executor=DaskExecutor(workers=2), progress=Progress(cfg, quiet=True))
    assert s.rerun == len(running)
    assert s.ran == 16 - len(before) and s.failed == 0
    designs = StudyStore(cfg, readonly=True).designs()
    complete = [d for d in designs if d.status == "complete"]
    assert sorted(d.key for d in complete) == [f"doe-{i:04d}" for i in range(16)]  # each once
    for d in complete:
        if d.key in before:  # finished before the kill: the same trial, run once
            assert d.number == before[d.key].number and d.info["attempt"] == 1
    assert {d.status for d in designs if d.number in running} == {"interrupted"}
