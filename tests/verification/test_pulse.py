"""Crash pulse figures against the analytic half-sine and constant pulses."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from crashlite.verify.pulse import G_MM_S2, crash_pulse, olc

V0 = 15555.6  # mm/s, 56 km/h
CRUSH = 600.0  # mm
W = V0 / CRUSH  # rad/s: single mass on a linear spring, C = v0 sqrt(m/k) = v0/ω
T_M = 0.5 * math.pi / W  # time of maximum crush
T = np.arange(0, 0.2, 1e-5)


def half_sine_velocity(t):
    """Elastic impact: v0 cos ωt during contact (0..π/ω), then rebound at -v0."""
    return np.where(t < math.pi / W, V0 * np.cos(W * t), -V0)


def test_half_sine_pulse_from_velocity():
    p = crash_pulse(T, velocity=half_sine_velocity(T))
    assert p.v0 == V0
    assert p.dynamic_crush == pytest.approx(CRUSH, rel=1e-6)
    assert p.time_of_crush == pytest.approx(T_M, abs=1e-5)
    assert p.time_to_zero_velocity == pytest.approx(T_M, rel=1e-6)
    assert p.peak_deceleration == pytest.approx(V0 * W, rel=1e-6)
    assert p.time_of_peak == pytest.approx(T_M, abs=1e-5)
    assert p.mean_deceleration == pytest.approx(2 * V0 * W / math.pi, rel=1e-6)


def olc_half_sine_by_hand():
    """OLC of the half-sine from its closed form x(t) = v0 sin(ωt)/ω."""
    x = lambda t: V0 * math.sin(W * t) / W  # noqa: E731
    v = lambda t: V0 * math.cos(W * t)  # noqa: E731
    t1 = brentq(lambda t: V0 * t - x(t) - 65.0, 1e-6, math.pi / W)
    d = lambda t2: (t2 - t1) * (V0 + v(t2)) / 2 - (x(t2) - x(t1)) - 235.0  # noqa: E731
    t2 = brentq(d, t1 + 1e-9, math.pi / W)
    return (V0 - v(t2)) / (t2 - t1), t1, t2


def test_half_sine_olc():
    ref, t1, t2 = olc_half_sine_by_hand()
    p = crash_pulse(T, velocity=half_sine_velocity(T))
    assert p.olc_t1 == pytest.approx(t1, rel=1e-5)
    assert p.olc_t2 == pytest.approx(t2, rel=1e-5)
    assert p.olc == pytest.approx(ref, rel=1e-5)
    # the restraint phase runs into the rebound (t2 > t_m): the occupant must
    # then be held harder than the mean deceleration of the vehicle
    assert t2 > T_M and p.olc > p.mean_deceleration


def test_half_sine_pulse_from_acceleration_in_minus_x():
    a = np.where(T < math.pi / W, V0 * W * np.sin(W * T), 0.0)  # a vehicle moving in -x slows: a > 0
    p = crash_pulse(T, acceleration=a, v0=-V0)
    assert p.v0 == V0
    assert p.dynamic_crush == pytest.approx(CRUSH, rel=1e-6)
    assert p.peak_deceleration == pytest.approx(V0 * W, rel=1e-7)  # the grid misses t_m by < 5e-6 s
    assert p.time_to_zero_velocity == pytest.approx(T_M, rel=1e-6)
    assert p.olc == pytest.approx(olc_half_sine_by_hand()[0], rel=1e-5)


def test_constant_deceleration_olc_is_60_over_47_of_it():
    # free flight: a t1²/2 = 65; restraint: a t1 (t2 - t1)/2 = 235;
    # OLC = a t2/(t2 - t1) = a (1 + 130/470) = 60/47 a, while the vehicle still moves
    a = 7.0 * G_MM_S2
    t = np.arange(0, 0.22, 1e-5)
    v = V0 - a * t
    assert V0 / a > t[-1]  # the vehicle does not stop in the record
    o, t1, t2 = olc(t, v)
    assert t1 == pytest.approx(math.sqrt(130.0 / a), rel=1e-6)
    assert t2 == pytest.approx(t1 + 470.0 / (a * t1), rel=1e-6)
    assert o == pytest.approx(60.0 / 47.0 * a, rel=1e-6)
    p = crash_pulse(t, velocity=v)
    assert p.as_dict()["olc_g"] == pytest.approx(7.0 * 60 / 47, rel=1e-6)
    assert p.time_to_zero_velocity is None and "does not stop" in p.note
    assert p.mean_deceleration == pytest.approx(a, rel=1e-9)


def test_constant_deceleration_to_standstill_olc():
    # the vehicle stops at ts = v0/a after S = v0²/(2a); the occupant is
    # still moving: (t2 - t1) v0/2 = 235 + S - x(t1), OLC = v0/(t2 - t1)
    a = 30.0 * G_MM_S2
    ts = V0 / a
    v = np.where(T < ts, V0 - a * T, 0.0)
    t1 = math.sqrt(130.0 / a)
    x1 = V0 * t1 - a * t1**2 / 2
    s = V0**2 / (2 * a)
    ref = V0**2 / (2 * (235.0 + s - x1))
    p = crash_pulse(T, velocity=v)
    assert p.olc == pytest.approx(ref, rel=1e-5)
    assert p.olc_t2 > ts
    assert p.dynamic_crush == pytest.approx(s, rel=1e-6)
    assert p.time_to_zero_velocity == pytest.approx(ts, abs=1e-5)  # one sample
    assert p.peak_deceleration == pytest.approx(a, rel=1e-6)
    assert p.mean_deceleration == pytest.approx(a, rel=5e-4)


def test_solver_spring_mass_pulse(tmp_path):
    """The example deck: 1263 kg at 56 km/h on a linear spring sized for 600 mm."""
    from crashlite.results import load
    from crashlite.solver import run

    run("src/crashlite/examples/pulse/pulse.k", out=tmp_path)
    h = load(tmp_path)
    p = crash_pulse(h.read("nodout", "time"), velocity=h.read("nodout", "x_velocity")[:, 0])
    assert p.dynamic_crush == pytest.approx(CRUSH, rel=0.01)
    assert p.time_to_zero_velocity == pytest.approx(T_M, rel=0.02)
    assert p.peak_deceleration == pytest.approx(V0 * W, rel=0.02)


def test_bad_input():
    with pytest.raises(ValueError, match="either"):
        crash_pulse(T)
    with pytest.raises(ValueError, match="v0"):
        crash_pulse(T, acceleration=np.zeros_like(T))
    with pytest.raises(ValueError, match="zero"):
        crash_pulse(T, velocity=np.zeros_like(T))
    with pytest.raises(ValueError, match="NaN"):
        crash_pulse(T, velocity=np.full_like(T, np.nan))
