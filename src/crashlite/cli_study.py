"""``crashlite study ...``: run, resume, follow and report design studies."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path


def _run(args) -> int:
    from .study import load_study, run_study
    from .study.executor import ExecutorError, make_executor
    from .study.runner import Progress, StudyInterrupted, solver_options

    cfg = load_study(args.study)
    solver_options(cfg)  # an external solver not configured: said before any worker starts
    if args.cluster is not None and ":" not in args.cluster:
        raise ValueError(f"--cluster {args.cluster!r}: give MODULE:CALLABLE (a function returning a Dask cluster)")
    executor = make_executor(
        cfg.execution, scheduler=args.scheduler, workers=args.workers, serial=args.serial, cluster=args.cluster
    )
    progress = Progress(cfg, quiet=args.quiet)
    try:
        with executor:
            s = run_study(cfg, executor=executor, progress=progress, force=args.force)
    except ExecutorError as e:
        print(f"error: {e}", file=sys.stderr)
        return 3
    except StudyInterrupted as e:
        i = e.summary
        print(
            f"interrupted: {i.ran} design(s) finished in this session ({i.complete} complete, {i.failed} failed) "
            f"and are stored; {i.stopped} design(s) started and not finished were stopped, they run again when the study is resumed "
            f"(crashlite study run {args.study})",
            file=sys.stderr,
        )
        return 130
    except KeyboardInterrupt:  # before the first design started
        print("interrupted: no design of this session finished; run the study again to resume", file=sys.stderr)
        return 130
    print(
        f"study {cfg.name!r}: {s.ran} design(s) run in this session ({s.complete} complete, {s.failed} failed), "
        f"{s.skipped} already done, {s.rerun} interrupted one(s) rerun; {s.wall_time:.1f} s on {s.executor}"
    )
    if args.report:
        return _report_of(cfg, None)
    return 0


def _report_of(cfg, out) -> int:
    from .study import build_report

    summary = build_report(cfg, out)
    where = Path(out) if out else cfg.directory / "report"
    c = summary["counts"]
    print(
        f"report of {cfg.name!r} in {where}: {c['complete']} complete, {c['failed']} failed, "
        f"{c['feasible']} feasible; figures: " + ", ".join(f["file"] for f in summary["figures"])
    )
    if summary["best"]:
        b = summary["best"]
        print(
            f"best design {b['key']}: "
            + ", ".join(f"{k} = {v:.6g}" for k, v in b["values"].items())
            + " -> "
            + ", ".join(f"{k} = {v:.6g}" for k, v in b["responses"].items())
            + (f"; deck {where / summary['best_deck']}" if summary.get("best_deck") else "")
        )
    for n in summary["notes"]:
        print(f"note: {n}")
    return 0


def _report(args) -> int:
    from .study import load_study

    return _report_of(load_study(args.study), args.output)


def _status(args) -> int:
    from .study import load_study
    from .study.status import format_status, study_status

    s = study_status(load_study(args.study))
    print(json.dumps(s, indent=2) if args.json else format_status(s))
    return 0


def _workers(text: str) -> int:
    """--workers: a whole number of 1 or more."""
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"a whole number of worker processes, got {text!r}") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"must be 1 or more, got {n}")
    return n


def add_commands(sub) -> None:
    """Register ``study`` and its subcommands on the top-level parser."""
    fmt = argparse.ArgumentDefaultsHelpFormatter
    st = sub.add_parser("study", help="design studies: DOE, sensitivity, optimisation (Dask, resumable)")
    ssub = st.add_subparsers(dest="study_command", required=True)
    r = ssub.add_parser("run", help="run or resume the study of a study file", formatter_class=fmt)
    r.add_argument("study", type=Path, help="study file (TOML)")
    r.add_argument(
        "--scheduler",
        default=None,
        help="address of a running Dask scheduler (tcp://host:8786); default: a LocalCluster on this machine",
    )
    r.add_argument(
        "--cluster",
        default=None,
        metavar="MODULE:CALLABLE",
        help="a function returning a Dask cluster to run on (e.g. a dask-jobqueue SLURMCluster); "
        "overrides the study file's [execution] scheduler and cluster",
    )
    r.add_argument(
        "--workers", type=_workers, default=None, help="LocalCluster worker processes (default: one per core)"
    )
    r.add_argument("--serial", action="store_true", help="run the designs one by one in this process (no Dask)")
    r.add_argument("--force", action="store_true", help="take over a study whose session looks alive")
    r.add_argument("--report", action="store_true", help="write the report when the study is done")
    r.add_argument("--quiet", action="store_true", help="no line per design")
    r.set_defaults(func=_run)
    p = ssub.add_parser("report", help="figures, summary.json and the best design's deck", formatter_class=fmt)
    p.add_argument("study", type=Path)
    p.add_argument("-o", "--output", type=Path, default=None, help="report folder (default: <study folder>/report)")
    p.set_defaults(func=_report)
    s = ssub.add_parser("status", help="designs done / running / failed and the best so far")
    s.add_argument("study", type=Path)
    s.add_argument("--json", action="store_true")
    s.set_defaults(func=_status)
