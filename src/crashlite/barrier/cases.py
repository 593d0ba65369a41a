"""One barrier run under the rigid impactor (``run_case``), its CFC 60
impactor force, where a barrier is crushed solid and the ISO/TS 18571
rating of a pair of runs: what ``verify``, ``calibrate`` and ``report``
share (see ``verify`` for the method).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from .loadcases import Impactor, write_impactor_case
from .simplified import Placement, SimplifiedBarrier
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
    hourglass: dict = field(default_factory=dict)  # hourglass share of the internal energy (verify.hourglass)
    deleted: int = 0  # the barrier's shells and solids deleted by the end (a torn element takes its crush)

    @property
    def name(self) -> str:
        return f"{self.barrier} {round(100 * self.overlap)} %"

    def summary(self) -> dict:
        return {
            "barrier": self.barrier,
            "overlap_percent": 100.0 * self.overlap,
            "deck": str(self.deck),
            **self.counts,
            "time_step_ms": self.dt * 1e3,
            "cycles": self.cycles,
            "run_time_s": self.run_time,
            "energy_ratio": self.energy_ratio,
            "impactor_energy_lost_kJ": self.lost / 1e6,
            "barrier_energy_kJ": self.absorbed / 1e6,
            "peak_force_kN_cfc60": float(_cfc(self.time, self.force).max() / 1e3),
            "max_travel_mm": float(self.travel.max()),
            "hourglass_percent": self.hourglass,
            "deleted_elements": self.deleted,
        }


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


def run_case(
    name: str,
    overlap: float,
    folder: Path,
    barrier: SimplifiedBarrier,
    spec: ODBSpec,
    impactor: Impactor,
    end_time: float,
    progress: bool = False,
    counts: bool = True,
    save: bool = True,
) -> Case:
    """Write and run one barrier under the impactor at ``overlap``;
    ``save``: write the results (and LS-DYNA ASCII files) to folder/out."""
    pl = Placement()
    imp = replace(impactor, overlap=overlap)
    deck = write_impactor_case(folder, barrier, pl, imp, end_time, spec=spec)
    case = Case(name, overlap, Path(folder), deck, _counts(deck) if counts else {})
    if progress and counts:
        print(f"{case.name}: {case.counts['elements']:,} elements", flush=True)
    _run(case, imp, progress, save)
    return case


def _run(case: Case, impactor: Impactor, progress: bool, save: bool = True) -> None:
    from ..solver import run
    from ..verify.hourglass import results_share

    r = run(case.deck, out=case.folder / "out" if save else None, quiet=not progress, output_dt=1e-4)
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
    case.hourglass = results_share(r)
    case.deleted = r.deleted()


def solid_force(spec: ODBSpec, overlap: float = 1.0) -> float:
    """Impactor force [N] past which a barrier is crushed solid: the main
    block densified (``full_factor`` × plateau) over the part of its face
    the impactor covers."""
    return overlap * spec.main.curve.full_factor * spec.main.curve.plateau


def crushed_solid(case: Case, spec: ODBSpec) -> float:
    """Time [s] at which the raw impactor force first passes
    ``solid_force`` (the end of the run if it never does)."""
    k = np.flatnonzero(case.force > solid_force(spec, case.overlap))
    return float(case.time[k[0]]) if len(k) else float(case.time[-1])


def crush_phase_end(ref: Case, cmp: Case, spec: ODBSpec) -> float:
    """End [s] of the rated crush phase: the first of the two barriers
    crushed solid."""
    return min(crushed_solid(ref, spec), crushed_solid(cmp, spec))


def rated_force(case: Case, t1: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(time, CFC 60 force) of a case over [0, t1]: the raw force is cut at
    ``t1`` before it is filtered, so that what follows does not ring back."""
    k = slice(None) if t1 is None else case.time <= t1
    return case.time[k], _cfc(case.time[k], case.force[k])


def rate_pair(ref: Case, cmp: Case, t1: float | None = None) -> dict:
    """ISO/TS 18571 rating of the CFC 60 impactor force of ``cmp`` against
    ``ref`` over [0, t1] (see ``rated_force``)."""
    from ..verify.rating import iso_rating

    r = iso_rating(*rated_force(ref, t1), *rated_force(cmp, t1), 0.0, t1)
    return {
        "overall": r.overall,
        "grade": r.grade,
        "corridor": r.corridor,
        "phase": r.phase,
        "magnitude": r.magnitude,
        "slope": r.slope,
        "until_ms": None if t1 is None else t1 * 1e3,
    }
