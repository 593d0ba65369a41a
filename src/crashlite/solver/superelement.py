"""Linear superelements (*ELEMENT_DIRECT_MATRIX_INPUT) in the time loop.

A superelement is a symmetric stiffness matrix K on translational DOFs of
grid points (nodes), read from the DMIG file its keyword names. It returns
f = −K (x − x₀) on those DOFs and stores ½ uᵀKu as internal energy (exact
for a linear element, so the energy balance closes). It is linear in the
displacements: rigid translations are free to any size, rotations to
first order (a car's pitch of 1° over 1.5 m leaves 0.2 mm of spurious
deformation). Its stable step, from the largest eigenvalue of M^-½ K M^-½
with each node's mass halved (a node shares its mass with the elements
beside it), is computed once. A mass matrix (DMIG ``MASS``) is solved as
given on the superelements' DOFs (``consistent``): a reduced structure's
mass is dense, and lumping it loses the coupling of its boundary to its
interior and its modes; with a mass matrix the stable step comes from the
generalised eigenvalues of K against M plus half the rest of the nodes'
mass. Damping matrices and rotational DOFs are refused.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..keyword.dmig import matrix_file, read_dmig
from ..keyword.errors import Problem
from ..model.model import Model
from .consistent import ConsistentMass
from .groups import ElementGroup
from .kernels.matrix import matrix_forces
from .state import State


class SuperelementGroup(ElementGroup):
    """One or more linear superelements (one matrix each)."""

    kind = "superelement"
    in_parts = False  # no part: its energy counts in glstat, not matsum

    def __init__(self, ids, dof_nodes: list, dof_comps: list, stiffness: list, masses: list, x0: np.ndarray):
        self.ids = np.asarray(ids, np.int64)
        self.pid = np.zeros(len(self.ids), np.int64)
        self.dof_nodes = dof_nodes  # per element (k,) node index of each DOF
        self.dof_comps = dof_comps  # per element (k,) component 0–2
        self.k = stiffness
        self.m = masses  # per element (k, k) mass matrix on its DOFs, or None
        self.nodes = [np.unique(n) for n in dof_nodes]
        width = max((len(n) for n in self.nodes), default=0)
        self.conn = np.full((len(self.ids), width), -1, np.int64)
        for e, n in enumerate(self.nodes):
            self.conn[e, : len(n)] = n
        self.energy = np.zeros(len(self.ids))
        self._f = [np.zeros(len(n)) for n in dof_nodes]  # force on each DOF
        self._u = [np.zeros(len(n)) for n in dof_nodes]
        self._x0 = [x0[n, c].copy() for n, c in zip(dof_nodes, dof_comps)]
        self._dt = None  # (ne,) stable steps, computed once the masses are known

    @staticmethod
    def _dof_lumped(m: np.ndarray, comps: np.ndarray) -> np.ndarray:
        """(k,) a mass matrix's lumped mass per DOF: the row's sum over the
        DOFs of the same component (the mass moving with a unit translation),
        its diagonal where that is not positive."""
        same = comps[:, None] == comps[None, :]
        r = (m * same).sum(axis=1)
        return np.where(r > 0, r, np.diag(m))

    def node_lumped(self, n_nodes: int) -> np.ndarray:
        """(n_nodes,) the superelements' mass lumped on their nodes (the mean over each node's DOFs)."""
        total, count = np.zeros(n_nodes), np.zeros(n_nodes)
        for nodes, comps, m in zip(self.dof_nodes, self.dof_comps, self.m):
            if m is not None:
                np.add.at(total, nodes, self._dof_lumped(m, comps))
                np.add.at(count, nodes, 1.0)
        return np.where(count > 0, total / np.maximum(count, 1.0), 0.0)

    def lumped(self, n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
        return self.node_lumped(n_nodes), np.zeros(n_nodes)

    def consistent(self, n_nodes: int) -> ConsistentMass | None:
        """The superelements' mass matrices on the union of their DOFs, for the loop (``consistent``)."""
        if all(m is None for m in self.m):
            return None
        keys = np.unique(
            np.concatenate([3 * n + c for n, c, m in zip(self.dof_nodes, self.dof_comps, self.m) if m is not None])
        )
        pos = {int(k): i for i, k in enumerate(keys)}
        big = np.zeros((len(keys), len(keys)))
        for nodes, comps, m in zip(self.dof_nodes, self.dof_comps, self.m):
            if m is not None:
                at = np.array([pos[int(k)] for k in 3 * nodes + comps])
                big[np.ix_(at, at)] += m
        nodes, comps = keys // 3, keys % 3
        return ConsistentMass(nodes, comps, big, self.node_lumped(n_nodes)[nodes])

    def forces(self, st: State) -> None:
        for e, (n, c, k) in enumerate(zip(self.dof_nodes, self.dof_comps, self.k)):
            self.energy[e] = matrix_forces(k, st.x, self._x0[e], n, c, self._u[e], self._f[e], st.f)

    def critical_dt(self, st: State) -> float:
        if getattr(st, "mass", None) is None:  # asked for the elements' geometric steps only (contact SOFT = 1)
            return np.inf
        if self._dt is None:
            self._dt = np.full(len(self.ids), np.inf)
            own = self.node_lumped(len(st.mass))
            for e, (n, _c, k) in enumerate(zip(self.dof_nodes, self.dof_comps, self.k)):
                self._dt[e] = self._element_dt(k, self.m[e], st.mass[n], own[n])
            self._dt_min = float(self._dt.min()) if len(self._dt) else np.inf  # linear: the same every cycle
        return self._dt_min

    @staticmethod
    def _element_dt(k, m, node_mass, own) -> float:
        """2/ω_max: against half the nodes' lumped mass, or with a mass
        matrix against M plus half the rest of the nodes' mass (elements
        beside them); DOFs without mass move with something heavier."""
        if m is None:
            mass = 0.5 * node_mass
            free = mass > 0
            s = 1.0 / np.sqrt(mass[free])
            lam = float(np.linalg.eigvalsh(k[np.ix_(free, free)] * s[:, None] * s[None, :])[-1]) if free.any() else 0.0
        else:
            from scipy.linalg import eigh

            full = m + np.diag(0.5 * np.maximum(node_mass - own, 0.0))
            lam = float(eigh(k, full, eigvals_only=True, subset_by_index=[len(k) - 1, len(k) - 1])[0])
        return 2.0 / np.sqrt(lam) if lam > 0 else np.inf

    def corner_forces(self) -> np.ndarray:
        out = np.zeros(self.conn.shape + (3,))
        for e, (n, c) in enumerate(zip(self.dof_nodes, self.dof_comps)):
            col = np.searchsorted(self.nodes[e], n)
            np.add.at(out[e], (col, c), self._f[e])
        return out


