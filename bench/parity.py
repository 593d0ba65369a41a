"""crashlite against LS-DYNA on the public parity decks (tests/parity).

Runs every case whose deck is present (tests/parity/fetch.sh brings them),
unchanged, and prints per case crashlite's figures, LS-DYNA's, and their
ratio: peak pole force, final displacement of the body's rear centre, final
rigid-body velocity of the body, final internal energy; then crashlite's
kinetic energy, sliding energy (its lowest against the internal energy),
energy balance, cycles and run time; where LS-DYNA's d3plot is beside the
deck, the whole-field deviation of crashlite's d3plot from it. Over the
designs of the small car's Latin hypercube it ends with how crashlite
follows LS-DYNA from design to design: per quantity the ratios' median and
range, and the Pearson and Spearman (rank) correlation of crashlite's
values with LS-DYNA's (what a design study needs: the same trends and the
same order of designs). Usage::

    python bench/parity.py [--lhs 5] [--only lhs] [--out /tmp/crashlite-parity]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "parity"))

from cases import available, cases, field_deviation, main_deck, measured, repo_dir  # noqa: E402

from crashlite.solver import run  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lhs", type=int, default=5, help="designs of the study's Latin hypercube to run too")
    ap.add_argument("--only", default="", help="run the cases whose name contains this")
    ap.add_argument("--out", type=Path, default=Path("/tmp/crashlite-parity"))
    args = ap.parse_args(argv)
    todo = [c for c in cases(args.lhs) if available(c) and args.only in c.name]
    if not todo:
        print("no parity deck present: run tests/parity/fetch.sh first")
        return 1
    print(f"{'case':<20} {'quantity':<6} {'crashlite':>13} {'LS-DYNA':>13} {'ratio':>7}")
    designs: dict[str, list] = {}  # quantity -> [(crashlite, LS-DYNA)] over the Latin hypercube's designs
    for case in todo:
        t0 = time.perf_counter()
        res = run(main_deck(case, args.out / case.name), out=args.out / case.name)
        wall = time.perf_counter() - t0
        got = measured(case, res)
        for q, ref in case.reference.items():
            spread = f"  (LS-DYNA's own scatter {100 * case.spread[q]:.2g} %)" if q in case.spread else ""
            print(f"{case.name:<20} {q:<6} {got[q]:>13.6g} {ref:>13.6g} {got[q] / ref:>7.3f}{spread}")
            if "-lhs" in case.name:
                designs.setdefault(q, []).append((got[q], ref))
        if case.d3plot:
            dev = field_deviation(repo_dir(case) / case.d3plot, args.out / case.name)
            print(
                f"{case.name:<20} d3plot against LS-DYNA's: displacement field {dev['u_field']:.3f} % of the "
                f"largest displacement (every node, every state), shell stresses {dev['stress_field']:.3f} % "
                "of the largest stress (every shell and layer, last state)"
            )
        total = res.kinetic + res.internal + res.sliding + res.hourglass + res.wall
        supplied = res.kinetic[0] + res.internal[0] + res.external
        print(
            f"{case.name:<20} kinetic energy at the end {res.kinetic[-1]:.4g}, hourglass {res.hourglass[-1]:.4g}, "
            f"sliding lowest {res.sliding.min():.4g} ({100 * res.sliding.min() / res.internal.max():.2f} % of "
            f"the internal energy), end {res.sliding[-1]:.4g}; energy balance "
            f"{np.abs(total - supplied).max() / np.abs(supplied).max() * 100:.2f} %; {res.cycles} cycles, {wall:.0f} s"
        )
        for w in res.info.get("warnings", []):
            print(f"{'':<20} warning: {w}")
    if len(next(iter(designs.values()), [])) >= 3:
        trends(designs)
    return 0


def trends(designs: dict) -> None:
    """How crashlite follows LS-DYNA over the Latin hypercube's designs."""
    from scipy.stats import pearsonr, spearmanr

    n = len(next(iter(designs.values())))
    print(f"\nover {n} designs of the Latin hypercube (crashlite / LS-DYNA):")
    print(f"{'quantity':<8} {'median':>7} {'min':>7} {'max':>7} {'Pearson':>8} {'Spearman':>9}  LS-DYNA's range")
    for q, pairs in designs.items():
        got, ref = np.array(pairs).T
        r = got / ref
        print(
            f"{q:<8} {np.median(r):>7.3f} {r.min():>7.3f} {r.max():>7.3f} {pearsonr(got, ref)[0]:>8.3f} "
            f"{spearmanr(got, ref)[0]:>9.3f}  {ref.min():.4g} .. {ref.max():.4g}"
        )


if __name__ == "__main__":
    raise SystemExit(main())
