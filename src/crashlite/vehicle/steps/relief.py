"""Longitudinal stiffness of the replaced structure under inertia relief.

Step 3 of the paper bears the replaced structure at the rear-axle points
and pushes its rigid interface: K_axle = F / u. In the crash nothing holds
the rear axle; the interface force decelerates the replaced structure's own
mass, spread over all of it. The surrogate's springs join the interface to
one rigid body with that mass at its CoG, so under a steady deceleration
they shorten by the interface's displacement *relative to the structure's
mean rigid motion*. Inertia relief (as in NASTRAN's INREL) computes exactly
that:

- the free structure is loaded by F on the rigid interface and by its
  nodes' d'Alembert forces −m_i (a + α × (r_i − c)), with a = F / M and
  α = I_c⁻¹ ((p − c) × F) so that the loads are in equilibrium;
- six support DOFs on three nodes (3-2-1, statically determinate) remove
  the rigid modes without reacting anything;
- the rigid motion that best fits the displacements in the mass metric is
  taken out, and K_relief = F / u_def with u_def the interface's remaining
  displacement along F.

A uniform bar pushed at one end this way shortens to its centre of mass by
F·L / (3·EA): K_relief = 3·EA/L, three times the bar held at its far end
(test). On a vehicle the rear structure between the seats and the axle, which
the axle-borne K counts in full, carries only the inertia behind it, so
K_relief is several times K_axle.

The same holds across the axis: pushed sideways or twisted, the interface
moves relative to the structure's mean rigid motion by what the
structure's own inertia bends or twists it. A uniform beam pushed across
at one end comes to 105·EI/L³ (35 times the cantilever's 3·EI/L³), twisted
to 3·GJ/L (three times GJ/L held at the far end). The surrogate's beam
takes its shear and roll stiffness from these when its springs do.
"""

from __future__ import annotations

import itertools

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from ...model import mass as mk
from .cut import Cut
from .massprops import NodeSelection, _given_inertia, element_moments, node_indices
from .statics import LinearStatic
from .stiffness import (
    StiffnessResult,
    build_static,
    solve_named,
    transverse_loads,
    transverse_stiffnesses,
    vehicle_axes,
)

_NODES = {"shells": lambda t: t.nodes, "solids": lambda t: t.nodes, "beams": lambda t: t.nodes[:, :2]}


def replaced_node_masses(cut: Cut) -> tuple[np.ndarray, list]:
    """(n_nodes,) the replaced structure's mass lumped to its nodes (each
    element's mass shared evenly by its distinct nodes, point masses on
    removed nodes) and notes."""
    model = cut.model
    m = np.zeros(len(model.nodes))
    notes = []
    moments = element_moments(model)
    for t, mom in moments.items():
        sel = cut.replaced[t]
        if not sel.any():
            continue
        conn = np.asarray(_NODES[t](getattr(model, t)), np.int64)[sel]
        valid = conn >= 0
        for j in range(1, conn.shape[1]):  # a repeated node (degenerate element) counts once
            valid[:, j] &= np.all(conn[:, :j] != conn[:, j : j + 1], axis=1)
        w = mom.mass[sel] / valid.sum(axis=1)
        np.add.at(m, conn[valid], np.broadcast_to(w[:, None], conn.shape)[valid])
    for tab in (model.masses, model.inertias):
        if len(tab):
            sel = cut.removed_nodes[tab.node]
            np.add.at(m, tab.node[sel], tab.mass[sel])
    if any(_given_inertia(p) is not None for p in model.parts.values()):
        notes.append("*PART_INERTIA values are not lumped: the parts' element masses are used")
    return m, notes


def static_masses(cut: Cut, ls: LinearStatic) -> tuple:
    """The replaced mass on the nodes of the static model ``ls`` (masses on
    nodes it lacks cannot be loaded): (node masses, the nodes with mass,
    total, CoG, notes)."""
    m, notes = replaced_node_masses(cut)
    m[~ls.in_structure] = 0.0
    carry = np.flatnonzero(m > 0)
    big_m = float(m.sum())
    if not big_m > 0:
        raise ValueError("the replaced structure has no mass")
    c = (m[carry, None] * cut.model.nodes.xyz[carry]).sum(axis=0) / big_m
    return m, carry, big_m, c, notes


