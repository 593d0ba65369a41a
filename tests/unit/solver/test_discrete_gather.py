"""The springs' and dampers' force gather over their own nodes against a
plain scatter-add: +fe on n1, −fe on n2, nothing on ground (−1) or any
other node, in a fixed order."""

import numpy as np

from crashlite.solver.kernels.discrete import gather, incidence


def test_gather_over_the_elements_own_nodes_is_the_scatter_add():
    rng = np.random.default_rng(11)
    n_nodes, ne = 50, 40
    n1 = rng.integers(0, 12, ne)  # few nodes, many elements on each
    n2 = rng.integers(-1, 12, ne)  # -1: to ground
    fe = rng.normal(size=(ne, 3))
    rows, ptr, elem, sign = incidence(n1, n2)
    assert set(rows) == set(n1) | set(n2[n2 >= 0])  # only the nodes with elements
    out = rng.normal(size=(n_nodes, 3))
    want = out.copy()
    np.add.at(want, n1, fe)
    np.add.at(want, n2[n2 >= 0], -fe[n2 >= 0])
    gather(rows, ptr, elem, sign, fe, out)
    np.testing.assert_allclose(out, want, rtol=1e-13, atol=1e-13)
    untouched = np.setdiff1d(np.arange(n_nodes), rows)
    np.testing.assert_array_equal(out[untouched], want[untouched])


def test_gather_sums_in_element_order():
    """The sum at a node runs over its elements by number: the same bits
    however the elements were listed by node."""
    n1 = np.array([3, 3, 3], np.int64)
    n2 = np.array([-1, -1, -1], np.int64)
    fe = np.array([[1e16, 0, 0], [1.0, 0, 0], [-1e16, 0, 0]])
    rows, ptr, elem, sign = incidence(n1, n2)
    out = np.zeros((5, 3))
    gather(rows, ptr, elem, sign, fe, out)
    assert out[3, 0] == (1e16 + 1.0) - 1e16  # 0.0 in this order (1.0 in another)
