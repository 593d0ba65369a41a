"""Controls and cards without physical meaning are refused at set-up naming
the card (file, line, keyword, field), never run to a wrong answer nor
reported as a node "without mass" (issue 35).

Each deck is the pulse example (one mass on a spring) or a one-element
model with one field changed.
"""

from importlib import resources

import pytest

from crashlite import read_deck
from crashlite.solver import run
from crashlite.solver.setup import SetupError, build

PULSE = (resources.files("crashlite") / "examples" / "pulse" / "pulse.k").read_text()


def _pulse(tmp_path, old: str, new: str, name: str = "pulse.k") -> str:
    assert old in PULSE
    p = tmp_path / name
    p.write_text(PULSE.replace(old, new, 1))
    return str(p)


def _line_of(path: str, text: str) -> int:
    return next(k for k, ln in enumerate(open(path).read().splitlines(), 1) if ln.startswith(text))


def _refused(deck: str):
    with pytest.raises(SetupError) as e:
        build(read_deck(deck))
    assert not any("has no mass" in p.message for p in e.value.problems), e.value
    return e.value.problems


def test_tssfac_above_one_is_refused_naming_the_card(tmp_path):
    """TSSFAC = 3 stepped past the stable step: one step past ENDTIM and an
    energy ratio of 56, exit 0."""
    deck = _pulse(tmp_path, "       0.0      0.01\n", "       0.0       3.0\n")
    (p,) = _refused(deck)
    assert (p.file, p.keyword, p.field) == (deck, "CONTROL_TIMESTEP", "TSSFAC")
    assert p.line == _line_of(deck, "       0.0       3.0")
    assert "TSSFAC = 3" in p.message and "(0, 1]" in p.message


def test_tssfac_of_one_is_accepted(tmp_path):
    """The stable step itself (TSSFAC = 1) is LS-DYNA's upper bound: not refused."""
    deck = _pulse(tmp_path, "       0.0      0.01\n", "       0.0       1.0\n")
    assert build(read_deck(deck)).tssfac == 1.0


def test_a_spring_with_negative_stiffness_is_refused(tmp_path):
    deck = _pulse(tmp_path, "         1        &k\n", "         1   -1000.0\n")
    (p,) = _refused(deck)
    assert (p.keyword, p.field) == ("MAT_SPRING_ELASTIC", "K")
    assert p.line == _line_of(deck, "         1   -1000.0") and "K = -1000 < 0" in p.message


def test_a_negative_endcyc_sets_no_cycle_limit(tmp_path):
    """ENDCYC < 0 ran 0 cycles; as LS-DYNA, only ENDCYC > 0 limits the
    cycles: the run reaches ENDTIM, with a warning naming the field."""
    ref = run(_pulse(tmp_path, "      0.12\n", "      0.12         0\n", "ref.k"))
    deck = _pulse(tmp_path, "      0.12\n", "      0.12        -5\n")
    res = run(deck)
    assert res.cycles == ref.cycles > 100 and res.time[-1] >= 0.12
    assert any("ENDCYC" in w and "-5" in w and deck in w for w in res.info["warnings"])


def test_a_negative_element_mass_is_named(tmp_path):
    deck = _pulse(tmp_path, "     100       2              &m\n", "     100       2            -1.0\n")
    (p,) = _refused(deck)
    assert (p.file, p.keyword, p.field) == (deck, "ELEMENT_MASS", "MASS")
    assert p.line == _line_of(deck, "     100       2            -1.0")
    assert "element 100 on node 2" in p.message and "-1 < 0" in p.message


SHELL = """*KEYWORD
*NODE
1,0,0,0
2,10,0,0
3,10,10,0
4,0,10,0
*ELEMENT_SHELL
1,1,1,2,3,4
*PART
plate
1,1,1
*SECTION_SHELL
1,2,0.8333,2
{t}
*MAT_ELASTIC
1,7.85e-9,210000.0,0.3
*CONTROL_TERMINATION
1e-5
*END
"""


@pytest.mark.parametrize("t", ["0.0,0.0,0.0,0.0", "-1.0,-1.0,-1.0,-1.0"])
def test_a_shell_section_without_thickness_is_named(tmp_path, t):
    deck = tmp_path / "shell.k"
    deck.write_text(SHELL.format(t=t))
    (p,) = _refused(str(deck))
    assert (p.keyword, p.field, p.line) == ("SECTION_SHELL", "T1", 14)
    assert "part 1" in p.message and "thickness" in p.message


def test_a_shell_giving_its_own_thickness_needs_none_from_the_section(tmp_path):
    deck = tmp_path / "shell.k"
    own = "*ELEMENT_SHELL_THICKNESS\n1,1,1,2,3,4\n1.0,1.0,1.0,1.0\n"
    deck.write_text(SHELL.format(t="0.0,0.0,0.0,0.0").replace("*ELEMENT_SHELL\n1,1,1,2,3,4\n", own))
    s = build(read_deck(str(deck)))
    assert s.mass.sum() == pytest.approx(7.85e-9 * 100.0)


