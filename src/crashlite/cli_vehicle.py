"""``crashlite vehicle ...``: the generic car and its frontal load cases."""

from __future__ import annotations

import argparse
import time
from pathlib import Path


def _generic(args) -> int:
    from .vehicle import generic_vehicle

    t0 = time.perf_counter()
    v = generic_vehicle(
        mesh_size=args.mesh_size,
        mass=args.mass,
        cog_x=args.cog_x,
        cog_z=args.cog_z,
        interface_x=args.interface_x,
        engine_mass=args.engine_mass,
        axle_mass=args.axle_mass,
        front=args.front,
    )
    t1 = time.perf_counter()
    path = v.write(args.output, fmt=args.format)
    t2 = time.perf_counter()
    c = v.cog
    print(
        f"wrote {path}: {v.shells} shells, {len(v.model.nodes)} nodes, {len(v.model.parts)} parts; "
        f"mass {v.mass:.1f} kg (structure {v.structure_mass:.1f} kg), CoG ({c[0]:.1f}, {c[1]:.1f}, {c[2]:.1f}) mm; "
        f"{len(v.sections)} interface sections at x = {v.interface_x:g} mm; "
        f"generated in {t1 - t0:.1f} s, written in {t2 - t1:.1f} s"
    )
    return 0


def _usncap(args) -> int:
    from .vehicle import usncap_deck

    out = usncap_deck(
        args.car,
        args.output,
        speed_kmh=args.speed,
        end_time=args.end_time / 1000.0,
        gap=args.gap,
        ground=args.ground,
        units=args.units,
    )
    print(f"wrote {out}: run it with `crashlite run {out} -o OUT`")
    return 0


def _odb(args) -> int:
    from .vehicle import odb_deck

    out = odb_deck(
        args.car,
        args.output,
        barrier=args.barrier,
        speed_kmh=args.speed,
        overlap=args.overlap / 100.0,
        side=args.side,
        end_time=args.end_time / 1000.0,
        gap=args.gap,
        ground=args.ground,
        units=args.units,
        element_size=args.barrier_size,
        honeycomb=_honeycomb(args),
        beams=_beams(args),
    )
    print(f"wrote {out} (and {out.stem}_barrier{out.suffix}): run it with `crashlite run {out} -o OUT`")
    return 0


def _reduce(args) -> int:
    from .vehicle.reduce import reduce_vehicle

    t0 = time.perf_counter()
    red = reduce_vehicle(
        args.deck,
        args.results,
        load_cases=args.load_case,
        interface=args.interface,
        support=args.support,
        axle_parts=None if args.axle_parts is None else [int(p) if p.isdigit() else p for p in args.axle_parts],
        shares=args.shares,
        t_end=None if args.t_end is None else args.t_end / 1000.0 * _seconds(args.deck),
        interface_mode=args.interface_mode,
        spring_length=args.spring_length,
        damping_ratio=args.damping_ratio,
        mass_split=args.mass_split,
        springs=args.springs,
        modes=args.modes,
        connection=args.connection,
        condensed_modes=args.condensed_modes,
        cut_dashpots=not args.no_cut_dashpots,
        shells=args.shells,
        quiet=False,
    )
    files = red.write(args.output, args.report, fmt=args.format)
    s = red.summary()["model_size"]
    print(
        f"wrote {files['deck']} ({s['simplified_elements']} of {s['full_elements']} elements, "
        f"{s['element_reduction_percent']:.1f} % fewer; {s['removed_mass_percent']:.1f} % of the mass replaced), "
        f"{files['summary']} and {files['html']} in {time.perf_counter() - t0:.1f} s"
    )
    return 0


