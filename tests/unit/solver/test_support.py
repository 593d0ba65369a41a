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


def test_a_card_read_verbatim_is_never_taken_as_run(tmp_path):
    # each name starts with a prefix the solver runs, but the reader does not type it (an option or variant
    # crashlite does not read): accepting it on the prefix would drop a constraint, a move or a velocity silently
    extra = (
        "*BOUNDARY_SPC_NODE_FOO\n1,0,1,1,1\n"
        "*PART_ADAPTIVE_FAILURE\n1,100.0\n"
        "*INITIAL_VELOCITY_GENERATION_START_TIME\n1,1000.0\n"
        "*LOAD_BODY_PARTS\n1\n"
    )
    p = tmp_path / "d.k"
    p.write_text(DECK.format(extra=extra))
    with pytest.raises(SetupError) as e:
        build(read_deck(p))
    assert [(pr.keyword, pr.line) for pr in e.value.problems] == [
        ("BOUNDARY_SPC_NODE_FOO", 21),
        ("PART_ADAPTIVE_FAILURE", 23),
        ("INITIAL_VELOCITY_GENERATION_START_TIME", 25),
        ("LOAD_BODY_PARTS", 27),
    ]


def test_an_unread_definition_is_refused_only_where_a_part_names_it(tmp_path):
    unused = "*MAT_MODIFIED_PIECEWISE_LINEAR_PLASTICITY_TITLE\nnot used\n99,7.85e-9,210000.0,0.3\n*DEFINE_BOX\n5,0,1,0,1,0,1\n"
    p = tmp_path / "d.k"
    p.write_text(DECK.format(extra=unused))
    model = read_deck(p)
    sim = build(model)  # runs: nothing names material 99 or box 5
    said = [w for w in sim.warnings if "passed over" in w.message]
    assert {w.keyword for w in said} >= {"MAT_MODIFIED_PIECEWISE_LINEAR_PLASTICITY_TITLE", "DEFINE_BOX"}
    used = DECK.replace("1,1,1\n*SECTION_DISCRETE", "1,1,99\n*SECTION_DISCRETE")
    p.write_text(used.format(extra=unused))
    with pytest.raises(SetupError) as e:
        build(read_deck(p))
    msg = [pr.message for pr in e.value.problems if pr.keyword.startswith("MAT_MODIFIED")]
    assert msg and "part(s) 1 use it" in msg[0]


def test_an_spc_with_birth_and_death_holds_over_the_whole_run_or_is_refused(tmp_path):
    # DEATH at the end time (or 0: 1e20) and BIRTH 0 is a plain SPC; a window inside the run is refused by name
    spc = "*BOUNDARY_SPC_NODE_BIRTH_DEATH_ID\n3,ends\n2,0,1,1,0,0,0,0\n0.0,{death}\n"
    p = tmp_path / "d.k"
    for death in ("0.01", "0.0"):
        p.write_text(DECK.format(extra=spc.format(death=death)))
        sim = build(read_deck(p))
        assert sim.fixed.tolist() == [[False, False, False], [True, True, False]]
    p.write_text(DECK.format(extra=spc.format(death="0.004")))
    with pytest.raises(SetupError) as e:
        build(read_deck(p))
    assert [(pr.keyword, pr.field) for pr in e.value.problems] == [("BOUNDARY_SPC_NODE_BIRTH_DEATH_ID", "DEATH")]
    assert "DEATH = 0.004 lies inside the run" in e.value.problems[0].message
