"""``crashlite barrier ...``: the offset deformable barrier from the command line."""

from __future__ import annotations

import argparse
from pathlib import Path


def _spec(curves):
    """The ODB spec, with the block curves of a characterisation when given."""
    from .barrier import ODBSpec

    if curves is None:
        return ODBSpec()
    from .barrier.characterise import characterised_spec, read_curves

    return characterised_spec(read_curves(curves))


def _simplified(args) -> int:
    from .barrier import Placement, offset_placement, simplified_barrier
    from .units import system

    if args.vehicle_width:
        pl = offset_placement(
            args.vehicle_width, args.overlap / 100.0, args.side, args.y_centre, args.x_face, args.direction, args.ground
        )
    else:
        pl = Placement(args.x_face, args.direction, args.y_min, args.ground)
    b = simplified_barrier(
        _spec(args.curves),
        placement=pl,
        n_width=args.columns,
        n_main=args.rows_main,
        n_bumper=args.rows_bumper,
        id_offset=args.id_offset,
        units=system(args.units),
    )
    path = b.write(args.output)
    print(
        f"wrote {path}: {b.beams} discrete beams, {b.shells} cladding shells, {b.mass:.6g} mass units; "
        f"front node set {b.set_ids['front']}, barrier part set {b.set_ids['parts']}"
    )
    return 0


def _impactor(args) -> int:
    from .barrier import Placement, simplified_barrier
    from .barrier.loadcases import Impactor, write_impactor_case
    from .units import kmh

    pl = Placement()
    b = simplified_barrier(_spec(args.curves), placement=pl, cladding=not args.no_cladding)
    main = write_impactor_case(
        args.output,
        b,
        pl,
        Impactor(
            args.mass / 1000.0,
            kmh(args.speed),
            args.overlap / 100.0,
            height=tuple(args.height) if args.height else None,
        ),
        end_time=args.end_time / 1000.0,
    )
    print(f"wrote {main} (and barrier.k): run it with `crashlite run {main} -o OUT`")
    return 0


def _characterise(args) -> int:
    from .barrier.characterise import characterise, write_curves
    from .barrier.report import write_characterisation_page

    chars = characterise(
        element_size=args.size, speed=args.speed * 1000.0, directory=args.output / "runs", progress=True
    )
    path = write_curves(chars, args.output / "curves.json")
    write_characterisation_page(args.output, chars)
    for c in chars.values():
        k = c.curve
        print(
            f"{c.block}: peak {k.peak / 1e3:.0f} kN at {k.rise:.1f} mm, plateau {k.plateau / 1e3:.0f} kN, "
            f"compaction from {100 * k.compaction:.0f} % of the depth ({c.solids:,} solids, {c.wall_time:.1f} s)"
        )
    print(f"wrote {path} and {args.output / 'index.html'}: use the curves with --curves {path}")
    return 0


def _verify(args) -> int:
    from .barrier.verify import verify_barriers

    curves = _spec(args.curves) if args.curves is not None else args.simplified_curves
    s = verify_barriers(
        args.output,
        element_size=args.size,
        end_time=args.end_time / 1000.0,
        overlaps=[o / 100.0 for o in args.overlap],
        progress=True,
        curves=curves,
        calibration_runs=args.calibration_runs,
    )
    if s["calibration"] is not None:
        c = s["calibration"]
        print(
            f"simplified curves calibrated against {c['reference']} in {c['runs']} runs: misfit "
            f"{c['misfit_start']:.3f} -> {c['misfit']:.3f}; {args.output / 'calibration' / 'curves.json'}"
        )
    for e in s["overlaps"]:
        r = e["rating_crush_phase"]
        print(
            f"{e['overlap_percent']:.0f} % overlap: ISO/TS 18571 {r['overall']:.3f} ({r['grade']}) to "
            f"{r['until_ms']:.1f} ms, {e['rating_whole_event']['overall']:.3f} over the whole event; "
            f"run time detailed / simplified {e['run_time_ratio']:.0f}x"
        )
    print(f"wrote {args.output / 'index.html'} and {args.output / 'summary.json'}")
    return 0


