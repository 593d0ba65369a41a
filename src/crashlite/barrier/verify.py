"""Verification of the simplified barrier against the detailed one (the
paper's figures 5–8 and table 1).

A rigid impactor (5000 kg, 64 km/h) strikes both barriers at 100 % and 40 %
overlap. For each overlap the runs are compared with the verification
toolkit (energies, wall force, timing: a report of its own), and the
impactor force, CFC 60, is rated by ISO/TS 18571 over the whole event and
over the crush phase: until the impactor has travelled the depth at which
the main block starts to compact, after which both barriers bottom out on
their compaction stiffening and the force is no longer the barrier's
characteristic. A table-1 analogue (nodes, elements by type, time step,
cycles, run time) and every figure go into ``summary.json`` and an index
page.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .detailed import detailed_barrier
from .loadcases import Impactor, write_impactor_case
from .simplified import Placement, simplified_barrier
from .spec import ODBSpec

CFC = 60.0


@dataclass
class Case:
    """One barrier run under the impactor."""

    barrier: str  # "detailed" or "simplified"
    overlap: float  # fraction of the barrier width
    folder: Path
    deck: Path
    counts: dict = field(default_factory=dict)
    time: np.ndarray | None = None  # (n,) [s]
    force: np.ndarray | None = None  # (n,) impactor force, unfiltered [N]
    travel: np.ndarray | None = None  # (n,) impactor travel [mm]
    dt: float = 0.0
    cycles: int = 0
    run_time: float = 0.0  # time loop [s]
    energy_ratio: float = 0.0  # total / initial energy at the end
    absorbed: float = 0.0  # energy in the barrier at the end [mJ]
    lost: float = 0.0  # impactor kinetic energy lost [mJ]

    @property
    def name(self) -> str:
        return f"{self.barrier} {round(100 * self.overlap)} %"

    def summary(self) -> dict:
        return {"barrier": self.barrier, "overlap_percent": 100.0 * self.overlap, "deck": str(self.deck),
                **self.counts, "time_step_ms": self.dt * 1e3, "cycles": self.cycles, "run_time_s": self.run_time,
                "energy_ratio": self.energy_ratio, "impactor_energy_lost_kJ": self.lost / 1e6,
                "barrier_energy_kJ": self.absorbed / 1e6,
                "peak_force_kN_cfc60": float(_cfc(self.time, self.force).max() / 1e3),
                "max_travel_mm": float(self.travel.max())}


def _cfc(t, f):
    from ..verify.filters import filter_signal

    tf, ff = filter_signal(t, f, CFC)
    return np.interp(t, tf, ff)


def _counts(deck: Path) -> dict:
    from .. import read_deck

    m = read_deck(deck)
    n = {"nodes": len(m.nodes), "solids": len(m.solids), "shells": len(m.shells), "beams": len(m.discretes)}
    n["elements"] = n["solids"] + n["shells"] + n["beams"]
    return n


def _run(case: Case, impactor: Impactor, progress: bool) -> None:
    from ..solver import run

    r = run(case.deck, out=case.folder / "out", quiet=not progress, output_dt=1e-4)
    case.time = r.time
    case.force = -r.wall_force[:, 0, 0]
    v = r.wall_velocity[:, 0]
    case.travel = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(r.time))])
    case.dt, case.cycles = float(r.dt), int(r.cycles)
    case.run_time = float(getattr(r, "loop_time", r.wall_time))
    e0 = 0.5 * impactor.mass * impactor.speed**2
    case.lost = e0 - 0.5 * impactor.mass * float(v[-1]) ** 2
    case.absorbed = float(r.internal[-1] + (r.hourglass[-1] if r.recorded("hourglass") else 0.0))
    case.energy_ratio = float(r.energy_ratio[-1])


def crush_phase_end(case: Case, spec: ODBSpec) -> float:
    """Time [s] at which the impactor has travelled the main block's
    compaction onset (fraction of the whole depth)."""
    reach = spec.main.curve.compaction * spec.depth
    k = np.flatnonzero(case.travel >= reach)
    return float(case.time[k[0]]) if len(k) else float(case.time[-1])


def rate_pair(ref: Case, cmp: Case, t1: float | None = None) -> dict:
    """ISO/TS 18571 rating of the CFC 60 impactor force of ``cmp`` against
    ``ref`` over [0, t1]."""
    from ..verify.rating import iso_rating

    r = iso_rating(ref.time, _cfc(ref.time, ref.force), cmp.time, _cfc(cmp.time, cmp.force), 0.0, t1)
    return {"overall": r.overall, "grade": r.grade, "corridor": r.corridor, "phase": r.phase,
            "magnitude": r.magnitude, "slope": r.slope, "until_ms": None if t1 is None else t1 * 1e3}


def verify_barriers(directory, spec: ODBSpec | None = None, element_size: float = 25.0, end_time: float = 0.045,
                    overlaps=(1.0, 0.4), impactor: Impactor | None = None, progress: bool = False,
                    report: bool = True) -> dict:
    """Run the impactor on both barriers at each overlap into ``directory``
    and write the reports; returns the summary (also ``summary.json``).
    ``spec`` supplies the simplified barrier's curves (e.g. characterised
    ones) and the geometry of both; ``element_size`` [mm] is the detailed
    barrier's."""
    spec = spec or ODBSpec()
    imp = impactor or Impactor()
    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    pl = Placement()
    builders = {"detailed": lambda: detailed_barrier(spec, pl, element_size=element_size),
                "simplified": lambda: simplified_barrier(spec, pl)}
    cases: dict[tuple[str, float], Case] = {}
    for ov in overlaps:
        for name, build in builders.items():
            folder = out / "cases" / f"{name}_{round(100 * ov)}"
            deck = write_impactor_case(folder, build(), pl, Impactor(imp.mass, imp.speed, ov, imp.gap), end_time,
                                       spec=spec)
            case = Case(name, ov, folder, deck, _counts(deck))
            if progress:
                print(f"{case.name}: {case.counts['elements']:,} elements", flush=True)
            _run(case, imp, progress)
            cases[name, ov] = case
    summary = {"impactor": {"mass_kg": imp.mass * 1000.0, "speed_km_h": imp.speed * 3.6e-3},
               "element_size_mm": element_size, "end_time_ms": end_time * 1e3,
               "curves": {b.name: b.curve.__dict__ for b in (spec.main, spec.bumper)},
               "cases": [c.summary() for c in cases.values()], "overlaps": []}
    for ov in overlaps:
        d, s = cases["detailed", ov], cases["simplified", ov]
        t_c = crush_phase_end(d, spec)
        entry = {"overlap_percent": 100.0 * ov,
                 "rating_crush_phase": rate_pair(d, s, t_c), "rating_whole_event": rate_pair(d, s),
                 "elements_percent": 100.0 * s.counts["elements"] / d.counts["elements"],
                 "run_time_ratio": d.run_time / s.run_time if s.run_time > 0 else None,
                 "run_time_reduction_percent": 100.0 * (1.0 - s.run_time / d.run_time) if d.run_time > 0 else None}
        if report:
            entry["report"] = _compare_report(d, s, out / f"overlap_{round(100 * ov)}")
        summary["overlaps"].append(entry)
    from ..report.build import jsonable

    (out / "summary.json").write_text(json.dumps(jsonable(summary), indent=2) + "\n")
    if report:
        from .report import write_index

        write_index(out, summary, cases)
    return summary


def _compare_report(d: Case, s: Case, folder: Path) -> str:
    """The toolkit's model-to-model report of one overlap; its folder."""
    from ..report.build import write_report
    from ..verify.compare import Options, compare_paths

    c = compare_paths(d.folder / "out", s.folder / "out", Options(cfc=CFC, time_scale=1.0),
                      names=(d.name, s.name), decks=(d.deck, s.deck))
    write_report(c, folder)
    return str(folder / "index.html")
