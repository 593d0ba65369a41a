"""Mesh convergence of the detailed ODB barrier under the paper's rigid
impactor (5000 kg, 64 km/h), at several element sizes, in one process.

Per element size and overlap it prints what a reference barrier must hold
still as its mesh is refined: the energy the barrier has taken and the
mean impactor force over the crush phase (up to where the first of the
sizes is crushed solid, ``barrier.cases.crushed_solid``, so that every
size is compared over the same time), the mean force over three stretches
of the impactor's travel (the bumper, the main block, the last of the
block), the hourglass energy as a share of the internal energy (at the end
and its largest, ``verify.hourglass``; the usual limit is 10 %), cycles and
time loop; then each figure against the finest size's. Usage::

    python bench/barrier_convergence.py [--sizes 100 75 50] [--overlaps 100 40] [--end-ms 45] [--elform 1]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np

from crashlite.barrier import ODBSpec, Placement
from crashlite.barrier.cases import crushed_solid, run_case
from crashlite.barrier.detailed import detailed_barrier
from crashlite.barrier.loadcases import Impactor

WINDOWS = ((0.0, 150.0), (150.0, 300.0), (300.0, 450.0))  # impactor travel [mm]


def _phase(case, t1: float) -> dict:
    """Figures of one run over [0, t1]: travel, work, mean force, and the
    mean force over each travel window (work over the window / its length)."""
    k = np.searchsorted(case.time, t1, side="right")
    f, s = case.force[:k], case.travel[:k]
    dw = 0.5 * (f[1:] + f[:-1]) * np.diff(s)
    work = np.concatenate([[0.0], np.cumsum(dw)])
    out = {
        "travel_mm": float(s[-1]),
        "work_kJ": float(work[-1]) / 1e6,
        "mean_force_kN": float(work[-1]) / float(s[-1]) / 1e3 if s[-1] > 0 else float("nan"),
    }
    for a, b in WINDOWS:
        wa, wb = np.interp([a, min(b, s[-1])], s, work)
        out[f"{a:g}-{b:g} mm kN"] = (wb - wa) / (min(b, s[-1]) - a) / 1e3 if s[-1] > a else float("nan")
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sizes", type=float, nargs="+", default=[100.0, 75.0, 50.0], help="element sizes [mm]")
    ap.add_argument("--overlaps", type=float, nargs="+", default=[100.0, 40.0], help="impactor overlaps [%%]")
    ap.add_argument("--end-ms", type=float, default=45.0, help="simulated time [ms]")
    ap.add_argument("--elform", type=int, default=1, help="*SECTION_SOLID ELFORM of the honeycomb (1 or 2)")
    args = ap.parse_args()
    spec, imp, pl = ODBSpec(), Impactor(), Placement()
    sizes = sorted(args.sizes, reverse=True)
    with tempfile.TemporaryDirectory() as tmp:
        for ov in args.overlaps:
            cases = {}
            for size in sizes:
                b = detailed_barrier(spec, pl, element_size=size, elform=args.elform)
                cases[size] = run_case(
                    f"detailed {size:g}", ov / 100.0, Path(tmp) / f"{ov:g}-{size:g}", b, spec, imp, args.end_ms / 1e3
                )
                print(f"  {ov:g} % overlap, {size:g} mm: {cases[size].cycles} cycles", flush=True)
            t1 = min(crushed_solid(c, spec) for c in cases.values())
            phases = {size: _phase(c, t1) for size, c in cases.items()}
            fine = phases[sizes[-1]]
            print(f"\n{ov:g} % overlap, crush phase to {1e3 * t1:.1f} ms (the first size crushed solid)")
            keys = ["travel_mm", "work_kJ", "mean_force_kN", *[f"{a:g}-{b:g} mm kN" for a, b in WINDOWS]]
            head = ["size mm", "solids", *keys, "HG end %", "HG max %", "cycles", "loop s"]
            print("".join(f"{h:>15}" for h in head))
            for size in sizes:
                c, p = cases[size], phases[size]
                hg = c.hourglass or {}
                row = [size, c.counts["solids"], *[p[k] for k in keys]]
                row += [hg.get("end_percent", float("nan")), hg.get("max_percent", float("nan")), c.cycles, c.run_time]
                print("".join(f"{v:>15.4g}" for v in row), flush=True)
            print("against the finest size: " + ", ".join(keys[1:]))
            for size in sizes:
                p = phases[size]
                print(f"{size:>15g}" + "".join(f"{p[k] / fine[k]:>15.3f}" for k in keys[1:]))


if __name__ == "__main__":
    main()
