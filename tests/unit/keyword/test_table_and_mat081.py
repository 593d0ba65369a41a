"""*DEFINE_TABLE and *MAT_PLASTICITY_WITH_DAMAGE (*MAT_081) read as LS-DYNA
reads them: the fixed columns (VALUE and LCID 20 wide), the manual's
defaults for blank and zero fields, references to a table from LCSS, the
writer's round trip."""

import pytest

from crashlite.keyword.errors import DeckError
from crashlite.keyword.reader import read_deck
from crashlite.keyword.schema import Record, lookup
from crashlite.keyword.writer import write_deck

# the hat profile's cards (kg, mm, ms, GPa): MID 81 in columns 1-10, RO 7.85e-6 in 11-20
HAT = """*KEYWORD
*MAT_PLASTICITY_WITH_DAMAGE
        817.85000E-6      70.0       0.3       0.0       0.0       0.5       0.0
       0.0       0.0       110         0       1.5       0.0         0         0
       0.0       0.0       0.0       0.0       0.0       0.0       0.0       0.0
       0.0       0.0       0.0       0.0       0.0       0.0       0.0       0.0
*DEFINE_TABLE
       110
                 0.0       111
                 5.0       112
*DEFINE_CURVE
       111         0       1.0       1.0       0.0       0.0         0         0
                 0.0                 0.4
                 0.1                0.73
*DEFINE_CURVE
       112         0       1.0       1.2       0.0       0.0         0         0
                 0.0                 0.4
                 0.1                0.73
*END
"""


def _read(tmp_path, text, name="d.k"):
    p = tmp_path / name
    p.write_text(text)
    return read_deck(p)


def _table(model, tbid=110) -> Record:
    (t,) = [k for k in model.keywords if isinstance(k, Record) and k.keyword == "DEFINE_TABLE" and k.id == tbid]
    return t


def test_the_hat_cards_read_in_their_columns(tmp_path):
    m = _read(tmp_path, HAT)
    mat = m.materials[81]
    assert lookup("MAT_081")[0] is mat.spec and mat.keyword == "MAT_PLASTICITY_WITH_DAMAGE"
    want = dict(ro=7.85e-6, e=70.0, pr=0.3, sigy=0.0, etan=0.0, eppf=0.5, tdel=0.0, c=0.0, p=0.0)
    want.update(lcss=110, lcsr=0, eppfr=1.5, vp=0.0, lcdm=0, numint=0)
    for f, v in want.items():
        assert mat[f] == pytest.approx(v), f
    t = _table(m)
    assert (t["tbid"], t["sfa"], t["offa"]) == (110, 1.0, 0.0)
    assert t.rows["value"].tolist() == [0.0, 5.0] and t.rows["lcid"].tolist() == [111, 112]


def test_blank_and_zero_fields_take_the_manuals_defaults(tmp_path):
    """EPPF 1e12 (no softening), EPPFR 1e14 (no rupture) from a blank or a
    0; NUMINT 0 (all points), LCDM 0; SFA 1 and OFFA 0 of the table; cards
    3 and 4 (EPS, ES) may be left out."""
    for fill in ("", "0"):
        f = fill.rjust(10) if fill else " " * 10
        text = (
            "*KEYWORD\n*MAT_081\n"
            f"         5    7.8e-6     210.0       0.3       0.3{f}{f}{f}\n"
            f"{f}{f}        20{f}{f}{f}{f}{f}\n"
            f"*DEFINE_TABLE\n        20{f}{f}\n"
            f"{'1.0'.rjust(20)}{'21'.rjust(20)}\n"
            "*DEFINE_CURVE\n21\n0.0,0.3\n1.0,0.5\n*END\n"
        )
        m = _read(tmp_path, text)
        mat = m.materials[5]
        assert mat["eppf"] == 1e12 and mat["eppfr"] == 1e14, fill
        assert mat["numint"] == 0 and mat["lcdm"] == 0 and mat["tdel"] == 0.0 and mat["vp"] == 0.0
        assert [mat[f"eps{i}"] for i in range(1, 9)] == [0.0] * 8
        t = _table(m, 20)
        assert t["sfa"] == 1.0 and t["offa"] == 0.0


def test_an_lcss_naming_a_table_resolves_and_a_missing_curve_of_a_table_does_not(tmp_path):
    _read(tmp_path, HAT)  # LCSS 110 is the table: no dangling reference
    with pytest.raises(DeckError) as e:
        _read(tmp_path, HAT.replace("                 5.0       112", "                 5.0       113"))
    assert any(p.keyword == "DEFINE_TABLE" and p.field == "LCID" and "113" in p.message for p in e.value.problems)
    with pytest.raises(DeckError) as e:
        _read(tmp_path, HAT.replace("0.0       110", "0.0       119"))
    assert any(p.field == "LCSS" and "curve 119 is not defined" in p.message for p in e.value.problems)


@pytest.mark.parametrize("fmt", ["fixed", "long"])
def test_round_trip(tmp_path, fmt):
    text = HAT.replace("*DEFINE_TABLE\n       110\n", "*DEFINE_TABLE_TITLE\nrates\n       110       2.0       0.5\n")
    text = text.replace("*MAT_PLASTICITY_WITH_DAMAGE\n", "*MAT_PLASTICITY_WITH_DAMAGE_TITLE\nsheet\n")
    text = text.replace(
        "0.0       110         0       1.5       0.0         0         0",
        "0.0       110         0       1.5       0.0        17         3",
    )
    text = text.replace("*END\n", "*DEFINE_CURVE\n17\n0.0,0.0\n1.0,1.0\n*END\n")
    m = _read(tmp_path, text)
    out = write_deck(m, tmp_path / "out.k", fmt=fmt)[0]
    back = read_deck(out)
    a, b = m.materials[81], back.materials[81]
    assert b.name == "MAT_PLASTICITY_WITH_DAMAGE_TITLE"
    for k, v in a.values.items():
        assert b.values[k] == (pytest.approx(v) if isinstance(v, float) else v), k
    assert (b["lcdm"], b["numint"]) == (17, 3)
    ta, tb = _table(m), _table(back)
    assert tb.name == "DEFINE_TABLE_TITLE" and (tb["sfa"], tb["offa"]) == (2.0, 0.5)
    assert tb.rows["value"].tolist() == ta.rows["value"].tolist() == [0.0, 5.0]
    assert tb.rows["lcid"].tolist() == [111, 112]