PLP = "*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,7.85e-9,210000.0,0.3,200.0,1000.0\n" + "0,0,0,0,0,0,0,0\n" * 3


@pytest.mark.parametrize("material", ["elastic", "piecewise"])
def test_a_refused_shell_formulation_is_the_only_problem_of_its_part(tmp_path, material):
    """ELFORM 13 refused: the section was dropped, so its shells had no
    thickness and their nodes no mass; "thickness <= 0" for every shell
    (T1 = 1 on the card) and "has no mass" for every node followed."""
    deck = tmp_path / "shell.k"
    text = SHELL.format(t="1.0,1.0,1.0,1.0").replace("1,2,0.8333,2\n", "1,13,0.8333,2\n")
    if material == "piecewise":
        text = text.replace("*MAT_ELASTIC\n1,7.85e-9,210000.0,0.3\n", PLP)
    deck.write_text(text)
    with pytest.raises(SetupError) as e:
        build(read_deck(str(deck)))
    (elform,) = e.value.problems
    assert (elform.keyword, elform.field, elform.line) == ("SECTION_SHELL", "ELFORM", 13)
    assert "shell formulation 13 is not supported" in elform.message
    assert "thickness <= 0" not in str(e.value) and "has no mass" not in str(e.value)


def test_nodes_of_a_refused_part_only_are_not_reported_massless(tmp_path):
    """A good part beside the refused one: their shared nodes have mass;
    a node on a spring alone still has none and is reported."""
    deck = tmp_path / "shell.k"
    good = (
        "*ELEMENT_SHELL\n1,1,1,2,3,4\n2,2,2,5,6,3\n*ELEMENT_DISCRETE\n3,3,5,7\n"
        "*PART\ngood\n2,2,1\n*SECTION_SHELL\n2,2\n1.0,1.0,1.0,1.0\n"
        "*PART\nspring\n3,3,3\n*SECTION_DISCRETE\n3,0\n*MAT_SPRING_ELASTIC\n3,100.0\n"
    )
    text = SHELL.format(t="1.0,1.0,1.0,1.0").replace("1,2,0.8333,2\n", "1,13,0.8333,2\n")
    text = text.replace("*ELEMENT_SHELL\n1,1,1,2,3,4\n", good).replace(
        "4,0,10,0\n", "4,0,10,0\n5,20,0,0\n6,20,10,0\n7,30,0,0\n"
    )
    deck.write_text(text)
    with pytest.raises(SetupError) as e:
        build(read_deck(str(deck)))
    massless = [p.message for p in e.value.problems if "has no mass" in p.message]
    assert massless == ["node 7 carries elements but has no mass"], e.value
    assert "thickness <= 0" not in str(e.value) and "shell formulation 13" in str(e.value)


def test_a_beam_section_without_area_is_named(tmp_path):
    deck = tmp_path / "beam.k"
    deck.write_text(
        "*KEYWORD\n*NODE\n1,0,0,0\n2,100,0,0\n3,200,0,0\n*ELEMENT_BEAM\n1,1,1,2\n2,1,2,3\n"
        "*PART\nbar\n1,1,1\n*SECTION_BEAM\n1,2\n0.0,1.0,1.0,2.0\n*MAT_ELASTIC\n"
        "1,7.85e-9,210000.0,0.3\n*CONTROL_TERMINATION\n1e-5\n*END\n"
    )
    (p,) = _refused(str(deck))
    assert (p.keyword, p.field, p.line) == ("SECTION_BEAM", "A", 14)
    assert "area 0 <= 0" in p.message and "2 beam(s)" in p.message


SOLID = """*KEYWORD
*NODE
1,0,0,0
2,10,0,0
3,10,10,0
4,0,10,0
5,0,0,10
6,10,0,10
7,10,10,10
8,0,10,10
*ELEMENT_SOLID
{row}
*PART
block
1,1,1
*SECTION_SOLID
1,1
*MAT_ELASTIC
1,7.85e-9,210000.0,0.3
*CONTROL_TERMINATION
1e-5
*END
"""


def test_an_inverted_solid_is_named(tmp_path):
    deck = tmp_path / "solid.k"
    deck.write_text(SOLID.format(row="7,1,5,6,7,8,1,2,3,4"))
    (p,) = _refused(str(deck))
    assert (p.keyword, p.line) == ("ELEMENT_SOLID", 12)
    assert "solid 7 has volume -1000 <= 0" in p.message and "inverted" in p.message
    deck.write_text(SOLID.format(row="7,1,1,2,3,4,5,6,7,8"))
    assert build(read_deck(str(deck))).mass.sum() == pytest.approx(7.85e-9 * 1000.0)