def _verify(args) -> int:
    from .vehicle.verify.verification import split_text, verify_vehicle

    if (args.twin is None) != (args.twin_deck is None):
        raise SystemExit("crashlite vehicle verify: --twin and --twin-deck go together")
    v = verify_vehicle(
        args.full,
        args.simplified,
        args.deck_full,
        args.deck_simplified,
        load_case=args.load_case,
        crash_boxes=args.crash_boxes,
        firewall=args.firewall,
        reference=args.reference,
        engine=args.engine,
        cfc=args.cfc,
        cell_frame=tuple(args.cell_frame),
        twin=args.twin,
        twin_deck=args.twin_deck,
    )
    files = v.write(args.output)
    f = v.figures
    fw = f.get("firewall_intrusion") or {}
    print(
        f"{f['load_case']}: energy ratings {f['energy_ratings_deceleration_phase']}, crash-box internal energy "
        f"{_pc(f['crash_box_internal_energy_deviation_percent'])}, firewall intrusion max "
        f"{_pc(fw.get('max_deviation_percent'))} mean {_pc(fw.get('mean_deviation_percent'))}{split_text(fw)}, "
        f"time reduction {_pc(f['time_reduction_percent'])}; wrote {files['html']} and {files['summary']}"
    )
    if f.get("elastic_twin"):
        from .vehicle.verify.study_report import twin_text

        print(twin_text(f["elastic_twin"]).lstrip("; "))
    for n in v.notes:
        print(f"note: {n}")
    return 0


def _twin(args) -> int:
    from . import read_deck
    from .keyword.writer import write_deck
    from .vehicle.connection.twin import elastic_twin
    from .vehicle.reduce import section_assemblies
    from .vehicle.steps.cut import cut_behind

    model = read_deck(args.deck)
    if args.interface is not None:
        x = float(args.interface)
    else:
        point = section_assemblies(model)[2]
        if point is None:
            raise SystemExit(f"{args.deck}: no common plane of titled cross sections: give --interface")
        x = float(point[0])
    t = elastic_twin(cut_behind(model, x=x))
    write_deck(t.model, args.output, fmt=args.format)
    s = t.summary()
    print(
        f"wrote {args.output}: {s['elements_made_elastic']} elements behind x = {x:g} elastic "
        f"({s['parts_made_elastic']} parts, {s['parts_split']} of them split at the interface, "
        f"{s['elastic_materials']} *MAT_ELASTIC)"
    )
    for n in t.notes:
        print(f"note: {n}")
    return 0


def _interface(args) -> int:
    import json

    from . import read_deck
    from .report.build import jsonable
    from .vehicle.connection.interface import propose_interface

    p = propose_interface(
        read_deck(args.deck),
        args.results,
        strain=args.strain / 100.0,
        allowed=args.allowed / 100.0,
        energy=args.energy / 100.0,
        step=args.step,
        also=args.at,
    )
    bent = any("interface_warping_max" in c for c in p.candidates)
    print(
        f"{'x':>9} {'energy behind':>14} {'strained area':>14} {'p99 εp':>8} {'mass replaced':>14} "
        f"{'elements replaced':>18}" + (f" {'cut bends max/rms':>18}" if bent else "") + "  most energy behind"
    )
    for c in p.candidates:
        mark = "  <- proposed" if p.x is not None and c["x"] == p.x else ""
        most = ", ".join(f"{k} {v:.2f} %" for k, v in c["most_energy_behind"].items())
        warp = f" {c['interface_warping_max']:9.2f} /{c['interface_warping_rms']:6.2f}" if bent else ""
        print(
            f"{c['x']:9.1f} {c['energy_behind_percent']:13.2f}% {c['strained_area_percent_behind']:13.2f}% "
            f"{100 * c['p99_plastic_strain_behind']:7.2f}% {c['replaced_mass_percent']:13.1f}% "
            f"{c['replaced_elements_percent']:17.1f}%{warp}  {most}{mark}"
        )
    if bent:
        print(
            "cut bends: how far the cut's nodes move along the axis out of the rigid motion that best fits them "
            "(largest value and largest rms over the run) [length]: a rigid interface holds the cut flat"
        )
    for n in p.notes:
        print(f"note: {n}")
    if args.json is not None:
        args.json.write_text(json.dumps(jsonable(p.summary()), indent=1) + "\n")
    return 0


