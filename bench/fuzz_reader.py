"""Fuzz the keyword reader: N mutated decks, counts by outcome (issue 34).

    python bench/fuzz_reader.py [N] [--seed S] [--limit SECONDS] [--show K]

Each case is a mutated copy of a bundled example or of a small typed deck of
one keyword family (crashlite.keyword.fuzz), read with read_deck in this
process under a per-case time limit. Outcomes: ``read`` (accepted),
``DeckError`` (refused with the problems listed), ``traceback`` (any other
exception: a bug) and ``hang`` (past the limit: a bug). The first K failing
cases are printed with their (seed, index), which fuzz.case() reproduces.
Exit code 1 when any case crashed or hung.
"""

from __future__ import annotations

import argparse
import collections
import sys
import tempfile
import time
from pathlib import Path

from crashlite.keyword import fuzz


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("n", nargs="?", type=int, default=1000, help="number of cases (1000)")
    ap.add_argument("--seed", type=int, default=34, help="run seed (34, as the suite's test)")
    ap.add_argument("--limit", type=float, default=20.0, help="seconds per case before it counts as a hang")
    ap.add_argument("--show", type=int, default=5, help="failing cases to print")
    a = ap.parse_args(argv)
    pool = fuzz.seeds()
    counts = collections.Counter({o: 0 for o in fuzz.OUTCOMES})
    by_mutation = collections.defaultdict(collections.Counter)
    failures = []
    slowest = (0.0, None)
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(a.n):
            files, muts = fuzz.case(a.seed, i, pool)
            t = time.perf_counter()
            outcome, detail = fuzz.run_case(files, a.limit, Path(tmp))
            dt = time.perf_counter() - t
            slowest = max(slowest, (dt, i), key=lambda x: x[0])
            counts[outcome] += 1
            for m in set(muts):
                by_mutation[m][outcome] += 1
            if outcome in ("traceback", "hang"):
                failures.append((i, muts, outcome, detail))
            if (i + 1) % 1000 == 0:
                print(f"  {i + 1} cases, {dict(counts)}", file=sys.stderr, flush=True)
    wall = time.perf_counter() - t0
    print(
        f"{a.n} fuzzed decks, seed {a.seed}, {wall:.1f} s ({1000 * wall / max(a.n, 1):.1f} ms a case; "
        f"slowest case {slowest[1]}: {slowest[0]:.2f} s)"
    )
    for o in fuzz.OUTCOMES:
        print(f"  {o:10s} {counts[o]:7d}")
    print("by mutation (a case may hold several):")
    for m in sorted(by_mutation):
        c = by_mutation[m]
        print(f"  {m:16s} " + "  ".join(f"{o} {c[o]}" for o in fuzz.OUTCOMES if c[o]))
    for i, muts, outcome, detail in failures[: a.show]:
        print(f"\ncase ({a.seed}, {i}) {muts}: {outcome}\n{detail}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
