"""Time accounting of runs, as the paper's table 1: elements by type, time
step, cycles, CPU and wall time, and the reduction against a reference run.

Run facts come from a crashlite ``Results``, a crashlite results folder
(results.npz; element counts from the deck when given) or an LS-DYNA
folder or ``d3hsp`` file (its closing timing lines).
"""

from __future__ import annotations

import math
import re
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..model.model import Model
    from ..solver.results import Results


@dataclass
class RunInfo:
    """What a run cost. Times in seconds; None where the source lacks it."""

    name: str
    elements: dict[str, int] = field(default_factory=dict)  # element count by type
    time_step: float | None = None  # last (or only) time step [time unit of the run]
    cycles: int | None = None
    end_time: float | None = None  # simulated time [time unit of the run]
    cpu_time: float | None = None  # [s]
    wall_time: float | None = None  # the run time compared [s]: crashlite: its time loop
    source: str = ""
    # start-up outside the compared time (crashlite: building the arrays, first forces, Numba
    # compilation) and the compilation in it [s]; None where the source does not tell it apart
    setup_time: float | None = None
    compile_time: float | None = None
    total_wall_time: float | None = None  # wall time of the whole run [s]

    @property
    def n_elements(self) -> int:
        return int(sum(self.elements.values()))

    def as_dict(self) -> dict:
        return {**asdict(self), "n_elements": self.n_elements}


def elements_of_model(model: Model) -> dict[str, int]:
    """Element counts of a crashlite Model by LS-DYNA element type."""
    from ..solver.results import element_counts

    return element_counts(model)


def run_info(source: Results | Path | str, name: str | None = None, deck: Path | str | Model | None = None) -> RunInfo:
    """RunInfo of a Results object, a crashlite results folder / results.npz,
    or an LS-DYNA output folder / d3hsp file; ``deck`` (path or Model)
    supplies the element counts when the source has none."""
    from ..solver.results import Results

    if isinstance(source, Results):
        ri = _from_results(source, name or "run", "results")
    else:
        p = Path(source)
        npz = p / "results.npz" if p.is_dir() else p
        d3hsp = p / "d3hsp" if p.is_dir() else p
        if npz.is_file() and npz.suffix == ".npz":
            ri = _from_npz(npz, name or p.name)
        elif d3hsp.is_file() and d3hsp.name.startswith("d3hsp"):
            ri = parse_d3hsp(d3hsp.read_text(errors="replace"), name or p.name, str(d3hsp))
        else:
            raise FileNotFoundError(f"{p}: no results.npz and no d3hsp to take the run time from")
    if deck is not None and not ri.elements:
        from .. import read_deck

        model = deck if hasattr(deck, "shells") else read_deck(deck)
        ri.elements = elements_of_model(model)
    return ri


def _from_results(res, name: str, source: str) -> RunInfo:
    """The run time compared is the time loop (``loop_time``); results of
    crashlite versions that did not record it give their whole wall time."""
    looped = res.loop_time > 0 or res.cpu_time > 0
    return RunInfo(
        name,
        dict((res.info or {}).get("elements") or {}),
        float(res.time_step[-1]) if res.recorded("time_step") else float(res.dt),
        int(res.cycles),
        float(res.time[-1]) if len(res.time) else None,
        float(res.cpu_time) if looped else None,
        float(res.loop_time) if looped else float(res.wall_time),
        source,
        float(res.setup_time) if looped else None,
        float(res.compile_time) if looped else None,
        float(res.wall_time),
    )


def _from_npz(path: Path, name: str) -> RunInfo:
    """Only the few entries needed (the field states stay on disk)."""
    from types import SimpleNamespace

    with np.load(path) as z:
        keys = set(z.files)
        t = z["time"] if "time" in keys else np.zeros(0)
        steps = z["time_step"] if "time_step" in keys else np.zeros(0)
        res = SimpleNamespace(
            info={"elements": {k[len("info_elements_") :]: int(z[k]) for k in keys if k.startswith("info_elements_")}},
            time=t,
            dt=float(z["dt"]) if "dt" in keys else (float(steps[-1]) if steps.size else 0.0),
            cycles=int(z["cycles"]) if "cycles" in keys else 0,
            recorded=lambda name: name == "time_step" and steps.size == t.size and steps.size > 0,
            time_step=steps,
            **{
                k: float(z[k]) if k in keys else 0.0
                for k in ("wall_time", "loop_time", "cpu_time", "setup_time", "compile_time")
            },
        )
    return _from_results(res, name, str(path))