def add_commands(sub) -> None:
    """Register ``barrier`` and its subcommands on the top-level parser."""
    bar = sub.add_parser("barrier", help="the offset deformable barrier (ODB)")
    bsub = bar.add_subparsers(dest="barrier_command", required=True)
    s = bsub.add_parser(
        "simplified",
        help="write the paper's simplified barrier of discrete beams as an include deck",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter,
    )
    s.add_argument("-o", "--output", type=Path, required=True)
    s.add_argument("--vehicle-width", type=float, default=0.0, help="vehicle width [mm]: place for an offset test")
    s.add_argument("--overlap", type=float, default=40.0, help="overlap [%% of vehicle width]")
    s.add_argument("--side", choices=("left", "right"), default="left", help="driver side")
    s.add_argument("--y-centre", type=float, default=0.0, help="vehicle centre line y [mm]")
    s.add_argument("--y-min", type=float, default=-500.0, help="barrier edge y without --vehicle-width [mm]")
    s.add_argument("--x-face", type=float, default=0.0, help="barrier front face x [mm]")
    s.add_argument("--direction", type=int, choices=(1, -1), default=1, help="travel direction of the vehicle (x)")
    s.add_argument("--ground", type=float, default=0.0, help="ground z [mm]")
    s.add_argument("--columns", type=int, default=36, help="beam columns across the width")
    s.add_argument("--rows-main", type=int, default=20, help="beam rows of the main block")
    s.add_argument("--rows-bumper", type=int, default=10, help="beam rows of the bumper")
    s.add_argument("--id-offset", type=int, default=0, help="added to every ID")
    s.add_argument("--units", default="mm-t-s", help="unit system of the deck (mm-t-s, mm-kg-ms, mm-g-ms, m-kg-s)")
    s.add_argument("--curves", type=Path, help="block curves of `crashlite barrier characterise` (curves.json)")
    s.set_defaults(func=_simplified)
    i = bsub.add_parser(
        "impactor",
        help="the rigid impactor load case on the simplified barrier",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter,
    )
    i.add_argument("-o", "--output", type=Path, required=True, help="folder for main.k and barrier.k")
    i.add_argument("--mass", type=float, default=5000.0, help="impactor mass [kg]")
    i.add_argument("--speed", type=float, default=64.0, help="impact speed [km/h]")
    i.add_argument("--overlap", type=float, default=100.0, help="overlap [%% of the barrier width]")
    i.add_argument("--end-time", type=float, default=100.0, help="end time [ms]")
    i.add_argument(
        "--height",
        type=float,
        nargs=2,
        metavar=("LOW", "HIGH"),
        help="a strip impactor from LOW to HIGH mm above ground (a bumper beam's height: 390 500)",
    )
    i.add_argument("--no-cladding", action="store_true", help="beams only")
    i.add_argument("--curves", type=Path, help="block curves of `crashlite barrier characterise` (curves.json)")
    i.set_defaults(func=_impactor)
    fmt = argparse.ArgumentDefaultsHelpFormatter
    c = bsub.add_parser(
        "characterise",
        formatter_class=fmt,
        help="compress each detailed block alone and reduce its force-crush curve to the simplified one",
    )
    c.add_argument("-o", "--output", type=Path, required=True, help="folder for curves.json, index.html and the runs")
    c.add_argument("--size", type=float, default=25.0, help="element size of the detailed blocks [mm]")
    c.add_argument("--speed", type=float, default=10.0, help="impactor speed [m/s]")
    c.set_defaults(func=_characterise)
    v = bsub.add_parser(
        "verify",
        formatter_class=fmt,
        help="rigid impactor on the detailed and the simplified barrier: runs, reports, table 1",
    )
    v.add_argument("-o", "--output", type=Path, required=True, help="folder for the runs and the reports")
    v.add_argument("--size", type=float, default=25.0, help="element size of the detailed barrier [mm]")
    v.add_argument("--end-time", type=float, default=45.0, help="end time [ms]")
    v.add_argument("--overlap", type=float, nargs="+", default=[100.0, 40.0], help="overlaps [%%]")
    v.add_argument(
        "--simplified-curves",
        choices=["calibrated", "characterised", "paper"],
        default="calibrated",
        help="curves of the simplified barrier: characterised from compression tests of the detailed "
        "blocks and calibrated against the detailed barrier at the largest overlap (the paper's "
        "procedure), characterised only, or the paper's curves",
    )
    v.add_argument(
        "--curves",
        type=Path,
        help="curves.json for the simplified barrier instead (from `barrier characterise` or a calibration)",
    )
    v.add_argument("--calibration-runs", type=int, default=80, help="most simplified runs of the calibration")
    v.set_defaults(func=_verify)
