"""Node-field comparison: displacement difference on common node IDs."""

import numpy as np
import pytest

from crashlite.verify.errors import CompareError
from crashlite.verify.fields import FieldStates, compare_fields

X0 = np.array([[0.0, 0, 0], [100.0, 0, 0], [200.0, 0, 0], [300.0, 0, 0]])


def states(ids, u_end, x0=X0):
    """Two states: the initial geometry at t = 0 and x0 + u_end at t = 0.1;
    linear in between."""
    return FieldStates(np.array([0.0, 0.1]), np.stack([x0, x0 + u_end]), np.asarray(ids, np.int64), [], "test")


def test_known_difference_field_at_the_end_and_half_way():
    u = np.array([[10.0, 0, 0], [20.0, 0, 0], [40.0, 0, 0], [0.0, 0, 0]])
    ref = states([1, 2, 3, 4], u)
    cmp = states([1, 2, 3, 4], 1.1 * u)
    fc = compare_fields(ref, cmp, 0.1)
    g = fc.figures
    assert g["max_displacement_ref"] == 40.0 and g["node_of_max_ref"] == 3
    assert g["max_difference"] == pytest.approx(4.0) and g["node_of_max_difference"] == 3
    assert g["mean_difference"] == pytest.approx(0.1 * 70.0 / 4)
    assert g["max_relative_deviation_percent"] == pytest.approx(10.0)
    assert g["mean_relative_deviation_percent"] == pytest.approx(100 * 7.0 / 4 / 40.0)
    assert g["max_displacement_deviation_percent"] == pytest.approx(10.0)
    half = compare_fields(ref, cmp, 0.05)  # linear between states
    assert half.figures["max_difference"] == pytest.approx(2.0)


def test_nodes_are_matched_by_id_not_by_position():
    u = np.array([[10.0, 0, 0], [20.0, 0, 0], [40.0, 0, 0], [0.0, 0, 0]])
    ref = states([1, 2, 3, 4], u)
    # same nodes in another order, one node renumbered (4 -> 9)
    order = [2, 0, 1, 3]
    cmp = states(np.array([3, 1, 2, 9]), u[order], X0[order])
    fc = compare_fields(ref, cmp, 0.1)
    assert fc.figures["max_difference"] == 0.0
    assert list(fc.ids) == [1, 2, 3]
    assert list(fc.only_ref) == [4] and list(fc.only_cmp) == [9]
    s = fc.summary()
    assert s["only_ref"] == {"count": 1, "ids": [4]} and s["only_cmp"] == {"count": 1, "ids": [9]}


def test_one_component_and_a_node_selection():
    u = np.array([[0.0, 5, 0], [20.0, 0, 0], [40.0, 3, 0], [0.0, 0, 0]])
    ref = states([1, 2, 3, 4], u)
    cmp = states([1, 2, 3, 4], u + [[0.0, 0, 0], [1.0, 0, 0], [0.0, 9, 0], [0.0, 0, 0]])
    fc = compare_fields(ref, cmp, 0.1, nodes=[2, 3, 77], component="x")
    assert list(fc.ids) == [2, 3]
    assert fc.figures["max_difference"] == pytest.approx(1.0) and fc.figures["node_of_max_difference"] == 2


def test_errors_no_ids_no_common_nodes_still_reference_time_outside():
    u = np.ones((4, 3))
    with pytest.raises(CompareError, match="no node IDs"):
        compare_fields(FieldStates(np.array([0.0, 0.1]), np.stack([X0, X0 + u])), states([1, 2, 3, 4], u), 0.1)
    with pytest.raises(CompareError, match="no node is in both runs"):
        compare_fields(states([1, 2, 3, 4], u), states([5, 6, 7, 8], u), 0.1)
    with pytest.raises(CompareError, match="do not move"):
        compare_fields(states([1, 2, 3, 4], 0 * u), states([1, 2, 3, 4], u), 0.1)
    with pytest.raises(CompareError, match="outside"):
        compare_fields(states([1, 2, 3, 4], u), states([1, 2, 3, 4], u), 0.2)
