"""Deviation figures of curve pairs against closed-form values."""

import math

import numpy as np
import pytest

from crashlite.verify.curves import deviation, make_pair, relative_percent
from crashlite.verify.errors import CompareError

T = np.linspace(0.0, 0.1, 1001)
W = math.pi / 0.1  # one half sine over the record


def test_identical_curves_have_zero_deviation_and_rate_1():
    y = 5e5 * np.sin(W * T)
    p = make_pair("wall", "force", "force", T, y, T, y)
    d = p.deviation
    assert d["peak_deviation_percent"] == 0.0 and d["integral_deviation_percent"] == 0.0
    assert d["max_abs_difference"] == 0.0
    assert p.rating.overall == pytest.approx(1.0, abs=1e-12) and p.rating.grade == "excellent"


def test_half_sine_peak_integral_and_value_by_hand():
    y = np.sin(W * T)
    d = deviation(T, y, T, 1.1 * y, at=0.05)
    assert d["peak_ref"] == pytest.approx(1.0, abs=1e-12) and d["time_of_peak_ref"] == pytest.approx(0.05)
    assert d["integral_ref"] == pytest.approx(2.0 / W, rel=1e-5)  # trapezoids on 1000 steps
    assert d["value_ref"] == pytest.approx(1.0, abs=1e-12)
    for k in ("peak", "value", "integral"):
        assert d[f"{k}_deviation_percent"] == pytest.approx(10.0, abs=1e-9)
    assert d["max_abs_difference"] == pytest.approx(0.1, abs=1e-12)


def test_common_range_is_the_overlap_and_interpolates_between_samples():
    # the comparison is sampled on another, shorter grid: figures on [0, 0.0605]
    t2 = np.arange(0.0, 0.0606, 0.0011)
    d = deviation(T, T, t2, t2)  # y = t on both
    assert d["t1"] == pytest.approx(t2[-1])
    assert d["integral_ref"] == pytest.approx(t2[-1] ** 2 / 2, rel=1e-12)
    assert d["integral_deviation_percent"] == pytest.approx(0.0, abs=1e-9)
    assert d["value_cmp"] == pytest.approx(t2[-1])


def test_relative_figures_are_none_where_the_reference_is_zero():
    assert relative_percent(0.0, 3.0) is None
    d = deviation(T, np.zeros_like(T), T, np.sin(W * T))
    assert d["peak_deviation_percent"] is None and d["integral_deviation_percent"] is None


def test_a_constant_curve_is_compared_but_not_rated():
    p = make_pair("energy", "total", "energy", T, np.full_like(T, 7.0), T, np.full_like(T, 7.0))
    assert p.rating is None and "not rated" in p.note and "constant" in p.note
    assert p.deviation["value_deviation_percent"] == 0.0


def test_no_common_time_range_is_an_error():
    with pytest.raises(CompareError, match="no common time range"):
        deviation(T, T, T + 1.0, T)


def test_nan_is_an_error_not_a_figure():
    y = np.sin(W * T)
    y[5] = np.nan
    with pytest.raises(CompareError, match="NaN"):
        deviation(T, y, T, np.sin(W * T))


def test_value_time_outside_the_range_is_an_error():
    with pytest.raises(CompareError, match="outside the common range"):
        deviation(T, T, T, T, at=0.2)
