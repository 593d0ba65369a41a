"""Throughput of the generic car in US NCAP, full and simplified, at two mesh sizes.

For each mesh size: the generic car (shells, MAT_024, rigid engine and rear
axle, self-contact, spot welds) runs the US NCAP load case (56 km/h, rigid
wall) for ``--end`` ms; the run is reduced at the interface (steps 1–4 of
the paper, shares from this run) and the simplified car runs the same load
case. Prints elements, cycles, time-loop seconds, µs per element-cycle of
each run (Numba compilation excluded: it is timed apart by the solver) and
the simplified/full time ratio, all measured in this one process. Usage::

    python bench/vehicle.py [--mesh 60 38] [--end 10] [--out DIR]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numba

from crashlite.vehicle.workflow import us_ncap_study


def _row(name: str, info: dict) -> str:
    el, cyc, loop = info["n_elements"], info["cycles"], info["wall_time"]
    return (
        f"  {name:<11}{el:>9}{cyc:>9}{loop:>10.2f}{1e6 * loop / max(el * cyc, 1):>12.3f}"
        f"{info['time_step'] * 1e6:>11.3f}"
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh", type=float, nargs="+", default=[60.0, 38.0], help="element sizes [mm]")
    ap.add_argument("--end", type=float, default=10.0, help="simulated time [ms]")
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args()
    root = args.out or Path(tempfile.mkdtemp(prefix="crashlite-bench-vehicle-"))
    print(f"generic car, US NCAP 56 km/h, {args.end:g} ms, {numba.get_num_threads()} thread(s); runs in {root}")
    print(f"  {'model':<11}{'elements':>9}{'cycles':>9}{'loop [s]':>10}{'µs/el-cycle':>12}{'dt [µs]':>11}")
    for h in args.mesh:
        st = us_ncap_study(root / f"mesh{h:g}", mesh_size=h, end_time=args.end / 1000.0, say=lambda *a: None)
        t = st.verification.figures["time"]
        print(f" mesh {h:g} mm")
        print(_row("full", t["full"]))
        print(_row("simplified", t["simplified"]))
        full, sim = t["full"]["wall_time"], t["simplified"]["wall_time"]
        print(
            f"  simplified / full time loop: {sim / full:.3f} ({100 * (1 - sim / full):.0f} % less), "
            f"elements {t['elements_simplified'] / t['elements_full']:.3f}"
        )


if __name__ == "__main__":
    main()