def _honeycomb_arguments(p) -> None:
    """The barriers' options beside --barrier-size (odb, study)."""
    p.add_argument(
        "--barrier-face-size",
        type=float,
        default=None,
        help="rows and columns of the detailed barrier across its face [mm] (default: --barrier-size): "
        "a car loads strips of it, and the elements beside the strips crush by half its push",
    )
    p.add_argument(
        "--barrier-elform",
        type=int,
        choices=(1, 2),
        default=None,
        help="the detailed honeycomb's solid formulation (default: detailed_barrier's, 1)",
    )
    p.add_argument(
        "--barrier-slip",
        type=_slip,
        default=None,
        help="slip at which the detailed honeycomb's cell walls tear [mm], or 'cell': each block's own cell "
        "(19.14 and 6.4 mm), or 'columns': columns on nodes of their own joined by links torn at one cell, an "
        "element torn at a cell's slip across a cell (default: its shear failure strain)",
    )
    p.add_argument(
        "--barrier-shear-strength",
        type=float,
        default=None,
        help="the detailed honeycomb's transverse shear strength (its cell walls') × its crush plateau (default: "
        "detailed_barrier's, 0.5; aluminium honeycomb's plate-shear strengths are 1.4 (L) and 0.8 (W) × its crush "
        "strength)",
    )
    p.add_argument(
        "--barrier-beams",
        type=int,
        nargs=3,
        default=None,
        metavar=("WIDTH", "MAIN", "BUMPER"),
        help="the simplified barrier's grid: nodes across, main-block rows, bumper rows (default 36 20 10: the "
        "paper's 720 + 360 beams)",
    )


def _beams(args) -> dict | None:
    """--barrier-beams, by simplified_barrier's names."""
    from .barrier.simplified import GRID

    return dict(zip(GRID, args.barrier_beams)) if args.barrier_beams else None


def _slip(text: str) -> float | str:
    """--barrier-slip: a slip in mm, 'cell' or 'columns'."""
    from .barrier.detailed import SLIP_WORDS

    if text in SLIP_WORDS:
        return text
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"a slip in mm, 'cell' or 'columns', got {text!r}") from None


def _honeycomb(args) -> dict:
    """The options given, by detailed_barrier's names: the rest keep its defaults."""
    face = args.barrier_face_size
    given = {
        "elform": args.barrier_elform,
        "shear_slip": args.barrier_slip,
        "shear_strength": args.barrier_shear_strength,
        "height_size": face,
        "width_size": face,
    }
    return {k: v for k, v in given.items() if v is not None}


def _study(args) -> int:
    from .vehicle.workflow import paper_study

    st = paper_study(
        args.output,
        mesh_size=args.mesh_size,
        barrier_size=args.barrier_size,
        barrier_options=_honeycomb(args),
        beams=_beams(args),
        usncap_end=args.usncap_end / 1000.0,
        odb_end=args.odb_end / 1000.0,
        interface_x=args.interface_x,
        shares=args.shares,
        variants=not args.no_variants,
        quiet=not args.progress,
        twin=args.twin,
        front=args.front,
    )
    t = st.summary["time"]
    print(
        f"time-loop reduction: US NCAP vehicle {_pc(t['us_ncap']['vehicle_reduction_percent'])}; ODB "
        + ", ".join(
            f"{k.replace('_reduction_percent', '')} {_pc(v)}" for k, v in t["odb"].items() if k.endswith("_percent")
        )
    )
    from .vehicle.verify.study_report import verification_lines

    for line in verification_lines(st.summary):
        print(line)
    print(f"wrote {args.output / 'index.html'} and {args.output / 'summary.json'}")
    return 0


def _pc(v) -> str:
    return "–" if v is None else f"{v:.2f} %"


def _seconds(deck) -> float:
    """Time units per second of a deck's unit system (from its densities)."""
    from .vehicle.car.loadcases import vehicle_info

    return vehicle_info(deck).units.time