_NUM = r"([-+]?\d+(?:\.\d*)?(?:[EeDd][-+]?\d+)?)"
_D3HSP = {
    "cpu_time": re.compile(r"Total CPU time\s*=\s*" + _NUM + r"\s*seconds", re.I),
    "wall_time": re.compile(r"Elapsed time\s*" + _NUM + r"\s*seconds", re.I),
    "cycles": re.compile(r"Problem cycle\s*=\s*(\d+)", re.I),
    "end_time": re.compile(r"Problem time\s*=\s*" + _NUM, re.I),
}
_D3HSP_CYCLES = re.compile(r"seconds\s+for\s+(\d+)\s+cycles", re.I)
_D3HSP_ELEMENTS = re.compile(r"number of (\w[\w ]*?) elements\b[ .]*?\s(\d+)\s*$", re.I | re.M)


def parse_d3hsp(text: str, name: str = "LS-DYNA", source: str = "d3hsp") -> RunInfo:
    """Run facts from the text of an LS-DYNA d3hsp file: the last
    ``Problem time``/``Problem cycle``, ``Total CPU time = … seconds``,
    ``Elapsed time … seconds for … cycles`` and ``number of … elements``
    lines it holds."""

    def last(rx):
        m = rx.findall(text)
        return float(m[-1].replace("D", "E").replace("d", "e")) if m else None

    ri = RunInfo(name, source=source)
    ri.cpu_time = last(_D3HSP["cpu_time"])
    ri.wall_time = last(_D3HSP["wall_time"])
    ri.end_time = last(_D3HSP["end_time"])
    c = last(_D3HSP["cycles"])
    if c is None:
        m = _D3HSP_CYCLES.findall(text)
        c = float(m[-1]) if m else None
    ri.cycles = None if c is None else int(c)
    for kind, count in _D3HSP_ELEMENTS.findall(text):
        if int(count):
            ri.elements[kind.strip().lower()] = int(count)
    if ri.cpu_time is None and ri.wall_time is None:
        raise ValueError(f"{source}: no 'Total CPU time' or 'Elapsed time' line (did the run terminate?)")
    return ri


def reduction(reference: float | None, value: float | None) -> float | None:
    """Time saved in % of the reference: 100·(1 − value/reference)."""
    if reference is None or value is None or not reference > 0:
        return None
    return 100.0 * (1.0 - value / reference)


def timing_table(runs: list[RunInfo], reference: int = 0) -> list[dict]:
    """One row per run: elements (total, % of the reference, by type), time
    step, cycles, CPU and wall time and their reductions against
    ``runs[reference]`` in % (for crashlite runs the time loop; the
    start-up, ``setup_time``, is listed but not compared)."""
    if not runs:
        raise ValueError("timing_table: no runs")
    ref = runs[reference]
    rows = []
    for r in runs:
        share = 100.0 * r.n_elements / ref.n_elements if ref.n_elements else None
        rows.append(
            {
                "name": r.name,
                "elements": r.n_elements,
                "elements_by_type": dict(r.elements),
                "element_share_percent": share,
                "time_step": r.time_step,
                "cycles": r.cycles,
                "end_time": r.end_time,
                "cpu_time": r.cpu_time,
                "wall_time": r.wall_time,
                "setup_time": r.setup_time,
                "compile_time": r.compile_time,
                "total_wall_time": r.total_wall_time,
                "cpu_reduction_percent": reduction(ref.cpu_time, r.cpu_time),
                "wall_reduction_percent": reduction(ref.wall_time, r.wall_time),
                "speedup": (ref.wall_time / r.wall_time if ref.wall_time and r.wall_time else None),
            }
        )
    return rows


def format_duration(seconds: float | None) -> str:
    """'5 h 48 min', '3 min 20 s', '40 s', '0.84 s' (as table 1 writes times)."""
    if seconds is None or not math.isfinite(seconds):
        return "–"
    if seconds < 60:
        return f"{seconds:.3g} s"
    s = int(round(seconds))
    h, rest = divmod(s, 3600)
    m, sec = divmod(rest, 60)
    return f"{h} h {m} min" if h else f"{m} min {sec} s"