def mass_matrix(ls: LinearStatic, m: np.ndarray) -> sp.dia_matrix:
    """(6·n_total)² diagonal: the node masses ``m`` (of ``static_masses``) on
    the static model's translations; rotations carry none."""
    diag = np.zeros(6 * ls.n_total)
    for i in range(3):
        diag[6 * np.arange(ls.n) + i] = m
    return sp.diags(diag)


def _support_321(xyz: np.ndarray, candidates: np.ndarray) -> list:
    """Three nodes and six DOFs among ``candidates`` that hold the rigid
    modes and nothing more: [(node, dofs), ...] with the best conditioning."""
    p = xyz[candidates]
    c = p.mean(axis=0)
    a = candidates[np.argmin(np.linalg.norm(p - c, axis=1))]
    b = candidates[np.argmax(np.linalg.norm(p - xyz[a], axis=1))]
    e = xyz[b] - xyz[a]
    e /= np.linalg.norm(e)
    off = np.cross(p - xyz[a], e)
    cc = candidates[np.argmax(np.linalg.norm(off, axis=1))]
    best, pick = -1.0, None
    for pair in itertools.combinations(range(3), 2):
        for k in range(3):
            rows = [(a, d) for d in range(3)] + [(b, d) for d in pair] + [(cc, k)]
            g = np.zeros((6, 6))  # constrained displacement components of the six rigid modes
            for i, (n, d) in enumerate(rows):
                r = xyz[n] - c
                g[i, d] = 1.0
                g[i, 3:] = np.cross(r, np.eye(3)[d])  # (θ × r)_d = θ · (r × e_d)
            s = np.linalg.svd(g, compute_uv=False)
            if s[-1] / s[0] > best:
                best, pick = s[-1] / s[0], rows
    if best < 1e-6:
        raise ValueError("the replaced structure's nodes lie on a line: no 3-2-1 support")
    out: dict = {}
    for n, d in pick:
        out.setdefault(int(n), []).append(d)
    return list(out.items())


