"""Metamodels of the responses over the design space.

* ``linear`` and ``quadratic`` polynomial response surfaces (least squares;
  the quadratic one with all interactions, needing (d+1)(d+2)/2 designs);
* ``rbf``: thin-plate-spline radial basis functions with a linear trend
  (scipy's RBFInterpolator), exact at the designs;
* ``auto``: the one with the smallest leave-one-out error.

Inputs are scaled to the unit cube of the bounds. Each fit carries its
leave-one-out (PRESS) RMSE and R², the measure of whether a metamodel can
be trusted for sensitivity or optimisation.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def _features(u: np.ndarray, kind: str) -> np.ndarray:
    n, d = u.shape
    cols = [np.ones(n)] + [u[:, j] for j in range(d)]
    if kind == "quadratic":
        cols += [u[:, i] * u[:, j] for i in range(d) for j in range(i, d)]
    return np.stack(cols, axis=1)


def n_terms(kind: str, d: int) -> int:
    return {"linear": d + 1, "quadratic": (d + 1) * (d + 2) // 2}.get(kind, d + 2)


@dataclass
class Metamodel:
    kind: str
    lower: np.ndarray  # (d,)
    upper: np.ndarray  # (d,)
    loo_rmse: float  # leave-one-out root mean square error [response unit]
    loo_r2: float  # 1 - PRESS / total sum of squares
    n: int  # designs fitted
    _coef: np.ndarray | None = None
    _rbf: object = None
    _loo: np.ndarray | None = None

    def unit(self, x) -> np.ndarray:
        return (np.atleast_2d(np.asarray(x, float)) - self.lower) / (self.upper - self.lower)

    def predict(self, x) -> np.ndarray:
        """(m,) predictions at variable values x (m, d)."""
        u = self.unit(x)
        if self.kind == "rbf":
            return self._rbf(u)
        return _features(u, self.kind) @ self._coef

    @property
    def loo_predictions(self) -> np.ndarray:
        return self._loo

    def describe(self) -> dict:
        return {"kind": self.kind, "designs": self.n, "loo_rmse": self.loo_rmse, "loo_r2": self.loo_r2}


def _fit_poly(u, y, kind):
    a = _features(u, kind)
    coef, *_ = np.linalg.lstsq(a, y, rcond=None)
    # leave-one-out residuals from the hat matrix: e_i / (1 - h_ii)
    pinv = np.linalg.pinv(a)
    h = np.einsum("ij,ji->i", a, pinv)
    e = y - a @ coef
    with np.errstate(divide="ignore", invalid="ignore"):
        loo = np.where(h < 1 - 1e-10, e / (1 - h), np.nan)
    return coef, y - loo


def _fit_rbf(u, y):
    from scipy.interpolate import RBFInterpolator

    rbf = RBFInterpolator(u, y, kernel="thin_plate_spline", degree=1)
    loo = np.empty_like(y)
    for i in range(len(y)):
        m = np.ones(len(y), bool)
        m[i] = False
        try:
            loo[i] = RBFInterpolator(u[m], y[m], kernel="thin_plate_spline", degree=1)(u[i : i + 1])[0]
        except (np.linalg.LinAlgError, ValueError):
            loo[i] = np.nan
    return rbf, loo


def fit(x, y, lower, upper, kind: str = "auto") -> Metamodel:
    """Fit a metamodel of y (n,) at variable values x (n, d)."""
    x = np.atleast_2d(np.asarray(x, float))
    y = np.asarray(y, float)
    ok = np.isfinite(y) & np.all(np.isfinite(x), axis=1)
    x, y = x[ok], y[ok]
    lower, upper = np.asarray(lower, float), np.asarray(upper, float)
    n, d = x.shape
    if kind == "auto":
        kinds = [k for k in ("quadratic", "rbf", "linear") if n >= n_terms(k, d) + 1]
        if not kinds:
            raise ValueError(f"metamodel: {n} designs for {d} variables; at least {d + 2} are needed")
        fits = [fit(x, y, lower, upper, k) for k in kinds]
        return min(fits, key=lambda m: m.loo_rmse if np.isfinite(m.loo_rmse) else np.inf)
    need = n_terms(kind, d)
    if n < need:
        raise ValueError(f"metamodel {kind}: {n} designs for {d} variables; at least {need} are needed")
    u = (x - lower) / (upper - lower)
    coef = rbf = None
    if kind in ("linear", "quadratic"):
        coef, loo = _fit_poly(u, y, kind)
    elif kind == "rbf":
        rbf, loo = _fit_rbf(u, y)
    else:
        raise ValueError(f"unknown metamodel {kind!r} (auto, linear, quadratic, rbf)")
    err = y - loo
    good = np.isfinite(err)
    rmse = float(np.sqrt(np.mean(err[good] ** 2))) if good.any() else float("nan")
    sst = float(np.sum((y - y.mean()) ** 2))
    r2 = float(1.0 - np.sum(err[good] ** 2) / sst) if sst > 0 and good.all() else float("nan")
    return Metamodel(kind, lower, upper, rmse, r2, n, coef, rbf, loo)
