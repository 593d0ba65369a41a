"""Fuzzing the reader (issue 34): mutated copies of the bundled decks and of
small typed decks of each keyword family either read or end in DeckError;
never a traceback and never a hang.

The normal run reads CRASHLITE_FUZZ_CASES cases (default 400) of the fixed
seed CRASHLITE_FUZZ_SEED (default 34); a longer run for benchmarks:
``CRASHLITE_FUZZ_CASES=10000 pytest tests/unit/keyword/test_fuzz.py`` or
``python bench/fuzz_reader.py 10000``. A failure names the case, so that
``crashlite.keyword.fuzz.case(seed, index)`` reproduces it.
"""

import os
import random

from crashlite.keyword import fuzz

CASES = int(os.environ.get("CRASHLITE_FUZZ_CASES", "400"))
SEED = int(os.environ.get("CRASHLITE_FUZZ_SEED", "34"))
LIMIT_S = 20.0  # per case: generous, only a hang passes it


def test_seeds_read_cleanly():
    # mutations start from decks that read: an error is then the mutation's
    for files in fuzz.seeds():
        assert fuzz.run_case(files, LIMIT_S) == ("read", ""), sorted(files)


def test_mutations_are_reproducible():
    a = fuzz.case(SEED, 7)
    b = fuzz.case(SEED, 7)
    assert a == b


def test_every_mutation_applies():
    pool = fuzz.seeds()
    for name, (fn, _) in fuzz.MUTATIONS.items():
        rng = random.Random(name)
        files = dict(pool[3])
        fn(rng, files, "main.k")
        assert isinstance(files["main.k"], bytes), name


def test_fuzzed_decks_read_or_raise_deck_error(tmp_path):
    pool = fuzz.seeds()
    bad = []
    counts = dict.fromkeys(fuzz.OUTCOMES, 0)
    for i in range(CASES):
        files, muts = fuzz.case(SEED, i, pool)
        outcome, detail = fuzz.run_case(files, LIMIT_S, tmp_path)
        counts[outcome] += 1
        if outcome in ("traceback", "hang"):
            bad.append(f"case ({SEED}, {i}) {muts}: {outcome}\n{detail}")
    assert not bad, f"{len(bad)} of {CASES} fuzzed decks crashed or hung ({counts}):\n" + "\n".join(bad[:3])
    # the mix stays meaningful: most mutations are caught, some decks still read
    assert counts["DeckError"] > CASES // 3 and counts["read"] > CASES // 20, counts
