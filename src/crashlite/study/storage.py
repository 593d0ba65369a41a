"""Study state in a real database: optuna's RDB storage (SQLite file by
default, a PostgreSQL URL works the same).

Every design is one optuna trial: its parameters are the variables, its
values the objectives, and its user attributes hold the design key
(``doe-0003``, ``opt-0012``, ...), the phase, the status (running,
complete, failed, interrupted), the responses, the constraint violations
(``constraints``, ≤ 0 when met, which optuna's samplers read) and the
run's facts or failure message.

Resuming: a design whose key has a COMPLETE trial, or a FAIL trial that
failed by itself, is never run again. A trial still RUNNING when a session
starts belongs to a session that was killed: it is closed as
"interrupted" (optuna state FAIL) and its design runs again. The session
that runs a study holds it (``driver`` attribute, with a heartbeat); a
second session on the same study is refused while the first is alive.
"""

from __future__ import annotations

import json
import math
import os
import socket
import time
from dataclasses import dataclass, field
from pathlib import Path

from .config import StudyConfig, StudyError

HEARTBEAT_S = 10.0  # the running session refreshes its claim this often
STALE_S = 60.0  # a claim older than this is dead (another host)


@dataclass
class Design:
    """One design as stored."""

    number: int  # optuna trial number
    key: str
    phase: str
    status: str  # running, complete, failed, interrupted, waiting
    values: dict  # variable -> value
    responses: dict = field(default_factory=dict)
    constraints: list = field(default_factory=list)
    feasible: bool | None = None
    objectives: list | None = None
    message: str = ""
    info: dict = field(default_factory=dict)  # wall_time, attempt, host, pid, directory, ...
    started: float | None = None
    finished: float | None = None

    @property
    def done(self) -> bool:
        return self.status in ("complete", "failed")


def _quiet_optuna():
    import optuna

    optuna.logging.set_verbosity(optuna.logging.WARNING)
    return optuna


def make_storage(url: str, where: str = ""):
    """optuna storage of ``url``; ``where`` ("study.toml: [study] storage")
    prefixes the error when it cannot be opened or made."""
    optuna = _quiet_optuna()
    head = f"{where}: " if where else ""
    kwargs = {}
    try:
        if url.startswith("sqlite:///"):
            Path(url[len("sqlite:///") :]).parent.mkdir(parents=True, exist_ok=True)
            kwargs = {"connect_args": {"timeout": 60}}
        return optuna.storages.RDBStorage(url, engine_kwargs=kwargs)
    except Exception as e:  # noqa: BLE001 - bad URL, missing driver, server down, a folder not writable
        raise StudyError(f"{head}cannot open the study storage {url!r}: {type(e).__name__}: {e}") from None


def _native() -> bool:
    from optuna.trial import Trial

    return hasattr(Trial, "set_constraint")


NATIVE_CONSTRAINTS = _native()


def constraints_of(trial) -> list[float]:
    """optuna constraints_func: the violations stored with the trial."""
    return list(trial.user_attrs.get("constraints", []))


