"""Stable time step of discrete elements (nodal rule)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .discretes import Discrete
from .groups import ElementGroup
from .kernels.discrete import CURVE, DAMPER, GENERAL, INELASTIC
from .setup import Setup
from .state import State


def stiffness(d: Discrete) -> np.ndarray:
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


def effective_mass(s: Setup) -> np.ndarray:
    """(n,) nodal masses for the nodal rule: a rigid-body node moves with
    the body's smallest effective mass at that point (translation and
    rotation, rigid.RigidBody.inverse_mass_at) [mass]."""
    mass = s.mass.copy()
    for b in s.bodies:
        mass[b.nodes] = 1.0 / b.inverse_mass_at(b.r_body)
    return mass


def effective_rot_inertia(s: Setup) -> np.ndarray:
    """(n,) nodal rotational inertias for the beams' rotation rule: a
    rigid-body node turns with its body, whose smallest principal inertia
    stands in [mass·length²]."""
    inertia = s.rot_inertia.copy() if s.rot_inertia is not None else np.zeros(len(s.mass))
    for b in s.bodies:
        inertia[b.nodes] = float(np.linalg.eigvalsh(b.inertia_body)[0])
    return inertia


def beam_steps(s: Setup) -> np.ndarray:
    """(n_beams,) critical step of each beam with the effective masses and
    inertias of its end nodes (a beam between rigid bodies moves them)."""
    from .beams import element_dt

    return element_dt(s.beams, effective_mass(s), effective_rot_inertia(s))


def stable_dt(s: Setup) -> float:
    """TSSFAC × the smallest critical step: 2/ω with ω² = k (1/m1 + 1/m2)
    for springs (k the steepest curve slope for non-linear ones), and
    2 / (c (1/m1 + 1/m2)) for dampers; inf without such elements."""
    d = s.discrete
    dt_beam = float(np.nanmin(beam_steps(s))) if s.beams is not None and len(s.beams.ids) else np.inf
    if len(d.ids) == 0:
        return s.tssfac * dt_beam
    return s.tssfac * min(float(discrete_dt(s).min()), dt_beam)


def discrete_dt(s: Setup) -> np.ndarray:
    """(n_discrete,) critical step of each discrete element (nodal rule,
    without TSSFAC; inf for elements with nothing to resolve) [time]."""
    d = s.discrete
    mass = effective_mass(s)
    inv = 1.0 / np.where((mass > 0) & ~s.fixed.all(axis=1), mass, np.inf)  # held nodes: ground
    inv_sum = inv[d.n1] + np.where(d.n2 >= 0, inv[np.maximum(d.n2, 0)], 0.0)
    k = stiffness(d)
    damper = d.kind == DAMPER
    with np.errstate(divide="ignore", invalid="ignore"):
        dt_spring = np.where(~damper & (k > 0), 2.0 / np.sqrt(k * inv_sum), np.inf)
        dt_damper = np.where(damper & (k > 0), 2.0 / (k * inv_sum), np.inf)
    return np.minimum(dt_spring, dt_damper)


# a step that would need more cycles than this to reach the end time is no step: the run would not end
MAX_CYCLES = 1e9


def smallest_step(s: Setup, groups: Sequence[ElementGroup], st: State) -> tuple[float, str]:
    """(step, description) of the element with the smallest critical step
    (TSSFAC applied), naming it, its nodes and, for rigid-body nodes, the
    body and its effective mass there; for diagnoses."""
    ids = s.node_ids if s.node_ids is not None else np.arange(len(s.mass))
    body_of = {int(i): b for b in s.bodies for i in b.nodes}
    mass = effective_mass(s)

    def node(i: int) -> str:
        b = body_of.get(int(i))
        text = f"node {int(ids[i])}"
        if b is not None:
            return text + f" (of rigid body {b.body_id}, effective mass {mass[i]:.4g} there)"
        return text + f" (mass {s.mass[i]:.4g})"

    found: list[tuple[float, str]] = []

    def lowest(dts: np.ndarray, name: str, eids, nodes_of) -> None:
        dts = np.asarray(dts, float)
        if not len(dts):
            return
        bad = np.isnan(dts)
        e = int(np.flatnonzero(bad)[0]) if bad.any() else int(np.argmin(dts))
        found.append(
            (
                float(dts[e]) * s.tssfac,
                f"*ELEMENT_{name} {int(eids[e])} on " + ", ".join(node(i) for i in nodes_of(e) if i >= 0),
            )
        )

    d = s.discrete
    if len(d.ids):
        lowest(discrete_dt(s), "DISCRETE", d.ids, lambda e: (d.n1[e], d.n2[e]))
    if s.beams is not None and len(s.beams.ids):
        b = s.beams
        lowest(beam_steps(s), "BEAM", b.ids, lambda e: (b.n1[e], b.n2[e]))
    for g in groups:
        if hasattr(g, "critical_dt") and hasattr(g, "_dt") and len(g.ids):
            g.critical_dt(st)
            lowest(g._dt, g.kind.upper(), g.ids, lambda e, g=g: tuple(dict.fromkeys(g.conn[e].tolist())))
    if not found:
        return np.inf, "no element with a time step"
    nan = [f for f in found if np.isnan(f[0])]
    return nan[0] if nan else min(found, key=lambda f: f[0])


def step_problem(dt: float, t: float, end_time: float, end_cycle: int) -> str | None:
    """Why ``dt`` at time t is no usable step (None when it is): not a
    number, not positive, or so small that the run would not end."""
    if np.isnan(dt):
        return f"the stable time step at t = {t:.6g} is not a number"
    if not dt > 0:
        return f"the stable time step at t = {t:.6g} is {dt:.4g}"
    cycles = (end_time - t) / dt
    if cycles > MAX_CYCLES and not (0 < end_cycle <= MAX_CYCLES):
        return (
            f"the stable time step at t = {t:.6g} is {dt:.4g}: {cycles:.3g} more cycles to the end time "
            f"{end_time:.6g}, the run would not end"
        )
    return None


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
    need = np.where(
        d.kind == DAMPER, k * target * (np.where(grounded, 0.5, 1.0)), k * target**2 * np.where(grounded, 0.25, 0.5)
    )
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
