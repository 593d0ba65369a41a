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


def test_bulk_viscosity_zeros_read_as_lsdyna_defaults_and_shell_type_is_said(tmp_path):
    """*CONTROL_BULK_VISCOSITY: Q1 = Q2 = 0 read as LS-DYNA's 1.5 and 0.06
    (blank and 0 are one value in a fixed field: a tiny value turns it off);
    TYPE −2 (shells too) runs with a warning that crashlite's shells take none."""
    from crashlite.solver.solids import _bulk_viscosity

    deck = _with(tmp_path, "*CONTROL_BULK_VISCOSITY\n       0.0       0.0        -2\n")
    model = read_deck(deck)
    assert _bulk_viscosity(model) == (1.5, 0.06)
    (w,) = [w for w in build(model).warnings if w.keyword == "CONTROL_BULK_VISCOSITY"]
    assert w.field == "TYPE" and "TYPE -2" in w.message and "solids only" in w.message
    assert _bulk_viscosity(read_deck(_with(tmp_path, "*CONTROL_BULK_VISCOSITY\n1e-9,2e-9\n"))) == (1e-9, 2e-9)
    assert not [
        w for w in build(read_deck(_with(tmp_path, "*CONTROL_BULK_VISCOSITY\n1.2\n"))).warnings if "BULK" in w.keyword
    ]
