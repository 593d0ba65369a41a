"""Stable time step of discrete elements (nodal rule)."""

import numpy as np

from .kernels.discrete import CURVE, DAMPER, GENERAL, INELASTIC
from .setup import Setup


def stiffness(d) -> np.ndarray:
    """Largest stiffness (damping constant for dampers) of each element:
    the steepest curve slope for non-linear springs, or KU if steeper."""
    k = np.abs(d.k * d.scale)

    def steepest(a, b):
        dx = np.diff(d.curve_x[a:b])
        slope = np.abs(np.diff(d.curve_y[a:b])[dx > 0] / dx[dx > 0])
        return slope.max() if len(slope) else 0.0

    for e in np.flatnonzero((d.kind == CURVE) | (d.kind == INELASTIC) | (d.kind == GENERAL)):
        s = steepest(d.curve_start[e], d.curve_stop[e])
        if d.kind[e] == GENERAL and d.ucurve_stop is not None:
            s = max(s, steepest(d.ucurve_start[e], d.ucurve_stop[e]))
        k[e] = abs(d.scale[e]) * max(s, abs(d.k[e]) if d.kind[e] == INELASTIC else 0.0)
    return k


def stable_dt(s: Setup) -> float:
    """TSSFAC × the smallest critical step: 2/ω with ω² = k (1/m1 + 1/m2)
    for springs (k the steepest curve slope for non-linear ones), and
    2 / (c (1/m1 + 1/m2)) for dampers; inf without such elements."""
    from .beams import beam_dt

    d = s.discrete
    dt_beam = beam_dt(s.beams, s.mass, s.rot_inertia) if s.beams is not None else np.inf
    if len(d.ids) == 0:
        return s.tssfac * dt_beam
    mass = s.mass.copy()
    for b in s.bodies:  # a body node moves with the body's effective mass at that point
        r2 = np.einsum("ij,ij->i", b.r_body, b.r_body)
        mass[b.nodes] = 1.0 / (1.0 / b.mass + r2 / np.linalg.eigvalsh(b.inertia_body)[0])
    inv = 1.0 / np.where((mass > 0) & ~s.fixed.all(axis=1), mass, np.inf)  # held nodes: ground
    inv_sum = inv[d.n1] + np.where(d.n2 >= 0, inv[np.maximum(d.n2, 0)], 0.0)
    k = stiffness(d)
    damper = d.kind == DAMPER
    with np.errstate(divide="ignore"):
        dt_spring = np.where(~damper & (k > 0), 2.0 / np.sqrt(k * inv_sum), np.inf)
        dt_damper = np.where(damper & (k > 0), 2.0 / (k * inv_sum), np.inf)
    dt = min(dt_spring.min(), dt_damper.min(), dt_beam)
    return s.tssfac * dt


def scale_masses(s: Setup, model_pids: np.ndarray | None = None) -> dict[int, float]:
    """Mass scaling (*CONTROL_TIMESTEP DT2MS): raise the nodal masses of
    elements whose critical step is below |DT2MS| so that it becomes |DT2MS|
    (the run then steps at TSSFAC·|DT2MS|). Returns the mass added per part
    of the elements that needed it."""
    target = abs(s.dt2ms)
    d = s.discrete
    added_by_part: dict[int, float] = {}
    if target <= 0:
        return added_by_part
    if s.beams is not None and s.rot_inertia is not None:
        from .beams import scale_beams

        extra = scale_beams(s.beams, s.mass, s.rot_inertia, target)
        pids = s.beam_pid if len(s.beam_pid) == len(extra) else np.zeros(len(extra), np.int64)
        for pid in np.unique(pids[extra > 0]):
            added_by_part[int(pid)] = float(extra[pids == pid].sum())
    if len(d.ids) == 0:
        return added_by_part
    k = stiffness(d)
    # 2/ω ≥ target with ω² = k (1/m1 + 1/m2): both node masses ≥ k·target²/2
    # (grounded elements: ≥ k·target²/4); dampers: 2/(c(1/m1+1/m2)) ≥ target
    # a fully constrained node acts as ground and gets no mass
    held = s.fixed.all(axis=1)
    grounded = (d.n2 < 0) | held[d.n1] | held[np.maximum(d.n2, 0)]
    need = np.where(d.kind == DAMPER, k * target * (np.where(grounded, 0.5, 1.0)),
                    k * target**2 * np.where(grounded, 0.25, 0.5))
    before = s.mass.copy()
    for nodes in (d.n1, d.n2):
        ok = nodes >= 0
        ok[ok] &= ~held[nodes[ok]]
        np.maximum.at(s.mass, nodes[ok], need[ok])
    added = s.mass - before
    if model_pids is not None:
        for e in range(len(d.ids)):
            for nd in (d.n1[e], d.n2[e]):
                if nd >= 0 and added[nd] > 0:
                    pid = int(model_pids[e])
                    added_by_part[pid] = added_by_part.get(pid, 0.0) + float(added[nd])
                    added[nd] = 0.0  # count each node once
    return added_by_part
