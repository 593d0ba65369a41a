"""Worked example (docs/study.md): crash-box and rail thicknesses for the
least mass under intrusion and deceleration limits, optimised once on the
full model and once on its surrogate, both optima then run on the full
model.

    python -m crashlite.study.example OUT [--workers 2] [--element-size 12.5]

writes OUT/full and OUT/surrogate (deck, study.toml, study folder with
report) and OUT/example.json with both optima and their full-model check.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from .models import front_structure

STUDY = """# {variant}: crash box and rail thickness for the least mass
[study]
name = "front-{variant}"
deck = "{variant}.k"

[variables.t_box]
part = "crash box"
property = "thickness"
bounds = [0.8, 1.6]

[variables.t_rail]
part = "rail"
property = "thickness"
bounds = [1.2, 2.4]

[responses.mass]          # front structure mass
type = "mass"
parts = ["crash box", "rail"]
scale = 1000.0            # tonne -> kg
unit = "kg"

[responses.intrusion]     # dynamic crush: largest travel of the vehicle mass towards the wall
type = "intrusion"
nodes = [900001]
component = "x"
over = "history"
unit = "mm"

[responses.deceleration]  # CFC 60 peak deceleration of the vehicle mass
type = "deceleration"
node = 900001
cfc = 60

[responses.box_energy]
type = "part_energy"
parts = ["crash box"]
unit = "N mm"

[objectives]
mass = "minimize"

[constraints]
intrusion = {{ upper = {intrusion} }}
deceleration = {{ upper = {deceleration} }}

[doe]
method = "lhs"
designs = {designs}
seed = 1

[sensitivity]
method = "sobol"          # on the metamodels of the designs run

[optimization]
method = "metamodel"      # sequential: optimum on the metamodels, run, shrink the region
iterations = {iterations}
points = {points}

[execution]
workers = {workers}
"""


def write_case(
    out: Path,
    variant: str,
    workers: int,
    element_size: float,
    designs: int = 12,
    iterations: int = 3,
    points: int = 2,
    intrusion: float = 36.0,
    deceleration: float = 300.0,
    **deck,
) -> Path:
    """Deck and study file of one variant in ``out``; returns the study file."""
    out.mkdir(parents=True, exist_ok=True)
    front_structure(out / f"{variant}.k", variant, element_size=element_size, **deck)
    p = out / "study.toml"
    p.write_text(
        STUDY.format(
            variant=variant,
            workers=workers,
            designs=designs,
            iterations=iterations,
            points=points,
            intrusion=intrusion,
            deceleration=deceleration,
        )
    )
    return p


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=Path)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--element-size", type=float, default=12.5)
    ap.add_argument("--rear-length", type=float, default=900.0)
    args = ap.parse_args(argv)
    from . import build_report, load_study, run_study
    from .executor import DaskExecutor
    from .runner import Progress

    summary = {}
    with DaskExecutor(workers=args.workers) as ex:
        for variant in ("full", "surrogate"):
            p = write_case(args.out / variant, variant, args.workers, args.element_size, rear_length=args.rear_length)
            cfg = load_study(p)
            t0 = time.perf_counter()
            s = run_study(cfg, executor=ex, progress=Progress(cfg))
            rep = build_report(cfg)
            summary[variant] = {
                "study": str(p),
                "designs": rep["counts"]["complete"],
                "wall_time": time.perf_counter() - t0,
                "ran": s.ran,
                "best": rep["best"],
                "report": str(cfg.directory / "report"),
            }
        # both optima on the full model
        from .evaluate import Task, evaluate

        full = load_study(args.out / "full" / "study.toml")
        checks = {}
        for variant in ("full", "surrogate"):
            best = summary[variant]["best"]
            task = Task(
                f"check-{variant}", best["values"], str(args.out / "check" / variant), full.template, full.responses
            )
            checks[variant] = ex.client.submit(evaluate, task, pure=False)
        for variant, fut in checks.items():
            r = fut.result()
            summary[variant]["on_full_model"] = r["responses"] if r["status"] == "complete" else r["message"]
    (args.out / "example.json").write_text(json.dumps(summary, indent=2))
    for variant in ("full", "surrogate"):
        b = summary[variant]["best"]
        print(
            f"{variant:9s}: {summary[variant]['designs']} designs in {summary[variant]['wall_time']:.0f} s; optimum "
            + ", ".join(f"{k} = {v:.3f}" for k, v in b["values"].items())
            + "; on the full model: "
            + ", ".join(f"{k} = {v:.4g}" for k, v in summary[variant]["on_full_model"].items())
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
