"""Running a study: its phases, designs in flight on the executor, every
result into the database as it arrives.

Phases, in order, each only where the study file asks for it:

1. ``doe``: the design of experiments (keys doe-0000, ...);
2. ``morris`` / ``sobol``: sensitivity designs run on the deck;
3. ``opt``: optuna (TPE, NSGA-II or random sampling, with the constraints),
   asked for a new design whenever a worker is free; every design of the
   earlier phases is already in the optuna study, so it starts informed;
   or ``mm``: a sequential metamodel optimisation (the LS-OPT way): fit
   the metamodels on every design so far, optimise on them, run the
   predicted optimum and a few designs in a region shrunk around it.

A planned design already complete or failed is skipped, so running the
same study file again resumes it.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from .config import StudyConfig
from .evaluate import Task, evaluate
from .interrupts import held_interrupts

# the best and the Pareto-optimal designs: in ``optimize`` (which steers by
# them); importable here
from .optimize import best_design, pareto  # noqa: F401
from .storage import Design, StudyStore, constraints_of

if TYPE_CHECKING:
    from .executor import DaskExecutor, SerialExecutor


@dataclass
class RunSummary:
    ran: int = 0  # designs run in this session
    complete: int = 0
    failed: int = 0
    skipped: int = 0  # planned designs found done
    rerun: int = 0  # interrupted designs of an earlier session run again
    stopped: int = 0  # designs running when Ctrl-C stopped this session (they run again on resume)
    phases: dict = field(default_factory=dict)
    wall_time: float = 0.0
    executor: str = ""


class StudyInterrupted(KeyboardInterrupt):
    """Ctrl-C stopped the study: the designs that finished are stored, the
    ones that were running are closed as interrupted (they run again when
    the study is resumed), the cluster is closed. ``summary``: what this
    session did."""

    def __init__(self, summary: RunSummary):
        super().__init__(f"interrupted after {summary.ran} design(s) of this session")
        self.summary = summary


class Progress:
    """Whole-study progress: designs done / running / failed and the best
    design so far, one line per finished design."""

    def __init__(self, cfg: StudyConfig, stream=None, quiet: bool = False):
        self.cfg = cfg
        self.stream = stream or sys.stdout
        self.quiet = quiet
        self.done = self.failed = 0
        self.running = 0
        self.best: Design | None = None
        self.pareto = 0

    def load(self, designs: list[Design]) -> None:
        self.done = sum(d.status == "complete" for d in designs)
        self.failed = sum(d.status == "failed" for d in designs)
        self.best, self.pareto = best_design(self.cfg, designs)

    def say(self, text: str) -> None:
        if not self.quiet:
            print(text, file=self.stream, flush=True)

    def line(self, phase: str, i: int, n: int, d: Design) -> str:
        what = (
            f"{d.key} complete in {d.info.get('wall_time', 0.0):.1f} s"
            if d.status == "complete"
            else f"{d.key} FAILED: {d.message[:160]}"
        )
        best = ""
        if self.best is not None and self.cfg.objectives:
            o = self.cfg.objectives[0]
            if len(self.cfg.objectives) == 1:
                best = f" | best {o.response} = {self.best.responses[o.response]:.6g} ({self.best.key})"
            else:
                best = f" | {self.pareto} Pareto-optimal"
        return (
            f"[{phase} {i}/{n}] {what} | study: {self.done} done, {self.running} in flight, {self.failed} failed{best}"
        )


class _Source:
    """Designs of one phase, handed out as workers become free."""

    phase = ""

    def total(self) -> int:
        raise NotImplementedError

    def next(self, store: StudyStore, inflight: int):
        """(trial, values, key) for the next design, or None (none now)."""
        raise NotImplementedError

    def finished(self) -> bool:
        raise NotImplementedError

    def told(self, design: Design) -> None:
        pass


class _Planned(_Source):
    def __init__(self, phase: str, keys: list[str], points: np.ndarray, variables, done: set[str]):
        self.phase = phase
        self.n = len(keys)
        self.todo = [
            (k, dict(zip([v.name for v in variables], map(float, p)))) for k, p in zip(keys, points) if k not in done
        ]
        self.skipped = self.n - len(self.todo)

    def total(self):
        return self.n

    def next(self, store, inflight):
        if not self.todo:
            return None
        key, values = self.todo.pop(0)
        trial, vals = store.start_fixed(key, self.phase, values)
        return trial, vals, key

    def finished(self):
        return not self.todo


class _Optuna(_Source):
    phase = "opt"

    def __init__(self, cfg: StudyConfig, designs: list[Design]):
        self.cfg = cfg
        self.budget = cfg.optimization.trials
        mine = [d for d in designs if d.phase == "opt"]
        done_keys = {d.key for d in mine if d.done}
        self.done = len(done_keys)
        self.skipped = self.done
        last = {}
        for d in mine:  # the last trial of each key
            last[d.key] = d
        self.again = [
            (d.key, d.values)
            for d in last.values()
            if d.status == "interrupted" and d.key not in done_keys and d.values
        ]
        nums = [int(d.key.split("-")[1]) for d in mine if d.key.split("-")[-1].isdigit()]
        self.counter = max(nums) + 1 if nums else 0
        self.launched = 0

    def total(self):
        return self.budget

    def next(self, store, inflight):
        if self.done + self.launched >= self.budget:
            return None
        self.launched += 1
        if self.again:
            key, values = self.again.pop(0)
            trial, vals = store.start_fixed(key, self.phase, values)
            return trial, vals, key
        key = f"opt-{self.counter:04d}"
        self.counter += 1
        trial, vals = store.start_sampled(key, self.phase)
        return trial, vals, key

    def finished(self):
        return self.done + self.launched >= self.budget


class _MetamodelOpt(_Source):
    """Sequential metamodel optimisation with a shrinking region."""

    phase = "mm"

    def __init__(self, cfg: StudyConfig, store: StudyStore, points: int):
        self.cfg = cfg
        self.store = store
        self.opt = cfg.optimization
        self.points = max(1, self.opt.points or points)
        self.iteration = 0
        self.todo: list = []
        self.waiting = 0
        self.skipped = 0
        self.planned = 0

    def total(self):
        return self.opt.iterations * self.points

    def _plan(self, k: int) -> list:
        stored = self.store.attr(f"mm_plan_{k}")
        if stored is not None:
            return [(p["key"], p["values"]) for p in stored]
        from .optimize import metamodel_step

        designs = [d for d in self.store.designs() if d.status == "complete"]
        plan = metamodel_step(self.cfg, designs, k, self.points)
        self.store.set_attr(f"mm_plan_{k}", [{"key": key, "values": v} for key, v in plan])
        return plan

    def next(self, store, inflight):
        while not self.todo:
            if inflight or self.iteration >= self.opt.iterations:
                return None  # the next plan needs every design of this one
            done = store.done_keys()
            plan = self._plan(self.iteration)
            self.iteration += 1
            self.todo = [(k, v) for k, v in plan if k not in done]
            self.skipped += len(plan) - len(self.todo)
        key, values = self.todo.pop(0)
        trial, vals = store.start_fixed(key, self.phase, values)
        return trial, vals, key

    def finished(self):
        return not self.todo and self.iteration >= self.opt.iterations


def _sampler(cfg: StudyConfig):
    import optuna

    opt = cfg.optimization
    seed = opt.seed if opt else 0
    if opt is None or opt.method in ("metamodel", "random"):
        return optuna.samplers.RandomSampler(seed=seed)
    from .storage import NATIVE_CONSTRAINTS

    cons = constraints_of if cfg.constraints and not NATIVE_CONSTRAINTS else None
    if opt.method == "nsga2":
        return optuna.samplers.NSGAIISampler(population_size=opt.population, seed=seed, constraints_func=cons)
    return optuna.samplers.TPESampler(
        seed=seed, constraints_func=cons, multivariate=True, n_startup_trials=min(10, max(2, opt.trials // 4))
    )


def _task(cfg: StudyConfig, key: str, values: dict, options: dict | None = None) -> Task:
    return Task(
        key=key,
        values=values,
        directory=str(cfg.directory / "designs" / key),
        template=cfg.template,
        responses=cfg.responses,
        threads=cfg.execution.threads_per_run,
        keep=cfg.execution.keep,
        options=dict(options or {}),
    )


def solver_options(cfg: StudyConfig) -> dict:
    """The designs' run options: {"solver": external.SolverSettings} for
    ``[execution] solver = "lsdyna"`` (resolved here, where the study is
    started, and sent with every design), {} for crashlite's solver."""
    if cfg.execution.solver == "crashlite":
        return {}
    from ..external import ExternalSolverError, settings
    from .errors import StudyError

    try:
        return {"solver": settings(cfg.execution.solver)}
    except ExternalSolverError as e:
        raise StudyError(f"{cfg.path}: [execution] solver = {cfg.execution.solver!r}: {e}") from None


