"""Reading fixed, free, long and I10 formats, comments, and mesh tables."""

import numpy as np
import pytest

from crashlite import DeckError, read_deck, write_deck
from crashlite.keyword.equality import model_differences

PLATE = """
*KEYWORD
*NODE
       1             0.0             0.0             0.0
       2           100.0             0.0             0.0       1       0
       3           100.0           100.0             0.0
       4,0.0,100.0,0.0,7,7
$ a comment between rows
*ELEMENT_SHELL
       1       1       1       2       3       4
       2       1       1       3       4
*PART
plate
         1         1         1
*SECTION_SHELL
         1         2
       1.5
*MAT_ELASTIC
         1   7.85e-9  210000.0       0.3
*END
"""


def test_fixed_and_free_rows(deck):
    m = read_deck(deck("plate.k", PLATE))
    assert m.nodes.ids.tolist() == [1, 2, 3, 4]
    np.testing.assert_array_equal(m.nodes.xyz[3], [0.0, 100.0, 0.0])
    assert m.nodes.tc.tolist() == [0, 1, 0, 7] and m.nodes.rc.tolist() == [0, 0, 0, 7]
    # 0-based connectivity; the triangle repeats its third node
    assert m.shells.nodes.tolist() == [[0, 1, 2, 3], [0, 2, 3, 3]]
    assert m.shells.pid.tolist() == [1, 1]
    assert m.parts[1]["heading"] == "plate"
    assert m.materials[1]["ro"] == 7.85e-9


def test_touching_fields_are_split_by_column(deck):
    text = PLATE.replace("         1   7.85e-9  210000.0       0.3", "         11.00000E-7  210000.0       0.3")
    m = read_deck(deck("touch.k", text))
    assert m.materials[1]["mid"] == 1
    assert m.materials[1]["ro"] == 1e-7


def test_node_coordinates_touching_in_16_wide_fields(deck):
    text = """
    *KEYWORD
    *NODE
          12-1.234567890e+02-2.000000000e-03 3.500000000e+01
    *END
    """
    m = read_deck(deck("n.k", text))
    assert m.nodes.ids.tolist() == [12]
    assert m.nodes.xyz[0].tolist() == [-123.4567890, -0.002, 35.0]


def test_fortran_exponents_and_integral_reals(deck):
    text = """
    *KEYWORD
    *NODE
           1          1.5d+2           -2.E1              .5
       2.000             1e3          1.0E-3            -0.0
    *END
    """
    m = read_deck(deck("f.k", text))
    assert m.nodes.ids.tolist() == [1, 2]
    assert m.nodes.xyz.tolist() == [[150.0, -20.0, 0.5], [1000.0, 0.001, -0.0]]


def test_long_format_deck_and_suffixes(deck):
    node_long = f"{1:20d}{0.1234567890123456!r:>20}{2.0:20}{3.0:20}"
    solid_i10 = "".join(f"{v:10d}" for v in (1, 1, 1, 2, 1, 1, 1, 1, 1, 1))
    text = "\n".join(
        [
            "*KEYWORD LONG=Y",
            "*NODE",
            node_long,
            "*NODE-",
            f"{2:8d}{4.0:16}{5.0:16}{6.0:16}",
            "*ELEMENT_SOLID%",
            solid_i10,
            "*PART",
            "block",
            "1,1,1",
            "*SECTION_SOLID",
            "1,1",
            "*MAT_ELASTIC",
            "1,1e-9,1.,0.3",
            "*END",
        ]
    )
    m = read_deck(deck("long.k", text))
    assert m.nodes.xyz.tolist() == [[0.1234567890123456, 2.0, 3.0], [4.0, 5.0, 6.0]]
    assert m.solids.nodes.tolist() == [[0, 1, 0, 0, 0, 0, 0, 0]]


def test_i10_header(deck):
    text = "\n".join(["*KEYWORD I10=Y", "*NODE", f"{1234567890:10d}{1.0:16}{2.0:16}{3.0:16}", "*END"])
    m = read_deck(deck("i10.k", text))
    assert m.nodes.ids.tolist() == [1234567890]
    assert m.nodes.xyz.tolist() == [[1.0, 2.0, 3.0]]


def test_keywords_are_case_insensitive(deck):
    m = read_deck(deck("lc.k", PLATE.lower().replace("plate\n", "Plate\n")))
    assert len(m.shells) == 2 and m.parts[1]["heading"] == "Plate"


