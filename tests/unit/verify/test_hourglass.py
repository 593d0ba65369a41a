"""The hourglass share of a run (verify.hourglass) against hand-made histories."""

import numpy as np
import pytest

from crashlite.verify.hourglass import hourglass_share


def test_share_at_the_end_and_largest_once_internal_energy_counts():
    t = np.linspace(0.0, 1.0, 11)
    ie = np.array([0.0, 1.0, 5.0, 20.0, 40.0, 60.0, 80.0, 90.0, 95.0, 100.0, 100.0])
    hg = np.array([0.0, 0.9, 1.0, 3.0, 6.0, 7.0, 8.0, 8.0, 8.0, 8.0, 7.0])
    s = hourglass_share(t, ie, hg)
    assert s["end_percent"] == pytest.approx(7.0)
    # 0.9 of 1.0 (90 %) comes before the internal energy reaches a tenth of its largest: not counted
    assert s["max_percent"] == pytest.approx(15.0)  # 3 of 20 at t = 0.3
    assert s["max_time"] == pytest.approx(0.3)
    assert "part" not in s


def test_part_with_most_hourglass_energy_and_its_own_share():
    t = np.array([0.0, 1.0])
    ie, hg = np.array([0.0, 100.0]), np.array([0.0, 12.0])
    pie = np.array([[0.0, 0.0, 0.0], [30.0, 50.0, 20.0]])
    phg = np.array([[0.0, 0.0, 0.0], [1.0, 10.0, 1.0]])
    s = hourglass_share(t, ie, hg, np.array([7, 8, 9]), pie, phg)
    assert s["part"] == {"id": 8, "hourglass": 10.0, "percent_of_its_internal": pytest.approx(20.0)}


def test_no_hourglass_history_or_no_internal_energy_gives_nothing():
    t = np.linspace(0.0, 1.0, 3)
    assert hourglass_share(t, np.ones(3), np.zeros(0)) == {}
    assert hourglass_share(t, np.zeros(3), np.zeros(3)) == {}
