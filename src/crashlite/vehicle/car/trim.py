"""Mass trim: lumped masses that bring a structure to a target mass and CoG.

Each mass group is spread evenly over its nodes, so it acts at the mean of
their coordinates. The group masses m_i solve

    Σ m_i = M − M_s,    Σ m_i c_i = M·G − M_s·G_s

(M, G the target mass and centre of gravity, M_s, G_s the structure's) and
stay as close as they can to the nominal masses scaled to the mass needed:
minimum Σ ((m_i − m0_i)/m0_i)², a weighted least-norm correction; groups
driven negative are dropped and the rest solved again.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike


def solve(
    base_mass: float,
    base_cog: ArrayLike,
    centres: ArrayLike,
    nominal: ArrayLike,
    mass: float,
    cog: ArrayLike,
    tol: float = 1e-9,
) -> np.ndarray:
    """Group masses (k,) [mass units of the inputs]; ``centres`` (k, 3) the
    group centres. Raises ValueError when the target cannot be reached with
    non-negative group masses."""
    centres = np.asarray(centres, float)
    nominal = np.asarray(nominal, float)
    need = mass - base_mass
    if need <= 0:
        raise ValueError(f"the structure alone ({base_mass:.6g}) is at least the target mass ({mass:.6g})")
    if np.any(nominal <= 0):
        raise ValueError("nominal group masses must be > 0")
    m0 = nominal * need / nominal.sum()
    a = np.vstack([np.ones(len(m0)), centres.T])  # (4, k)
    b = np.concatenate([[need], mass * np.asarray(cog, float) - base_mass * np.asarray(base_cog, float)])
    scale = np.array([1.0, *np.abs(centres).max(axis=0).clip(1.0)])  # equations of comparable size
    a, b = a / scale[:, None], b / scale
    free = np.ones(len(m0), bool)
    m = m0.copy()
    for _ in range(len(m0)):
        af = a[:, free]
        w = m0[free] ** 2
        r = b - af @ m0[free]
        lam = np.linalg.lstsq((af * w) @ af.T, r, rcond=None)[0]
        m = np.zeros_like(m0)
        m[free] = m0[free] + w * (af.T @ lam)
        if not np.any(m < 0):
            break
        free &= m > 0
    if np.any(m < 0) or np.abs(a @ m - b).max() > tol * max(1.0, np.abs(b).max()):
        raise ValueError(
            "the target mass and centre of gravity cannot be reached with non-negative "
            "lumped masses at the mass groups' positions"
        )
    return m
