"""Mesh convergence of the detailed ODB barrier under the paper's rigid
impactor (5000 kg, 64 km/h), at several element sizes, in one process.

Per element size and overlap it prints what a reference barrier must hold
still as its mesh is refined: the energy the barrier has taken and the
mean impactor force over the crush phase (up to where the barrier is
crushed solid, ``barrier.cases.crushed_solid``; the shortest crush phase
of the sizes, so that every size is compared over the same time), the
peak CFC 60 force in that phase (the force cut there, then filtered), the hourglass energy as a share of the
internal energy (at the end and its largest, ``verify.hourglass``; the
usual limit is 10 %), cycles and time loop. Each figure is also given
against the finest size's. Usage::

    python bench/barrier_convergence.py [--sizes 100 50 25] [--overlaps 100 40] [--end-ms 45]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np

from crashlite.barrier import ODBSpec, Placement
from crashlite.barrier.cases import crushed_solid, rated_force, run_case
from crashlite.barrier.detailed import detailed_barrier
from crashlite.barrier.loadcases import Impactor


def _phase(case, t1: float) -> dict:
    """Figures of one run over [0, t1]."""
    k = np.searchsorted(case.time, t1, side="right")
    f = case.force[:k]
    travel = float(case.travel[k - 1])
    work = float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(case.travel[:k])))
    return {
        "travel_mm": travel,
        "work_kJ": work / 1e6,
        "mean_force_kN": work / travel / 1e3 if travel > 0 else float("nan"),
        "peak_kN": float(rated_force(case, t1)[1].max() / 1e3),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sizes", type=float, nargs="+", default=[100.0, 50.0, 25.0], help="element sizes [mm]")
    ap.add_argument("--overlaps", type=float, nargs="+", default=[100.0, 40.0], help="impactor overlaps [%%]")
    ap.add_argument("--end-ms", type=float, default=45.0, help="simulated time [ms]")
    args = ap.parse_args()
    spec, imp, pl = ODBSpec(), Impactor(), Placement()
    sizes = sorted(args.sizes, reverse=True)
    with tempfile.TemporaryDirectory() as tmp:
        for ov in args.overlaps:
            cases = {}
            for size in sizes:
                b = detailed_barrier(spec, pl, element_size=size)
                cases[size] = run_case(
                    f"detailed {size:g}", ov / 100.0, Path(tmp) / f"{ov:g}-{size:g}", b, spec, imp, args.end_ms / 1e3
                )
                print(f"  {ov:g} % overlap, {size:g} mm: {cases[size].cycles} cycles", flush=True)
            t1 = min(crushed_solid(c, spec) for c in cases.values())
            fine = _phase(cases[sizes[-1]], t1)
            print(f"\n{ov:g} % overlap, crush phase to {1e3 * t1:.1f} ms (the first size crushed solid)")
            head = ["size mm", "solids", "travel mm", "work kJ", "mean kN", "peak kN", "HG end %", "HG max %"]
            print("".join(f"{h:>11}" for h in head) + f"{'cycles':>9}{'loop s':>9}   vs finest: work, mean, peak")
            for size in sizes:
                c, p = cases[size], _phase(cases[size], t1)
                hg = c.hourglass or {}
                row = [size, c.counts["solids"], p["travel_mm"], p["work_kJ"], p["mean_force_kN"], p["peak_kN"]]
                row += [hg.get("end_percent", float("nan")), hg.get("max_percent", float("nan"))]
                ratios = ", ".join(f"{p[k] / fine[k]:.3f}" for k in ("work_kJ", "mean_force_kN", "peak_kN"))
                print(
                    "".join(f"{v:>11.4g}" for v in row) + f"{c.cycles:>9}{c.run_time:>9.1f}   {ratios}",
                    flush=True,
                )


if __name__ == "__main__":
    main()
