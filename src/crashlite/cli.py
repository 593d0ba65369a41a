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
    from .solver.part_moves import moved_model

    model = read_deck(args.deck, strict=args.strict)
    s = summary(model, moved_model(model, []))  # a *PART_MOVE card that cannot apply is the run's to refuse
    print(json.dumps(s, indent=2) if args.json else format_summary(s))
    return 0


def _convert(args) -> int:
    from . import read_deck, write_deck

    if Path(args.output).is_dir():  # checked before reading: a deck may take minutes to read
        raise IsADirectoryError(
            f"-o {args.output} is a folder: -o names the deck file to write "
            f"(e.g. {Path(args.output) / Path(args.deck).name})"
        )
    model = read_deck(args.deck, strict=args.strict)
    written = write_deck(model, args.output, fmt=args.format, split=args.split)
    for w in model.warnings:
        print(f"warning: {w}", file=sys.stderr)
    print("wrote " + ", ".join(str(p) for p in written))
    return 0


INTERRUPTED = 130  # exit status of a run stopped by Ctrl-C (128 + SIGINT), as shells report it


def _added_mass(res, model) -> str:
    """'; mass scaling (DT2MS) added ...' for the summary, or ''."""
    added = res.info.get("added_mass") or {}
    total = float(sum(added.values()))
    if total <= 0:
        return ""
    try:
        base = float(model.mass_properties().mass)
    except Exception:  # the summary goes on without the share  # noqa: BLE001
        base = 0.0
    share = f" to a model of {base:.4g} (+{100.0 * total / base:.3g} %)" if base > 0 else ""
    parts = ", ".join(f"part {p}: {m:.4g}" for p, m in sorted(added.items())[:10])
    return f"; mass scaling (DT2MS) added {total:.4g}{share} ({parts})"


def _deleted(res) -> str:
    """'; N elements deleted (part P: n, ...)' for the summary, or '': a
    deleted element carries nothing more (LS-DYNA reports its eroded ones)."""
    total = res.deleted()
    if not total:
        return ""
    worst = sorted(((int(n), int(p)) for p, n in zip(res.part_ids, res.part_deleted[-1]) if n), reverse=True)[:5]
    return f"; {total} elements deleted (" + ", ".join(f"part {p}: {n}" for n, p in worst) + ")"


def _run_external(args) -> int:
    """``crashlite run DECK --solver lsdyna|openradioss``: the deck unchanged
    in that solver, in the output folder; its results read back."""
    from .external import ExternalSolverError
    from .external import run as run_external
    from .results import load

    echo = None if args.quiet else (lambda line: print(line, flush=True))
    try:
        ext = run_external(args.deck, args.output, args.solver, force=args.force, echo=echo)
    except ExternalSolverError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    try:
        history = load(ext.folder)
    except FileNotFoundError as e:
        print(f"error: {ext.solver} terminated normally but left no results crashlite reads: {e}", file=sys.stderr)
        return 2
    head = (
        f"{ext.solver}: normal termination ({ext.termination}), {ext.wall_time:.1f} s wall"
        if ext.ran
        else f"{ext.solver}: {args.output} already holds a normally terminated run of this deck ({ext.termination}); "
        "not run again (--force runs it)"
    )
    print(
        f"{head}; results in {args.output} ({', '.join(history.categories()) or 'no time histories'}), read by "
        "crashlite.results.load"
    )
    return 0