@pytest.mark.parametrize(
    "material, field",
    [
        ("1,0.0,210000.0,0.3", "RO"),
        ("1,-7.85e-9,210000.0,0.3", "RO"),
        ("1,7.85e-9,0.0,0.3", "E"),
        ("1,7.85e-9,-210000.0,0.3", "E"),
        ("1,7.85e-9,210000.0,0.5", "PR"),
    ],
)
def test_a_material_without_density_or_stiffness_names_its_field(tmp_path, material, field):
    deck = tmp_path / "shell.k"
    deck.write_text(SHELL.format(t="1.0,1.0,1.0,1.0").replace("1,7.85e-9,210000.0,0.3", material))
    (p,) = _refused(str(deck))
    assert (p.keyword, p.field, p.line) == ("MAT_ELASTIC", field, 16)


@pytest.mark.parametrize("speed", ["1e30", "6e6"])
def test_an_initial_velocity_faster_than_sound_is_refused(tmp_path, speed):
    """The plate's steel carries sound at sqrt(E/RO) = 5.17e6 mm/s; a node
    set off faster is no crash (at 1e30 the run went on for three steps to
    an energy ratio of 1e300 and exit 0)."""
    deck = tmp_path / "shell.k"
    deck.write_text(
        SHELL.format(t="1.0,1.0,1.0,1.0").replace(
            "*CONTROL_TERMINATION", f"*INITIAL_VELOCITY_NODE\n3,{speed},0,0\n*CONTROL_TERMINATION"
        )
    )
    (p,) = _refused(str(deck))
    assert p.keyword == "INITIAL_VELOCITY_NODE" and p.line == 17  # the keyword line: rows keep none
    assert "node 3" in p.message and "faster than sound" in p.message


def test_a_crash_speed_is_not_refused(tmp_path):
    deck = tmp_path / "shell.k"
    deck.write_text(
        SHELL.format(t="1.0,1.0,1.0,1.0").replace(
            "*CONTROL_TERMINATION", "*INITIAL_VELOCITY\n0\n17800.0,0,0\n*CONTROL_TERMINATION"
        )
    )
    s = build(read_deck(str(deck)))
    assert s.v0[:, 0] == pytest.approx(17800.0)


def test_a_shell_with_two_nodes_at_one_point_is_named(tmp_path):
    """Nodes 2 and 3 of a quadrilateral at one point (a collapsed edge, not
    a triangle N3 = N4): the run went on with its energy ratio at 1.2."""
    deck = tmp_path / "shell.k"
    deck.write_text(SHELL.format(t="1.0,1.0,1.0,1.0").replace("3,10,10,0", "3,10,0,0"))
    (p,) = _refused(str(deck))
    assert (p.keyword, p.field) == ("ELEMENT_SHELL", "N2")
    assert "nodes 2 and 3" in p.message and "triangle" in p.message


def test_a_zero_length_spring_without_orientation_is_named(tmp_path):
    """A spring between two nodes at one point, no VID: its direction is
    undefined (the run took one step four times the end time, energy
    ratio 2.3, exit 0)."""
    deck = tmp_path / "zero.k"
    deck.write_text(
        "\n".join(
            [
                "*KEYWORD",
                "*NODE",
                "1,0,0,0",
                "2,0,0,0",
                "*ELEMENT_DISCRETE",
                "7,1,1,2",
                "*PART",
                "s",
                "1,1,1",
                "*SECTION_DISCRETE",
                "1,0",
                "*MAT_SPRING_ELASTIC",
                "1,100",
                "*ELEMENT_MASS",
                "1,1,0.001",
                "2,2,0.001",
                "*CONTROL_TERMINATION",
                "1e-3",
                "*END",
            ]
        )
    )
    (p,) = _refused(str(deck))
    assert (p.keyword, p.field) == ("ELEMENT_DISCRETE", "VID")
    assert "discrete element 7" in p.message and "nodes 1 and 2" in p.message


def test_a_zero_length_spring_with_an_orientation_runs(tmp_path):
    deck = tmp_path / "zero.k"
    deck.write_text(
        "\n".join(
            [
                "*KEYWORD",
                "*NODE",
                "1,0,0,0",
                "2,0,0,0",
                "*ELEMENT_DISCRETE",
                "7,1,1,2,3",
                "*PART",
                "s",
                "1,1,1",
                "*SECTION_DISCRETE",
                "1,0",
                "*MAT_SPRING_ELASTIC",
                "1,100",
                "*DEFINE_SD_ORIENTATION",
                "3,0,1.0,0,0",
                "*ELEMENT_MASS",
                "1,1,0.001",
                "2,2,0.001",
                "*CONTROL_TERMINATION",
                "1e-3",
                "*END",
            ]
        )
    )
    s = build(read_deck(str(deck)))
    assert s.discrete.length0[0] == 0.0
