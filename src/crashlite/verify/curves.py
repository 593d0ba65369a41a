"""A pair of curves (reference and comparison) with its deviation figures
and its ISO/TS 18571 rating."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from .errors import CompareError
from .rating import Rating, RatingError, common_interval, iso_rating


@dataclass
class CurvePair:
    """One quantity of two runs.

    t_ref (n,), y_ref (n,), t_cmp (k,), y_cmp (k,): the curves [time],
    [``unit``]; ``deviation`` the figures of ``deviation()``; ``rating``
    None when the rating is not defined (``note`` says why).
    """

    group: str  # energy, part, section, wall, discrete, node_displacement, node_acceleration
    name: str  # what is compared, e.g. "part 12 (crash box L) internal_energy"
    unit: str  # kind of quantity: energy, force, length, acceleration
    t_ref: np.ndarray
    y_ref: np.ndarray
    t_cmp: np.ndarray
    y_cmp: np.ndarray
    deviation: dict = field(default_factory=dict)
    rating: Rating | None = None
    note: str = ""

    def summary(self) -> dict:
        """The figures, without the arrays (JSON-ready)."""
        return {
            "group": self.group,
            "name": self.name,
            "unit": self.unit,
            **self.deviation,
            "rating": None if self.rating is None else self.rating.as_dict(),
            "note": self.note,
        }


def relative_percent(ref: float, value: float) -> float | None:
    """100·(value − ref)/|ref|; None when ref is 0 (no relative figure)."""
    if ref == 0.0 or not (math.isfinite(ref) and math.isfinite(value)):
        return None
    return 100.0 * (value - ref) / abs(ref)


def _peak(t: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Signed value of largest magnitude and its time."""
    k = int(np.argmax(np.abs(y)))
    return float(y[k]), float(t[k])


def _peak_percent(ref: float, value: float) -> float | None:
    """Deviation of a peak in magnitude, 100·(|value| − |ref|)/|ref|, where
    both peaks have one sign (a compressive secforc peak 10 % larger reads
    +10 %, not −10 %); signed as ``relative_percent`` where they differ."""
    if ref * value > 0:
        return relative_percent(abs(ref), abs(value))
    return relative_percent(ref, value)


def _integral(t: np.ndarray, y: np.ndarray, a: float, b: float) -> float:
    """∫ y dt over [a, b] with linear interpolation (trapezoids)."""
    inside = (t > a) & (t < b)
    tt = np.concatenate([[a], t[inside], [b]])
    yy = np.concatenate([[np.interp(a, t, y)], y[inside], [np.interp(b, t, y)]])
    return float(np.sum(0.5 * (yy[1:] + yy[:-1]) * np.diff(tt)))


def deviation(t_ref: ArrayLike, y_ref: ArrayLike, t_cmp: ArrayLike, y_cmp: ArrayLike, at: float | None = None) -> dict:
    """Deviation figures of a comparison curve from a reference on their
    common time range [t0, t1]: peaks (signed value of largest magnitude and
    its time), values at ``at`` (default t1), integrals over [t0, t1]
    (e.g. the impulse of a force), each with the relative deviation
    100·(cmp − ref)/|ref| in % (None where ref is 0; peaks of one sign
    compare magnitudes), and the largest
    absolute difference on the reference's samples."""
    t_ref, y_ref = np.asarray(t_ref, float), np.asarray(y_ref, float)
    t_cmp, y_cmp = np.asarray(t_cmp, float), np.asarray(y_cmp, float)
    for name, t, y in (("reference", t_ref, y_ref), ("comparison", t_cmp, y_cmp)):
        if t.ndim != 1 or y.shape != t.shape or len(t) < 2:
            raise CompareError(f"the {name} curve needs (n,) times and values with n ≥ 2, got {t.shape}, {y.shape}")
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(y))):
            raise CompareError(f"the {name} curve holds NaN or infinite values")
    try:
        a, b = common_interval(t_ref, t_cmp)
    except RatingError as e:
        raise CompareError(str(e)) from None
    at = b if at is None else float(at)
    if not a <= at <= b:
        raise CompareError(f"time {at:.6g} is outside the common range [{a:.6g}, {b:.6g}]")
    mr = (t_ref >= a) & (t_ref <= b)
    mc = (t_cmp >= a) & (t_cmp <= b)
    # the ends of the range belong to both curves even between samples
    tr = np.unique(np.concatenate([[a, b], t_ref[mr]]))
    tc = np.unique(np.concatenate([[a, b], t_cmp[mc]]))
    yr, yc = np.interp(tr, t_ref, y_ref), np.interp(tc, t_cmp, y_cmp)
    pr, tpr = _peak(tr, yr)
    pc, tpc = _peak(tc, yc)
    vr, vc = float(np.interp(at, t_ref, y_ref)), float(np.interp(at, t_cmp, y_cmp))
    ir, ic = _integral(t_ref, y_ref, a, b), _integral(t_cmp, y_cmp, a, b)
    diff = float(np.max(np.abs(np.interp(tr, t_cmp, y_cmp) - yr)))
    return {
        "t0": a,
        "t1": b,
        "peak_ref": pr,
        "peak_cmp": pc,
        "time_of_peak_ref": tpr,
        "time_of_peak_cmp": tpc,
        "peak_deviation_percent": _peak_percent(pr, pc),
        "at_time": at,
        "value_ref": vr,
        "value_cmp": vc,
        "value_deviation_percent": relative_percent(vr, vc),
        "integral_ref": ir,
        "integral_cmp": ic,
        "integral_deviation_percent": relative_percent(ir, ic),
        "max_abs_difference": diff,
    }


def make_pair(
    group: str,
    name: str,
    unit: str,
    t_ref: ArrayLike,
    y_ref: ArrayLike,
    t_cmp: ArrayLike,
    y_cmp: ArrayLike,
    at: float | None = None,
    time_scale: float = 1.0,
    rate: bool = True,
) -> CurvePair:
    """A CurvePair with its figures; a rating that is not defined (e.g. a
    curve that stays zero) leaves ``rating`` None and says why in ``note``."""
    p = CurvePair(
        group,
        name,
        unit,
        np.asarray(t_ref, float),
        np.asarray(y_ref, float),
        np.asarray(t_cmp, float),
        np.asarray(y_cmp, float),
    )
    p.deviation = deviation(p.t_ref, p.y_ref, p.t_cmp, p.y_cmp, at)
    if rate:
        try:
            p.rating = iso_rating(p.t_ref, p.y_ref, p.t_cmp, p.y_cmp, time_scale=time_scale)
        except RatingError as e:
            p.note = f"not rated: {e}"
    return p