def _rigid_fit(r: np.ndarray, u: np.ndarray, w: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Translation t and small rotation θ about c minimising Σ w |u − t − θ × (r − c)|²."""
    d = r - c
    a = np.zeros((len(r), 3, 6))
    a[:, :, :3] = np.eye(3)
    a[:, 0, 4], a[:, 0, 5] = d[:, 2], -d[:, 1]  # θ × d = (θy dz − θz dy, θz dx − θx dz, θx dy − θy dx)
    a[:, 1, 3], a[:, 1, 5] = -d[:, 2], d[:, 0]
    a[:, 2, 3], a[:, 2, 4] = d[:, 1], -d[:, 0]
    sw = np.sqrt(w)[:, None, None]
    sol = np.linalg.lstsq((a * sw).reshape(-1, 6), (u[:, :, None] * sw).reshape(-1), rcond=None)[0]
    return sol[:3], sol[3:]


def relieved_stiffness(
    cut: Cut,
    force: float = 1000.0,
    direction: ArrayLike | None = None,
    interface_nodes: NodeSelection | None = None,
    drill: float = 1e-3,
    transverse: tuple | None = None,
) -> StiffnessResult:
    """K of the replaced structure of ``cut`` under inertia relief (module
    docstring): the rigid interface (default: all cut nodes) pushed with
    ``force`` along ``direction`` (default −axis), the structure's mass
    reacting it. ``transverse`` = (force, moment): also pushed across the
    direction and twisted about it, each reacted by the inertia likewise, on
    the same factorisation (``StiffnessResult.transverse``: lateral,
    vertical, shear = the softer, roll) and, with the interface also twisted
    about both transverse directions, its whole 6×6 flexibility
    (``StiffnessResult.flexibility``: the interface's displacement and
    rotation relative to the structure's best-fit rigid motion per unit
    force and moment on it, global axes, at ``load_point``)."""
    model = cut.model
    d = -cut.axis if direction is None else np.asarray(direction, float)
    d = d / np.linalg.norm(d)
    ls, counts, notes = build_static(model, cut.replaced, drill)
    nodes = cut.interface_nodes if interface_nodes is None else node_indices(model, interface_nodes)
    nodes = nodes[ls.in_structure[nodes]]
    if not len(nodes):
        raise ValueError("no interface node is a node of the replaced structure")
    master = ls.add_rigid(nodes)
    m, carry, big_m, c, mnotes = static_masses(cut, ls)
    xyz = model.nodes.xyz
    i_c = mk.combine(mk.point_moments(xyz[carry], m[carry])).inertia
    p = ls.position(master)
    across = {} if transverse is None else transverse_loads(d, *transverse)
    turns = {} if transverse is None else _turns(d, transverse[1])
    pushes = [(force * d, np.zeros(3))] + list(across.values()) + list(turns.values())
    cases = []
    for f, mom in pushes:  # the interface load and the d'Alembert forces that balance it
        alpha = np.linalg.pinv(i_c) @ (np.cross(p - c, f) + mom)
        loads = {master: np.concatenate([f, mom])}
        inertia = -m[carry, None] * (f / big_m + np.cross(alpha, xyz[carry] - c))
        for n, v in zip(carry.tolist(), inertia):
            loads[n] = np.concatenate([v, np.zeros(3)])
        cases.append(loads)
    cand = np.flatnonzero(ls.in_structure & ~ls.tied())  # (a held node of a rigid group would hold the group)
    for n, dofs in _support_321(xyz, cand):
        ls.fix([n], dofs)
    sol, *others = solve_named(ls, model, cases)

    def relative(s):  # the interface's motion less the structure's best-fit rigid motion: (3,), (3,)
        t, th = _rigid_fit(xyz[carry], s.u[: ls.n, :3][carry], m[carry], c)
        return s.u[master, :3] - (t + np.cross(th, p - c)), s.u[master, 3:] - th

    u_def = float(relative(sol)[0] @ d)
    if not u_def > 0:
        raise ValueError(f"the interface moves {u_def:.3g} along the load relative to the structure: not stable")
    motions = [relative(o) for o in others]
    trans = transverse_stiffnesses(across, motions[: len(across)]) if across else None
    flex = None
    if across:  # response = C · load over the six independent load cases: C = R G⁻¹
        g = np.array([np.concatenate(fm) for fm in pushes]).T
        r = np.array([np.concatenate(relative(x)) for x in [sol] + others]).T
        flex = r @ np.linalg.inv(g)
        flex = 0.5 * (flex + flex.T)  # symmetric to round-off (Maxwell–Betti)
    for s in [sol] + others:
        if np.linalg.norm(s.reaction_force) > 1e-6 * force:
            notes.append(f"the 3-2-1 support reacts {np.linalg.norm(s.reaction_force):.3g} (loads not in equilibrium)")
    return StiffnessResult(
        force / u_def,
        float(force),
        u_def,
        d,
        p,
        sol.u[master].copy(),
        sol.reaction_force,
        counts,
        sol.n_dofs,
        list(cut.notes) + notes + mnotes + sol.notes,
        sol,
        np.flatnonzero(ls.in_structure),
        trans,
        flex,
    )


def _turns(axis: np.ndarray, moment: float) -> dict:
    """The interface twisted about the two transverse directions (pitch and
    yaw for a car): with the ``transverse_loads`` cases, six independent
    loads that give the interface's whole 6×6 flexibility."""
    _, e_lat, e_ver = vehicle_axes(axis)
    return {"pitch": (np.zeros(3), e_lat * moment), "yaw": (np.zeros(3), e_ver * moment)}
