"""Crash pulse figures of a vehicle velocity (or acceleration) history.

Peak and mean deceleration, dynamic crush, time to zero velocity and the
occupant load criterion (OLC, Kübler et al. 2009, as Euro NCAP uses it): a
virtual occupant first flies freely at the initial velocity until it has
moved ``free_flight`` (65 mm) relative to the vehicle, then is restrained
with a constant deceleration chosen so that it reaches the vehicle's
velocity after a further ``restraint`` (235 mm) of relative travel; OLC is
that deceleration.

Signals are taken along the direction of travel: the sign of the initial
velocity defines "forward", so a vehicle moving in −x works as well.
Results are in the signals' units (length, time); ``as_dict(g)`` adds
figures in g with ``g`` in the same units (9806.65 mm/s² by default).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np
from numpy.typing import ArrayLike

from .filters import filter_signal, is_uniform, resample

G_MM_S2 = 9806.65  # standard gravity [mm/s²]


@dataclass(frozen=True)
class Pulse:
    """Crash pulse figures; decelerations positive when slowing down."""

    v0: float  # initial speed along the travel direction [length/time]
    peak_deceleration: float  # [length/time²]
    time_of_peak: float  # [time]
    mean_deceleration: float  # speed lost / time to zero speed (or the record) [length/time²]
    dynamic_crush: float  # largest forward displacement [length]
    time_of_crush: float  # [time]
    time_to_zero_velocity: float | None  # None when the vehicle never stops in the record [time]
    olc: float | None  # occupant load criterion; None when the occupant's travel is not used up [length/time²]
    olc_t1: float | None  # end of the free flight [time]
    olc_t2: float | None  # occupant and vehicle at the same speed [time]
    note: str = ""  # why a figure is missing

    def as_dict(self, g: float = G_MM_S2) -> dict:
        d = asdict(self)
        for k in ("peak_deceleration", "mean_deceleration", "olc"):
            d[k + "_g"] = None if d[k] is None else d[k] / g
        return d


def olc(
    t: ArrayLike, v: ArrayLike, free_flight: float = 65.0, restraint: float = 235.0
) -> tuple[float | None, float | None, float | None]:
    """(OLC, t1, t2) of a forward-speed history.

    t (n,) [time], v (n,) [length/time], speed along the travel direction
    (positive), sampled finely enough for piecewise-linear integration;
    free_flight, restraint [length]. None where the record ends first.
    """
    t = np.asarray(t, float)
    v = np.asarray(v, float)
    u0 = v[0]
    x = _cumtrapz(t, v)  # vehicle travel
    rel = u0 * (t - t[0]) - x  # occupant (at u0) minus vehicle
    t1 = _first_crossing(t, rel, free_flight)
    if t1 is None:
        return None, None, None
    x1 = np.interp(t1, t, x)
    # after t1 the occupant slows at a constant rate from u0 to the vehicle
    # speed at t2: relative travel D(t2) = (t2 - t1)(u0 + v(t2))/2 - (x(t2) - x(t1))
    k = np.searchsorted(t, t1, side="right")
    tt = np.concatenate([[t1], t[k:]])
    vv = np.concatenate([[np.interp(t1, t, v)], v[k:]])
    xx = np.concatenate([[x1], x[k:]])
    d = (tt - t1) * (u0 + vv) / 2.0 - (xx - x1)
    t2 = _first_crossing(tt, d, restraint)
    if t2 is None or t2 <= t1:
        return None, t1, None
    return (u0 - float(np.interp(t2, t, v))) / (t2 - t1), t1, t2


def crash_pulse(
    t: ArrayLike,
    velocity: ArrayLike | None = None,
    acceleration: ArrayLike | None = None,
    v0: float | None = None,
    cfc: float | None = None,
    free_flight: float = 65.0,
    restraint: float = 235.0,
    time_scale: float = 1.0,
    step: float | None = None,
) -> Pulse:
    """Pulse figures from a velocity or an acceleration history.

    t (n,) [time]; velocity (n,) [length/time], or acceleration (n,)
    [length/time²] with the initial velocity ``v0``; cfc: J211 class the
    deceleration is filtered with (None: unfiltered; vehicle structure:
    60); free_flight, restraint: the OLC distances [length] (65, 235 mm);
    time_scale: seconds per time unit (for the filter); step: uniform
    step the signal is resampled to when uneven [time] (default its
    median step).
    """
    if (velocity is None) == (acceleration is None):
        raise ValueError("crash_pulse: give either a velocity or an acceleration history")
    t = np.asarray(t, float)
    y = np.asarray(velocity if velocity is not None else acceleration, float)
    if t.ndim != 1 or y.shape != t.shape or len(t) < 3:
        raise ValueError(f"crash_pulse: t and the signal must be (n,) with n ≥ 3; got {t.shape}, {y.shape}")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(y))):
        raise ValueError("crash_pulse: the history holds NaN or infinite values")
    if not is_uniform(t) or step is not None:
        t, y = resample(t, y, step)
    dt = t[1] - t[0]
    if velocity is not None:
        v = y
        acc = np.gradient(v, dt)
    else:
        if v0 is None:
            raise ValueError("crash_pulse: an acceleration history needs the initial velocity v0")
        acc = y
        v = float(v0) + _cumtrapz(t, acc)
    if v[0] == 0.0:
        raise ValueError("crash_pulse: the initial velocity is zero, so there is no direction of travel")
    sign = math.copysign(1.0, v[0])
    u = sign * v  # forward speed
    dec = -sign * acc  # deceleration, positive when slowing
    if cfc is not None:
        dec = filter_signal(t, dec, cfc, dt=dt, time_scale=time_scale)[1]
    ip = int(np.argmax(dec))
    x = _cumtrapz(t, u)
    ic = int(np.argmax(x))
    tz = _first_crossing(t, -u, 0.0)
    t_end = tz if tz is not None else t[-1]
    u_end = 0.0 if tz is not None else u[-1]
    o, t1, t2 = olc(t, u, free_flight, restraint)
    notes = []
    if tz is None:
        notes.append("the vehicle does not stop within the record: mean deceleration over the record")
    if o is None:
        notes.append("the occupant's free flight and restraint travel are not used up within the record: no OLC")
    return Pulse(
        v0=float(u[0]),
        peak_deceleration=float(dec[ip]),
        time_of_peak=float(t[ip]),
        mean_deceleration=float((u[0] - u_end) / (t_end - t[0])),
        dynamic_crush=float(x[ic]),
        time_of_crush=float(t[ic]),
        time_to_zero_velocity=tz,
        olc=None if o is None else float(o),
        olc_t1=t1,
        olc_t2=t2,
        note="; ".join(notes),
    )


def _cumtrapz(t: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Running trapezoid integral, 0 at t[0]: (n,)."""
    out = np.zeros_like(y, dtype=float)
    out[1:] = np.cumsum(0.5 * (y[1:] + y[:-1]) * np.diff(t))
    return out


def _first_crossing(t: np.ndarray, y: np.ndarray, level: float) -> float | None:
    """First time y reaches ``level`` from below (linear between samples)."""
    above = np.flatnonzero(y >= level)
    if len(above) == 0:
        return None
    k = int(above[0])
    if k == 0:
        return float(t[0])
    y0, y1 = y[k - 1], y[k]
    return float(t[k - 1] + (level - y0) / (y1 - y0) * (t[k] - t[k - 1]))
