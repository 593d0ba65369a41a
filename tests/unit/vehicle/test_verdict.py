"""The simplified vehicle's verdict table: each figure against its bound."""

import pytest

from crashlite.vehicle.verify.verdict import intrusion_bound, verdict, verdict_lines


def _figures(**kw):
    f = {
        "energy_rating_min": 0.96,
        "crash_box_internal_energy_deviation_percent": -1.9,
        "firewall_intrusion_mean_deviation_percent": 2.9,
        "firewall_intrusion_max_deviation_percent": 14.0,
        "time_reduction_percent": 61.0,
        "elastic_twin": {"premise": {"firewall_intrusion_max_deviation_percent": 10.0}},
    }
    f.update(kw)
    return f


def test_every_figure_inside_its_bound_passes():
    rows = verdict(_figures())
    assert [r.passed for r in rows] == [True] * 5
    assert intrusion_bound(_figures()) == pytest.approx(15.0)  # the twin's 10 % + 5 points


@pytest.mark.parametrize(
    "key, value, row",
    [
        ("energy_rating_min", 0.949, 0),
        ("crash_box_internal_energy_deviation_percent", 2.01, 1),
        ("crash_box_internal_energy_deviation_percent", -2.01, 1),
        ("firewall_intrusion_mean_deviation_percent", 3.01, 2),
        ("firewall_intrusion_max_deviation_percent", 15.01, 3),
        ("time_reduction_percent", 59.9, 4),
    ],
)
def test_a_figure_past_its_bound_fails_alone(key, value, row):
    rows = verdict(_figures(**{key: value}))
    assert [r.passed for r in rows] == [i != row for i in range(5)]
    assert "FAIL" in verdict_lines(rows)[row + 1]


def test_without_a_twin_the_largest_intrusion_bound_is_the_papers_5_percent():
    f = _figures(elastic_twin=None, firewall_intrusion_max_deviation_percent=5.5)
    assert intrusion_bound(f) == 5.0
    assert verdict(f)[3].passed is False


def test_a_figure_not_measured_is_said_so_not_passed():
    f = _figures()
    del f["firewall_intrusion_mean_deviation_percent"]
    rows = verdict(f)
    assert rows[2].passed is None and rows[2].value is None
    assert verdict_lines(rows)[3].endswith("not measured")