def run_study(
    cfg: StudyConfig,
    executor: SerialExecutor | DaskExecutor | None = None,
    progress: Progress | None = None,
    force: bool = False,
    fn: Callable[[Task], dict] = evaluate,
    cluster: object | None = None,
) -> RunSummary:
    """Run (or resume) every phase of a study; returns what this session
    did. ``executor`` defaults to a Dask LocalCluster of the study file's
    [execution]; ``cluster`` (instead of ``executor``): a Dask cluster
    object to run on, e.g. dask-jobqueue's ``SLURMCluster(...)`` (anything
    with a ``scheduler_address``; the caller scales and closes it); ``fn``
    is the per-design function the workers run.

    Ctrl-C raises :class:`StudyInterrupted` (a KeyboardInterrupt) within
    about a second: the running designs are closed as interrupted and
    cancelled, a cluster started here is closed, the finished designs stay
    stored."""
    if executor is not None and cluster is not None:
        raise ValueError("give executor or cluster, not both")
    options = solver_options(cfg)  # before anything is stored: a solver not configured stops here
    t0 = time.perf_counter()
    progress = progress or Progress(cfg)
    cfg.directory.mkdir(parents=True, exist_ok=True)
    store = StudyStore(cfg, sampler=_sampler(cfg))
    store.claim(force=force)
    summary = RunSummary()
    try:
        _run_phases(cfg, store, executor, progress, summary, fn, options, cluster)
    except KeyboardInterrupt:
        summary.wall_time = time.perf_counter() - t0
        raise StudyInterrupted(summary) from None
    finally:
        with held_interrupts(drop=True):
            store.release()
    summary.wall_time = time.perf_counter() - t0
    return summary