class StudyStore:
    """The optuna study of a crashlite study."""

    def __init__(self, cfg: StudyConfig, sampler=None, readonly: bool = False):
        optuna = _quiet_optuna()
        self.cfg = cfg
        where = f"{cfg.path}: [study] storage"
        self.storage = make_storage(cfg.storage, where)
        self.directions = [o.goal for o in cfg.objectives] or ["minimize"]
        if readonly:
            try:
                self.study = optuna.load_study(study_name=cfg.name, storage=self.storage)
            except KeyError:
                raise StudyError(
                    f"{cfg.path}: [study] name: no study {cfg.name!r} in {cfg.storage} "
                    f"(run it first: crashlite study run {cfg.path})"
                ) from None
        else:
            try:
                self.study = optuna.create_study(
                    storage=self.storage,
                    study_name=cfg.name,
                    load_if_exists=True,
                    directions=self.directions,
                    sampler=sampler,
                )
            except Exception as e:  # noqa: BLE001 - a storage that opens but cannot be written
                raise StudyError(
                    f"{where}: cannot write the study {cfg.name!r} to {cfg.storage!r}: {type(e).__name__}: {e}"
                ) from None
            self._check_fingerprint()
        stored = [d.name.lower() for d in self.study.directions]
        if stored != self.directions:
            raise StudyError(
                f"{cfg.path}: [objectives]: the stored study {cfg.name!r} has directions {stored}, "
                f"the study file {self.directions}; use a new study name"
            )
        self._beat = 0.0

    # --- identity --------------------------------------------------------------
    def _check_fingerprint(self) -> None:
        fp = json.loads(json.dumps(self.cfg.fingerprint()))
        old = self.study.user_attrs.get("fingerprint")
        if old is None:
            self.study.set_user_attr("fingerprint", fp)
            return
        diffs = []
        for k in sorted(set(old) | set(fp)):
            if old.get(k) != fp.get(k):
                diffs.append(f"{k}: stored {json.dumps(old.get(k))[:200]}, now {json.dumps(fp.get(k))[:200]}")
        if diffs:
            raise StudyError(
                f"{self.cfg.path}: the study file no longer matches study {self.cfg.name!r} in "
                f"{self.cfg.storage} (" + "; ".join(diffs) + "); give [study] name a new "
                "name to start another study"
            )

    # --- the running session's claim ---------------------------------------------
    def claim(self, force: bool = False) -> None:
        d = self.study.user_attrs.get("driver")
        if d and not force:
            age = time.time() - float(d.get("beat", 0))
            same_host = d.get("host") == socket.gethostname()
            alive = age < STALE_S and (not same_host or _pid_alive(int(d.get("pid", 0))))
            if alive:
                raise StudyError(
                    f"{self.cfg.path}: study {self.cfg.name!r} is being run by process "
                    f"{d.get('pid')} on {d.get('host')} (last heartbeat {age:.0f} s ago); "
                    f"wait for it to end or stop it"
                )
        self.heartbeat(force=True)

    def heartbeat(self, force: bool = False) -> None:
        now = time.time()
        if force or now - self._beat >= HEARTBEAT_S:
            self.study.set_user_attr("driver", {"host": socket.gethostname(), "pid": os.getpid(), "beat": now})
            self._beat = now

    def release(self) -> None:
        try:
            self.study.set_user_attr("driver", None)
        except Exception:  # noqa: BLE001
            pass

    # --- reading -----------------------------------------------------------------
    def designs(self) -> list[Design]:
        from optuna.trial import TrialState

        out = []
        for t in self.study.get_trials(deepcopy=False):
            a = t.user_attrs
            key = a.get("design")
            if key is None:
                continue
            status = a.get("status", "running")
            if t.state == TrialState.RUNNING:
                status = "running"
            elif t.state == TrialState.WAITING:
                status = "waiting"
            elif t.state == TrialState.COMPLETE:
                status = "complete"
            elif status not in ("failed", "interrupted"):
                status = "interrupted"
            r = a.get("result", {})
            out.append(
                Design(
                    number=t.number,
                    key=key,
                    phase=a.get("phase", ""),
                    status=status,
                    values=dict(t.params) or dict(r.get("values", {})),
                    responses=dict(r.get("responses", {})),
                    constraints=list(a.get("constraints", [])),
                    feasible=r.get("feasible"),
                    objectives=list(t.values) if t.values is not None else None,
                    message=r.get("message", a.get("message", "")),
                    info={k: v for k, v in r.items() if k not in ("responses", "values", "message")},
                    started=t.datetime_start.timestamp() if t.datetime_start else None,
                    finished=t.datetime_complete.timestamp() if t.datetime_complete else None,
                )
            )
        return out

    def done_keys(self) -> set[str]:
        return {d.key for d in self.designs() if d.done}

    # --- recovery ----------------------------------------------------------------
    def recover(self) -> list[Design]:
        """Close the trials a killed session left RUNNING (or WAITING) as
        interrupted; returns them (their designs run again)."""
        from optuna.trial import TrialState

        stale = []
        for _t in self.study.get_trials(deepcopy=False, states=(TrialState.WAITING,)):
            trial = self.study.ask()  # pops the waiting trial
            self.storage.set_trial_user_attr(trial._trial_id, "status", "interrupted")
            self.study.tell(trial, state=TrialState.FAIL)
        for t in self.study.get_trials(deepcopy=False, states=(TrialState.RUNNING,)):
            self.storage.set_trial_user_attr(t._trial_id, "status", "interrupted")
            self.storage.set_trial_user_attr(
                t._trial_id, "result", {"message": "interrupted: its session ended before the run did"}
            )
            self.study.tell(t.number, state=TrialState.FAIL, skip_if_finished=True)
            stale.append(t)
        keys = {t.user_attrs.get("design") for t in stale}
        return [d for d in self.designs() if d.key in keys and d.status == "interrupted"]

    # --- writing -----------------------------------------------------------------
    def _suggest(self, trial) -> dict:
        vals = {}
        for v in self.cfg.variables:
            if v.integer:
                vals[v.name] = trial.suggest_int(v.name, int(v.lower), int(v.upper))
            else:
                vals[v.name] = trial.suggest_float(v.name, v.lower, v.upper)
        return vals

    def start_fixed(self, key: str, phase: str, values: dict):
        """A RUNNING trial for a planned design; returns (trial, values)."""
        fixed = {}
        for v in self.cfg.variables:
            x = min(max(float(values[v.name]), v.lower), v.upper)
            fixed[v.name] = int(round(x)) if v.integer else x
        self.study.enqueue_trial(fixed, user_attrs={"design": key, "phase": phase, "status": "running"})
        trial = self.study.ask()
        if trial.user_attrs.get("design") != key:  # another process enqueued: should not happen
            raise StudyError(
                f"study {self.cfg.name!r}: trial {trial.number} is not design {key} "
                f"(is another session running this study?)"
            )
        return trial, self._suggest(trial)

    def start_sampled(self, key: str, phase: str):
        """A RUNNING trial whose values the optuna sampler chooses."""
        trial = self.study.ask()
        trial.set_user_attr("design", key)
        trial.set_user_attr("phase", phase)
        trial.set_user_attr("status", "running")
        return trial, self._suggest(trial)

    def finish(self, trial, result: dict) -> Design:
        """Record a design's result (from evaluate) and close its trial."""
        from optuna.trial import TrialState

        info = {k: v for k, v in result.items() if k not in ("traceback",)}
        info["directory"] = _relative(info.get("directory"), self.cfg.directory)
        if "deck" in info:
            info["deck"] = _relative(info["deck"], self.cfg.directory)
        status = result.get("status")
        values = None
        if status == "complete":
            resp = result["responses"]
            cons = []
            for c in self.cfg.constraints:
                cons += c.violations(resp[c.response])
            info["feasible"] = all(c <= 0 for c in cons)
            values = [resp[o.response] for o in self.cfg.objectives] or [0.0]
            if not all(math.isfinite(v) for v in values):
                status = "failed"
                info["message"] = f"objective not finite: {values}"
            else:
                self.storage.set_trial_user_attr(trial._trial_id, "constraints", cons)
                if NATIVE_CONSTRAINTS:  # optuna >= 5: the samplers read the trial's own constraints
                    for i, c in enumerate(cons):
                        trial.set_constraint(f"c{i}", c)
        if status != "complete" and not info.get("message"):
            info["message"] = "failed without a message"
        self.storage.set_trial_user_attr(trial._trial_id, "result", info)
        self.storage.set_trial_user_attr(trial._trial_id, "status", "complete" if status == "complete" else "failed")
        if status == "complete":
            self.study.tell(trial, values)
        else:
            self.study.tell(trial, state=TrialState.FAIL)
        return next(d for d in self.designs() if d.number == trial.number)

    def interrupt(self, trial, why: str) -> None:
        from optuna.trial import TrialState

        try:
            self.storage.set_trial_user_attr(trial._trial_id, "status", "interrupted")
            self.storage.set_trial_user_attr(trial._trial_id, "result", {"message": f"interrupted: {why}"})
            self.study.tell(trial, state=TrialState.FAIL, skip_if_finished=True)
        except Exception:  # noqa: BLE001 - best effort on the way out; the next session recovers it
            pass

    def set_attr(self, key: str, value) -> None:
        self.study.set_user_attr(key, value)

    def attr(self, key: str, default=None):
        return self.study.user_attrs.get(key, default)


def _relative(path, base) -> str | None:
    if not path:
        return path
    try:
        return os.path.relpath(path, base)
    except ValueError:
        return str(path)


def _pid_alive(pid: int) -> bool:
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True
