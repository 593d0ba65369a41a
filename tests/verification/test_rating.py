"""ISO/TS 18571 ratings against hand-computed cases."""

import numpy as np
import pytest

from crashlite.verify.rating import RatingError, grade, iso_rating

N = 1501
T = np.arange(N) * 1e-4  # 0 .. 0.15 s at the standard's 10 kHz


def half_sine(t, start=0.02, width=0.05):
    return np.where((t > start) & (t < start + width), np.sin(np.pi * (t - start) / width), 0.0)


def corridor_by_hand(ref, cmp):
    """ISO/TS 18571 corridor score: 1 inside 5 % of the reference peak,
    0 outside 50 %, ((b - d)/(b - a))^2 between."""
    peak = np.max(np.abs(ref))
    a, b = 0.05 * peak, 0.5 * peak
    d = np.abs(cmp - ref)
    c = np.where(d < a, 1.0, np.where(d > b, 0.0, ((b - d) / (b - a)) ** 2))
    return c.mean()


def test_identical_curves_rate_1():
    y = 120e3 * half_sine(T)
    r = iso_rating(T, y, T, y)
    assert (r.corridor, r.phase, r.magnitude, r.slope, r.overall) == (1.0, 1.0, 1.0, 1.0, 1.0)
    assert r.grade == "excellent" and r.shift == 0.0 and r.n_samples == N


def test_time_shift_lowers_phase_by_the_shift_over_20_percent_of_the_interval():
    y = half_sine(T)
    shift = 50  # samples: 5 ms
    y2 = half_sine(T, start=0.02 + shift * 1e-4)
    r = iso_rating(T, y, T, y2)
    # E_P = (0.2 N - n) / (0.2 N), kp = 1
    assert r.phase == pytest.approx((0.2 * N - shift) / (0.2 * N), abs=1e-12)
    assert r.shift == pytest.approx(0.005, abs=1e-12)
    # after the shift the curves coincide: magnitude and slope are perfect
    assert r.magnitude == pytest.approx(1.0, abs=1e-9)
    assert r.slope == pytest.approx(1.0, abs=1e-9)
    z = corridor_by_hand(y, y2)  # the corridor is rated on the unshifted curves
    assert r.corridor == pytest.approx(z, abs=1e-12)
    assert r.overall == pytest.approx(0.4 * z + 0.2 * (r.phase + 2.0), abs=1e-9)


def test_scaled_rectangular_pulse_rates_by_hand():
    # a 20 % higher plateau: no time warping can help, so the magnitude
    # error is exactly 0.2 -> E_M = 1 - 0.2/0.5; the slope error is 0.2 ->
    # E_S = 1 - 0.2/2; no shift -> E_P = 1
    y = np.where((T >= 0.02) & (T < 0.07), 1.0, 0.0)
    r = iso_rating(T, y, T, 1.2 * y)
    assert r.phase == 1.0
    assert r.magnitude == pytest.approx(0.6, abs=1e-9)
    assert r.slope == pytest.approx(0.9, abs=1e-9)
    plateau = np.count_nonzero(y)
    z = (N - plateau + plateau * ((0.5 - 0.2) / 0.45) ** 2) / N
    assert r.corridor == pytest.approx(z, abs=1e-12)
    assert r.overall == pytest.approx(0.4 * z + 0.2 * (1.0 + 0.6 + 0.9), abs=1e-9)


def test_scaled_half_sine_slope_and_corridor():
    y = half_sine(T)
    r = iso_rating(T, y, T, 1.1 * y)
    assert r.phase == 1.0
    assert r.slope == pytest.approx(1 - 0.1 / 2.0, abs=1e-9)  # linear in the curve: exact
    assert r.corridor == pytest.approx(corridor_by_hand(y, 1.1 * y), abs=1e-12)
    # time warping can only help the scaled curve: no worse than the unwarped error 0.1
    assert 1 - 0.1 / 0.5 - 1e-9 <= r.magnitude < 1.0


def test_curves_on_different_grids_are_rated_on_their_overlap():
    t_ref = np.linspace(0, 0.15, 301)
    t_cmp = np.linspace(0.01, 0.2, 97)
    r = iso_rating(t_ref, half_sine(t_ref), t_cmp, half_sine(t_cmp))
    assert r.t0 == pytest.approx(0.01) and r.t1 == pytest.approx(0.15, abs=1e-4)
    assert r.overall > 0.94  # the same pulse, sampled differently


def test_time_in_milliseconds():
    y = half_sine(T)
    r_s = iso_rating(T, y, T, 1.1 * y)
    r_ms = iso_rating(T * 1e3, y, T * 1e3, 1.1 * y, time_scale=1e-3)
    assert r_ms.overall == pytest.approx(r_s.overall, abs=1e-12)
    assert r_ms.n_samples == N


@pytest.mark.parametrize(
    "score, name",
    [
        (1.0, "excellent"),
        (0.9401, "excellent"),
        (0.94, "good"),
        (0.81, "good"),
        (0.80, "fair"),
        (0.59, "fair"),
        (0.58, "poor"),
        (0.0, "poor"),
    ],
)
def test_grades(score, name):
    assert grade(score) == name


def test_undefined_ratings_are_refused():
    with pytest.raises(RatingError, match="no common time range"):
        iso_rating(T, half_sine(T), T + 1.0, half_sine(T))
    with pytest.raises(RatingError, match="constant"):
        iso_rating(T, np.zeros(N), T, half_sine(T))
