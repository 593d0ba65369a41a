"""crashlite against LS-DYNA on the public parity decks (tests/parity).

Runs every case whose deck is present (tests/parity/fetch.sh brings them),
unchanged, and prints per case crashlite's figures, LS-DYNA's, and their
ratio: peak pole force, final displacement of the body's rear centre, final
rigid-body velocity of the body, final internal energy; then crashlite's
kinetic energy, sliding energy (its lowest against the internal energy),
energy balance, cycles and run time. Usage::

    python bench/parity.py [--lhs 5] [--out /tmp/crashlite-parity]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "parity"))

from cases import available, cases, main_deck, measured  # noqa: E402

from crashlite.solver import run  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lhs", type=int, default=5, help="designs of the study's Latin hypercube to run too")
    ap.add_argument("--out", type=Path, default=Path("/tmp/crashlite-parity"))
    args = ap.parse_args(argv)
    todo = [c for c in cases(args.lhs) if available(c)]
    if not todo:
        print("no parity deck present: run tests/parity/fetch.sh first")
        return 1
    print(f"{'case':<20} {'quantity':<6} {'crashlite':>13} {'LS-DYNA':>13} {'ratio':>7}")
    for case in todo:
        t0 = time.perf_counter()
        res = run(main_deck(case, args.out / case.name), out=args.out / case.name)
        wall = time.perf_counter() - t0
        got = measured(case, res)
        for q, ref in case.reference.items():
            spread = f"  (LS-DYNA's own scatter {100 * case.spread[q]:.2g} %)" if q in case.spread else ""
            print(f"{case.name:<20} {q:<6} {got[q]:>13.6g} {ref:>13.6g} {got[q] / ref:>7.3f}{spread}")
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
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
