"""The detailed and the simplified ODB under a strip impactor: a rigid face
only as high as a car's bumper beam (z = 390–500 mm, 40 % of the width,
5 t at 64 km/h), whose edges shear the honeycomb beside it as the beam's
do, without a car in the run.

The main block under the strip alone crushes at its plateau stress × the
strip's area (0.342 MPa × 110 × 400 mm = 15 kN): what the impactor meets
above that, once the bumper is crushed, is the honeycomb dragged along
beside it. Per barrier it prints the mean force over windows of travel,
the energy to the end and the ISO/TS 18571 rating of the CFC 60 force
against the finest detailed face. Usage::

    python bench/barrier_strip.py [--faces 50 35 25] [--depth 50] [--slip cell | MM [BUMPER]] [--elform 2]
        [--end-ms 20] [--shear-strength S] [--lateral L] [--honeycomb classic|transverse]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

from _honeycomb_options import add_honeycomb_options, given
from crashlite.barrier import ODBSpec, simplified_barrier
from crashlite.barrier.cases import rate_pair, run_case
from crashlite.barrier.detailed import SLIP_WORDS, detailed_barrier
from crashlite.barrier.loadcases import Impactor

WINDOWS = ((0, 50), (50, 100), (100, 200), (200, 300), (300, 350))  # [mm] of travel
STRIP = (390.0, 500.0)  # [mm] above ground: the generic car's bumper beam


def _windows(case) -> list[float]:
    """Mean force [kN] over each window of travel (work over travel)."""
    out = []
    for lo, hi in WINDOWS:
        k = (case.travel >= lo) & (case.travel < hi)
        x = case.travel[k]
        out.append(np.trapezoid(case.force[k], x) / (x[-1] - x[0]) / 1e3 if k.sum() > 2 else float("nan"))
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--faces", type=float, nargs="+", default=[50.0, 35.0, 25.0], help="detailed face sizes [mm]")
    ap.add_argument("--depth", type=float, default=50.0, help="detailed element size along the depth [mm]")
    ap.add_argument(
        "--slip",
        nargs="+",
        default=["cell"],
        help="tear slip: 'cell', 'columns' (split columns torn at one cell) or MM [BUMPER MM]",
    )
    ap.add_argument("--elform", type=int, default=2, help="the honeycomb's *SECTION_SOLID ELFORM")
    ap.add_argument("--end-ms", type=float, default=20.0, help="simulated time [ms]")
    add_honeycomb_options(ap)
    args = ap.parse_args()
    slip = args.slip[0] if args.slip[0] in SLIP_WORDS else (float(args.slip[0]), float(args.slip[-1]))
    spec, imp, end = ODBSpec(), Impactor(height=STRIP), args.end_ms / 1e3
    cases = {}
    with tempfile.TemporaryDirectory() as tmp:
        for face in sorted(args.faces, reverse=True):
            b = detailed_barrier(
                element_size=args.depth,
                height_size=face,
                width_size=face,
                elform=args.elform,
                shear_slip=slip,
                **given(args),
            )
            t0 = time.perf_counter()
            cases[f"detailed, face {face:g}"] = run_case("detailed", 0.4, Path(tmp) / f"d{face:g}", b, spec, imp, end)
            print(f"detailed face {face:g} mm: {time.perf_counter() - t0:.0f} s", flush=True)
        cases["simplified"] = run_case("simplified", 0.4, Path(tmp) / "s", simplified_barrier(), spec, imp, end)
    ref = list(cases)[-2] if len(cases) > 1 else None
    print(
        f"\nstrip z {STRIP[0]:g}-{STRIP[1]:g} mm, 40 %, 5 t at 64 km/h; detailed ELFORM {args.elform}, tear {slip}, {args.honeycomb or 'default'} honeycomb"
    )
    head = "".join(f"{f'{lo}-{hi} mm':>12s}" for lo, hi in WINDOWS)
    print(f"{'mean force [kN] over travel':28s}{head}{'energy kJ':>12s}{'rating':>10s}{'cycles':>10s}{'loop s':>10s}")
    for name, c in cases.items():
        means = "".join(f"{m:12.1f}" for m in _windows(c))
        energy = np.trapezoid(c.force, c.travel) / 1e6
        rating = rate_pair(cases[ref], c)["overall"] if ref and name != ref else float("nan")
        print(f"{name:28s}{means}{energy:12.2f}{rating:10.3f}{c.cycles:10d}{c.run_time:10.1f}")


if __name__ == "__main__":
    main()
