"""Bad input: every problem named with file, line, keyword and field, all at once."""

import pytest

from crashlite import DeckError, read_deck
from crashlite.cli import main


def test_all_problems_reported_together(deck):
    p = deck(
        "bad.k",
        """
        *KEYWORD
        *NODE
               1             0.0             0.0             0.0
               1             1.0             0.0             0.0
               2             1.0           abc             0.0
        *ELEMENT_SHELL
               1       7       1       2      99       1
        *PART
        plate
                 7         3         4
        *SECTION_SHELL
                 3         2
             &nope
        *INCLUDE
        missing.k
        *END
        """,
    )
    with pytest.raises(DeckError) as e:
        read_deck(p)
    msgs = [str(x) for x in e.value.problems]
    text = "\n".join(msgs)
    assert "bad.k:5: *NODE, field Y: expected a real number, got 'abc'" in text
    assert "node ID 1 defined more than once" in text
    assert "N3" in text and "node 99" in text
    assert "bad.k:10: *PART, field MID: material 4 is not defined" in text
    assert "bad.k:13: *SECTION_SHELL, field T1: undefined parameter '&nope'" in text
    assert "missing.k" in text and "not found" in text


def test_missing_card_and_bad_integer(deck):
    p = deck(
        "bad2.k",
        """
        *KEYWORD
        *MAT_ELASTIC
               1.5     1e-09    2000.0       0.3
        *RIGIDWALL_GEOMETRIC_CYLINDER
                 0
                 0         0         0         0         0         1
        *END
        """,
    )
    with pytest.raises(DeckError) as e:
        read_deck(p)
    text = str(e.value)
    assert "bad2.k:3: *MAT_ELASTIC, field MID: expected an integer, got '1.5'" in text
    # a missing card is a blank one (LS-DYNA), but RADCYL has no default
    assert "*RIGIDWALL_GEOMETRIC_CYLINDER, field RADCYL" in text and "no default" in text


def test_cli_reports_without_traceback(deck, capsys):
    p = deck("bad3.k", "*KEYWORD\n*NODE\n       1     x\n*END\n")
    assert main(["info", str(p)]) == 2
    err = capsys.readouterr().err
    assert "bad3.k:3: *NODE, field X" in err and "Traceback" not in err


def test_missing_deck_file(tmp_path):
    with pytest.raises(DeckError, match="not found"):
        read_deck(tmp_path / "nope.k")