def add_commands(sub) -> None:
    """Register ``vehicle`` and its subcommands on the top-level parser."""
    from .vehicle.verify.verification import CELL_FRAME

    fmt = argparse.ArgumentDefaultsHelpFormatter
    veh = sub.add_parser("vehicle", help="the generic compact car and its frontal load cases")
    vsub = veh.add_subparsers(dest="vehicle_command", required=True)
    g = vsub.add_parser(
        "generic", help="write the parametric generic compact car (shells, mm-t-s)", formatter_class=fmt
    )
    g.add_argument("-o", "--output", type=Path, required=True)
    g.add_argument(
        "--mesh-size", type=float, default=25.0, help="element size [mm] (38: ~20 k shells, 25: ~45 k, 5: ~1.1 M)"
    )
    g.add_argument("--mass", type=float, default=1263.0, help="total mass [kg]")
    g.add_argument(
        "--cog-x", type=float, default=-1100.0, help="centre of gravity x [mm] (front axle at 0, +x forward)"
    )
    g.add_argument("--cog-z", type=float, default=500.0, help="centre of gravity height [mm] (ground at 0)")
    g.add_argument("--interface-x", type=float, default=-600.0, help="x of the interface cross sections [mm]")
    g.add_argument("--engine-mass", type=float, default=170.0, help="rigid engine and gearbox [kg]")
    g.add_argument("--axle-mass", type=float, default=73.0, help="rigid rear axle [kg]")
    g.add_argument(
        "--front",
        choices=("generic", "stiff"),
        default="generic",
        help="bumper beam: 'stiff' is a second front (2.5 mm, 45 mm deep instead of 1.6 mm, 70 mm)",
    )
    g.add_argument("--format", choices=("fixed", "long", "i10", "free"), default="fixed")
    g.set_defaults(func=_generic)
    lc = vsub.add_parser("loadcase", help="a frontal load case deck that includes a vehicle deck")
    lsub = lc.add_subparsers(dest="loadcase", required=True)
    u = lsub.add_parser("usncap", help="US NCAP: 100 %% rigid wall", formatter_class=fmt)
    o = lsub.add_parser("odb", help="Euro NCAP ODB: 40 %% offset deformable barrier", formatter_class=fmt)
    for p, speed, end in ((u, 56.0, 100.0), (o, 64.0, 120.0)):
        p.add_argument("car", type=Path, help="vehicle deck (drives in +x, z up)")
        p.add_argument("-o", "--output", type=Path, required=True)
        p.add_argument("--speed", type=float, default=speed, help="impact speed [km/h]")
        p.add_argument("--end-time", type=float, default=end, help="end time [ms]")
        p.add_argument("--gap", type=float, default=1.0, help="wall or barrier face ahead of the vehicle [mm]")
        p.add_argument("--ground", type=float, default=0.0, help="ground height [mm]")
        p.add_argument("--units", default=None, help="unit system of the vehicle deck (default: from its densities)")
    u.set_defaults(func=_usncap)
    o.add_argument("--barrier", choices=("simplified", "detailed"), default="simplified")
    o.add_argument("--overlap", type=float, default=40.0, help="overlap [%% of the vehicle width]")
    o.add_argument("--side", choices=("left", "right"), default="left", help="driver side")
    o.add_argument("--barrier-size", type=float, default=20.0, help="element size of the detailed barrier [mm]")
    _honeycomb_arguments(o)
    o.set_defaults(func=_odb)
    r = vsub.add_parser(
        "reduce", formatter_class=fmt, help="the four-step simplified vehicle from a full deck and its runs"
    )
    r.add_argument("deck", type=Path, help="full vehicle deck (interface cross sections titled by assembly)")
    r.add_argument(
        "--results",
        type=Path,
        nargs="+",
        required=True,
        help="results of full runs, one per load case (crashlite folder, LS-DYNA binout or ASCII)",
    )
    r.add_argument("--load-case", nargs="+", default=None, help="names of the load cases, in the order of --results")
    r.add_argument("-o", "--output", type=Path, required=True, help="simplified deck to write")
    r.add_argument("--report", type=Path, default=None, help="folder of reduction.json/.html (default: beside -o)")
    r.add_argument(
        "--interface",
        type=float,
        default=None,
        help="x of the interface [deck length unit] (default: the plane of the cross sections)",
    )
    r.add_argument(
        "--support",
        default=None,
        help="rear-axle attachment points: *SET_NODE title or ID (default: the set titled ...axle...)",
    )
    r.add_argument("--axle-parts", nargs="+", default=None, help="rear-axle parts (titles or IDs), for table 2")
    r.add_argument("--shares", default="combined", help="'combined' (mean over the load cases) or a load case")
    r.add_argument("--t-end", type=float, default=None, help="ignore section forces after this time [ms]")
    r.add_argument(
        "--connection",
        choices=("condensed", "craig-bampton", "springs"),
        default="condensed",
        help="join the cut to the rear body by the replaced structure condensed onto the cut nodes "
        "(a linear superelement: the cut bends as the structure behind it); replace the structure by "
        "a Craig-Bampton superelement with its mass and held modes (no rear body); or join it by a "
        "rigid interface and one spring per load path (the paper; the options below)",
    )
    r.add_argument(
        "--condensed-modes",
        type=int,
        default=0,
        help="with the condensed connection, the replaced structure's N lowest free modes move on their "
        "own beside the residual stiffness of the rest (0: quasi-static); with craig-bampton, its N "
        "lowest modes held at the boundary",
    )
    r.add_argument(
        "--shells",
        choices=("static", "kernel"),
        default="static",
        help="the replaced shells' stiffness in the condensed and craig-bampton connections: a linear "
        "solver's (QM6 membrane, MITC4 plate) or the time loop's own shell elements linearised (the "
        "stiffness the full run integrates)",
    )
    r.add_argument(
        "--no-cut-dashpots",
        action="store_true",
        help="with the condensed connection, leave out the dashpots of the replaced structure's wave "
        "impedance between the cut nodes and the rear body (waves then come back from the cut)",
    )
    r.add_argument(
        "--interface-mode",
        choices=("rigid", "assembly"),
        default="rigid",
        help="one rigid body over the cut, or one per assembly",
    )
    r.add_argument("--spring-length", type=float, default=100.0, help="spring length [deck length unit]")
    r.add_argument("--damping-ratio", type=float, default=0.0, help="damping ratio of dampers beside the springs")
    r.add_argument(
        "--mass-split",
        choices=("axle", "cog"),
        default="axle",
        help="replaced mass shared between interface and rear body along the axis, or all at its CoG",
    )
    r.add_argument(
        "--springs",
        choices=("relief", "axle"),
        default="relief",
        help="the K the springs share: the replaced structure's under inertia relief (held by its own "
        "mass, as in the crash), or step 3's, borne at the rear axle (the paper)",
    )
    r.add_argument(
        "--modes",
        type=int,
        default=0,
        help="also the replaced structure's lowest N modes, held at the interface (effective masses) "
        "and free (share of the interface's compliance), and where they live: what a rigid rear "
        "leaves out (a minute or two on a car)",
    )
    r.add_argument("--format", choices=("fixed", "long", "i10", "free"), default="fixed")
    r.set_defaults(func=_reduce)
    w = vsub.add_parser(
        "verify",
        formatter_class=fmt,
        help="compare a simplified vehicle's run with the full model's (energies, crash boxes, "
        "firewall intrusion, engine acceleration, time)",
    )
    w.add_argument("full", type=Path, help="results of the full model")
    w.add_argument("simplified", type=Path, help="results of the simplified model, same load case")
    w.add_argument("--deck-full", type=Path, required=True, help="deck of the full run (names parts and nodes)")
    w.add_argument("--deck-simplified", type=Path, required=True, help="deck of the simplified run")
    w.add_argument("-o", "--output", type=Path, required=True, help="report folder (index.html, summary.json)")
    w.add_argument("--load-case", default="US NCAP")
    w.add_argument("--crash-boxes", nargs="+", default=["crash box left", "crash box right"], help="part titles")
    w.add_argument("--firewall", default="firewall nodes", help="*SET_NODE title of the firewall")
    w.add_argument(
        "--reference",
        default="rear seat left",
        help="history node title of the passenger-cell node whose stop ends the deceleration phase",
    )
    w.add_argument(
        "--cell-frame",
        nargs="+",
        default=list(CELL_FRAME),
        metavar="TITLE",
        help="history node titles of passenger-cell nodes (three or more, apart along x and y): the "
        "intrusion is measured in their rigid motion's frame",
    )
    w.add_argument("--engine", default="engine top", help="history node title of the engine-top sensor")
    w.add_argument("--cfc", type=float, default=60.0, help="SAE J211 filter class of the accelerations")
    w.add_argument(
        "--twin",
        type=Path,
        default=None,
        help="results of the full model's elastic twin (crashlite vehicle twin) in the same load case: "
        "splits the deviations into the elastic premise's and the surrogate's",
    )
    w.add_argument("--twin-deck", type=Path, default=None, help="deck of the elastic twin's run")
    w.set_defaults(func=_verify)
    tw = vsub.add_parser(
        "twin",
        formatter_class=fmt,
        help="write the full model's elastic twin: the structure behind the interface elastic "
        "(*MAT_ELASTIC of the same density and moduli), everything else as it is",
    )
    tw.add_argument("deck", type=Path, help="full vehicle deck")
    tw.add_argument(
        "--interface",
        type=float,
        default=None,
        help="x of the interface [deck length unit] (default: the plane of the cross sections)",
    )
    tw.add_argument("-o", "--output", type=Path, required=True, help="deck to write")
    tw.add_argument("--format", choices=("fixed", "long", "i10", "free"), default="fixed")
    tw.set_defaults(func=_twin)
    f = vsub.add_parser(
        "interface",
        formatter_class=fmt,
        help="propose the interface: the foremost plane with the structure behind it elastic",
    )
    f.add_argument("deck", type=Path, help="full vehicle deck")
    f.add_argument("--results", type=Path, required=True, help="crashlite results of a full run with field states")
    f.add_argument("--strain", type=float, default=1.0, help="plastic strain that counts as strained [%%]")
    f.add_argument(
        "--allowed", type=float, default=1.0, help="share of the shell area behind allowed to reach --strain [%%]"
    )
    f.add_argument(
        "--energy", type=float, default=3.0, help="share of the energy the shells absorb allowed behind the plane [%%]"
    )
    f.add_argument("--step", type=float, default=None, help="candidate spacing [length] (default 4 elements)")
    f.add_argument(
        "--at",
        type=float,
        nargs="+",
        default=(),
        metavar="X",
        help="rate these planes too (e.g. the interface in use) [length]",
    )
    f.add_argument("--json", type=Path, default=None, help="write the candidates as JSON")
    f.set_defaults(func=_interface)
    y = vsub.add_parser(
        "study",
        formatter_class=fmt,
        help="the paper's study on the generic car: full and simplified runs in US NCAP and Euro "
        "NCAP ODB (detailed and simplified barrier), one surrogate, verification, time reduction",
    )
    y.add_argument("-o", "--output", type=Path, required=True, help="study folder")
    y.add_argument("--mesh-size", type=float, default=38.0, help="element size of the car [mm]")
    y.add_argument("--barrier-size", type=float, default=50.0, help="element size of the detailed barrier [mm]")
    _honeycomb_arguments(y)
    y.add_argument("--usncap-end", type=float, default=80.0, help="end time of the US NCAP runs [ms]")
    y.add_argument("--odb-end", type=float, default=100.0, help="end time of the ODB runs [ms]")
    y.add_argument("--interface-x", type=float, default=-600.0, help="x of the interface [mm]")
    y.add_argument("--shares", default="combined", help="'combined', 'US NCAP' or 'Euro NCAP ODB'")
    y.add_argument(
        "--no-variants",
        action="store_true",
        help="skip the ODB runs with one simplification only (full car + simplified barrier, "
        "simplified car + detailed barrier)",
    )
    y.add_argument(
        "--twin",
        action="store_true",
        help="also run the full car's elastic twin in US NCAP: splits that verification's deviations "
        "into the elastic premise's and the surrogate's",
    )
    y.add_argument(
        "--front", choices=("generic", "stiff"), default="generic", help="the car's bumper beam (vehicle generic)"
    )
    y.add_argument("--progress", action="store_true", help="show each run's progress")
    y.set_defaults(func=_study)