def _run(args) -> int:
    if args.solver != "crashlite":
        return _run_external(args)
    from . import read_deck
    from .results.folder import OutputFolder
    from .solver import run
    from .solver.loop import RunError

    folder = OutputFolder(args.output, deck=args.deck, force=args.force)
    folder.check()  # before the deck is read or anything run: a file, the deck, foreign files
    model = read_deck(args.deck)
    folder.check(model.files)  # the includes too
    try:
        folder.clear()  # the previous run's files: no stale history or state beside the new ones
        try:
            res = run(model, out=args.output, quiet=args.quiet)
        except RunError as e:
            res = e.results
            for w in res.info.get("warnings", []):
                print(f"warning: {w}", file=sys.stderr)
            print(f"error: {e}; the states until then are in {args.output}", file=sys.stderr)
            return 2
        except KeyboardInterrupt:
            print("interrupted during set-up: nothing was run, no results written", file=sys.stderr)
            return INTERRUPTED
    finally:
        folder.record()
    for w in res.info.get("warnings", []):
        print(f"warning: {w}", file=sys.stderr)
    ratio = res.energy_ratio
    stopped = res.info.get("stopped") or ""
    head = f"{stopped}: " if stopped else ""
    print(
        f"{head}{res.cycles} cycles, dt {res.dt:.4g}, end time {res.time[-1]:.6g}, "
        f"energy ratio {ratio.min():.4f}..{ratio.max():.4f}, {res.wall_time:.2f} s wall"
        f"{_added_mass(res, model)}{_deleted(res)}; results{' so far' if stopped else ''} in {args.output}/results.npz"
    )
    return INTERRUPTED if stopped.startswith("interrupted") else 0


def _path_arg(text: str) -> Path:
    """A path argument; an empty one (-o "") names nothing and is refused."""
    if not text.strip():
        raise argparse.ArgumentTypeError("an empty path names no file or folder")
    return Path(text)


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="crashlite",
        description="crashlite: LS-DYNA decks in and out, and an explicit solver for simplified frontal crash models",
    )
    sub = p.add_subparsers(dest="command", required=True)
    info = sub.add_parser("info", help="summarise a keyword deck: counts, parts, mass, CoG")
    info.add_argument("deck", type=Path)
    info.add_argument("--json", action="store_true", help="print JSON instead of text")
    info.add_argument("--strict", action="store_true", help="keywords crashlite does not type are errors")
    info.set_defaults(func=_info)
    conv = sub.add_parser("convert", help="read a deck and write it again (format, includes resolved)")
    conv.add_argument("deck", type=Path)
    conv.add_argument("-o", "--output", type=_path_arg, required=True, help="the deck file to write")
    conv.add_argument("--format", choices=("fixed", "long", "i10", "free"), default="fixed")
    conv.add_argument("--split", action="store_true", help="nodes and elements in an include file")
    conv.add_argument("--strict", action="store_true")
    conv.set_defaults(func=_convert)
    run = sub.add_parser(
        "run",
        help="run a deck with the explicit solver (masses, springs, dampers, "
        "beams, rigid bodies, rigid walls at this stage), or unchanged in an "
        "installed LS-DYNA or OpenRadioss (--solver)",
    )
    run.add_argument("deck", type=Path)
    run.add_argument(
        "-o",
        "--output",
        type=_path_arg,
        required=True,
        help="results folder; one reused by an earlier run is emptied of that run's files (listed in "
        "its crashlite-run.json) first; files of the names a run writes that no run wrote "
        "refuse the run, and the deck is never overwritten",
    )
    run.add_argument(
        "--force",
        action="store_true",
        help="overwrite files in the results folder that have the "
        "names a run writes but no crashlite run wrote; with "
        "--solver, also run again a deck already run there",
    )
    run.add_argument(
        "--solver",
        choices=("crashlite", "lsdyna", "openradioss"),
        default="crashlite",
        help="crashlite's solver, or the deck unchanged in an installed LS-DYNA or OpenRadioss in the "
        "results folder (executable and options: CRASHLITE_LSDYNA, CRASHLITE_LSDYNA_NCPU, "
        "CRASHLITE_LSDYNA_MEMORY, CRASHLITE_MPI or ~/.config/crashlite/solvers.toml; see "
        "docs/external.md)",
    )
    run.add_argument("--quiet", action="store_true", help="no progress bar (with --solver: no solver output)")
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
    except (OSError, ValueError, KeyError, FloatingPointError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"interrupted (crashlite {args.command})", file=sys.stderr)
        return INTERRUPTED


if __name__ == "__main__":
    sys.exit(main())
