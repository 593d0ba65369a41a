"""SAE J211-1 CFC filters against their defined response and scipy."""

import math

import numpy as np
import pytest
from scipy import signal

from crashlite.verify.filters import (
    CFC_CLASSES,
    cfc_coefficients,
    cfc_filter,
    corner_frequency,
    default_pad,
    filter_signal,
    gain,
    resample,
)

FS = 10_000.0  # Hz, the sampling rate of crash test channels
DT = 1.0 / FS


@pytest.mark.parametrize("cfc", CFC_CLASSES)
def test_coefficients_are_the_prewarped_two_pole_butterworth(cfc):
    # scipy's digital Butterworth prewarps its corner exactly as J211 does
    b, a = signal.butter(2, 2.0775 * cfc, fs=FS)
    a0, a1, a2, b1, b2 = cfc_coefficients(cfc, DT)
    np.testing.assert_allclose([a0, a1, a2], b, rtol=1e-12)
    np.testing.assert_allclose([1.0, -b1, -b2], a, rtol=1e-12, atol=1e-15)
    assert a0 + a1 + a2 + b1 + b2 == pytest.approx(1.0, abs=1e-14)  # DC gain 1


@pytest.mark.parametrize("cfc, f_n", [(60, 100.0), (180, 300.0), (600, 1000.0), (1000, 1650.0)])
def test_minus_3db_point_is_j211_f_n(cfc, f_n):
    # the forward+backward pass is a 4-pole Butterworth in the warped
    # frequency: gain 1/sqrt(2) where (Ω/Ωd)^4 = sqrt(2) - 1
    f3 = corner_frequency(cfc, DT)
    assert gain(f3, cfc, DT) == pytest.approx(1.0 / math.sqrt(2.0), rel=1e-12)
    # without warping (fine sampling) it is 0.8022 * 2.0775 * CFC = 1.6667 CFC,
    # J211's F_N (1650 Hz for CFC 1000 is J211's rounding: 1.3 % off)
    f3_fine = corner_frequency(cfc, 1e-7)
    assert f3_fine == pytest.approx((math.sqrt(2) - 1) ** 0.25 * 2.0775 * cfc, rel=1e-6)
    assert f3_fine == pytest.approx(f_n, rel=0.015)
    # at F_H = CFC the gain lies inside J211's +0.5/-1 dB corridor
    db = 20 * math.log10(gain(cfc, cfc, DT))
    assert -1.0 < db < 0.5
    # and equals the warped 4-pole Butterworth 1/(1 + (Ω/Ωd)^4), Ω = tan(π f T)
    ratio = math.tan(math.pi * cfc * DT) / math.tan(math.pi * 2.0775 * cfc * DT)
    assert gain(cfc, cfc, DT) == pytest.approx(1 / (1 + ratio**4), rel=1e-12)


