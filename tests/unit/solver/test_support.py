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
    p = tmp_path / "d.k"
    p.write_text(DECK.format(extra="*DAMPING_GLOBAL\n0,0.1\n*CONSTRAINED_SPOTWELD\n1,1,2\n"))
    with pytest.raises(SetupError) as e:
        build(read_deck(p))
    msgs = [(pr.keyword, pr.line) for pr in e.value.problems]
    assert ("DAMPING_GLOBAL", 21) in msgs and ("CONSTRAINED_SPOTWELD", 23) in msgs
    assert len(msgs) == 2  # output requests and the cards it runs are not listed


def test_output_requests_are_accepted(tmp_path):
    p = tmp_path / "d.k"
    p.write_text(DECK.format(extra=""))
    assert build(read_deck(p)).end_time == 0.01
