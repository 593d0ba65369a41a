"""Mesh convergence of the detailed ODB barrier under the generic car
(Euro NCAP ODB: 40 %, 64 km/h), at several element sizes, beside the
simplified barrier, in one process.

The rigid impactor (``barrier_convergence.py``) loads the whole face; a
car's rails and bumper beam load a strip of it, and what the honeycomb
beside the imprint does (dragged along by its transverse shear until the
cell walls tear) depends on the element size. Per barrier it prints the
energy the barrier has taken at 20 ms, 40 ms and the end, the car's
internal energy and its crash boxes', the hourglass share (end and
largest, ``verify.hourglass``), the barrier's solids deleted by the end
(0 for a saved run that did not count them), cycles and time loop; then each figure
against the finest detailed size's, and the ISO/TS 18571 rating of the
barrier's energy history against it. Usage::

    python bench/odb_car_convergence.py [--sizes 100 75 50] [--mesh-size 60] [--end-ms 80] [--front generic]
        [--elform 1] [--shear-failure 1.5] [--shear-slip 0 [BUMPER] | cell | columns] [--height-size MM] [--width-size MM]
        [--honeycomb classic|transverse] [--beams 36 20 10] [--save DIR] [--reference DIR ...]

``--save DIR`` keeps each run's results (``Results.save``) in DIR/<run>;
``--reference DIR`` adds such a saved detailed run (of the same car) as a
row without running it again: ``--sizes`` (none) ``--beams …`` compares
simplified barriers against a reference measured once.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

from _honeycomb_options import NAMES, add_honeycomb_options, given
from crashlite.barrier.detailed import SLIP_WORDS
from crashlite.barrier.simplified import GRID
from crashlite.solver import run
from crashlite.solver.loop import RunError
from crashlite.solver.results import Results
from crashlite.vehicle.car.generic import generic_vehicle
from crashlite.vehicle.car.loadcases import odb_deck, vehicle_info
from crashlite.verify.curves import make_pair
from crashlite.verify.hourglass import results_share

TIMES = (0.02, 0.04)  # [s] besides the end


def _figures(r, barrier_parts: np.ndarray, boxes: list[int]) -> dict:
    ids = np.asarray(r.part_ids)
    bar = np.isin(ids, barrier_parts)
    box = np.isin(ids, boxes)
    e_bar = r.part_internal[:, bar].sum(axis=1) / 1e6  # N·mm -> kJ
    out = {f"barrier {1e3 * t:g} ms kJ": float(np.interp(t, r.time, e_bar, right=np.nan)) for t in TIMES}
    hg = results_share(r)
    out |= {
        "barrier end kJ": float(e_bar[-1]),
        "car IE kJ": float(r.internal[-1] / 1e6 - e_bar[-1]),
        "crash boxes kJ": float(r.part_internal[-1, box].sum() / 1e6),
        "car KE end kJ": float(r.kinetic[-1] / 1e6),
        "HG end %": hg.get("end_percent", np.nan),
        "HG max %": hg.get("max_percent", np.nan),
        # the barrier's solids deleted by the end (a torn MAT_026 element is deleted, and its crush with it)
        "deleted": r.deleted(barrier_parts),
        "cycles": int(r.cycles),
        "loop s": float(r.loop_time),
    }
    return out, (np.asarray(r.time), e_bar)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sizes", type=float, nargs="*", default=[100.0, 75.0, 50.0], help="barrier element sizes [mm]")
    ap.add_argument("--mesh-size", type=float, default=60.0, help="the car's element size [mm]")
    ap.add_argument("--end-ms", type=float, default=80.0, help="simulated time [ms]")
    ap.add_argument("--front", default="generic", choices=("generic", "stiff"), help="the car's front")
    ap.add_argument("--elform", type=int, default=1, help="*SECTION_SOLID ELFORM of the honeycomb (1 or 2)")
    ap.add_argument("--shear-failure", type=float, default=1.5, help="the honeycomb's SSEF (0: none)")
    ap.add_argument(
        "--shear-slip",
        nargs="+",
        default=["0"],
        help="tear slip [mm] (SSEF = slip / size) instead; two values: main block, bumper (--shear-slip 19.14 6.4: a "
        "cell); or 'cell', or 'columns' (split columns, links torn at a cell)",
    )
    ap.add_argument(
        "--height-size", type=float, default=None, help="element size across the height [mm] (default: the size)"
    )
    ap.add_argument(
        "--width-size", type=float, default=None, help="element size across the width [mm] (default: the size)"
    )
    add_honeycomb_options(ap)
    ap.add_argument(
        "--beams", type=int, nargs=3, default=None, metavar=("WIDTH", "MAIN", "BUMPER"), help="simplified barrier grid"
    )
    ap.add_argument("--save", type=Path, default=None, help="keep each run's results in DIR/<run>")
    ap.add_argument("--reference", type=Path, nargs="*", default=[], help="saved detailed runs to compare against")
    args = ap.parse_args()
    sizes = sorted(args.sizes, reverse=True)
    beams = dict(zip(GRID, args.beams)) if args.beams else None
    v = generic_vehicle(args.mesh_size, front=args.front)
    boxes = [v.part_ids[f"crash box {s}"] for s in ("left", "right")]
    honeycomb = {
        "elform": args.elform,
        "shear_failure": args.shear_failure,
        "shear_slip": args.shear_slip[0]
        if args.shear_slip[0] in SLIP_WORDS
        else (float(args.shear_slip[0]), float(args.shear_slip[-1])),
    }
    honeycomb.update(given(args, ("height_size", "width_size") + NAMES))  # the rest keep detailed_barrier's defaults
    rows, hist = {}, {}
    with tempfile.TemporaryDirectory() as tmp:
        car = v.write(Path(tmp) / "car.k")
        first_barrier_id = 2 * vehicle_info(car).id_offset  # odb_deck's barrier IDs start above it

        def add(name: str, r) -> None:
            barrier_parts = np.asarray(r.part_ids)[np.asarray(r.part_ids) > first_barrier_id]
            rows[name], hist[name] = _figures(r, barrier_parts, boxes)

        for ref in args.reference:
            add(f"detailed {ref.name}", Results.load(ref))
        for kind, size in [("detailed", s) for s in sizes] + [("simplified", sizes[-1] if sizes else 0.0)]:
            name = f"detailed {size:g} mm" if kind == "detailed" else "simplified"
            t0 = time.perf_counter()
            deck = odb_deck(
                car,
                Path(tmp) / f"{kind}_{size:g}.k",
                barrier=kind,
                end_time=args.end_ms / 1e3,
                element_size=size,
                honeycomb=honeycomb,
                beams=beams,
            )
            try:
                r = run(deck, out=Path(tmp) / f"run_{kind}_{size:g}", quiet=True)
            except RunError as e:  # a stopped run still says how far the barrier got
                r = e.results
                name += f" (stopped {1e3 * r.time[-1]:.1f} ms)"
                print(f"{name}: {e}", flush=True)
            if args.save:
                r.save(args.save / (f"{kind}_{size:g}" if kind == "detailed" else "simplified"))
            add(name, r)
            print(f"{name}: {time.perf_counter() - t0:.0f} s", flush=True)
    keys = list(next(iter(rows.values())))
    print(
        f"\ncar {args.mesh_size:g} mm ({args.front} front), ODB 40 % 64 km/h to {args.end_ms:g} ms; honeycomb {honeycomb}; beams {beams}"
    )
    print(f"{'':32s}" + "".join(f"{k:>20s}" for k in keys))
    for name, f in rows.items():
        print(f"{name:32s}" + "".join(f"{f[k]:20.4g}" for k in keys))
    done = [n for n in rows if n.startswith("detailed") and "stopped" not in n]
    if not done:
        return
    ref = done[-1]  # the finest detailed barrier that ran to the end
    print(f"\nagainst {ref}")
    print(f"{'':32s}" + "".join(f"{k:>20s}" for k in keys[:6]) + f"{'rating barrier E':>20s}")
    for name, f in rows.items():
        if name == ref:
            continue
        p = make_pair("energy", "barrier", "kJ", *hist[ref], *hist[name])
        rating = p.rating.overall if p.rating is not None else float("nan")
        ratios = "".join(f"{f[k] / rows[ref][k]:20.3f}" if rows[ref][k] else f"{'-':>20s}" for k in keys[:6])
        print(f"{name:32s}{ratios}{rating:20.3f}")


if __name__ == "__main__":
    main()