def test_part_title_is_a_part_whose_heading_is_the_title(deck, tmp_path):
    """*PART_TITLE (LS-PrePost and ANSA write it; LS-DYNA runs it) reads as
    *PART: the heading card is the title, no further card; written back, it
    reads the same."""
    m = read_deck(deck("pt.k", PLATE.replace("*PART\n", "*PART_TITLE\n")))
    assert m.parts[1]["heading"] == "plate" and m.parts[1]["secid"] == 1 and m.parts[1]["mid"] == 1
    assert not m.warnings and len(m.shells) == 2
    write_deck(m, tmp_path / "out.k")
    assert model_differences(m, read_deck(tmp_path / "out.k")) == []


@pytest.mark.parametrize("fmt", ["fixed", "long", "i10", "free"])
def test_written_deck_reads_back_equal(deck, tmp_path, fmt):
    m = read_deck(deck("plate.k", PLATE))
    out = tmp_path / f"out_{fmt}.k"
    write_deck(m, out, fmt=fmt)
    assert model_differences(m, read_deck(out)) == []


def test_values_that_do_not_fit_switch_to_long_then_free(deck, tmp_path):
    m = read_deck(deck("plate.k", PLATE))
    m.nodes.xyz[0] = [0.1 + 0.2, 1.0 / 3.0, -1.2345678901234567e-300]
    m.nodes.ids[0] = 123456789012
    out = tmp_path / "hard.k"
    write_deck(m, out)
    text = out.read_text()
    assert "*NODE+" in text  # long format for the block that needs it
    back = read_deck(out)
    assert back.nodes.xyz[0].tolist() == m.nodes.xyz[0].tolist()
    assert back.nodes.ids[0] == 123456789012


def test_unknown_keyword_kept_verbatim_and_in_place(deck, tmp_path):
    text = PLATE.replace("*END", "*DEFINE_BOX\n$ box comment\n         1       0.0     100.0\n*END")
    m = read_deck(deck("u.k", text))
    assert any("DEFINE_BOX" in str(w) for w in m.warnings)
    raw = m.unknown[0]
    assert raw.keyword == "DEFINE_BOX" and raw.lines == ["$ box comment", "         1       0.0     100.0"]
    out = tmp_path / "u_out.k"
    write_deck(m, out)
    assert "*DEFINE_BOX\n$ box comment\n         1       0.0     100.0\n" in out.read_text()
    with pytest.raises(DeckError, match="DEFINE_BOX"):
        read_deck(deck("u.k", text), strict=True)


def test_writer_refuses_to_overwrite_input(deck):
    p = deck("plate.k", PLATE)
    m = read_deck(p)
    before = p.read_text()
    with pytest.raises(FileExistsError):
        write_deck(m, p)
    assert p.read_text() == before


def test_split_writes_mesh_include(deck, tmp_path):
    m = read_deck(deck("plate.k", PLATE))
    files = write_deck(m, tmp_path / "split" / "main.k", split=True)
    assert [f.name for f in files] == ["main.k", "main_mesh.k"]
    assert "*NODE" not in files[0].read_text() and "*NODE" in files[1].read_text()
    assert model_differences(m, read_deck(files[0])) == []


def test_two_card_solids_and_eight_node_shells(deck):
    text = "\n".join(
        [
            "*KEYWORD",
            "*NODE",
            *[f"{i:8d}{float(i):16}{0.0:16}{0.0:16}" for i in range(1, 9)],
            "*ELEMENT_SOLID",
            f"{1:8d}{1:8d}",
            "".join(f"{i:8d}" for i in range(1, 9)),
            "*PART",
            "b",
            "1,1,1",
            "*SECTION_SOLID",
            "1,1",
            "*MAT_ELASTIC",
            "1,1e-9,1.,0.3",
            "*END",
        ]
    )
    m = read_deck(deck("two.k", text))
    assert m.solids.nodes.tolist() == [list(range(8))]
    bad = text.replace(
        "*ELEMENT_SOLID",
        "*ELEMENT_SHELL\n" + "".join(f"{i:8d}" for i in (5, 1, 1, 2, 3, 4, 5, 6, 7, 8)) + "\n*ELEMENT_SOLID",
    )
    with pytest.raises(DeckError, match="8-node shells are not supported"):
        read_deck(deck("bad.k", bad))


def test_fast_layout_kernel_signs_and_overflow():
    from crashlite.keyword.fastformat import fixed_lines

    lines = fixed_lines([np.array([-5, 12, 0, -1234567]), np.array([0.5, -1e-05, 3.0, 1e16])], [0, 1], [8, 10])
    assert lines == ["      -5       0.5", "      12    -1e-05", "       0       3.0", "-1234567     1e+16"]
    assert fixed_lines([np.array([-12345678])], [0], [8]) is None  # 9 characters: does not fit
