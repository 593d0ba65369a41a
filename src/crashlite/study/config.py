"""The study file (TOML): deck, design variables, responses, objectives,
constraints, design of experiments, sensitivity, optimisation, execution.

Every problem names the study file and the key, e.g.
``study.toml: [variables.t_box] bounds: lower 2.0 is not below upper 1.0``.
The deck is read once here, so a part name, node or section the deck lacks
is reported before any run starts. See docs/study.md for the format.
"""

from __future__ import annotations

import builtins
import math
import os
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

# StudyError lives in ``errors`` (``designs`` raises it too); importable here
from .errors import StudyError
from .responses import ResponseSpec, parse_response

PROPERTIES = ("thickness", "yield")
DOE_METHODS = ("lhs", "sobol", "halton", "random")
OPT_METHODS = ("tpe", "nsga2", "random", "metamodel")
SENSITIVITY_METHODS = ("sobol", "morris")
METAMODELS = ("auto", "quadratic", "linear", "rbf")
SOLVERS = ("crashlite", "lsdyna", "openradioss")  # [execution] solver: crashlite's own, or crashlite.external


@dataclass
class Variable:
    name: str
    lower: float
    upper: float
    parameter: str | None = None  # a *PARAMETER of the deck
    parts: list = field(default_factory=list)  # part names or IDs (part variables)
    property: str | None = None  # "thickness" or "yield" (part variables)
    integer: bool = False  # an I-type parameter
    baseline: float | None = None  # value in the deck

    @builtins.property
    def kind(self) -> str:
        return "parameter" if self.parameter else self.property

    def describe(self) -> dict:
        d = {"name": self.name, "bounds": [self.lower, self.upper], "kind": self.kind}
        if self.parameter:
            d["parameter"] = self.parameter
        else:
            d["parts"] = list(self.parts)
        if self.integer:
            d["integer"] = True
        return d


@dataclass
class Objective:
    response: str
    goal: str  # "minimize" or "maximize"


@dataclass
class Constraint:
    response: str
    lower: float | None = None
    upper: float | None = None

    def violations(self, value: float) -> list[float]:
        """Normalised violations, ≤ 0 when met (optuna's convention)."""
        out = []
        if self.upper is not None:
            out.append((value - self.upper) / (abs(self.upper) or 1.0))
        if self.lower is not None:
            out.append((self.lower - value) / (abs(self.lower) or 1.0))
        return out

    def text(self) -> str:
        parts = []
        if self.lower is not None:
            parts.append(f"{self.lower:g} ≤")
        parts.append(self.response)
        if self.upper is not None:
            parts.append(f"≤ {self.upper:g}")
        return " ".join(parts)


@dataclass
class DoeSettings:
    method: str = "lhs"
    designs: int = 0
    seed: int = 0
    scramble: bool = True


@dataclass
class SensitivitySettings:
    method: str = "sobol"  # sobol: from the metamodel of the designs run; morris: own runs
    runs: bool = False  # sobol: Saltelli runs of the deck instead of the metamodel
    samples: int = 1024  # sobol: base samples N (metamodel: cheap; runs: N·(d+2) runs)
    trajectories: int = 10  # morris: r, r·(d+1) runs
    levels: int = 4
    seed: int = 0


@dataclass
class OptimizationSettings:
    method: str = "tpe"
    trials: int = 0
    population: int = 16  # nsga2
    seed: int = 0
    iterations: int = 4  # metamodel: sequential iterations
    points: int = 0  # metamodel: designs per iteration (0: the number of workers)
    shrink: float = 0.6  # metamodel: region shrink per iteration


@dataclass
class ExecutionSettings:
    workers: int = 0  # 0: one per core
    threads_per_run: int = 1
    scheduler: str | None = None  # tcp://host:8786
    allowed_failures: int = 3  # worker deaths a design survives (retries)
    memory_limit: str = "auto"
    keep: str = "all"  # results of every design ("all"), or only decks and responses ("decks")
    solver: str = "crashlite"  # or an external solver: "lsdyna", "openradioss" (crashlite.external)
    cluster: str | None = None  # "module:callable" returning a Dask cluster (dask-jobqueue's SLURMCluster, ...)


