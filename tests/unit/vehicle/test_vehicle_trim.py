"""Mass trim: group masses that reach a target mass and centre of gravity."""

import numpy as np
import pytest

from crashlite.vehicle.car.trim import solve


def test_reaches_mass_and_cog_close_to_the_nominal_split():
    centres = np.array([[0.0, 0, 0], [1000.0, 0, 0], [0.0, 500, 0], [0.0, -500, 0], [500.0, 0, 800]])
    nominal = np.array([1.0, 1.0, 1.0, 1.0, 1.0])
    m = solve(2.0, [200.0, 0.0, 100.0], centres, nominal, 10.0, [400.0, 10.0, 200.0])
    assert m.sum() == pytest.approx(8.0)
    cog = (2.0 * np.array([200.0, 0.0, 100.0]) + m @ centres) / 10.0
    assert cog == pytest.approx([400.0, 10.0, 200.0])
    assert np.all(m >= 0)


def test_target_out_of_reach_or_structure_too_heavy():
    centres = np.array([[0.0, 0, 0], [1000.0, 0, 0], [0.0, 500, 100], [0.0, -500, 100]])
    with pytest.raises(ValueError, match="cannot be reached"):
        solve(1.0, [0, 0, 0], centres, np.ones(4), 2.0, [2000.0, 0.0, 0.0])  # beyond the furthest group
    with pytest.raises(ValueError, match="at least the target"):
        solve(3.0, [0, 0, 0], centres, np.ones(4), 2.0, [0.0, 0.0, 0.0])


def test_groups_driven_negative_are_dropped():
    centres = np.array([[0.0, 0, 0], [1000.0, 0, 0], [2000.0, 0, 0], [1000.0, 100, 0], [1000.0, -100, 0]])
    m = solve(0.0, [0, 0, 0], centres, np.array([10.0, 1.0, 10.0, 1.0, 1.0]), 1.0, [1900.0, 0.0, 0.0])
    assert np.all(m >= 0) and m[0] == 0.0
    assert m @ centres[:, 0] == pytest.approx(1900.0)
