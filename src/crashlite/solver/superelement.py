"""Linear superelements (*ELEMENT_DIRECT_MATRIX_INPUT) in the time loop.

A superelement is a symmetric stiffness matrix K on translational DOFs of
grid points (nodes), read from the DMIG file its keyword names. It returns
f = −K (x − x₀) on those DOFs and stores ½ uᵀKu as internal energy (exact
for a linear element, so the energy balance closes). It is linear in the
displacements: rigid translations are free to any size, rotations to
first order (a car's pitch of 1° over 1.5 m leaves 0.2 mm of spurious
deformation). Its stable step, from the largest eigenvalue of M^-½ K M^-½
with each node's mass halved (a node shares its mass with the elements
beside it), is computed once. A mass matrix is lumped by row sums;
damping matrices and rotational DOFs are refused.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..keyword.dmig import matrix_file, read_dmig
from ..keyword.errors import Problem
from ..model.model import Model
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
        self.m = masses  # per element (k,) lumped mass per DOF or None
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

    def lumped(self, n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
        mass = np.zeros(n_nodes)
        for nodes, comps, m in zip(self.dof_nodes, self.dof_comps, self.m):
            if m is not None:  # a node's mass from its x DOF (a lumped matrix repeats it on y and z)
                x = comps == 0
                np.add.at(mass, nodes[x], m[x])
        return mass, np.zeros(n_nodes)

    def forces(self, st: State) -> None:
        for e, (n, c, k) in enumerate(zip(self.dof_nodes, self.dof_comps, self.k)):
            self.energy[e] = matrix_forces(k, st.x, self._x0[e], n, c, self._u[e], self._f[e], st.f)

    def critical_dt(self, st: State) -> float:
        if getattr(st, "mass", None) is None:  # asked for the elements' geometric steps only (contact SOFT = 1)
            return np.inf
        if self._dt is None:
            self._dt = np.full(len(self.ids), np.inf)
            for e, (n, _c, k) in enumerate(zip(self.dof_nodes, self.dof_comps, self.k)):
                m = 0.5 * st.mass[n]  # shared with the elements beside it
                free = m > 0  # massless DOFs (rigid-body nodes) move with something heavier
                s = 1.0 / np.sqrt(m[free])
                lam = (
                    float(np.linalg.eigvalsh(k[np.ix_(free, free)] * s[:, None] * s[None, :])[-1])
                    if free.any()
                    else 0.0
                )
                if lam > 0:
                    self._dt[e] = 2.0 / np.sqrt(lam)
        return float(self._dt.min()) if len(self._dt) else np.inf

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
            lump = np.abs(mm).sum(axis=1)
            mass = np.array([lump[at[tuple(d)]] if tuple(d) in at else 0.0 for d in dofs.tolist()])
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
