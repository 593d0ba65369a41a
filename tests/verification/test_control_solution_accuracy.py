"""*CONTROL_SOLUTION and *CONTROL_ACCURACY: run as crashlite runs with one
warning saying what crashlite does instead; a thermal analysis (SOLN ≠ 0)
is refused naming the card and field. The pulse example (one mass on a
spring, its closed-form period) is run with each card added."""

from importlib import resources

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.solver import run
from crashlite.solver.setup import SetupError, build

PULSE = (resources.files("crashlite") / "examples" / "pulse" / "pulse.k").read_text()


def _with(tmp_path, card: str) -> str:
    p = tmp_path / "pulse.k"
    p.write_text(PULSE.replace("*END", card + "*END", 1))
    return str(p)


@pytest.mark.parametrize(
    "card,name",
    [
        ("*CONTROL_SOLUTION\n         0         0         1      1001\n", "CONTROL_SOLUTION"),
        ("*CONTROL_ACCURACY\n         1         2\n", "CONTROL_ACCURACY"),
    ],
)
def test_accuracy_and_structural_solution_run_with_one_warning(tmp_path, card, name):
    plain = run(_with(tmp_path, ""))
    deck = _with(tmp_path, card)
    (w,) = [w for w in build(read_deck(deck)).warnings if w.keyword == name]
    assert w.file == deck and w.line == PULSE.count("\n", 0, PULSE.index("*END")) + 1
    res = run(deck)  # the same answer as without the card
    np.testing.assert_allclose(res.kinetic, plain.kinetic, rtol=0, atol=1e-12 * plain.kinetic.max())


def test_a_thermal_solution_is_refused_naming_the_field(tmp_path):
    deck = _with(tmp_path, "*CONTROL_SOLUTION\n         2\n")
    with pytest.raises(SetupError) as e:
        build(read_deck(deck))
    (p,) = [p for p in e.value.problems if p.keyword == "CONTROL_SOLUTION"]
    assert p.file == deck and "SOLN 2" in p.message and "thermal" in p.message
