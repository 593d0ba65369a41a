"""One design, start to end, as a worker runs it: write its deck, run it
with crashlite's solver (or an external one, ``Task.options["solver"]``),
take the responses.

``evaluate(task)`` never raises for a design's own problem (a deck that
does not read, a run that diverges, a response the run lacks): it returns
a record with status "failed" and the message, so the study goes on.
"""

from __future__ import annotations

import os
import shutil
import socket
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path


@dataclass
class Task:
    key: str  # design key, e.g. "doe-0003"
    values: dict  # variable -> value
    directory: str  # design folder (on a file system the workers share)
    template: object  # designs.DeckTemplate
    responses: dict  # name -> ResponseSpec
    threads: int = 1  # Numba threads of the run
    keep: str = "all"  # "all": keep the results folder; "decks": only deck and responses
    options: dict = field(default_factory=dict)


def _threads(n: int) -> int | None:
    """Set the Numba threads of this process; the count before (None: unchanged)."""
    try:
        import numba

        before = numba.get_num_threads()
        numba.set_num_threads(max(1, min(int(n), numba.config.NUMBA_NUM_THREADS)))
        return before
    except Exception:  # noqa: BLE001 - threads are a speed setting, never a reason to fail
        return None


def _attempt(directory: Path) -> int:
    """Count and record this start of the design (a rerun after a killed
    worker or session is attempt 2, ...)."""
    marks = directory.parent / f".{directory.name}.starts"
    marks.parent.mkdir(parents=True, exist_ok=True)
    with open(marks, "a") as f:
        f.write(f"{socket.gethostname()} {os.getpid()} {time.time():.3f}\n")
    return len(marks.read_text().splitlines())


def _run_external(deck: Path, folder: Path, solver, model, d3plot: bool = False):
    """Run the design deck in an external solver (``crashlite.external``)
    and read its results as a crashlite ``Results`` (time histories), with
    its d3plot's final state where ``d3plot`` (else None)."""
    from ..external import run as run_external
    from ..results import load
    from ..results.from_history import results_from_history

    ext = run_external(deck, folder, config=solver, force=True)
    try:
        history = load(folder)
    except FileNotFoundError as e:
        raise FileNotFoundError(f"{solver.name} terminated normally but left no results crashlite reads: {e}") from None
    final = _final_state(folder, solver) if d3plot else None
    return results_from_history(history, model), float(ext.wall_time), final


def _final_state(folder: Path, solver):
    """The final state of the run's d3plot (final displacements of nodes
    that are not history nodes)."""
    from ..results.d3plot import read_final_state

    state = read_final_state(folder)
    if state is None:
        raise FileNotFoundError(
            f"{solver.name} terminated normally but left no d3plot state in {folder}: the final displacement "
            "of nodes that are not history nodes is read from it"
        )
    return state


def evaluate(task: Task) -> dict:
    """Run one design; returns {key, status, responses, message, ...}."""
    t0 = time.perf_counter()
    before = _threads(task.threads)  # restored at the end: a serial study runs in the caller's process
    directory = Path(task.directory)
    out = {
        "key": task.key,
        "values": dict(task.values),
        "status": "failed",
        "responses": {},
        "message": "",
        "host": socket.gethostname(),
        "pid": os.getpid(),
        "attempt": _attempt(directory),
        "directory": str(directory),
    }
    stage = "writing the design deck"
    try:
        from .. import read_deck
        from ..solver import run
        from .responses import evaluate_responses, reads_d3plot

        deck = task.template.write(task.values, directory)
        out["deck"] = str(deck)
        stage = "reading the design deck"
        model = read_deck(deck)
        task.template.check(model, task.values)
        stage = "running"
        solver = task.options.get("solver")  # external.SolverSettings, or None: crashlite's solver
        final_state = None
        if solver is None:
            res = run(model, out=directory / "results", quiet=True)
            if str(res.info.get("stopped") or "").startswith("interrupted"):
                # Ctrl-C in a study run in this process (serial): the study stops, the design
                # is not a result (it runs again when the study is resumed)
                raise KeyboardInterrupt(res.info["stopped"])
            run_time = float(res.wall_time)
        else:
            d3plot = any(reads_d3plot(spec, model) for spec in task.responses.values())
            res, run_time, final_state = _run_external(deck, directory / "results", solver, model, d3plot)
            out["solver"] = solver.solver
            stage = "taking the responses"
        out.update(cycles=int(res.cycles), end_time=float(res.time[-1]) if len(res.time) else 0.0, run_time=run_time)
        stage = "taking the responses"
        out["responses"] = evaluate_responses(
            task.responses,
            res,
            model,
            task.values,
            final_state=final_state,
            solver=None if solver is None else solver.solver,
        )
        out["status"] = "complete"
    except Exception as e:  # noqa: BLE001 - a design's failure is a result, not a crash of the study
        out["message"] = f"{stage}: {type(e).__name__}: {e}"
        out["traceback"] = traceback.format_exc(limit=8)[-4000:]
    finally:
        if task.keep == "decks" and (directory / "results").exists():
            shutil.rmtree(directory / "results", ignore_errors=True)
        if before is not None:
            _threads(before)
    out["wall_time"] = time.perf_counter() - t0
    return out