@dataclass
class StudyConfig:
    path: Path  # the study file
    name: str
    deck: Path
    storage: str
    directory: Path
    variables: list[Variable]
    responses: dict[str, ResponseSpec]
    objectives: list[Objective]
    constraints: list[Constraint]
    doe: DoeSettings | None
    sensitivity: SensitivitySettings | None
    optimization: OptimizationSettings | None
    metamodel: str = "auto"
    execution: ExecutionSettings = field(default_factory=ExecutionSettings)
    template: object = None  # designs.DeckTemplate, built at load

    def where(self, key: str) -> str:
        return f"{self.path}: {key}"

    @property
    def variable_names(self) -> list[str]:
        return [v.name for v in self.variables]

    def fingerprint(self) -> dict:
        """What must not change between sessions of one study: the design
        space, the responses and the planned designs."""
        out = {
            "variables": [v.describe() for v in self.variables],
            "responses": {k: r.describe() for k, r in self.responses.items()},
            "deck": str(self.deck),
        }
        if self.doe:
            out["doe"] = {
                "method": self.doe.method,
                "designs": self.doe.designs,
                "seed": self.doe.seed,
                "scramble": self.doe.scramble,
            }
        if self.sensitivity and (self.sensitivity.method == "morris" or self.sensitivity.runs):
            s = self.sensitivity
            out["sensitivity"] = {
                "method": s.method,
                "samples": s.samples,
                "trajectories": s.trajectories,
                "levels": s.levels,
                "seed": s.seed,
            }
        return out


# --- reading -----------------------------------------------------------------


class _Reader:
    def __init__(self, path: Path):
        self.path = path

    def fail(self, key: str, msg: str):
        raise StudyError(f"{self.path}: {key}: {msg}")

    def table(self, data: dict, key: str, where: str, required: bool = False) -> dict | None:
        v = data.get(key)
        if v is None:
            if required:
                self.fail(where, f"missing table [{key}]")
            return None
        if not isinstance(v, dict):
            self.fail(where, f"{key} must be a table, got {type(v).__name__}")
        return v

    def known(self, data: dict, allowed, where: str) -> None:
        extra = [k for k in data if k not in allowed]
        if extra:
            self.fail(
                where,
                f"unknown key{'s' if len(extra) > 1 else ''} {', '.join(map(repr, extra))} "
                f"(known: {', '.join(allowed)})",
            )

    def number(self, data: dict, key: str, where: str, default=None, positive=False, integer=False):
        v = data.get(key, default)
        if v is None:
            return None
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            self.fail(where, f"{key} must be a finite number, got {v!r}")
        if integer and int(v) != v:
            self.fail(where, f"{key} must be a whole number, got {v!r}")
        if positive and v <= 0:
            self.fail(where, f"{key} must be positive, got {v!r}")
        return int(v) if integer else v

    def string(self, data: dict, key: str, where: str, default=None, choices=None):
        v = data.get(key, default)
        if v is None:
            return None
        if not isinstance(v, str):
            self.fail(where, f"{key} must be a string, got {v!r}")
        if choices is not None and v.lower() not in choices:
            self.fail(where, f"{key} = {v!r} is not one of {', '.join(choices)}")
        return v.lower() if choices is not None else v


