"""Adjusting the simplified barrier's curves to the detailed barrier.

The paper uses its 100 % overlap impactor case "mainly to adjust the
failure behaviour of the beam elements with the failure behaviour of the
[detailed] barrier" (section 2.1); its 40 % case then verifies. The curves
that the block compression tests give (``characterise``) describe each
block alone; in the whole barrier the bumper and the main block crush in
series and parallel, and the detailed honeycomb compacts gradually, so
the force the impactor feels differs. This module does the paper's
adjustment automatically: it varies five parameters of the two curves —
main-block plateau, its compaction onset and densified stiffening, bumper
plateau and peak — and runs the simplified barrier (well under a second a
run) until its CFC 60 impactor force over the crush phase matches the
detailed barrier's (Nelder–Mead on the RMS difference). No curve point is
set by hand.
"""

from __future__ import annotations

import json
import time
from collections.abc import Iterable
from dataclasses import asdict, dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .loadcases import Impactor
from .simplified import simplified_barrier
from .spec import ODBSpec

if TYPE_CHECKING:
    from .cases import Case

# (name, lower, upper) of each multiplier on the starting curves
PARAMETERS = (
    ("main block plateau", 0.6, 1.6),
    ("main block compaction onset", 0.8, 1.15),
    ("main block densified force", 0.25, 4.0),
    ("bumper plateau", 0.4, 2.0),
    ("bumper peak", 0.4, 2.0),
)


def adjusted(spec: ODBSpec, x: Iterable[float]) -> ODBSpec:
    """``spec`` with its curves scaled by the multipliers ``x`` (order of
    PARAMETERS, each clipped to its bounds)."""
    m = [float(np.clip(v, lo, hi)) for v, (_, lo, hi) in zip(x, PARAMETERS)]
    mc, bc = spec.main.curve, spec.bumper.curve
    compaction = min(mc.compaction * m[1], mc.full - 0.02)
    main = replace(
        mc, plateau=mc.plateau * m[0], peak=mc.peak * m[0], compaction=compaction, full_factor=mc.full_factor * m[2]
    )
    plateau = bc.plateau * m[3]
    bumper = replace(bc, plateau=plateau, peak=max(bc.peak * m[4], plateau))
    return replace(spec, main=replace(spec.main, curve=main), bumper=replace(spec.bumper, curve=bumper))


@dataclass
class Calibration:
    """Adjusted spec and the record of the search."""

    spec: ODBSpec
    multipliers: dict
    misfit_start: float  # RMS force difference / mean reference force over the crush phase
    misfit: float
    runs: int
    wall_time: float  # [s]
    until: float  # end of the matched crush phase [s]
    reference: str  # name of the reference case

    def summary(self) -> dict:
        return {
            "reference": self.reference,
            "multipliers": self.multipliers,
            "runs": self.runs,
            "wall_time_s": self.wall_time,
            "matched_until_ms": self.until * 1e3,
            "misfit_start": self.misfit_start,
            "misfit": self.misfit,
            "curves": {b.name: asdict(b.curve) for b in (self.spec.main, self.spec.bumper)},
        }

    def write_curves(self, path: Path | str) -> Path:
        """curves.json in the format of ``characterise.read_curves``."""
        p = Path(path)
        p.parent.mkdir(parents=True, exist_ok=True)
        data = {
            b.name: {
                "block": b.name,
                "depth_mm": b.depth,
                "curve": asdict(b.curve),
                "calibrated_against": self.reference,
                "misfit": self.misfit,
            }
            for b in (self.spec.main, self.spec.bumper)
        }
        p.write_text(json.dumps(data, indent=2) + "\n")
        return p


def misfit(reference: Case, case: Case, until: float) -> float:
    """RMS difference of the CFC 60 impactor forces over [0, until], both
    cut there before filtering, relative to the reference's mean force."""
    from .cases import rated_force

    t, f_ref = rated_force(reference, until)
    tc, f = rated_force(case, until)
    f = np.interp(t, tc, f, right=f[-1])
    return float(np.sqrt(np.mean((f - f_ref) ** 2)) / np.mean(np.abs(f_ref)))


def calibrate_curves(
    reference: Case,
    spec: ODBSpec,
    impactor: Impactor,
    end_time: float,
    directory: Path | str,
    max_runs: int = 80,
    progress: bool = False,
) -> Calibration:
    """Adjust ``spec``'s curves so that the simplified barrier under
    ``impactor`` at the reference case's overlap matches ``reference`` (a
    ``cases.Case`` of the detailed barrier) over its crush phase."""
    from scipy.optimize import minimize

    from .cases import crushed_solid, run_case

    until = crushed_solid(reference, spec)
    # the simplified run need not go past the matched phase
    end = min(end_time, until + 2e-3)
    folder = Path(directory)
    history: list[tuple[np.ndarray, float]] = []
    t0 = time.perf_counter()

    def objective(x) -> float:
        s = adjusted(spec, x)
        case = run_case(
            "simplified", reference.overlap, folder, simplified_barrier(s), s, impactor, end, counts=False, save=False
        )
        value = misfit(reference, case, until)
        history.append((np.array(x), value))
        if progress:
            print(f"calibration run {len(history)}: misfit {value:.4f}", flush=True)
        return value

    x0 = np.ones(len(PARAMETERS))
    simplex = np.vstack([x0] + [x0 + 0.15 * np.eye(len(x0))[i] for i in range(len(x0))])
    minimize(
        objective,
        x0,
        method="Nelder-Mead",
        options={"maxfev": max_runs, "initial_simplex": simplex, "xatol": 5e-3, "fatol": 1e-3},
    )
    best_x, best = min(history, key=lambda h: h[1])
    multipliers = {name: float(np.clip(v, lo, hi)) for v, (name, lo, hi) in zip(best_x, PARAMETERS)}
    return Calibration(
        adjusted(spec, best_x),
        multipliers,
        history[0][1],
        best,
        len(history),
        time.perf_counter() - t0,
        until,
        reference.name,
    )
