"""SAE J211-1 channel frequency class (CFC) filters.

The J211-1 filter is a two-pole Butterworth low-pass, designed by the
bilinear transform at wd = 2π·2.0775·CFC, run forward and then backward:
zero phase, and a magnitude response |H|² that is a four-pole Butterworth,
gain 1/(1 + (Ω/Ωd)⁴) with Ω = tan(ωT/2). Its −3 dB point is therefore
where (Ω/Ωd)⁴ = √2 − 1, i.e. at 0.8022·2.0775·CFC ≈ 1.667·CFC for fine
sampling: 100 Hz for CFC 60, 300 Hz for CFC 180, 1000 Hz for CFC 600,
1650 Hz for CFC 1000 (J211's F_N), and the gain at f = CFC (J211's F_H)
is −0.23 dB, inside the +0.5/−1 dB corridor.

Frequencies are in Hz, so time must be in seconds: ``time_scale`` gives
the seconds per unit of the time values passed (1.0 for mm–tonne–s
decks, 1e-3 for mm–kg–ms).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from .kernels import biquad_filtfilt

CFC_CLASSES = (60, 180, 600, 1000)  # the classes J211-1 names (any positive CFC is accepted)
DESIGN_FACTOR = 2.0775  # J211-1: wd = 2π · 2.0775 · CFC
_M3DB = (math.sqrt(2.0) - 1.0) ** 0.25  # Ω/Ωd at the −3 dB point of the forward+backward pass


def cfc_coefficients(cfc: float, dt: float) -> tuple[float, float, float, float, float]:
    """(a0, a1, a2, b1, b2) of J211-1 for a step ``dt`` [s]."""
    _check_class(cfc, dt)
    wd = 2.0 * math.pi * cfc * DESIGN_FACTOR
    wa = math.tan(wd * dt / 2.0)
    den = 1.0 + math.sqrt(2.0) * wa + wa * wa
    a0 = wa * wa / den
    b1 = -2.0 * (wa * wa - 1.0) / den
    b2 = (-1.0 + math.sqrt(2.0) * wa - wa * wa) / den
    return a0, 2.0 * a0, a0, b1, b2


def corner_frequency(cfc: float, dt: float) -> float:
    """Frequency [Hz] where the forward+backward filter's gain is 1/√2."""
    _check_class(cfc, dt)
    wa = math.tan(math.pi * cfc * DESIGN_FACTOR * dt)
    return math.atan(_M3DB * wa) / (math.pi * dt)


def gain(freq: ArrayLike, cfc: float, dt: float) -> np.ndarray:
    """Magnitude response of the forward+backward filter at ``freq`` [Hz]
    (array), from its coefficients: |H(e^{jωT})|²."""
    a0, a1, a2, b1, b2 = cfc_coefficients(cfc, dt)
    z = np.exp(-1j * 2.0 * np.pi * np.asarray(freq, float) * dt)  # z⁻¹
    h = (a0 + a1 * z + a2 * z * z) / (1.0 - b1 * z - b2 * z * z)
    return np.abs(h) ** 2


def default_pad(cfc: float, dt: float, n: int) -> int:
    """Samples of odd extension at each end: about twenty time constants of
    the filter's poles (τ = 1/(0.707·2π·2.0775·CFC) ≈ 0.108/CFC s), so the
    start-up transient (e⁻²⁰ of the lag of a ramp) has died out before the
    signal begins; at most n−1."""
    return int(min(n - 1, math.ceil(2.0 / (cfc * dt))))


def cfc_filter(y: ArrayLike, dt: float, cfc: float, pad: int | None = None, time_scale: float = 1.0) -> np.ndarray:
    """Zero-phase J211-1 filtering of a uniformly sampled signal.

    y: (n,) or (n, m) float64, m signals on one time grid [any unit];
    dt: time step [time unit, seconds × ``time_scale``⁻¹]; pad: samples of
    odd (point-symmetric) extension at both ends, default ``default_pad``.
    Returns an array shaped like y, in y's unit.
    """
    x = np.asarray(y, dtype=np.float64)
    if x.ndim not in (1, 2):
        raise ValueError(f"cfc_filter: y must be (n,) or (n, m), got shape {x.shape}")
    n = x.shape[0]
    if n < 3:
        raise ValueError(f"cfc_filter: {n} samples; at least 3 are needed")
    if not np.all(np.isfinite(x)):
        raise ValueError("cfc_filter: the signal holds NaN or infinite values")
    step = float(dt) * time_scale
    coeffs = cfc_coefficients(cfc, step)
    p = default_pad(cfc, step, n) if pad is None else int(pad)
    if not 0 <= p < n:
        raise ValueError(f"cfc_filter: pad {p} must lie in [0, {n - 1}] for {n} samples")
    cols = x.reshape(n, -1)
    # odd extension keeps value and slope continuous at the ends, so the
    # filter sees no step there
    ext = np.concatenate([2.0 * cols[:1] - cols[p:0:-1], cols, 2.0 * cols[-1:] - cols[-2 : -p - 2 : -1]])
    out = np.empty_like(ext)
    biquad_filtfilt(np.ascontiguousarray(ext), *coeffs, out)
    return out[p : p + n].reshape(x.shape)


