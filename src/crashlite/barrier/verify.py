"""Verification of the simplified barrier against the detailed one (the
paper's figures 5–8 and table 1).

A rigid impactor (5000 kg, 64 km/h) strikes both barriers at 100 % and 40 %
overlap. For each overlap the runs are compared with the verification
toolkit (energies, wall force, timing: a report of its own), and the
impactor force, CFC 60, is rated by ISO/TS 18571 over the whole event and
over the crush phase. The impactor carries about six times the energy the
barrier can absorb, so both barriers are crushed solid against the fixed
wall behind them; from then on the force is a stiff impact of the
impactor on the wall through compacted honeycomb, not the barrier's
characteristic, and the filtered peak of tens of MN rings back over the
crush phase. The crush phase therefore ends where the first of the two
barriers is crushed solid (its raw force passes the densified main block's
force over the face the impactor covers), and both forces are cut there before they are
filtered. A table-1 analogue (nodes, elements by type, time step,
cycles, run time) and every figure go into ``summary.json`` and an index
page.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field, replace
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


def run_case(name: str, overlap: float, folder: Path, barrier, spec: ODBSpec, impactor: Impactor, end_time: float,
             progress: bool = False, counts: bool = True, save: bool = True) -> Case:
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
    return {"overall": r.overall, "grade": r.grade, "corridor": r.corridor, "phase": r.phase,
            "magnitude": r.magnitude, "slope": r.slope, "until_ms": None if t1 is None else t1 * 1e3}


def verify_barriers(directory, spec: ODBSpec | None = None, element_size: float = 25.0, end_time: float = 0.045,
                    overlaps=(1.0, 0.4), impactor: Impactor | None = None, progress: bool = False,
                    report: bool = True, curves: "str | ODBSpec" = "calibrated",
                    calibration_runs: int = 80) -> dict:
    """Run the impactor on both barriers at each overlap into ``directory``
    and write the reports; returns the summary (also ``summary.json``).

    ``spec``: geometry of both barriers and the honeycomb curves of the
    detailed one; ``element_size`` [mm]: the detailed barrier's. The
    simplified barrier's curves (``curves``) are, as in the paper:
    "characterised" from compression tests of the detailed blocks
    (``characterise``, same element size), or "calibrated": characterised
    and then adjusted to the detailed barrier's response at the largest
    overlap (``calibrate``), which the other overlaps then verify;
    "paper" takes ``spec``'s own curves, and an ODBSpec its curves;
    ``calibration_runs``: the most simplified runs the calibration makes."""
    spec = spec or ODBSpec()
    imp = impactor or Impactor()
    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    pl = Placement()
    if isinstance(curves, ODBSpec):
        simple, source = curves, "given"
    elif curves == "paper":
        simple, source = spec, "paper"
    elif curves in ("characterised", "calibrated"):
        simple, source = _characterised(spec, element_size, out / "characterisation", progress), "characterised"
    else:
        raise ValueError(f"curves must be 'calibrated', 'characterised', 'paper' or an ODBSpec, got {curves!r}")
    calibrate = curves == "calibrated"
    order = sorted(overlaps, reverse=True)  # the calibration case (the largest overlap) runs first
    cases: dict[tuple[str, float], Case] = {}
    calibration = None
    for ov in order:
        cases["detailed", ov] = run_case("detailed", ov, out / "cases" / f"detailed_{round(100 * ov)}",
                                         detailed_barrier(spec, pl, element_size=element_size), spec, imp,
                                         end_time, progress)
        if calibrate and calibration is None:
            from .calibrate import calibrate_curves

            calibration = calibrate_curves(cases["detailed", ov], simple, imp, end_time, out / "calibration",
                                           max_runs=calibration_runs, progress=progress)
            calibration.write_curves(out / "calibration" / "curves.json")
            simple, source = calibration.spec, f"calibrated against {cases['detailed', ov].name}"
        cases["simplified", ov] = run_case("simplified", ov, out / "cases" / f"simplified_{round(100 * ov)}",
                                           simplified_barrier(simple, pl), simple, imp, end_time, progress)
    summary = {"impactor": {"mass_kg": imp.mass * 1000.0, "speed_km_h": imp.speed * 3.6e-3},
               "element_size_mm": element_size, "end_time_ms": end_time * 1e3,
               "simplified_curves_source": source,
               "curves": {b.name: b.curve.__dict__ for b in (simple.main, simple.bumper)},
               "detailed_curves": {b.name: b.curve.__dict__ for b in (spec.main, spec.bumper)},
               "calibration": None if calibration is None else calibration.summary(),
               "cases": [c.summary() for c in cases.values()], "overlaps": []}
    for ov in overlaps:
        d, s = cases["detailed", ov], cases["simplified", ov]
        t_c = crush_phase_end(d, s, spec)
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


def _characterised(spec: ODBSpec, element_size: float, folder: Path, progress: bool) -> ODBSpec:
    """Compression tests of the detailed blocks; their curves in ``spec``
    (curves.json and a page in ``folder``)."""
    from .characterise import characterise, characterised_spec, write_curves
    from .report import write_characterisation_page

    chars = characterise(spec, element_size, directory=folder / "runs", progress=progress)
    write_curves(chars, folder / "curves.json")
    write_characterisation_page(folder, chars)
    return characterised_spec({k: c.curve for k, c in chars.items()}, spec)


def _compare_report(d: Case, s: Case, folder: Path) -> str:
    """The toolkit's model-to-model report of one overlap; its folder."""
    from ..report.build import write_report
    from ..verify.compare import Options, compare_paths

    c = compare_paths(d.folder / "out", s.folder / "out", Options(cfc=CFC, time_scale=1.0),
                      names=(d.name, s.name), decks=(d.deck, s.deck))
    write_report(c, folder)
    return str(folder / "index.html")
