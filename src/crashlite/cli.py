"""Command line: a thin layer over the public API."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from .keyword.errors import DeckError


def _info(args) -> int:
    from . import read_deck
    from .model.summary import format_summary, summary

    model = read_deck(args.deck, strict=args.strict)
    s = summary(model)
    print(json.dumps(s, indent=2) if args.json else format_summary(s))
    return 0


def _convert(args) -> int:
    from . import read_deck, write_deck

    model = read_deck(args.deck, strict=args.strict)
    written = write_deck(model, args.output, fmt=args.format, split=args.split)
    for w in model.warnings:
        print(f"warning: {w}", file=sys.stderr)
    print("wrote " + ", ".join(str(p) for p in written))
    return 0


def _run(args) -> int:
    from .solver import run

    res = run(args.deck, out=args.output, quiet=args.quiet)
    for w in res.info.get("warnings", []):
        print(f"warning: {w}", file=sys.stderr)
    ratio = res.energy_ratio
    print(f"{res.cycles} cycles, dt {res.dt:.4g}, end time {res.time[-1]:.6g}, "
          f"energy ratio {ratio.min():.4f}..{ratio.max():.4f}, {res.wall_time:.2f} s wall; "
          f"results in {args.output}/results.npz")
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="crashlite", description="crashlite: LS-DYNA decks in and out, and "
                                "an explicit solver for simplified frontal crash models")
    sub = p.add_subparsers(dest="command", required=True)
    info = sub.add_parser("info", help="summarise a keyword deck: counts, parts, mass, CoG")
    info.add_argument("deck", type=Path)
    info.add_argument("--json", action="store_true", help="print JSON instead of text")
    info.add_argument("--strict", action="store_true", help="keywords crashlite does not type are errors")
    info.set_defaults(func=_info)
    conv = sub.add_parser("convert", help="read a deck and write it again (format, includes resolved)")
    conv.add_argument("deck", type=Path)
    conv.add_argument("-o", "--output", type=Path, required=True)
    conv.add_argument("--format", choices=("fixed", "long", "i10", "free"), default="fixed")
    conv.add_argument("--split", action="store_true", help="nodes and elements in an include file")
    conv.add_argument("--strict", action="store_true")
    conv.set_defaults(func=_convert)
    run = sub.add_parser("run", help="run a deck with the explicit solver (masses, springs, dampers, "
                                     "beams, rigid bodies, rigid walls at this stage)")
    run.add_argument("deck", type=Path)
    run.add_argument("-o", "--output", type=Path, required=True, help="results folder")
    run.add_argument("--quiet", action="store_true", help="no progress bar")
    run.set_defaults(func=_run)
    from .cli_barrier import add_commands as barrier_commands

    barrier_commands(sub)
    from .cli_compare import add_commands as compare_commands

    compare_commands(sub)
    from .cli_vehicle import add_commands as vehicle_commands

    vehicle_commands(sub)
    from .cli_study import add_commands as study_commands

    study_commands(sub)
    return p


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except DeckError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except (FileExistsError, FileNotFoundError, ValueError, KeyError, FloatingPointError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
