"""Simplified vs detailed offset deformable barrier under the paper's rigid
impactor (5000 kg, 64 km/h, 100 % overlap), run in one process.

The simplified barrier's curves come from the detailed one as in the
paper: compression tests of the detailed blocks, then the adjustment to
the detailed barrier's 100 % response (``crashlite.barrier.calibrate``).
Prints, as the paper's table 1: nodes, solids, shells, discrete beams,
total elements, time step, cycles and run time of each barrier, the
element and run-time ratios, and the ISO/TS 18571 rating of the CFC 60
impactor force over the crush phase. Each timed run follows a short
warm-up run of the same deck, so that compilation is not timed. Usage::

    python bench/barrier.py [--size 25] [--end-ms 45]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from crashlite.barrier import ODBSpec, Placement, simplified_barrier
from crashlite.barrier.calibrate import calibrate_curves
from crashlite.barrier.characterise import characterise, characterised_spec
from crashlite.barrier.detailed import detailed_barrier
from crashlite.barrier.loadcases import Impactor
from crashlite.barrier.verify import crush_phase_end, rate_pair, run_case


def _timed(folder: Path, name: str, barrier, spec, imp, end):
    run_case(name, 1.0, folder / "warm-up", barrier, spec, imp, end / 20.0, counts=False, save=False)
    return run_case(name, 1.0, folder / name, barrier, spec, imp, end, save=False)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--size", type=float, default=25.0, help="element size of the detailed barrier [mm]")
    ap.add_argument("--end-ms", type=float, default=45.0, help="simulated time [ms]")
    args = ap.parse_args()
    end = args.end_ms / 1000.0
    spec, imp, pl = ODBSpec(), Impactor(), Placement()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        t = time.perf_counter()
        chars = characterise(spec, args.size)
        print(f"characterisation of the detailed blocks: {time.perf_counter() - t:.1f} s")
        d = _timed(folder, "detailed", detailed_barrier(spec, pl, element_size=args.size), spec, imp, end)
        cal = calibrate_curves(
            d, characterised_spec({k: c.curve for k, c in chars.items()}, spec), imp, end, folder / "calibration"
        )
        print(
            f"calibration: {cal.runs} simplified runs in {cal.wall_time:.1f} s, misfit {cal.misfit_start:.3f} "
            f"-> {cal.misfit:.3f}"
        )
        s = _timed(folder, "simplified", simplified_barrier(cal.spec, pl), cal.spec, imp, end)
    print(f"{'':<22}{'detailed':>14}{'simplified':>14}")
    for key in ("nodes", "solids", "shells", "beams", "elements"):
        print(f"{key:<22}{d.counts[key]:>14,}{s.counts[key]:>14,}")
    print(f"{'cycles':<22}{d.cycles:>14,}{s.cycles:>14,}")
    print(f"{'time step [ms]':<22}{d.dt * 1e3:>14.3e}{s.dt * 1e3:>14.3e}")
    print(f"{'run time [s]':<22}{d.run_time:>14.2f}{s.run_time:>14.3f}")
    print(
        f"elements: simplified = {100 * s.counts['elements'] / d.counts['elements']:.2f} % of detailed; "
        f"run time ratio detailed / simplified = {d.run_time / s.run_time:.0f}x (target >= 100x)"
    )
    t_c = crush_phase_end(d, s, spec)
    r = rate_pair(d, s, t_c)
    print(
        f"ISO/TS 18571 rating of the simplified CFC 60 force to {t_c * 1e3:.1f} ms: {r['overall']:.3f} "
        f"({r['grade']}); corridor {r['corridor']:.3f}, phase {r['phase']:.3f}, magnitude {r['magnitude']:.3f}, "
        f"slope {r['slope']:.3f}"
    )


if __name__ == "__main__":
    main()