def load_study(path: Path | str, build_template: bool = True) -> StudyConfig:
    """Read and check a study file; the deck is read to resolve part
    names, parameters and response entities."""
    path = Path(path)
    if not path.is_file():
        raise StudyError(f"{path}: study file not found")
    try:
        data = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as e:
        raise StudyError(f"{path}: malformed TOML: {e}") from None
    except UnicodeDecodeError as e:
        raise StudyError(f"{path}: not a text file ({e})") from None
    r = _Reader(path)
    r.known(
        data,
        (
            "study",
            "variables",
            "responses",
            "objectives",
            "constraints",
            "doe",
            "sensitivity",
            "optimization",
            "metamodel",
            "execution",
        ),
        "top level",
    )
    st = r.table(data, "study", "top level", required=True)
    r.known(st, ("name", "deck", "storage", "directory"), "[study]")
    name = r.string(st, "name", "[study]", default=path.stem)
    if not name or not name.strip():
        r.fail("[study] name", "must not be empty")
    deck_text = r.string(st, "deck", "[study]")
    if deck_text is None:
        r.fail("[study] deck", "missing: the keyword deck the designs are made from")
    base = path.parent
    deck = (base / deck_text).resolve() if not os.path.isabs(deck_text) else Path(deck_text)
    if not deck.is_file():
        r.fail("[study] deck", f"deck file {str(deck)!r} not found")
    directory = r.string(st, "directory", "[study]", default=f"{path.stem}_study")
    directory = Path(directory) if os.path.isabs(directory) else (base / directory).resolve()
    storage = r.string(st, "storage", "[study]", default=None)
    if storage is None:
        storage = f"sqlite:///{directory / (path.stem + '.db')}"
    elif "://" not in storage:  # a bare file name: SQLite next to the study file
        p = Path(storage)
        storage = f"sqlite:///{p if p.is_absolute() else (base / p).resolve()}"
    elif storage.startswith("sqlite:///") and not storage.startswith("sqlite:////"):
        rel = storage[len("sqlite:///") :]
        storage = f"sqlite:///{(base / rel).resolve()}"
    variables = _variables(r, data)
    responses = _responses(r, data)
    objectives = _objectives(r, data, responses)
    constraints = _constraints(r, data, responses)
    doe = _doe(r, data)
    sens = _sensitivity(r, data)
    opt = _optimization(r, data, objectives)
    mm = (
        r.string(data, "metamodel", "top level", default="auto", choices=METAMODELS)
        if not isinstance(data.get("metamodel"), dict)
        else _metamodel_table(r, data["metamodel"])
    )
    ex = _execution(r, data)
    if doe is None and opt is None and sens is None:
        r.fail("top level", "nothing to run: give [doe], [sensitivity] or [optimization]")
    if (
        sens is not None
        and sens.method == "sobol"
        and not sens.runs
        and (doe is None or doe.designs == 0)
        and opt is None
    ):
        r.fail("[sensitivity]", "Sobol indices from the metamodel need designs: add [doe] (or runs = true)")
    _check_sizes(r, len(variables), doe, sens, opt)
    cfg = StudyConfig(
        path=path,
        name=name.strip(),
        deck=deck,
        storage=storage,
        directory=directory,
        variables=variables,
        responses=responses,
        objectives=objectives,
        constraints=constraints,
        doe=doe,
        sensitivity=sens,
        optimization=opt,
        metamodel=mm,
        execution=ex,
    )
    if build_template:
        from .designs import DeckTemplate

        cfg.template = DeckTemplate.build(cfg)
    return cfg


DESIGN_BYTES = 4096  # memory one planned design takes (plan entry, stored trial, progress), per variable 64 more
POINT_BYTES = 8  # one coordinate of a point the metamodel is evaluated at (Sobol indices without runs)


def memory_bytes() -> int:
    """Physical memory of this machine (8 GiB when it cannot be told)."""
    try:
        return int(os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
    except (ValueError, OSError, AttributeError):
        return 8 << 30


def _check_sizes(r: _Reader, d: int, doe, sens, opt) -> None:
    """Designs (and metamodel points) a study plans must fit in a quarter of
    the memory, else the key that asks for them is named before anything
    is allocated (designs = 1e9 ended in a MemoryError traceback)."""
    budget = memory_bytes() // 4
    per_design = DESIGN_BYTES + 64 * max(d, 1)
    asked = []
    if doe is not None:
        asked.append(("[doe] designs", doe.designs, doe.designs, per_design))
    if sens is not None and sens.method == "morris":
        asked.append(("[sensitivity] trajectories", sens.trajectories, sens.trajectories * (d + 1), per_design))
    if sens is not None and sens.method == "sobol":
        n = sens.samples * (2 * d + 2)
        asked.append(("[sensitivity] samples", sens.samples, n, per_design if sens.runs else POINT_BYTES * (2 * d + 4)))
    if opt is not None:
        asked.append(("[optimization] trials", opt.trials, opt.trials, per_design))
        asked.append(("[optimization] points", opt.points, opt.points * opt.iterations, per_design))
    for key, value, n, each in asked:
        if n * each > budget:
            most = budget // each
            scale = n / max(value, 1)
            r.fail(
                key,
                f"{value} asks for {n:,} planned designs or points, about {n * each / 2**30:.3g} GiB of "
                f"memory; a quarter of this machine's {memory_bytes() / 2**30:.3g} GiB holds at most "
                f"{int(most / scale):,}",
            )


def _metamodel_table(r: _Reader, t: dict) -> str:
    r.known(t, ("type",), "[metamodel]")
    return r.string(t, "type", "[metamodel]", default="auto", choices=METAMODELS)


def _variables(r: _Reader, data: dict) -> list[Variable]:
    t = r.table(data, "variables", "top level", required=True)
    if not t:
        r.fail("[variables]", "no design variable given")
    out = []
    for name, v in t.items():
        where = f"[variables.{name}]"
        if not isinstance(v, dict):
            r.fail(where, "must be a table with bounds and a parameter or parts")
        r.known(v, ("parameter", "part", "parts", "property", "bounds"), where)
        b = v.get("bounds")
        if (
            not isinstance(b, list)
            or len(b) != 2
            or not all(isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) for x in b)
        ):
            r.fail(f"{where} bounds", f"must be [lower, upper] (two finite numbers), got {b!r}")
        lo, hi = float(b[0]), float(b[1])
        if not lo < hi:
            r.fail(f"{where} bounds", f"lower {b[0]} is not below upper {b[1]}")
        has_param = "parameter" in v
        has_parts = "part" in v or "parts" in v
        if has_param == has_parts:
            r.fail(
                where,
                'give either parameter = "NAME" (a *PARAMETER of the deck) or part(s) with '
                'property = "thickness" | "yield"',
            )
        if has_param:
            pname = r.string(v, "parameter", where)
            if "property" in v:
                r.fail(f"{where} property", "applies to part variables, not to a parameter")
            out.append(Variable(name, lo, hi, parameter=pname.strip().lstrip("&")))
        else:
            if "part" in v and "parts" in v:
                r.fail(where, "give part or parts, not both")
            parts = v.get("parts", v.get("part"))
            parts = parts if isinstance(parts, list) else [parts]
            if not parts or not all(isinstance(p, (str, int)) and not isinstance(p, bool) for p in parts):
                r.fail(f"{where} parts", f"must be part names or IDs, got {v.get('parts', v.get('part'))!r}")
            prop = r.string(v, "property", where, default=None, choices=PROPERTIES)
            if prop is None:
                r.fail(f"{where} property", f"missing: one of {', '.join(PROPERTIES)}")
            if lo <= 0:
                r.fail(f"{where} bounds", f"a {prop} must be positive, lower bound is {b[0]}")
            out.append(Variable(name, lo, hi, parts=parts, property=prop))
    return out


