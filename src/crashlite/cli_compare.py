"""``crashlite compare A B -o REPORT_DIR``: two runs compared, with an HTML report."""

from __future__ import annotations

import argparse
from pathlib import Path


def _cfc(text: str):
    if text.lower() in ("none", "off", "0"):
        return None
    value = float(text)
    if not value > 0:
        raise argparse.ArgumentTypeError(f"CFC must be a positive class (60, 180, 600, 1000) or 'none', got {text}")
    return value


def _compare(args) -> int:
    from .report import write_report
    from .verify.compare import Options, compare_paths

    opts = Options(
        parts=args.parts,
        nodes=args.nodes,
        sections=args.sections,
        walls=args.walls,
        field_nodes=args.field_nodes,
        times=args.time,
        at=args.at,
        cfc=args.cfc,
        time_scale=args.time_scale,
        pulse_node=args.pulse_node,
        axis=args.axis,
        component=args.component,
    )
    names = tuple(args.names) if args.names else (None, None)
    c = compare_paths(args.reference, args.comparison, opts, names=names, decks=(args.deck_ref, args.deck_cmp))
    paths = write_report(c, args.output, pictures_view=args.view, with_plots=not args.no_plots)
    ov = c.overall()
    rating = "–" if ov["mean_rating"] is None else f"{ov['mean_rating']:.3f} (lowest {ov['min_rating']:.3f})"
    unmatched = ", ".join(f"{k}: {v['only_ref']['count']}/{v['only_cmp']['count']}" for k, v in c.mismatches.items())
    print(
        f"{ov['pairs']} curve pairs, {len(c.fields)} field comparisons; mean ISO/TS 18571 rating {rating}"
        + (f"; not matched (only {c.ref.name}/only {c.cmp.name}): {unmatched}" if unmatched else "")
        + f"\nreport {paths['html']}, figures {paths['summary']}"
    )
    return 0


def add_commands(sub) -> None:
    """Register ``compare`` on the top-level parser."""
    p = sub.add_parser(
        "compare",
        help="compare two runs (crashlite or LS-DYNA results): energies, part "
        "energies, section and wall forces, history nodes, node fields, crash "
        "pulse, time; HTML report and summary.json",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter,
    )
    p.add_argument("reference", type=Path, help="results of the reference run (crashlite folder, LS-DYNA folder)")
    p.add_argument("comparison", type=Path, help="results of the run compared with it")
    p.add_argument("-o", "--output", type=Path, required=True, help="report folder (index.html, summary.json)")
    p.add_argument(
        "--deck-ref",
        type=Path,
        help="deck of the reference run: part titles and sets, node IDs of its field states, element counts",
    )
    p.add_argument("--deck-cmp", type=Path, help="deck of the comparison run")
    p.add_argument("--names", nargs=2, metavar=("REF", "CMP"), help="names of the two runs in the report")
    p.add_argument("--parts", nargs="+", help="parts: IDs, titles or set:<part set ID> (default: the common part IDs)")
    p.add_argument("--nodes", nargs="+", type=int, help="history node IDs (default: the common ones)")
    p.add_argument("--sections", nargs="+", type=int, help="cross-section IDs (default: the common ones)")
    p.add_argument("--walls", nargs="+", type=int, help="rigid-wall IDs (default: the common ones)")
    p.add_argument(
        "--field-nodes", nargs="+", type=int, help="node IDs of the field comparison (default: all common nodes)"
    )
    p.add_argument(
        "--time",
        nargs="+",
        type=float,
        help="times of the field comparisons and pictures, in the "
        "runs' time unit (default: the last common field state)",
    )
    p.add_argument("--at", type=float, help="time of the 'value at' figures (default: end of the common range)")
    p.add_argument("--cfc", type=_cfc, default=60.0, help="SAE J211 class of the accelerations, or 'none'")
    p.add_argument(
        "--time-scale", type=float, default=1.0, help="seconds per time unit of the runs (1e-3 for mm-kg-ms decks)"
    )
    p.add_argument(
        "--pulse-node",
        type=int,
        help="history node of the crash pulse (default: the common history node with the smallest peak deceleration)",
    )
    p.add_argument("--axis", choices=("x", "y", "z"), default="x", help="direction of travel (crash pulse)")
    p.add_argument(
        "--component",
        choices=("x", "y", "z"),
        help="field comparison of one displacement component (default: the vector)",
    )
    p.add_argument("--view", choices=("iso", "side", "top", "front"), default="iso", help="view of the pictures")
    p.add_argument("--no-plots", action="store_true", help="tables only (faster)")
    p.set_defaults(func=_compare)