def is_uniform(t: ArrayLike, rtol: float = 1e-6) -> bool:
    """True when the steps of ``t`` agree within ``rtol`` of their mean."""
    d = np.diff(np.asarray(t, float))
    return len(d) > 0 and float(np.ptp(d)) <= rtol * abs(float(d.mean()))


def resample(
    t: ArrayLike, y: ArrayLike, dt: float | None = None, t0: float | None = None, t1: float | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Linear interpolation of (t, y) onto a uniform grid.

    t: (n,) strictly increasing [time]; y: (n,) or (n, m); dt: step [time],
    default the median step of t; t0, t1: range, default t's. Returns
    (t_u (k,), y_u (k,) or (k, m)); t_u ends at the last whole step ≤ t1.
    """
    t = np.asarray(t, dtype=np.float64)
    y = np.asarray(y, dtype=np.float64)
    if t.ndim != 1 or len(t) < 2 or y.shape[0] != len(t):
        raise ValueError(f"resample: need t (n,) with n ≥ 2 and y with n rows; got {t.shape} and {y.shape}")
    d = np.diff(t)
    if not np.all(d > 0):
        k = int(np.argmax(~(d > 0)))
        raise ValueError(f"resample: time must increase strictly (t[{k}] = {t[k]:.6g}, t[{k + 1}] = {t[k + 1]:.6g})")
    step = float(np.median(d)) if dt is None else float(dt)
    if not step > 0:
        raise ValueError(f"resample: step {step} must be positive")
    a = t[0] if t0 is None else float(t0)
    b = t[-1] if t1 is None else float(t1)
    if a < t[0] - 1e-12 * abs(t[0] or 1.0) or b > t[-1] + 1e-9 * step or b <= a:
        raise ValueError(f"resample: range [{a:.6g}, {b:.6g}] is not inside the signal's [{t[0]:.6g}, {t[-1]:.6g}]")
    k = int(math.floor((b - a) / step * (1 + 1e-12))) + 1
    tu = a + step * np.arange(k)
    if y.ndim == 1:
        return tu, np.interp(tu, t, y)
    return tu, np.stack([np.interp(tu, t, y[:, j]) for j in range(y.shape[1])], axis=1)


def filter_signal(
    t: ArrayLike, y: ArrayLike, cfc: float, dt: float | None = None, pad: int | None = None, time_scale: float = 1.0
) -> tuple[np.ndarray, np.ndarray]:
    """CFC-filter a signal that may be unevenly sampled.

    t: (n,) [time]; y: (n,) or (n, m). The signal is taken onto a uniform
    grid first: step ``dt`` [time] if given; otherwise its own step when it
    is already uniform and fine enough, else the finer of its median step
    and 1/(10·CFC) s (a sampling rate of at least 10·CFC, six times the
    −3 dB frequency). Returns (t_u (k,), y_filtered (k,) or (k, m)).
    """
    t = np.asarray(t, dtype=np.float64)
    if dt is None:
        limit = 0.1 / (cfc * time_scale) if cfc > 0 else math.inf
        med = float(np.median(np.diff(t))) if len(t) > 1 else 0.0
        if is_uniform(t) and med <= limit:
            return t.copy(), cfc_filter(y, med, cfc, pad, time_scale)
        dt = min(med, limit) if med > 0 else limit
    tu, yu = resample(t, y, dt)
    return tu, cfc_filter(yu, dt, cfc, pad, time_scale)


def _check_class(cfc: float, dt: float) -> None:
    if not (isinstance(cfc, (int, float, np.integer, np.floating)) and cfc > 0 and math.isfinite(cfc)):
        raise ValueError(f"CFC must be a positive number of Hz (J211-1 classes: {CFC_CLASSES}), got {cfc!r}")
    if not dt > 0:
        raise ValueError(f"time step must be positive, got {dt!r}")
    if DESIGN_FACTOR * cfc * dt >= 0.5:
        raise ValueError(
            f"step {dt:.4g} s is too coarse for CFC {cfc:g}: the design frequency "
            f"{DESIGN_FACTOR * cfc:.4g} Hz must lie below the Nyquist frequency "
            f"{0.5 / dt:.4g} Hz (use a step below {0.5 / (DESIGN_FACTOR * cfc):.3g} s)"
        )
