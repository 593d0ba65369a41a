"""The surrogate's connection of its interface to its rear body, against the structure it replaces.

With one rigid interface body (the default), the springs and the
anti-rotation beam join two rigid bodies: whatever their layout, the front
structure feels them only through one 6×6 stiffness at the interface. The
replaced structure's own 6×6, held by its inertia as in the crash, comes
from the inertia-relief solve of step 3 (``relief``: its flexibility C).
``compare_connection`` sets the two side by side, per direction of the
vehicle frame (axial, lateral, vertical, roll, pitch, yaw):

- the compliance under a load on that direction alone at the interface
  centre, every other direction free (what a force along the axis or a
  yawing moment through the interface meets), and the surrogate's over
  the structure's;
- the stiffness with every other direction held, likewise.

The springs carry axial force, pitch and yaw by their spread over the cut;
the beam, a cantilever from the rear-axle node, carries lateral and
vertical shear and roll, and with them bending about the transverse axes
(4·EI/L at its end). A ratio far from 1 says in which direction the
surrogate moves the interface too little or too much relative to the rear.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from ..steps.stiffness import vehicle_axes

if TYPE_CHECKING:
    from ..steps.surrogate import Surrogate

DIRECTIONS = ("axial", "lateral", "vertical", "roll", "pitch", "yaw")


def _skew(v: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def moved_to(k: np.ndarray, at: np.ndarray, point: np.ndarray) -> np.ndarray:
    """A 6×6 stiffness on a rigid body's motion [u; θ] at ``at`` expressed
    for its motion at ``point`` (u_at = u_point + θ × (at − point))."""
    t = np.eye(6)
    t[:3, 3:] = -_skew(np.asarray(at, float) - np.asarray(point, float))
    return t.T @ k @ t


def spring_stiffness(k: float, front: np.ndarray, direction: np.ndarray, point: np.ndarray) -> np.ndarray:
    """6×6 at ``point`` of an axial spring k along ``direction`` through ``front``
    from a body held fixed: k·a·aᵀ, a = [d; (front − point) × d]."""
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    a = np.concatenate([d, np.cross(np.asarray(front, float) - point, d)])
    return k * np.outer(a, a)


def beam_end_stiffness(held: np.ndarray, end: np.ndarray, ea: float, ei: float, gj: float) -> np.ndarray:
    """6×6 (global axes) at ``end`` of an Euler–Bernoulli beam from ``held``
    (fixed) to ``end``: EA/L, GJ/L and, in both bending planes, 12·EI/L³,
    4·EI/L and their coupling 6·EI/L²."""
    e1 = np.asarray(end, float) - np.asarray(held, float)
    length = float(np.linalg.norm(e1))
    e1 /= length
    ref = np.array([0.0, 0.0, 1.0]) if abs(e1[2]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e2 = np.cross(ref, e1)
    e2 /= np.linalg.norm(e2)
    e3 = np.cross(e1, e2)
    b = ei / length**3
    k = np.zeros((6, 6))
    k[0, 0], k[3, 3] = ea / length, gj / length
    k[1, 1] = k[2, 2] = 12.0 * b
    k[5, 5] = k[4, 4] = 4.0 * b * length**2
    k[1, 5] = k[5, 1] = -6.0 * b * length  # v along e2 turns the end about e3 the other way
    k[2, 4] = k[4, 2] = 6.0 * b * length
    r = np.zeros((6, 6))
    r[:3, :3] = r[3:, 3:] = np.column_stack([e1, e2, e3])
    return r @ k @ r.T


def connection_stiffness(sur: Surrogate, point: ArrayLike) -> np.ndarray:
    """6×6 of the surrogate's springs and anti-rotation beam at ``point``:
    the interface body's motion against the rear body (one interface body)."""
    if sur.interface != "rigid":
        raise ValueError("one 6×6 connection only joins one interface body to the rear body (interface='rigid')")
    point = np.asarray(point, float)
    k = sum((spring_stiffness(s.k, s.front, s.direction, point) for s in sur.springs), np.zeros((6, 6)))
    xyz = dict(zip(sur.model.nodes.ids.tolist(), sur.model.nodes.xyz))
    held, end = xyz[int(sur.node_ids["axle"])], xyz[int(sur.node_ids["interface centre"])]
    b = sur.beam
    beam = beam_end_stiffness(held, end, b["axial_stiffness"] * b["length"], b["EI"], b["GJ"])
    return k + moved_to(beam, end, point)


def vehicle_frame(axis: ArrayLike) -> np.ndarray:
    """6×6 rotation into the frame (axis, lateral, vertical) of ``stiffness.vehicle_axes``."""
    f = vehicle_axes(axis)
    r = np.zeros((6, 6))
    r[:3, :3] = r[3:, 3:] = f
    return r


def compare_connection(k_surrogate: np.ndarray, flexibility: np.ndarray, axis: ArrayLike) -> dict:
    """Per direction of the vehicle frame: compliance (that load alone, the
    rest free) and stiffness (the rest held) of the surrogate and of the
    structure, and the surrogate's over the structure's (module docstring)."""
    r = vehicle_frame(axis)
    c_sur = r @ np.linalg.inv(k_surrogate) @ r.T
    c_str = r @ flexibility @ r.T
    k_sur = r @ k_surrogate @ r.T
    k_str = np.linalg.inv(c_str)
    out = {}
    for j, name in enumerate(DIRECTIONS):
        out[name] = {
            "structure_compliance": float(c_str[j, j]),
            "surrogate_compliance": float(c_sur[j, j]),
            "compliance_ratio": float(c_sur[j, j] / c_str[j, j]),
            "stiffness_ratio_held": float(k_sur[j, j] / k_str[j, j]),
        }
    worst = max(out, key=lambda n: abs(np.log(out[n]["compliance_ratio"])))
    return {
        "directions": out,
        "largest_compliance_misfit": {"direction": worst, "ratio": out[worst]["compliance_ratio"]},
    }
