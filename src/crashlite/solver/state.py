"""The state of the time loop: the arrays every part of it (element groups,
constraints, walls, motions) reads and writes. Below every solver module
that takes it, so each can name its type."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class State:
    """The arrays every part of the loop reads and writes.

    x, v, f (n, 3): coordinates, half-step velocities, nodal forces;
    rot (n, 3, 3), w (n, 3), moment (n, 3): nodal rotations (integrated
    only when beams read them), angular velocities and moments (nodes with
    rotational inertia); mass, inv_mass,
    rot_inertia, inv_j (n,); fixed, fixed_rot (n, 3) held DOFs; t the time
    and dt the step just taken (0 at the first force evaluation).
    """

    x: np.ndarray
    v: np.ndarray
    f: np.ndarray
    rot: np.ndarray
    w: np.ndarray
    moment: np.ndarray
    mass: np.ndarray
    inv_mass: np.ndarray
    rot_inertia: np.ndarray
    inv_j: np.ndarray
    fixed: np.ndarray
    fixed_rot: np.ndarray
    t: float = 0.0
    dt: float = 0.0
