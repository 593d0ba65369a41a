"""ISO/TS 18571 objective rating of a curve against a reference.

R = 0.4·Z + 0.2·E_P + 0.2·E_M + 0.2·E_S: corridor score Z (inner and
outer corridors at a0 = 5 % and b0 = 50 % of the reference's peak, kz = 2),
phase score E_P (time shift of the best cross-correlation, up to 20 % of
the interval, kp = 1), magnitude score E_M (L1 error after the shift and
dynamic time warping, εm = 0.5) and slope score E_S (L1 error of the
smoothed derivatives, 2.0 → 0). The arithmetic is the PyPI package
``objective-rating-metrics``; this module brings both curves onto the
common interval at the 10 kHz the standard prescribes and checks that a
rating is defined at all.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np
from numpy.typing import ArrayLike

from .filters import resample

SAMPLE_STEP = 1e-4  # s: ISO/TS 18571 rates curves sampled at 10 kHz
MAX_SAMPLES = 10_001  # the DTW of the magnitude score builds an n×n matrix
GRADES = ((0.94, "excellent"), (0.80, "good"), (0.58, "fair"))


class RatingError(ValueError):
    """A rating that is not defined for the curves given."""


@dataclass(frozen=True)
class Rating:
    """Scores in [0, 1]; ``shift`` [time unit of the curves] is the time
    shift the phase score found; ``t0``, ``t1`` the rated interval."""

    corridor: float
    phase: float
    magnitude: float
    slope: float
    overall: float
    grade: str
    shift: float
    t0: float
    t1: float
    n_samples: int

    def as_dict(self) -> dict:
        return asdict(self)


def grade(score: float) -> str:
    """ISO/TS 18571 grade: excellent > 0.94, good > 0.80, fair > 0.58, else poor."""
    if not math.isfinite(score):
        raise RatingError(f"score {score!r} is not a number")
    for limit, name in GRADES:
        if score > limit:
            return name
    return "poor"


def common_interval(
    t_ref: ArrayLike, t_cmp: ArrayLike, t0: float | None = None, t1: float | None = None
) -> tuple[float, float]:
    """The overlap of two time axes (narrowed to [t0, t1] when given)."""
    a = max(float(t_ref[0]), float(t_cmp[0]), -math.inf if t0 is None else float(t0))
    b = min(float(t_ref[-1]), float(t_cmp[-1]), math.inf if t1 is None else float(t1))
    if not b > a:
        raise RatingError(
            f"no common time range: reference covers [{t_ref[0]:.6g}, {t_ref[-1]:.6g}], "
            f"comparison [{t_cmp[0]:.6g}, {t_cmp[-1]:.6g}]"
            + ("" if t0 is None and t1 is None else f", requested [{t0}, {t1}]")
        )
    return a, b


def iso_rating(
    t_ref: ArrayLike,
    y_ref: ArrayLike,
    t_cmp: ArrayLike,
    y_cmp: ArrayLike,
    t0: float | None = None,
    t1: float | None = None,
    time_scale: float = 1.0,
) -> Rating:
    """Rate ``y_cmp`` against ``y_ref`` by ISO/TS 18571.

    t_ref (n,), y_ref (n,), t_cmp (k,), y_cmp (k,): the two curves [time],
    [any unit, the same for both]; t0, t1: interval to rate, default the
    overlap of the two; time_scale: seconds per time unit. Both curves are
    interpolated onto a 10 kHz grid on the interval.
    """
    from objective_rating_metrics.rating import ISO18571

    a, b = common_interval(t_ref, t_cmp, t0, t1)
    step = SAMPLE_STEP / time_scale
    n = int(math.floor((b - a) / step * (1 + 1e-12))) + 1
    if n < 20:
        raise RatingError(f"interval [{a:.6g}, {b:.6g}] holds {n} samples at 10 kHz; ISO/TS 18571 needs more")
    if n > MAX_SAMPLES:
        raise RatingError(
            f"interval [{a:.6g}, {b:.6g}] holds {n} samples at 10 kHz (more than "
            f"{MAX_SAMPLES}): rate a shorter interval (t0, t1)"
        )
    tr, yr = resample(t_ref, y_ref, step, a, b)
    _, yc = resample(t_cmp, y_cmp, step, a, b)
    tr, yr, yc = tr[:n], yr[:n], yc[:n]
    if not (np.all(np.isfinite(yr)) and np.all(np.isfinite(yc))):
        raise RatingError("a curve holds NaN or infinite values")
    if np.ptp(yr) == 0.0 or np.ptp(yc) == 0.0:
        # the phase score's cross-correlation and the corridors need a varying reference
        raise RatingError("a curve is constant on the interval: the ISO/TS 18571 rating is not defined")
    ts = (tr - tr[0]) * time_scale  # the package differentiates with dt in seconds
    iso = ISO18571(np.column_stack([ts, yr]), np.column_stack([ts, yc]), dt=SAMPLE_STEP)
    scores = [iso.corridor_rating(-1), iso.phase_rating(-1), iso.magnitude_rating(-1), iso.slope_rating(-1)]
    overall = iso.overall_rating(-1)
    if not all(math.isfinite(s) for s in scores + [overall]):
        raise RatingError("the rating came out undefined (NaN): the curves are degenerate")
    z, ep, em, es = (float(s) for s in scores)
    return Rating(
        z, ep, em, es, float(overall), grade(float(overall)), float(iso._n_eps) * step, a, a + (n - 1) * step, n
    )
