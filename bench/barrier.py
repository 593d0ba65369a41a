"""Simplified vs detailed offset deformable barrier under the paper's rigid
impactor (5000 kg, 64 km/h, 100 % overlap), run in one process.

Prints, as the paper's table 1: nodes, solids, shells, discrete beams,
total elements, time step, cycles and run time of each barrier, the
element and run-time ratios, and the ISO/TS 18571 rating of the CFC 60
impactor force of the simplified barrier against the detailed one. Usage::

    python bench/barrier.py [--size 25] [--end-ms 20]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

from crashlite import read_deck
from crashlite.barrier import Placement, simplified_barrier
from crashlite.barrier.detailed import detailed_barrier
from crashlite.barrier.loadcases import Impactor, write_impactor_case
from crashlite.solver import run
from crashlite.verify.filters import filter_signal
from crashlite.verify.rating import iso_rating


def _case(folder: Path, barrier, end: float):
    pl = Placement()
    main = write_impactor_case(folder, barrier, pl, Impactor(), end_time=end)
    model = read_deck(main)
    run(main, output_dt=end / 10)  # warm-up: compiles what this model needs
    t = time.perf_counter()
    r = run(main, output_dt=1e-4)
    return model, r, time.perf_counter() - t


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--size", type=float, default=25.0, help="element size of the detailed barrier [mm]")
    ap.add_argument("--end-ms", type=float, default=20.0, help="simulated time [ms]")
    args = ap.parse_args()
    end = args.end_ms / 1000.0
    rows = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, b in (("detailed", detailed_barrier(element_size=args.size)),
                        ("simplified", simplified_barrier(cladding=False))):
            model, r, wall = _case(Path(tmp) / name, b, end)
            n = {"nodes": len(model.nodes), "solids": len(model.solids), "shells": len(model.shells),
                 "beams": len(model.discretes)}
            n["elements"] = n["solids"] + n["shells"] + n["beams"]
            rows[name] = dict(n, dt=r.dt, cycles=r.cycles, wall=wall, t=r.time, f=-r.wall_force[:, 0, 0])
    d, s = rows["detailed"], rows["simplified"]
    print(f"{'':<22}{'detailed':>14}{'simplified':>14}")
    for key in ("nodes", "solids", "shells", "beams", "elements", "cycles"):
        print(f"{key:<22}{d[key]:>14,}{s[key]:>14,}")
    print(f"{'time step [ms]':<22}{d['dt'] * 1e3:>14.3e}{s['dt'] * 1e3:>14.3e}")
    print(f"{'run time [s]':<22}{d['wall']:>14.2f}{s['wall']:>14.3f}")
    print(f"elements: simplified = {100 * s['elements'] / d['elements']:.2f} % of detailed; "
          f"run time ratio detailed / simplified = {d['wall'] / s['wall']:.0f}x (target >= 100x)")
    tf, fd = filter_signal(d["t"], d["f"], 60.0)
    tg, fs = filter_signal(s["t"], s["f"], 60.0)
    rating = iso_rating(tf, fd, tg, fs)
    print(f"CFC 60 impactor force, peak: detailed {fd.max() / 1e3:.0f} kN, simplified {fs.max() / 1e3:.0f} kN; "
          f"mean: {np.mean(fd) / 1e3:.0f} / {np.mean(fs) / 1e3:.0f} kN")
    print(f"ISO/TS 18571 rating of the simplified force: {rating.overall:.3f} ({rating.grade}); "
          f"corridor {rating.corridor:.3f}, phase {rating.phase:.3f}, magnitude {rating.magnitude:.3f}, "
          f"slope {rating.slope:.3f}")


if __name__ == "__main__":
    main()
