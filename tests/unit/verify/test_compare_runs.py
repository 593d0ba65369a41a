"""Run-to-run comparison on synthetic histories: matching by ID, listed
mismatches, known deviations and the errors of bad requests."""

import numpy as np
import pytest
from _histories import V0, T, history

from crashlite import read_deck
from crashlite.results import History
from crashlite.verify.compare import Options, Run, compare
from crashlite.verify.errors import CompareError


def run(name, **kw):
    model = kw.pop("model", None)
    return Run(name, f"/virtual/{name}", history(**kw), model)


def test_identical_runs_have_zero_deviations_and_rating_1():
    c = compare(run("a"), run("b"))
    groups = {p.group for p in c.pairs}
    assert groups == {"energy", "part", "section", "wall", "node_displacement", "node_acceleration"}
    for p in c.pairs:
        for k in ("peak", "value", "integral"):
            v = p.deviation[f"{k}_deviation_percent"]
            assert v is None or v == 0.0, (p.name, k)
        assert p.deviation["max_abs_difference"] == 0.0
        if p.rating is not None:
            assert p.rating.overall == pytest.approx(1.0, abs=1e-9), p.name
    assert c.overall()["min_rating"] == pytest.approx(1.0, abs=1e-9)
    assert not c.mismatches
    assert "hourglass energy: zero in both runs, not compared" in c.notes
    assert c.pulse["deviation_percent"]["peak_deceleration"] == 0.0


def test_scaled_copy_has_the_known_deviation():
    c = compare(run("a"), run("b", scale=1.25))
    (wall,) = c.group("wall")
    assert wall.deviation["peak_deviation_percent"] == pytest.approx(25.0, abs=1e-9)
    assert wall.deviation["integral_deviation_percent"] == pytest.approx(25.0, abs=1e-9)
    (sec,) = [p for p in c.group("section") if "x-force" in p.name]
    assert sec.deviation["peak_cmp"] == pytest.approx(1.25e5, rel=1e-12)
    for p in c.group("part"):
        assert p.deviation["peak_deviation_percent"] == pytest.approx(25.0, abs=1e-9)
    assert wall.rating.magnitude < 1.0 and wall.rating.phase == 1.0  # no time shift


def test_mismatched_ids_are_listed_not_guessed():
    c = compare(run("a", parts=(1, 2, 3), nodes=(5, 6)), run("b", parts=(1, 4), nodes=(5, 7), walls=(2,)))
    m = c.mismatches
    assert m["part"]["only_ref"]["ids"] == [2, 3] and m["part"]["only_cmp"]["ids"] == [4]
    assert m["node"]["only_ref"]["ids"] == [6] and m["node"]["only_cmp"]["ids"] == [7]
    assert m["wall"]["only_ref"]["ids"] == [1] and m["wall"]["only_cmp"]["ids"] == [2]
    assert [p.name for p in c.group("part")] == ["part 1 internal energy"]
    assert not c.group("wall")


def test_requested_entities_one_run_lacks_are_listed():
    c = compare(run("a", nodes=(5, 6)), run("b", nodes=(5,)), Options(nodes=[5, 6, 99], parts=[2, 1]))
    assert c.mismatches["node"]["only_ref"]["ids"] == [6]
    assert c.mismatches["node"]["in_neither"]["ids"] == [99]
    assert {p.name for p in c.group("node_displacement")} == {"node 5 x-displacement"}
    assert len(c.group("part")) == 2


def test_no_common_time_range_is_a_clear_error():
    with pytest.raises(CompareError, match=r"no common time range: a covers \[0, 0.1\], b \[1, 1.1\]"):
        compare(run("a"), run("b", shift=1.0))


def test_no_matching_entities_is_a_clear_error():
    with pytest.raises(CompareError, match="no requested node ID is in both runs"):
        compare(run("a"), run("b"), Options(nodes=[42]))
    with pytest.raises(CompareError, match="no requested part is in both runs"):
        compare(run("a", parts=(1,)), run("b", parts=(2,)), Options(parts=[1, 2]))
    with pytest.raises(CompareError, match="need the deck"):
        compare(run("a"), run("b"), Options(parts=["crash box L"]))
    with pytest.raises(CompareError, match="field comparison asked for"):
        compare(run("a"), run("b"), Options(times=[0.05]))


def test_nothing_in_common_is_an_error_not_nan():
    a = Run("a", "/virtual/a", History({"glstat": {"time": T, "total_energy": np.zeros_like(T)}}, "a"))
    b = Run("b", "/virtual/b", History({"glstat": {"time": T, "kinetic_energy": np.ones_like(T)}}, "b"))
    with pytest.raises(CompareError, match="nothing to compare"):
        compare(a, b)


