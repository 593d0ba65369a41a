"""Designs of experiments: Latin hypercube, Sobol and Halton sequences
(scipy.stats.qmc) and plain random points, in the unit cube, scaled to the
variables' bounds."""

from __future__ import annotations

import warnings

import numpy as np


def _qmc(cls, d: int, seed: int, **kw):
    try:
        return cls(d, rng=seed, **kw)
    except TypeError:  # scipy < 1.15 takes seed=
        return cls(d, seed=seed, **kw)


def unit_points(method: str, n: int, d: int, seed: int = 0, scramble: bool = True) -> np.ndarray:
    """(n, d) points in [0, 1)^d; the same for the same arguments."""
    from scipy.stats import qmc

    if n <= 0 or d <= 0:
        raise ValueError(f"a design of experiments needs n > 0 points in d > 0 dimensions, got n={n}, d={d}")
    if method == "lhs":
        return _qmc(qmc.LatinHypercube, d, seed, scramble=scramble).random(n)
    if method == "sobol":
        eng = _qmc(qmc.Sobol, d, seed, scramble=scramble)
        with warnings.catch_warnings():  # n need not be a power of two for a study
            warnings.simplefilter("ignore", UserWarning)
            return eng.random(n)
    if method == "halton":
        return _qmc(qmc.Halton, d, seed, scramble=scramble).random(n)
    if method == "random":
        return np.random.default_rng(seed).random((n, d))
    raise ValueError(f"unknown design of experiments {method!r} (lhs, sobol, halton, random)")


def to_bounds(unit: np.ndarray, variables) -> np.ndarray:
    """Unit-cube points onto the variables' bounds (integers rounded)."""
    lo = np.array([v.lower for v in variables])
    hi = np.array([v.upper for v in variables])
    x = lo + np.asarray(unit, float) * (hi - lo)
    for j, v in enumerate(variables):
        if v.integer:
            x[:, j] = np.clip(np.round(x[:, j]), v.lower, v.upper)
    return x


def to_unit(x: np.ndarray, variables) -> np.ndarray:
    lo = np.array([v.lower for v in variables])
    hi = np.array([v.upper for v in variables])
    return (np.asarray(x, float) - lo) / (hi - lo)


def problem(variables) -> dict:
    """The SALib problem of the variables."""
    return {
        "num_vars": len(variables),
        "names": [v.name for v in variables],
        "bounds": [[v.lower, v.upper] for v in variables],
    }


def doe(settings, variables) -> np.ndarray:
    """(n, d) variable values of the study's design of experiments."""
    return to_bounds(
        unit_points(settings.method, settings.designs, len(variables), settings.seed, settings.scramble), variables
    )