def _run_phases(cfg, store, executor, progress, summary, fn, options, cluster) -> None:
    """Every phase of the study, on ``executor`` (made and closed here if
    not given or not started)."""
    from .executor import make_executor

    with held_interrupts():
        stale = store.recover()
    if stale:
        progress.say(
            f"{len(stale)} design(s) interrupted in an earlier session will run again: "
            + ", ".join(d.key for d in stale[:10])
        )
    summary.rerun = len(stale)
    designs = store.designs()
    progress.load(designs)
    sources = _plan(cfg, store, designs)
    executor = executor or make_executor(cfg.execution, cluster=cluster)
    owned = not executor.started  # start (and close) it here unless the caller did
    if owned:
        executor.__enter__()
    try:
        summary.executor = executor.describe()
        ext = options.get("solver")
        progress.say(
            f"study {cfg.name!r}: {len(designs)} design(s) stored in {cfg.storage}; "
            f"running on {summary.executor}"
            + (f"; designs run in {ext.name} ({ext.executable})" if ext is not None else "")
        )
        for src in sources:
            _drive(cfg, store, executor, src, progress, summary, fn, options)
    except BaseException as e:
        if owned:
            with held_interrupts(drop=True):
                executor.__exit__(type(e), e, e.__traceback__)
        raise
    if owned:
        executor.__exit__(None, None, None)