@pytest.mark.parametrize("cfc", [60, 180])
def test_sine_at_the_corner_comes_out_at_1_over_sqrt2(cfc):
    f3 = corner_frequency(cfc, DT)
    t = np.arange(0, 0.5, DT)
    y = np.sin(2 * np.pi * f3 * t)
    out = cfc_filter(y, DT, cfc)
    mid = slice(len(t) // 4, 3 * len(t) // 4)  # steady state, away from the ends
    amp = np.sqrt(2 * np.mean(out[mid] ** 2))
    assert amp == pytest.approx(1 / math.sqrt(2), rel=0.01)
    # zero phase: the output stays in phase with the input
    corr = np.dot(out[mid], y[mid]) / np.sqrt(np.dot(out[mid], out[mid]) * np.dot(y[mid], y[mid]))
    assert corr > 0.9999


@pytest.mark.parametrize("cfc", CFC_CLASSES)
def test_sine_well_below_the_corner_passes_within_1_percent_up_to_the_ends(cfc):
    t = np.arange(0, 0.2, DT)
    f = 0.1 * cfc
    y = 3.0 * np.sin(2 * np.pi * f * t + 0.3) + 1.0
    out = cfc_filter(y, DT, cfc)
    assert np.max(np.abs(out - y)) < 0.01 * 3.0


def test_matches_scipy_filtfilt_with_the_same_odd_padding():
    rng = np.random.default_rng(1)
    t = np.arange(0, 0.15, DT)
    y = 50 * np.sin(2 * np.pi * 40 * t) + 10 * rng.standard_normal(len(t))
    for cfc in CFC_CLASSES:
        p = default_pad(cfc, DT, len(t))
        b, a = signal.butter(2, 2.0775 * cfc, fs=FS)
        ref = signal.filtfilt(b, a, y, padtype="odd", padlen=p)
        np.testing.assert_allclose(cfc_filter(y, DT, cfc), ref, rtol=0, atol=1e-9 * np.max(np.abs(y)))


def test_constant_and_ramp_pass_unchanged_so_the_ends_are_not_distorted():
    t = np.arange(0, 0.05, DT)
    np.testing.assert_allclose(cfc_filter(np.full_like(t, 7.5), DT, 60), 7.5, rtol=1e-13)
    ramp = -200.0 + 4.0e4 * t
    np.testing.assert_allclose(cfc_filter(ramp, DT, 60), ramp, rtol=0, atol=1e-9 * 2000)


def test_zero_phase_keeps_a_symmetric_pulse_in_place():
    t = np.arange(1001) * DT  # symmetric about t = 0.05
    y = np.exp(-(((t - 0.05) / 0.004) ** 2))
    out = cfc_filter(y, DT, 60)
    assert t[np.argmax(out)] == pytest.approx(0.05, abs=DT)
    np.testing.assert_allclose(out, out[::-1], atol=1e-9)  # the symmetric input stays symmetric
    assert out.max() < 1.0  # and is smoothed: CFC 60 cuts its high frequencies


def test_columns_are_filtered_independently():
    t = np.arange(0, 0.05, DT)
    y = np.stack([np.sin(2 * np.pi * 30 * t), np.cos(2 * np.pi * 200 * t)], axis=1)
    both = cfc_filter(y, DT, 180)
    np.testing.assert_array_equal(both[:, 1], cfc_filter(y[:, 1], DT, 180))


def test_uneven_signal_is_resampled_then_filtered():
    rng = np.random.default_rng(3)
    t = np.sort(np.concatenate([[0.0, 0.1], rng.uniform(0, 0.1, 600)]))
    y = np.sin(2 * np.pi * 12 * t)
    tu, out = filter_signal(t, y, 180)
    assert np.allclose(np.diff(tu), tu[1] - tu[0])
    assert tu[1] - tu[0] <= 0.1 / 180  # at least 10 CFC samples per second
    np.testing.assert_allclose(out, np.sin(2 * np.pi * 12 * tu), atol=0.01)


def test_time_scale_takes_milliseconds():
    t_ms = np.arange(0, 100.0, 0.1)
    y = np.sin(2 * np.pi * 80 * t_ms * 1e-3)
    a = cfc_filter(y, 0.1, 60, time_scale=1e-3)
    b = cfc_filter(y, 1e-4, 60)
    np.testing.assert_array_equal(a, b)
    assert np.sqrt(2 * np.mean(a[250:750] ** 2)) == pytest.approx(gain(80, 60, 1e-4), rel=0.01)


def test_bad_input_is_refused_with_a_message():
    with pytest.raises(ValueError, match="too coarse"):
        cfc_filter(np.zeros(100), 1e-3, 1000)
    with pytest.raises(ValueError, match="NaN"):
        cfc_filter(np.array([0.0, np.nan, 1.0, 2.0]), DT, 60)
    with pytest.raises(ValueError, match="positive"):
        cfc_filter(np.zeros(10), DT, -60)
    with pytest.raises(ValueError, match="increase strictly"):
        resample(np.array([0.0, 1.0, 1.0, 2.0]), np.zeros(4))