def build_superelements(model: Model, problems: list) -> SuperelementGroup | None:
    """The *ELEMENT_DIRECT_MATRIX_INPUT of ``model`` as a group; problems
    name the file, line and field."""
    recs = model.find("ELEMENT_DIRECT_MATRIX_INPUT")
    if not recs:
        return None
    ids, dn, dc, ks, ms = [], [], [], [], []
    for rec in recs:
        src, line = rec.where("filename")

        def bad(field, msg):
            problems.append(Problem(src or model.source or "", line, "ELEMENT_DIRECT_MATRIX_INPUT", field, msg))  # noqa: B023

        path = matrix_file(rec, Path(model.source or ".").parent)
        if path is None:
            bad("FILENAME", "no matrix file named")
            continue
        try:
            mats = read_dmig(path)
        except (OSError, ValueError) as e:
            bad("FILENAME", f"cannot read the matrix file: {e}")
            continue
        stif = str(rec.get("stif", "") or "").strip()
        if stif not in mats:
            bad("STIF", f"no matrix {stif!r} in {path} (it has {sorted(mats)})")
            continue
        if str(rec.get("damp", "") or "").strip():
            bad("DAMP", "damping matrices are not supported yet")
            continue
        dofs, k = mats[stif]
        mass = None
        mname = str(rec.get("mass", "") or "").strip()
        if mname:
            if mname not in mats:
                bad("MASS", f"no matrix {mname!r} in {path}")
                continue
            mdofs, mm = mats[mname]
            at = {tuple(d): i for i, d in enumerate(mdofs.tolist())}
            extra = set(at) - set(map(tuple, dofs.tolist()))
            if extra:
                bad("MASS", f"matrix {mname!r} has DOFs that {stif!r} has not: {sorted(extra)[:5]}")
                continue
            sel = np.array([at.get(tuple(d), -1) for d in dofs.tolist()])
            mass = np.where(
                (sel[:, None] >= 0) & (sel[None, :] >= 0), mm[np.ix_(np.maximum(sel, 0), np.maximum(sel, 0))], 0.0
            )
            mass = np.ascontiguousarray(0.5 * (mass + mass.T))
        if np.any(dofs[:, 1] > 3) or np.any(dofs[:, 1] < 1):
            bad("STIF", "only translational DOFs (components 1–3) are supported")
            continue
        idx = model.node_index(dofs[:, 0])
        if np.any(idx < 0):
            bad("STIF", f"grid point(s) {dofs[idx < 0, 0][:5].tolist()} of the matrix are not nodes of the deck")
            continue
        ids.append(int(rec.get("eid", 0) or 0))
        dn.append(idx.astype(np.int64))
        dc.append(dofs[:, 1].astype(np.int64) - 1)
        ks.append(np.ascontiguousarray(k))
        ms.append(mass)
    if not ids:
        return None
    return SuperelementGroup(ids, dn, dc, ks, ms, model.nodes.xyz)
