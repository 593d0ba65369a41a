"""crashlite against LS-DYNA on public decks, run unchanged (cases.py).

The decks are not part of crashlite: ``tests/parity/fetch.sh`` brings them.
Without them these tests do not run (the reason says how to get them); the
reading and set-up of a deck is checked quickly, the full runs are slow.

Bounds (issue 29, per case in cases.py): internal energy, final
displacements and cycles within 5 % of LS-DYNA's, peak wall forces within
10 %, sliding energy never below −1 % of the internal energy, energy
balance within 2 %.
"""

from __future__ import annotations

import numpy as np
import pytest
from cases import available, cases, field_deviation, main_deck, measured, repo_dir

from crashlite import read_deck
from crashlite.solver import run
from crashlite.solver.setup import build

FETCH = "the parity decks are not redistributed: run tests/parity/fetch.sh (network) to run these"
CASES = [pytest.param(c, id=c.name, marks=pytest.mark.skipif(not available(c), reason=FETCH)) for c in cases(lhs=0)]


@pytest.mark.parametrize("case", CASES)
def test_the_deck_reads_and_sets_up_unchanged(tmp_path, case):
    model = read_deck(main_deck(case, tmp_path))
    sim = build(model)  # no refusal (a SetupError would fail the test)
    # warned and passed over: sensors nothing uses, output requests crashlite does not write, and the
    # cards a case expects (each warning says what crashlite runs in its place); initial penetrations
    # moved out, as LS-DYNA moves them, are reported
    expected = ("SENSOR", "DATABASE_", "CONTROL_MPP") + case.warned
    warned = model.warnings + sim.warnings
    assert not [w for w in warned if not w.keyword.startswith(expected) and "moved out" not in w.message]


@pytest.mark.slow
@pytest.mark.parametrize("case", CASES)
def test_lsdyna_answers(tmp_path, case):
    res = run(main_deck(case, tmp_path))
    got = measured(case, res)
    missed = []
    for q, bound in case.bounds.items():
        ref = case.reference[q]
        if abs(got[q] / ref - 1.0) > bound:
            missed.append(f"{q}: crashlite {got[q]:.6g}, LS-DYNA {ref:.6g}")
    assert res.sliding.min() >= -0.01 * res.internal.max()
    total = res.kinetic + res.internal + res.sliding + res.hourglass
    supplied = total[0] + res.external
    # against the largest energy supplied: a model that starts at rest has none at first
    assert np.abs(total + res.wall - supplied).max() <= 0.02 * np.abs(supplied).max()
    _verdict(case, missed)


def _verdict(case, missed: list[str]) -> None:
    """Every bound met; a miss the case documents (``known``) is an expected
    failure with its reason, any other miss fails."""
    unknown = [m for m in missed if m.split(":")[0] not in case.known]
    assert not unknown, "; ".join(unknown)
    if missed:
        pytest.xfail("; ".join(f"{m} ({case.known[m.split(':')[0]]})" for m in missed))


@pytest.mark.slow
@pytest.mark.parametrize("case", [c for c in CASES if c.values[0].d3plot])
def test_lsdyna_fields(tmp_path, case):
    """crashlite's d3plot against LS-DYNA's, node by node and shell by shell
    (both read back through lasso-python): the whole field, not only the
    recorded nodes, and the order of the shell layers LS-DYNA writes."""
    run(main_deck(case, tmp_path), out=tmp_path / "out")
    dev = field_deviation(repo_dir(case) / case.d3plot, tmp_path / "out")
    _verdict(case, [f"{q}: {dev[q]:.3g} % of the largest value" for q, b in case.field_bounds.items() if dev[q] > b])