def test_parts_by_title_and_part_set_with_the_decks(deck):
    text = """
        *KEYWORD
        *PART
        crash box L
                 1         1         1
        *PART
        crash box R
                 {r}         1         1
        *SET_PART_LIST
                 7
                 1         {r}
        *SECTION_DISCRETE
                 1         0
        *MAT_SPRING_ELASTIC
                 1     100.0
        *END
        """
    ma = read_deck(deck("a.k", text.format(r=2)))
    mb = read_deck(deck("b.k", text.format(r=4)))  # the right crash box has another ID in b
    c = compare(run("a", model=ma), run("b", parts=(1, 4), model=mb), Options(parts=["crash box R", "set:7", "1"]))
    names = [p.name for p in c.group("part")]
    assert names == [
        "crash box R (part 2) | crash box R (part 4) internal energy",
        "part set 7 (parts 1, 2) | part set 7 (parts 1, 4) internal energy",
        "part 1 (crash box L) internal energy",
    ]
    box_r, both, _ = c.group("part")
    # part 2 of a carries 2x the base energy, part 4 of b (its second column) as well
    assert box_r.deviation["peak_deviation_percent"] == 0.0
    assert both.deviation["peak_ref"] == pytest.approx(3 * 0.25 * V0**2, rel=1e-6)


def test_a_nearly_constant_reference_is_compared_but_not_rated():
    a, b = run("a"), run("b")
    for r, wobble in ((a, 1e-6), (b, -1e-6)):
        g = r.history._data["glstat"]
        g["total_energy"] = 1e8 * (1 + wobble * np.sin(400 * T))
    c = compare(a, b)
    (total,) = [p for p in c.group("energy") if p.name == "total energy"]
    assert total.rating is None and "not rated" in total.note
    assert abs(total.deviation["value_deviation_percent"]) < 1e-3


def test_node_fields_without_common_nodes_are_noted_unless_asked_for():
    """Field states with disjoint node IDs: not asked for, the curves are
    still compared and the field comparison is a note; asked for (times or
    nodes), a clear error, never a NaN figure."""
    from crashlite.verify.fields import FieldStates

    x = np.zeros((2, 2, 3))
    x[1, :, 0] = -10.0
    a, b = run("a"), run("b")
    a.states = FieldStates(np.array([0.0, 0.1]), x, np.array([1, 2]), [], "a")
    b.states = FieldStates(np.array([0.0, 0.1]), x, np.array([3, 4]), [], "b")
    c = compare(a, b)
    assert not c.fields and c.pairs
    assert "field comparison: no node is in both runs: 2 only in the reference, 2 only in the comparison" in c.notes
    with pytest.raises(CompareError, match="no node is in both runs"):
        compare(a, b, Options(times=[0.1]))
    b.states.ids = np.array([2, 3])
    (f,) = compare(a, b).fields
    assert f.ids.tolist() == [2] and f.figures["max_difference"] == 0.0


def test_field_from_history_nodes_of_a_run_without_field_states():
    """history_states: first state's coordinates (or the deck's) plus the
    displacements; values by hand."""
    from crashlite.verify.fields import history_states

    t = np.array([0.0, 0.5, 1.0])
    ux = np.array([[0.0, 0.0], [-1.0, -2.0], [-3.0, -4.0]])
    zero = np.zeros_like(ux)
    nod = {
        "time": t,
        "ids": np.array([7, 9]),
        "x_displacement": ux,
        "y_displacement": zero,
        "z_displacement": zero,
        "x_coordinate": 100.0 + ux,
        "y_coordinate": zero + 5.0,
        "z_coordinate": zero,
    }
    s = history_states(History({"nodout": nod}, "h"))
    assert s.ids.tolist() == [7, 9] and s.cells == [] and s.source == "h (history nodes)"
    np.testing.assert_array_equal(s.x[0], [[100.0, 5.0, 0.0], [100.0, 5.0, 0.0]])
    np.testing.assert_array_equal(s.at(0.75)[:, 0], [98.0, 97.0])  # half way between -1/-3 and -2/-4
    bare = {k: v for k, v in nod.items() if "coordinate" not in k}
    assert history_states(History({"nodout": bare}, "h")).x[2, 1].tolist() == [-4.0, 0.0, 0.0]
    assert history_states(History({"glstat": {"time": t}}, "h")) is None
