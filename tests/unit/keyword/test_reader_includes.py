"""Includes, parameters and include transforms."""

import numpy as np
import pytest

from crashlite import DeckError, read_deck

MAT_SEC = """
*SECTION_SHELL
         1         2
      &thk
*MAT_PIECEWISE_LINEAR_PLASTICITY
         17.85000E-9  210000.0       0.3     &sigy
$ cards 2-4 blank: defaults

"""


def test_acceptance_relative_include_params_expression_thickness_touching(deck):
    deck(
        "model/mesh/plate.k",
        """
        *KEYWORD
        *NODE
               1             0.0             0.0             0.0
               2           100.0             0.0             0.0
               3           100.0           100.0             0.0
               4             0.0           100.0             0.0
        *ELEMENT_SHELL_THICKNESS
               1       1       1       2       3       4
                     1.1             1.2             1.3             1.4            30.0
        *END
        """,
    )
    deck("model/props.k", "*KEYWORD\n*PART\nplate\n         1         1         1" + MAT_SEC + "*END\n")
    main = deck(
        "model/main.k",
        """
        *KEYWORD
        *PARAMETER
        r thk            2.0i n                3
        R base         200.0
        *PARAMETER_EXPRESSION
        R sigy    base*1.5 + 10*sin(0)
        i twice   n*2
        *INCLUDE_PATH_RELATIVE
        mesh
        *INCLUDE
        props.k
        plate.k
        *END
        """,
    )
    m = read_deck(main)
    assert m.sections[1]["t1"] == 2.0
    mat = m.materials[1]
    assert (mat["mid"], mat["ro"], mat["sigy"]) == (1, 7.85e-9, 300.0)
    np.testing.assert_array_equal(m.shells.thickness, [[1.1, 1.2, 1.3, 1.4]])
    assert m.shells.beta[0] == 30.0
    params = {p.name: (p.type, p.value) for p in m.parameters}
    assert params == {"thk": ("R", 2.0), "n": ("I", 3), "base": ("R", 200.0), "sigy": ("R", 300.0), "twice": ("I", 6)}
    assert len(m.files) == 3


def test_negative_parameter_reference(deck):
    p = deck(
        "neg.k",
        """
        *KEYWORD
        *PARAMETER
        R x       5.0
        *NODE
               1             &x             -&x             0.0
        *END
        """,
    )
    assert read_deck(p).nodes.xyz[0].tolist() == [5.0, -5.0, 0.0]


def test_local_parameters_do_not_leak(deck):
    deck(
        "inc.k",
        """
        *KEYWORD
        *PARAMETER_LOCAL
        R y       2.0
        *NODE
               1             &y             0.0             0.0
        *END
        """,
    )
    main = deck(
        "main.k",
        """
        *KEYWORD
        *INCLUDE
        inc.k
        *NODE
               2             &y             0.0             0.0
        *END
        """,
    )
    with pytest.raises(DeckError) as e:
        read_deck(main)
    assert "undefined parameter '&y'" in str(e.value)
    assert "main.k:5" in str(e.value)


def test_include_transform_offsets_and_translation(deck):
    deck(
        "part.k",
        """
        *KEYWORD
        *NODE
               1             0.0             0.0             0.0
               2            10.0             0.0             0.0
               3            10.0            10.0             0.0
        *ELEMENT_SHELL
               1       1       1       2       3
        *PART
        tri
                 1         1         1
        *SECTION_SHELL
                 1         2
               1.0
        *MAT_ELASTIC
                 1     1e-09    2000.0       0.3
        *END
        """,
    )
    main = deck(
        "main.k",
        """
        *KEYWORD
        *INCLUDE
        part.k
        *INCLUDE_TRANSFORM
        part.k
        $#  idnoff    ideoff    idpoff    idmoff    idsoff    idfoff    iddoff
               100       100       100       100         0         0         0
        $#  idroff
                 0
        $#  fctmas    fcttim    fctlen    fcttem   incout1
               1.0       1.0       1.0
        $#  tranid
                 5
        *DEFINE_TRANSFORMATION
                 5
        TRANSL          0.0       0.0     500.0
        *END
        """,
    )
    m = read_deck(main)
    assert m.nodes.ids.tolist() == [1, 2, 3, 101, 102, 103]
    np.testing.assert_array_equal(m.nodes.xyz[3:], [[0, 0, 500], [10, 0, 500], [10, 10, 500]])
    assert sorted(m.parts) == [1, 101]
    assert m.parts[101]["secid"] == 101 and m.parts[101]["mid"] == 101
    assert m.shells.pid.tolist() == [1, 101]
    assert m.shells.nodes[1].tolist() == [3, 4, 5, 5]


def test_long_include_name_continued_and_include_path(deck):
    deck(
        "a/very_long_directory_name_for_the_include_test/nodes_of_the_model.k",
        "*KEYWORD\n*NODE\n       1             1.0             2.0             3.0\n*END\n",
    )
    deck("lib/other.k", "*KEYWORD\n*NODE\n       2             1.0             2.0             3.0\n*END\n")
    main = deck(
        "main.k",
        """
        *KEYWORD
        *INCLUDE_PATH
        lib
        *INCLUDE
        a/very_long_directory_name_for_the_include_test/ +
        nodes_of_the_model.k
        other.k
        *END
        """,
    )
    m = read_deck(main)
    assert m.nodes.ids.tolist() == [1, 2]


def test_include_loop_is_reported(deck):
    deck("a.k", "*KEYWORD\n*INCLUDE\nb.k\n*END\n")
    deck("b.k", "*KEYWORD\n*INCLUDE\na.k\n*END\n")
    with pytest.raises(DeckError, match="include loop"):
        read_deck(deck("main.k", "*KEYWORD\n*INCLUDE\na.k\n*END\n"))


def test_include_transform_rotate_and_scale(deck):
    """ROTATE 90° about z through (10, 0, 0), then SCALE 2 in x."""
    deck("pt.k", "*KEYWORD\n*NODE\n       1            20.0             0.0             5.0\n*END\n")
    main = deck(
        "main.k",
        """
        *KEYWORD
        *INCLUDE_TRANSFORM
        pt.k
               100         0         0         0         0         0         0
                 0
               1.0       1.0       1.0
                 7
        *DEFINE_TRANSFORMATION
                 7
        ROTATE          0.0       0.0       1.0      10.0       0.0       0.0      90.0
        SCALE           2.0       1.0       1.0
        *END
        """,
    )
    m = read_deck(main)
    assert m.nodes.ids.tolist() == [101]
    np.testing.assert_allclose(m.nodes.xyz[0], [20.0, 10.0, 5.0], atol=1e-12)


def test_include_transform_offsets_a_part_move_by_what_ifset_names(deck):
    """*PART_MOVE names a part (IFSET 0) or a part set (IFSET 1): an
    included one takes the part offset or the set offset accordingly."""
    deck(
        "moved.k",
        """
        *KEYWORD
        *PART_MOVE
               1             0.0             0.0            30.0       0       0
               2             5.0             0.0             0.0       0       1
        *END
        """,
    )
    main = deck(
        "main.k",
        """
        *KEYWORD
        *INCLUDE_TRANSFORM
        moved.k
               100       100       300       100        70         0         0
                 0
               1.0       1.0       1.0
                 0
        *END
        """,
    )
    (rec,) = read_deck(main).find("PART_MOVE")
    assert rec.rows["pid"].tolist() == [301, 72]