def _responses(r: _Reader, data: dict) -> dict[str, ResponseSpec]:
    t = r.table(data, "responses", "top level", required=True)
    if not t:
        r.fail("[responses]", "no response given")
    out = {}
    for name, v in t.items():
        where = f"[responses.{name}]"
        if not isinstance(v, dict):
            r.fail(where, "must be a table with a type")
        try:
            out[name] = parse_response(name, v)
        except ValueError as e:
            r.fail(where, str(e))
    for name, spec in out.items():
        for dep in spec.depends_on():
            if dep not in out:
                r.fail(
                    f"[responses.{name}] expression",
                    f"names {dep!r}, which is not a response (responses: {', '.join(out)})",
                )
            if list(out).index(dep) >= list(out).index(name):
                r.fail(f"[responses.{name}] expression", f"uses {dep!r}, which is defined after it")
    return out


def _objectives(r: _Reader, data: dict, responses) -> list[Objective]:
    t = r.table(data, "objectives", "top level")
    out = []
    for name, goal in (t or {}).items():
        where = f"[objectives] {name}"
        if name not in responses:
            r.fail(where, f"unknown response {name!r} (responses: {', '.join(responses)})")
        if not isinstance(goal, str) or goal.lower() not in ("minimize", "maximize", "minimise", "maximise"):
            r.fail(where, f'must be "minimize" or "maximize", got {goal!r}')
        out.append(Objective(name, goal.lower().replace("ise", "ize")))
    return out


def _constraints(r: _Reader, data: dict, responses) -> list[Constraint]:
    t = r.table(data, "constraints", "top level")
    out = []
    for name, c in (t or {}).items():
        where = f"[constraints] {name}"
        if name not in responses:
            r.fail(where, f"unknown response {name!r} (responses: {', '.join(responses)})")
        if not isinstance(c, dict):
            r.fail(where, "must be a table such as { upper = 50.0 } or { lower = 1.0, upper = 2.0 }")
        r.known(c, ("lower", "upper"), where)
        lo, hi = r.number(c, "lower", where), r.number(c, "upper", where)
        if lo is None and hi is None:
            r.fail(where, "give lower, upper or both")
        if lo is not None and hi is not None and not lo < hi:
            r.fail(where, f"lower {lo} is not below upper {hi}")
        out.append(Constraint(name, None if lo is None else float(lo), None if hi is None else float(hi)))
    return out


def _doe(r: _Reader, data: dict) -> DoeSettings | None:
    t = r.table(data, "doe", "top level")
    if t is None:
        return None
    w = "[doe]"
    r.known(t, ("method", "designs", "seed", "scramble"), w)
    n = r.number(t, "designs", w, integer=True, positive=True)
    if n is None:
        r.fail(f"{w} designs", "missing: the number of designs")
    scramble = t.get("scramble", True)
    if not isinstance(scramble, bool):
        r.fail(f"{w} scramble", f"must be true or false, got {scramble!r}")
    return DoeSettings(
        r.string(t, "method", w, "lhs", DOE_METHODS), n, r.number(t, "seed", w, 0, integer=True), scramble
    )


