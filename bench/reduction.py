"""Computational-time reduction of the simplified models (the paper's figures 25–27).

Runs, in this one process, the paper study on the generic car
(``crashlite.vehicle.workflow.paper_study``): full and simplified car in
US NCAP (56 km/h, rigid wall), and in Euro NCAP ODB (64 km/h, 40 %) the
full car against the detailed barrier, the simplified car against the
simplified barrier and the two mixed pairs; one surrogate for both load
cases. Prints every run's elements, cycles and time loop (Numba
compilation excluded), the time reductions of each simplification and of
both (targets: vehicle ≥ 60 %, combined ≥ 90 %; paper: 65 % and 92 %),
and the verification figures of both load cases. Usage::

    python bench/reduction.py [--mesh 38] [--barrier 50] [--usncap-end 80] [--odb-end 100] [--out DIR]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numba

from crashlite.vehicle.verify.study_report import verification_lines
from crashlite.vehicle.workflow import paper_study


def _pc(v) -> str:
    return "   –" if v is None else f"{v:5.1f} %"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh", type=float, default=38.0, help="element size of the car [mm]")
    ap.add_argument("--barrier", type=float, default=50.0, help="element size of the detailed barrier [mm]")
    ap.add_argument("--usncap-end", type=float, default=80.0, help="[ms]")
    ap.add_argument("--odb-end", type=float, default=100.0, help="[ms]")
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args()
    root = args.out or Path(tempfile.mkdtemp(prefix="crashlite-bench-reduction-"))
    print(
        f"paper study: car {args.mesh:g} mm, detailed barrier {args.barrier:g} mm, {numba.get_num_threads()} "
        f"thread(s); runs in {root}"
    )
    st = paper_study(
        root,
        mesh_size=args.mesh,
        barrier_size=args.barrier,
        usncap_end=args.usncap_end / 1e3,
        odb_end=args.odb_end / 1e3,
        say=lambda *a: None,
    )
    print(f"  {'run':<40}{'elements':>9}{'cycles':>9}{'loop [s]':>10}{'µs/el-cycle':>12}")
    for name, r in st.summary["runs"].items():
        el, cyc, loop = r["elements"], r["cycles"], r["loop_time_s"]
        print(f"  {name:<40}{el:>9}{cyc:>9}{loop:>10.1f}{1e6 * loop / max(el * cyc, 1):>12.3f}")
    t = st.summary["time"]
    print("time-loop reduction")
    print(
        f"  US NCAP, simplified vehicle                {_pc(t['us_ncap']['vehicle_reduction_percent'])}"
        f"   (target >= 60 %, paper 65 %)"
    )
    o = t["odb"]
    print(f"  ODB, simplified barrier (full car)         {_pc(o.get('barrier_reduction_percent'))}")
    print(f"  ODB, simplified vehicle (detailed barrier) {_pc(o.get('vehicle_reduction_percent'))}")
    print(
        f"  ODB, both simplified                       {_pc(o['combined_reduction_percent'])}"
        f"   (target >= 90 %, paper 92 %)"
    )
    print("verification (full against simplified)")
    for line in verification_lines(st.summary):
        print(f"  {line}")
    print(f"report: {root / 'index.html'}")


if __name__ == "__main__":
    main()
