"""*PART_MOVE, *INITIAL_VELOCITY_RIGID_BODY and *ELEMENT_MASS_PART(_SET)
typed: the hat-profile deck's fixed columns (PID 8, XMOV..ZMOV 16, CID and
IFSET 8; ten-wide velocity fields; PID 8, ADDMASS and FINMASS 16, LCID 8),
blank fields at LS-DYNA's defaults, several rows under one keyword, and the
writer's round trip in every format."""

from __future__ import annotations

import pytest

from crashlite import read_deck
from crashlite.keyword.schema import RawKeyword
from crashlite.keyword.writer import write_deck

_HEAD = """*KEYWORD
*NODE
1,0,0,0
*SECTION_SHELL
1
1.0
*MAT_RIGID
1,7.85e-9,210000.0,0.3
*PART
impactor
9,1,1
*PART
other
4,1,1
*SET_PART_LIST
3
4,9
"""


def _read(tmp_path, body: str):
    path = tmp_path / "d.k"
    path.write_text(_HEAD + body + "*END\n")
    return read_deck(path)


def _row(rec, k=0) -> dict:
    return {f: rec.rows[f][k].item() for f in rec.rows}


def test_the_hat_decks_cards(tmp_path):
    model = _read(
        tmp_path,
        "*PART_MOVE\n       9             0.0             0.0            30.0       0       0\n"
        "*INITIAL_VELOCITY_RIGID_BODY\n         9       0.0       0.0     -20.0       0.0       0.0       0.0         0\n"
        "*ELEMENT_MASS_PART\n       9             0.0             5.0       0\n",
    )
    assert not [k for k in model.keywords if isinstance(k, RawKeyword)]
    (move,), (vel,), (mass,) = (
        model.find("PART_MOVE"),
        model.find("INITIAL_VELOCITY_RIGID_BODY"),
        model.find("ELEMENT_MASS_PART"),
    )
    assert _row(move) == {"pid": 9, "xmov": 0.0, "ymov": 0.0, "zmov": 30.0, "cid": 0, "ifset": 0}
    assert _row(vel) == {"pid": 9, "vx": 0.0, "vy": 0.0, "vz": -20.0, "vxr": 0.0, "vyr": 0.0, "vzr": 0.0, "lcid": 0}
    assert _row(mass) == {"pid": 9, "addmass": 0.0, "finmass": 5.0, "lcid": 0}


def test_blank_fields_take_the_defaults(tmp_path):
    model = _read(
        tmp_path,
        "*PART_MOVE\n9\n3,,2.5,,,1\n*INITIAL_VELOCITY_RIGID_BODY\n9\n4,,,,,,1.5\n"
        "*ELEMENT_MASS_PART\n9,0.25\n*ELEMENT_MASS_PART_SET\n3,,1.0\n",
    )
    move = model.find("PART_MOVE")[0]
    assert _row(move, 0) == {"pid": 9, "xmov": 0.0, "ymov": 0.0, "zmov": 0.0, "cid": 0, "ifset": 0}
    assert _row(move, 1) == {"pid": 3, "xmov": 0.0, "ymov": 2.5, "zmov": 0.0, "cid": 0, "ifset": 1}
    vel = model.find("INITIAL_VELOCITY_RIGID_BODY")[0]
    assert len(vel.rows["pid"]) == 2 and _row(vel, 1)["vzr"] == 1.5 and _row(vel, 0)["lcid"] == 0
    part, pset = model.find("ELEMENT_MASS_PART")
    assert _row(part) == {"pid": 9, "addmass": 0.25, "finmass": 0.0, "lcid": 0}
    assert pset.name == "ELEMENT_MASS_PART_SET" and _row(pset) == {"pid": 3, "addmass": 0.0, "finmass": 1.0, "lcid": 0}


def test_a_part_set_of_part_move_is_not_read_as_a_part(tmp_path):
    """IFSET 1: PID 3 is a part set, not an undefined part."""
    model = _read(tmp_path, "*PART_MOVE\n3,1.0,,,,1\n")
    assert _row(model.find("PART_MOVE")[0])["ifset"] == 1


@pytest.mark.parametrize("fmt", ["fixed", "long", "free"])
def test_round_trip(tmp_path, fmt):
    model = _read(
        tmp_path,
        "*DEFINE_CURVE\n5\n0.0,1.0\n1.0,2.0\n*DEFINE_COORDINATE_VECTOR\n7,0,1,0,1,0,0\n"
        "*PART_MOVE\n9,1.5,-2.25,30.0,7,0\n3,0.125,,,,1\n"
        "*INITIAL_VELOCITY_RIGID_BODY\n9,1.0,2.0,-20.0,0.5,0.25,-0.75,7\n"
        "*ELEMENT_MASS_PART\n9,0.5,5.0,5\n*ELEMENT_MASS_PART_SET\n3,1.25\n",
    )
    write_deck(model, tmp_path / "back.k", fmt=fmt)
    back = read_deck(tmp_path / "back.k")
    for kw in ("PART_MOVE", "INITIAL_VELOCITY_RIGID_BODY", "ELEMENT_MASS_PART"):
        assert model.find(kw) == back.find(kw) and model.find(kw)
    assert "*ELEMENT_MASS_PART_SET\n" in (tmp_path / "back.k").read_text()