def _plan(cfg: StudyConfig, store: StudyStore, designs: list[Design]) -> list[_Source]:
    from .sampling import doe
    from .sensitivity import morris_points, saltelli_points

    done = {d.key for d in designs if d.done}
    out: list[_Source] = []
    if cfg.doe:
        pts = doe(cfg.doe, cfg.variables)
        out.append(_Planned("doe", [f"doe-{i:04d}" for i in range(len(pts))], pts, cfg.variables, done))
    s = cfg.sensitivity
    if s and s.method == "morris":
        pts = morris_points(cfg.variables, s.trajectories, s.levels, s.seed)
        out.append(_Planned("morris", [f"morris-{i:04d}" for i in range(len(pts))], pts, cfg.variables, done))
    if s and s.method == "sobol" and s.runs:
        pts = saltelli_points(cfg.variables, s.samples, s.seed)
        out.append(_Planned("sobol", [f"sobol-{i:05d}" for i in range(len(pts))], pts, cfg.variables, done))
    o = cfg.optimization
    if o and o.method == "metamodel":
        out.append(_MetamodelOpt(cfg, store, 0))
    elif o:
        out.append(_Optuna(cfg, designs))
    return out


def _drive(
    cfg,
    store: StudyStore,
    executor,
    src: _Source,
    progress: Progress,
    summary: RunSummary,
    fn,
    options: dict | None = None,
) -> None:
    if isinstance(src, _MetamodelOpt):
        src.points = max(1, cfg.optimization.points or executor.capacity)
    inflight: dict = {}  # handle -> (trial, key)
    n_done = src.skipped
    n_total = src.total()
    summary.skipped += src.skipped
    stats = summary.phases.setdefault(
        src.phase, {"planned": n_total, "skipped": src.skipped, "complete": 0, "failed": 0}
    )
    try:
        while True:
            while len(inflight) < max(executor.capacity, 1) + (1 if executor.name == "dask" else 0):
                with held_interrupts():  # the trial started and its design submitted, or neither
                    item = src.next(store, len(inflight))
                    if item is None:
                        break
                    trial, values, key = item
                    inflight[executor.submit(fn, _task(cfg, key, values, options))] = (trial, key)
                progress.running = len(inflight)
            if not inflight:  # nothing running and nothing more to start
                break
            for h in executor.wait(list(inflight), timeout=1.0):
                result = _result(executor, h, inflight[h][1], cfg)
                with held_interrupts():  # a finished design leaves the ones in flight stored whole
                    trial, key = inflight.pop(h)
                    if result is None:  # the cluster failed: stop, the design runs next time
                        store.interrupt(trial, "the cluster failed")
                        raise _ClusterLost(key)
                    d = store.finish(trial, result)
                summary.ran += 1
                if d.status == "complete":
                    summary.complete += 1
                    stats["complete"] += 1
                    progress.done += 1
                else:
                    summary.failed += 1
                    stats["failed"] += 1
                    progress.failed += 1
                if d.status == "complete" and cfg.objectives:
                    progress.best, progress.pareto = best_design(cfg, store.designs())
                n_done += 1
                progress.running = len(inflight)
                progress.say(progress.line(src.phase, n_done, n_total, d))
                src.told(d)
            store.heartbeat()
    except BaseException as e:
        with held_interrupts(drop=True):  # a second Ctrl-C does not cut this short
            summary.stopped += len(inflight)
            why = "the cluster failed" if isinstance(e, _ClusterLost) else "its session stopped"
            if isinstance(e, KeyboardInterrupt):
                why = "its session was interrupted (Ctrl-C)"
            for _h, (trial, _key) in inflight.items():
                store.interrupt(trial, why)
            executor.cancel(list(inflight))
        if isinstance(e, _ClusterLost):
            from .executor import ExecutorError

            raise ExecutorError(
                f"the cluster failed while design {e.args[0]} ran: {e.__cause__ or ''}; run the study again to resume"
            ) from e
        raise


class _ClusterLost(Exception):
    pass


def _result(executor, handle, key: str, cfg) -> dict | None:
    """The design's record; a design that killed its workers is failed,
    an executor failure (scheduler gone) returns None."""
    try:
        return executor.result(handle)
    except Exception as e:  # noqa: BLE001
        name = type(e).__name__
        if name == "KilledWorker":
            return {
                "key": key,
                "status": "failed",
                "responses": {},
                "message": f"the design's run killed {cfg.execution.allowed_failures} worker(s) (out of memory?): {e}",
            }
        if name in ("CancelledError",):
            return None
        return {"key": key, "status": "failed", "responses": {}, "message": f"worker error: {name}: {e}"}
