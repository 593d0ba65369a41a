"""Cards the solver does not run are refused before the first cycle."""

import pytest

from crashlite import read_deck
from crashlite.solver.setup import SetupError, build

DECK = """*KEYWORD
*NODE
1,0,0,0
2,10,0,0
*ELEMENT_MASS
1,1,0.1
2,2,0.1
*ELEMENT_DISCRETE
1,1,1,2
*PART
s
1,1,1
*SECTION_DISCRETE
1,0
*MAT_SPRING_ELASTIC
1,10.0
*DATABASE_GLSTAT
1e-3
*CONTROL_OUTPUT
1
{extra}*CONTROL_TERMINATION
0.01
*END
"""


def test_every_unrun_card_is_listed_with_its_line(tmp_path):
    # neither card is in support.RUN (spot welds are: they are no example of an unrun card)
    p = tmp_path / "d.k"
    p.write_text(DECK.format(extra="*DAMPING_GLOBAL\n0,0.1\n*CONSTRAINED_JOINT_SPHERICAL\n1,2\n"))
    with pytest.raises(SetupError) as e:
        build(read_deck(p))
    msgs = [(pr.keyword, pr.line) for pr in e.value.problems]
    assert msgs == [("DAMPING_GLOBAL", 21), ("CONSTRAINED_JOINT_SPHERICAL", 23)]  # nothing else listed
    assert all("is not run by the crashlite solver" in pr.message for pr in e.value.problems)


def test_run_and_unrun_cards_are_told_apart():
    from crashlite.solver.support import NEUTRAL, RUN

    known = RUN + NEUTRAL
    for card in (
        "CONSTRAINED_SPOTWELD",
        "CONSTRAINED_GENERALIZED_WELD_SPOT",
        "CONTACT_TIED_NODES_TO_SURFACE",
        "LOAD_NODE_POINT",
        "CONTACT_AUTOMATIC_SINGLE_SURFACE",
        "DATABASE_HISTORY_NODE",
    ):
        assert card.startswith(known), card
    for card in (
        "DAMPING_GLOBAL",
        "CONSTRAINED_JOINT_SPHERICAL",
        "CONTACT_ERODING_SINGLE_SURFACE",
        "INITIAL_STRESS_SHELL",
        "LOAD_SEGMENT",
    ):
        assert not card.startswith(known), card


def test_output_requests_are_accepted(tmp_path):
    p = tmp_path / "d.k"
    p.write_text(DECK.format(extra=""))
    assert build(read_deck(p)).end_time == 0.01


def test_mass_scaling_of_solids_is_refused_not_ignored(tmp_path):
    solid = """*NODE
11,0,0,0
12,1,0,0
13,1,1,0
14,0,1,0
15,0,0,1
16,1,0,1
17,1,1,1
18,0,1,1
*ELEMENT_SOLID
5,2,11,12,13,14,15,16,17,18
*PART
block
2,2,2
*SECTION_SOLID
2,1
*MAT_ELASTIC
2,7.85e-9,210000.0,0.3
*CONTROL_TIMESTEP
0.0,0.9,0,0.0,-1e-6
"""
    p = tmp_path / "d.k"
    p.write_text(DECK.format(extra=solid))
    with pytest.raises(SetupError) as e:
        build(read_deck(p))
    assert [pr.field for pr in e.value.problems] == ["DT2MS"]


def test_a_set_the_solver_cannot_resolve_is_a_setup_error(tmp_path):
    p = tmp_path / "d.k"
    p.write_text(DECK.format(extra="*SET_NODE_GENERAL\n77\nALL\n*INITIAL_VELOCITY\n77\n1.0,0,0\n"))
    with pytest.raises(SetupError, match="77"):
        build(read_deck(p))
