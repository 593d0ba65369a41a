"""Designs per hour of a study on the full model and on its surrogate,
measured in one run on one Dask LocalCluster, and their ratio.

    python bench/study.py                       # the built-in pair (below)
    python bench/study.py --full car.k --surrogate car_surrogate.k \\
        --parts "crash box L" "crash box R" "rail L" "rail R" [--designs 8 --workers 2]

Each deck gets the same study: one thickness variable per part named
(bounds ±20 % of the deck's value), a Latin hypercube of ``--designs``
designs, mass and internal energy as responses, run on the same warmed-up
cluster (one design per worker first, not counted, so every worker has
its Numba kernels loaded). Designs per hour = designs / study wall time ×
3600: what a study of that deck gets through this machine, writing decks,
running, extracting responses and storing them included.

Built-in pair (no --full/--surrogate): the crash box and rail of
crashlite.study.models driving into a rigid wall at 15 m/s, with a 900 mm
elastic rear frame of shells (full) or, as in the paper's step 4, that
frame replaced by a spring of its axial stiffness and its mass (surrogate).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

STUDY = """[study]
name = "bench-{name}"
deck = "{deck}"
directory = "{directory}"
{variables}
[responses.mass]
type = "mass"
parts = [{parts}]
[responses.energy]
type = "energy"
quantity = "internal"
[doe]
method = "lhs"
designs = {designs}
seed = {seed}
"""


def study_file(folder: Path, name: str, deck: Path, parts: list[str], designs: int, seed: int) -> Path:
    from crashlite import read_deck

    model = read_deck(deck)
    variables = []
    for i, part in enumerate(parts):
        pid = int(model.part_ids_of([part])[0])
        t = float(model.sections[model.parts[pid]["secid"]]["t1"])
        variables.append(
            f'[variables.t{i}]\npart = "{part}"\nproperty = "thickness"\nbounds = [{0.8 * t!r}, {1.2 * t!r}]\n'
        )
    p = folder / f"{name}.toml"
    p.write_text(
        STUDY.format(
            name=name,
            deck=deck.resolve(),
            directory=folder / name,
            variables="".join(variables),
            parts=", ".join(f'"{x}"' for x in parts),
            designs=designs,
            seed=seed,
        )
    )
    return p


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--full", type=Path, help="full model deck")
    ap.add_argument("--surrogate", type=Path, help="surrogate deck")
    ap.add_argument(
        "--parts",
        nargs="+",
        default=["crash box", "rail"],
        help="parts whose thickness the designs vary (names in both decks)",
    )
    ap.add_argument("--designs", type=int, default=6, help="designs per deck")
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--element-size", type=float, default=12.5, help="built-in pair: element size [mm]")
    args = ap.parse_args(argv)
    if (args.full is None) != (args.surrogate is None):
        ap.error("give both --full and --surrogate, or neither")
    from crashlite.study import load_study, run_study
    from crashlite.study.executor import DaskExecutor
    from crashlite.study.models import front_structure
    from crashlite.study.runner import Progress

    with tempfile.TemporaryDirectory(prefix="crashlite-bench-study-") as tmp:
        tmp = Path(tmp)
        if args.full is None:
            args.full = front_structure(tmp / "full.k", "full", element_size=args.element_size, rear_length=900.0)
            args.surrogate = front_structure(
                tmp / "surrogate.k", "surrogate", element_size=args.element_size, rear_length=900.0
            )
            print(
                f"built-in pair: crash box + rail, element size {args.element_size:g} mm; "
                f"full with a 900 mm shell rear frame, surrogate with its spring and mass"
            )
        decks = {"full": args.full, "surrogate": args.surrogate}
        from crashlite import read_deck

        for name, deck in decks.items():
            m = read_deck(deck)
            print(
                f"  {name:9s} {deck}: "
                + ", ".join(
                    f"{len(getattr(m, t))} {t}"
                    for t in ("shells", "solids", "beams", "discretes")
                    if len(getattr(m, t))
                )
            )
        rates = {}
        with DaskExecutor(workers=args.workers) as ex:
            print(f"{ex.describe()}; {args.designs} designs per deck")
            warm = load_study(study_file(tmp, "warmup", args.surrogate, args.parts, args.workers, 99))
            run_study(warm, executor=ex, progress=Progress(warm, quiet=True))
            for name, deck in decks.items():
                cfg = load_study(study_file(tmp, name, deck, args.parts, args.designs, 1))
                t0 = time.perf_counter()
                s = run_study(cfg, executor=ex, progress=Progress(cfg, quiet=True))
                wall = time.perf_counter() - t0
                if s.failed:
                    print(f"  {name}: {s.failed} of {s.ran} designs failed")
                from crashlite.study.storage import StudyStore

                runs = [
                    d.info.get("run_time", 0.0)
                    for d in StudyStore(cfg, readonly=True).designs()
                    if d.status == "complete"
                ]
                rates[name] = s.complete / wall * 3600.0
                print(
                    f"  {name:9s}: {s.complete} designs in {wall:6.1f} s -> {rates[name]:8.0f} designs/hour "
                    f"(solver {sum(runs) / max(len(runs), 1):.2f} s per design)"
                )
    print(f"surrogate / full designs per hour: {rates['surrogate'] / rates['full']:.2f}x")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
