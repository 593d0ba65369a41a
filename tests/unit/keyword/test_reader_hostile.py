"""Careless and hostile decks (issues 34 and 35): each ends in one DeckError
naming file, line, keyword and field, or reads as LS-DYNA reads it; never a
traceback, a hang or a silently wrong model."""

import numpy as np
import pytest

from crashlite import DeckError, read_deck
from crashlite.model.mesh import index_map


def _problems(path):
    with pytest.raises(DeckError) as e:
        read_deck(path)
    return e.value.problems


def _text(path):
    return "\n".join(str(p) for p in _problems(path))


_SPRING = """\
*KEYWORD
*NODE
       1             0.0             0.0             0.0
       2             1.0             0.0             0.0
*ELEMENT_DISCRETE
       1       1       1       2
*PART
spring
         1         1         1
*SECTION_DISCRETE
         1         0
*MAT_SPRING_ELASTIC
         1    1000.0
*END
"""


# ---------------------------------------------------------------- crashes found by the fuzzer

def test_unreadable_definition_id_is_reported_not_a_traceback(deck):
    # the PART's PID unreadable: it used to enter model.parts under None and
    # crash the reference check (TypeError in references.py)
    p = deck("m.k", _SPRING.replace("         1         1         1\n", "       abc         1         1\n"))
    probs = _problems(p)
    assert any(x.keyword == "PART" and x.field == "PID" and "'abc'" in x.message for x in probs)


def test_blank_definition_id_is_an_error_naming_the_field(deck):
    p = deck("m.k", _SPRING.replace("*MAT_SPRING_ELASTIC\n         1", "*MAT_SPRING_ELASTIC\n          "))
    probs = _problems(p)
    assert any(x.keyword == "MAT_SPRING_ELASTIC" and x.field == "MID" and "blank" in x.message
               and x.line == 13 for x in probs)


def test_index_map_of_an_empty_query():
    # (0,) queries used to fail to reshape (ValueError in mesh.py)
    look = index_map(np.array([3, 1, 2]))
    assert look(np.zeros(0, np.int64)).shape == (0,)
    assert look(np.zeros((0, 4), np.int64)).shape == (0, 4)
    assert look(np.zeros((0, 2, 3), np.int64)).shape == (0, 2, 3)
    assert look(np.array(2)).shape == ()


def test_mass_block_without_rows_reads(deck):
    p = deck("m.k", _SPRING.replace("*PART", "*ELEMENT_MASS\n*PART"))
    m = read_deck(p)
    assert len(m.masses) == 0


def test_include_transform_offset_past_64_bits(deck):
    deck("part.k", "*NODE\n       1             0.0             0.0             0.0\n")
    p = deck("m.k", "*KEYWORD\n*INCLUDE_TRANSFORM\npart.k\n1e300\n*END\n")
    probs = _problems(p)
    assert any(x.keyword == "INCLUDE_TRANSFORM" and x.field == "IDNOFF" and "64-bit" in x.message
               for x in probs)


def test_include_transform_offset_taking_an_id_past_64_bits(deck):
    deck("part.k", "*NODE\n9000000000000000000,0.0,0.0,0.0\n")
    p = deck("m.k", "*KEYWORD\n*INCLUDE_TRANSFORM\npart.k\n500000000000000000,,,,,,\n*END\n")
    text = _text(p)
    assert "part.k:1: *NODE, field NID: ID 9000000000000000000 plus the *INCLUDE_TRANSFORM offset" in text


def test_include_transform_fractional_offset_is_an_error(deck):
    deck("part.k", "*NODE\n       1             0.0             0.0             0.0\n")
    p = deck("m.k", "*KEYWORD\n*INCLUDE_TRANSFORM\npart.k\n       1.5\n*END\n")
    assert "*INCLUDE_TRANSFORM, field IDNOFF: expected an integer, got '1.5'" in _text(p)