def _sensitivity(r: _Reader, data: dict) -> SensitivitySettings | None:
    t = r.table(data, "sensitivity", "top level")
    if t is None:
        return None
    w = "[sensitivity]"
    r.known(t, ("method", "runs", "samples", "trajectories", "levels", "seed"), w)
    runs = t.get("runs", False)
    if not isinstance(runs, bool):
        r.fail(f"{w} runs", f"must be true or false, got {runs!r}")
    s = SensitivitySettings(
        method=r.string(t, "method", w, "sobol", SENSITIVITY_METHODS),
        runs=runs,
        samples=r.number(t, "samples", w, 1024, positive=True, integer=True),
        trajectories=r.number(t, "trajectories", w, 10, positive=True, integer=True),
        levels=r.number(t, "levels", w, 4, positive=True, integer=True),
        seed=r.number(t, "seed", w, 0, integer=True),
    )
    if s.levels < 2 or s.levels % 2:
        r.fail(f"{w} levels", f"Morris levels must be even and at least 2, got {s.levels}")
    if s.method == "morris" and runs is False and "runs" in t:
        r.fail(f"{w} runs", "Morris screening always runs its own designs")
    return s


def _optimization(r: _Reader, data: dict, objectives) -> OptimizationSettings | None:
    t = r.table(data, "optimization", "top level")
    if t is None:
        return None
    w = "[optimization]"
    r.known(t, ("method", "trials", "population", "seed", "iterations", "points", "shrink"), w)
    if not objectives:
        r.fail(w, "an optimisation needs [objectives]")
    o = OptimizationSettings(
        method=r.string(t, "method", w, "tpe", OPT_METHODS),
        trials=r.number(t, "trials", w, 0, integer=True),
        population=r.number(t, "population", w, 16, positive=True, integer=True),
        seed=r.number(t, "seed", w, 0, integer=True),
        iterations=r.number(t, "iterations", w, 4, positive=True, integer=True),
        points=r.number(t, "points", w, 0, integer=True),
        shrink=r.number(t, "shrink", w, 0.6, positive=True),
    )
    if o.method != "metamodel" and o.trials <= 0:
        r.fail(f"{w} trials", "missing: the number of optimisation runs (trials = N)")
    if o.method == "metamodel" and len(objectives) > 1:
        r.fail(f"{w} method", "the metamodel optimisation takes one objective; use nsga2 or tpe for several")
    if not 0 < o.shrink <= 1:
        r.fail(f"{w} shrink", f"must lie in (0, 1], got {o.shrink}")
    if o.points < 0:
        r.fail(f"{w} points", f"must not be negative, got {o.points}")
    return o


def _execution(r: _Reader, data: dict) -> ExecutionSettings:
    t = r.table(data, "execution", "top level") or {}
    w = "[execution]"
    r.known(
        t,
        ("workers", "threads_per_run", "scheduler", "allowed_failures", "memory_limit", "keep", "solver", "cluster"),
        w,
    )
    workers = r.number(t, "workers", w, 0, integer=True)
    if workers < 0:
        r.fail(f"{w} workers", f"must be 1 or more (0 or absent: one per core), got {workers}")
    failures = r.number(t, "allowed_failures", w, 3, integer=True)
    if failures < 0:
        r.fail(f"{w} allowed_failures", f"must not be negative, got {failures}")
    cluster = r.string(t, "cluster", w)
    if cluster is not None:
        module, _, name = cluster.partition(":")
        if not module.strip() or not name.strip():
            r.fail(
                f"{w} cluster",
                f'must be "module:callable" (a function returning a Dask cluster, e.g. '
                f'"mycluster:slurm"), got {cluster!r}',
            )
        if t.get("scheduler") is not None:
            r.fail(w, "give scheduler or cluster, not both")
    return ExecutionSettings(
        workers=workers,
        threads_per_run=r.number(t, "threads_per_run", w, 1, positive=True, integer=True),
        scheduler=r.string(t, "scheduler", w),
        allowed_failures=failures,
        memory_limit=str(t.get("memory_limit", "auto")),
        keep=r.string(t, "keep", w, "all", ("all", "decks")),
        solver=r.string(t, "solver", w, "crashlite", SOLVERS),
        cluster=cluster,
    )
