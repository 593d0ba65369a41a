"""Rigid motion that best fits a set of nodes, and displacements measured in it.

A crash test measures intrusion in a coordinate system fixed to the
passenger cell, so that the cell's pitch and yaw do not count; the same fit
applied to the nodes of an interface plane tells how far that plane is from
moving as one rigid body (its *warping*), which a rigid interface of a
simplified vehicle cannot follow.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike


def rigid_motion(p0: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(R, c0, c) of the rigid motion x ↦ R (x − c0) + c that best fits the
    nodes' initial positions p0 (k, 3) to their current ones p (least
    squares, Kabsch); fewer than three nodes: a translation only."""
    c0, c = p0.mean(axis=0), p.mean(axis=0)
    if len(p0) < 3:
        return np.eye(3), c0, c
    u, _, vt = np.linalg.svd((p0 - c0).T @ (p - c))
    d = np.sign(np.linalg.det(vt.T @ u.T))
    return vt.T @ np.diag([1.0, 1.0, d]) @ u.T, c0, c


def rearward_in_frame(
    x: np.ndarray, x0: np.ndarray, nodes: np.ndarray, frame: np.ndarray, axis: int | ArrayLike
) -> np.ndarray:
    """Rearward displacement of ``nodes`` along ``axis`` (an index 0–2 or a
    unit vector, the driving direction) in the frame of the ``frame`` nodes
    (their best-fitting rigid motion; positions x, initial x0)."""
    r, c0, c = rigid_motion(x0[frame], x[frame])
    local = (x[nodes] - c) @ r + c0  # back into the frame's initial position: Rᵀ (x − c) + c0
    a = np.eye(3)[axis] if np.ndim(axis) == 0 else np.asarray(axis, float)
    return -((local - x0[nodes]) @ a)


def warping(x: np.ndarray, x0: np.ndarray, nodes: np.ndarray, axis: int | ArrayLike) -> np.ndarray:
    """(k,) displacement of each of ``nodes`` along ``axis`` away from the
    rigid motion that best fits them all (0 for a plane that moves rigidly);
    positive rearwards."""
    return rearward_in_frame(x, x0, nodes, nodes, axis)


def warping_history(xs: np.ndarray, x0: np.ndarray, nodes: np.ndarray, axis: int | ArrayLike) -> dict:
    """Largest |warping| of ``nodes`` over the states xs (m, n, 3) and the
    largest root mean square over the nodes of one state, with the state
    index of each [length]."""
    if len(nodes) < 3 or len(xs) == 0:
        return {"max": 0.0, "rms": 0.0, "state_of_max": 0, "state_of_rms": 0}
    w = np.array([warping(x, x0, nodes, axis) for x in xs])
    peak = np.abs(w).max(axis=1)
    rms = np.sqrt((w * w).mean(axis=1))
    return {
        "max": float(peak.max()),
        "rms": float(rms.max()),
        "state_of_max": int(peak.argmax()),
        "state_of_rms": int(rms.argmax()),
    }
