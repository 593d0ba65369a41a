"""Linear static finite-element solve with rigid links (step 3's engine).

``LinearStatic`` collects element stiffness blocks (``vehicle.steps.elements``)
on the nodes of a model, rigid groups (nodes moving with a master node:
u_s = u_m + θ_m × (x_s − x_m), θ_s = θ_m), fixed degrees of freedom and
nodal loads, and solves K u = f:

- assembly in scipy.sparse (COO summed to CSR block by block);
- rigid groups and fixed DOFs by elimination, K_r = Tᵀ K T with the sparse
  transformation T from the independent DOFs to all DOFs; groups that share
  nodes are merged (the master of the first one leads, the others' masters
  follow it); a group with a fixed node is fixed whole;
- DOFs without stiffness (rotations of nodes with only springs or solids,
  unused nodes) are held and counted in ``notes``;
- SuperLU (``splu``, symmetric minimum-degree ordering, diagonal pivots,
  two steps of iterative refinement); a singular system (a mechanism: a
  pivot below 1e-12 of its diagonal term) is a ``MechanismError`` naming
  the nodes; the solution is checked by its residual and by equilibrium of
  loads and reactions.

Nodes are 0-based indices of the coordinates given; masters created by
``add_rigid`` are numbered after them. Six DOFs per node (ux uy uz rx ry rz);
solid blocks give three.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike
from scipy.sparse.linalg import MatrixRankWarning, SuperLU, splu


class MechanismError(ValueError):
    """The stiffness is singular: part of the structure can move freely.
    ``nodes``: node indices (masters after the model nodes) on the free motion."""

    def __init__(self, message: str, nodes=()):
        super().__init__(message)
        self.nodes = np.asarray(nodes, np.int64)


PIVOT_RATIO = 1e-12  # a pivot below this fraction of its diagonal term: a free motion


def reduced_columns(fixed: np.ndarray, slave_of: np.ndarray) -> np.ndarray:
    """(6·n_total,) each DOF's column in the reduced matrices tᵀKt of
    ``LinearStatic.reduction`` (−1: held, or a slave of a rigid group)."""
    indep = (slave_of < 0)[:, None] & ~fixed
    col = np.full(indep.size, -1)
    col[np.flatnonzero(indep.ravel())] = np.arange(int(indep.sum()))
    return col


def factor(k: sp.spmatrix, dof_node: np.ndarray, permc_spec: str = "MMD_AT_PLUS_A") -> SuperLU:
    """Sparse LU of the SPD matrix k with a symmetric ordering (``permc_spec``;
    "NATURAL": k's own) and diagonal pivots; a pivot much smaller than its
    diagonal term means a mechanism (MechanismError naming the nodes of
    ``dof_node``)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", MatrixRankWarning)
        try:
            lu = splu(k, permc_spec=permc_spec, diag_pivot_thresh=0.0, options={"SymmetricMode": True})
        except (MatrixRankWarning, RuntimeError) as e:
            raise MechanismError(
                f"the structure is a mechanism (singular stiffness: {e}); check that it is "
                "supported and that every part is connected"
            ) from None
    n = k.shape[0]
    col = np.empty(n, np.int64)
    col[lu.perm_c] = np.arange(n)  # column j of the factor is column col[j] of k
    ratio = np.abs(lu.U.diagonal()) / np.abs(k.diagonal()[col])
    bad = np.flatnonzero(~(ratio > PIVOT_RATIO))
    if len(bad):
        nodes = np.unique(dof_node[col[bad]])
        raise MechanismError(
            f"the structure is a mechanism: {len(bad)} free motion(s) (singular stiffness) "
            f"at {len(nodes)} node(s), node indices {nodes[:10].tolist()}; check that it is "
            "supported and that every part is connected",
            nodes,
        )
    return lu


def _factor_solve(k, f, dof_node):
    """Solve the SPD system k q = f (``factor``) with iterative refinement."""
    lu = factor(k, dof_node)
    q = lu.solve(f)
    absk = abs(k)
    for _ in range(3):  # iterative refinement; residual as the componentwise backward error
        r = f - k @ q
        scale = absk @ np.abs(q) + np.abs(f)
        residual = float(np.max(np.abs(r) / np.where(scale > 0, scale, 1.0)))
        if residual < 1e-14:
            break
        q = q + lu.solve(r)
    r = f - k @ q
    scale = absk @ np.abs(q) + np.abs(f)
    residual = float(np.max(np.abs(r) / np.where(scale > 0, scale, 1.0)))
    if not np.all(np.isfinite(q)) or residual > 1e-9:
        raise MechanismError(
            f"the stiffness is ill-conditioned (backward error {residual:.2e}): a near "
            "mechanism or very thin or soft parts"
        )
    return np.atleast_1d(q), residual


@dataclass
class StaticSolution:
    """Displacements and reactions of a linear static solve."""

    u: np.ndarray  # (n_nodes + n_masters, 6) displacements and rotations [length, rad]
    reaction: np.ndarray  # (n_nodes + n_masters, 6) K u − f at supported nodes and fixed groups [force, moment]
    load: np.ndarray  # (n_nodes + n_masters, 6) applied loads
    n_dofs: int  # independent DOFs solved for
    residual: float  # componentwise backward error max |K q − f| / (|K| |q| + |f|)
    notes: list = field(default_factory=list)

    @property
    def reaction_force(self) -> np.ndarray:
        """(3,) sum of the reaction forces."""
        return self.reaction[:, :3].sum(axis=0)


class LinearStatic:
    """A linear static problem on ``xyz`` (n, 3) node coordinates."""

    def __init__(self, xyz):
        self.xyz = np.asarray(xyz, float)
        self.n = len(self.xyz)
        self._blocks: list = []  # (dof indices (m, k) int64, stiffness (m, k, k))
        self._groups: list = []  # (node indices, master index)
        self._master_xyz: list = []
        self.fixed = np.zeros((self.n, 6), bool)
        self._loads: dict = {}
        self.in_structure = np.zeros(self.n, bool)  # nodes that carry elements (set by the builder)

    @property
    def n_total(self) -> int:
        return self.n + len(self._master_xyz)

    def add_elements(self, nodes: ArrayLike, stiffness: ArrayLike, dofs_per_node: int = 6) -> None:
        """Element blocks: ``nodes`` (m, k) node indices, ``stiffness``
        (m, k·d, k·d) with d = ``dofs_per_node`` (6, or 3 translations)."""
        nodes = np.asarray(nodes, np.int64)
        kmat = np.asarray(stiffness, float)
        if not len(nodes):
            return
        m, k = nodes.shape
        d = int(dofs_per_node)
        if kmat.shape != (m, k * d, k * d):
            raise ValueError(f"stiffness shape {kmat.shape}, expected {(m, k * d, k * d)}")
        if np.any(nodes < 0) or np.any(nodes >= self.n):
            raise ValueError("element node index out of range")
        dofs = (6 * nodes[:, :, None] + np.arange(d)).reshape(m, k * d)
        self._blocks.append((dofs, kmat))

    def add_rigid(self, nodes: ArrayLike, master: ArrayLike | None = None) -> int:
        """Tie ``nodes`` rigidly to a new master node at ``master`` (default:
        their centroid); returns the master's node index."""
        nodes = np.unique(np.asarray(nodes, np.int64))
        if not len(nodes):
            raise ValueError("a rigid group needs nodes")
        pos = self.xyz[nodes].mean(axis=0) if master is None else np.asarray(master, float).reshape(3)
        self._master_xyz.append(pos)
        idx = self.n + len(self._master_xyz) - 1
        self._groups.append((nodes, idx))
        return idx

    def tied(self) -> np.ndarray:
        """(n,) bool: model nodes that belong to a rigid group."""
        out = np.zeros(self.n, bool)
        for nodes, _ in self._groups:
            out[nodes] = True
        return out

    def position(self, node: int) -> np.ndarray:
        """(3,) coordinates of a model node or a master."""
        return self.xyz[node].copy() if node < self.n else np.array(self._master_xyz[node - self.n])

    def fix(self, nodes: ArrayLike, dofs: ArrayLike = (0, 1, 2, 3, 4, 5)) -> None:
        """Hold DOFs (0–5: ux uy uz rx ry rz) of model nodes."""
        nodes = np.asarray(nodes, np.int64)
        self.fixed[np.ix_(nodes, np.asarray(dofs, np.int64))] = True

    def load(self, node: int, force: ArrayLike = (0.0, 0.0, 0.0), moment: ArrayLike = (0.0, 0.0, 0.0)) -> None:
        """Add a nodal force and moment (a model node or a master)."""
        v = self._loads.setdefault(int(node), np.zeros(6))
        v[:3] += np.asarray(force, float)
        v[3:] += np.asarray(moment, float)

    # --- solve ------------------------------------------------------------------------------------
    def stiffness_matrix(self) -> sp.csr_matrix:
        """The assembled (6·n_total)² stiffness without constraints."""
        size = 6 * self.n_total
        k = sp.csr_matrix((size, size))
        for dofs, kmat in self._blocks:
            m, s = dofs.shape
            step = max(1, 4_000_000 // (s * s))
            for lo in range(0, m, step):
                d = dofs[lo : lo + step]
                rows = np.broadcast_to(d[:, :, None], (len(d), s, s)).ravel()
                cols = np.broadcast_to(d[:, None, :], (len(d), s, s)).ravel()
                k = k + sp.coo_matrix((kmat[lo : lo + step].ravel(), (rows, cols)), shape=(size, size)).tocsr()
        return k

    def _merged_groups(self):
        """Groups merged where they share nodes: list of (leading master, slave nodes, masters that follow)."""
        parent = list(range(len(self._groups)))

        def find(i):
            while parent[i] != i:
                parent[i] = parent[parent[i]]
                i = parent[i]
            return i

        owner = np.full(self.n, -1)
        for g, (nodes, _) in enumerate(self._groups):
            for other in np.unique(owner[nodes][owner[nodes] >= 0]):
                a, b = find(int(other)), find(g)
                parent[max(a, b)] = min(a, b)
            owner[nodes] = g
        merged: dict = {}
        for g, (nodes, master) in enumerate(self._groups):
            r = find(g)
            e = merged.setdefault(r, [self._groups[r][1], [], []])
            e[1].append(nodes)
            if master != e[0]:
                e[2].append(master)
        return [(m, np.unique(np.concatenate(s)), np.array(f, np.int64)) for m, s, f in merged.values()]

    def solve(self) -> StaticSolution:
        """Solve for the loads given with ``load``."""
        return self.solve_cases([self._loads])[0]

    def reduction(self) -> tuple[sp.csr_matrix, np.ndarray, np.ndarray, list[str]]:
        """(t, fixed, slave_of, notes): the map t (6·n_total, n_q) of the
        independent DOFs (free, not tied to a rigid group's master) to all
        DOFs, with u_slave = u_master + θ_master × r; the held DOFs and each
        node's master (−1: none)."""
        notes = []
        n_all = self.n_total
        size = 6 * n_all
        xyz = np.vstack([self.xyz] + ([np.array(self._master_xyz)] if self._master_xyz else []))
        fixed = np.zeros((n_all, 6), bool)
        fixed[: self.n] = self.fixed
        slave_of = np.full(n_all, -1)
        for master, nodes, follow in self._merged_groups():
            members = np.concatenate([nodes, follow])
            if np.any(slave_of[members] >= 0):
                raise ValueError("a node is tied to two rigid groups that were not merged")
            slave_of[members] = master
            if fixed[members].any():
                fixed[master] = True
                notes.append(f"a rigid group of {len(nodes)} nodes holds a support: the group is fixed")
            fixed[members] = False
        # transformation: independent DOFs (free, not slaves) -> all DOFs
        indep = (slave_of < 0)[:, None] & ~fixed
        col = np.full((n_all, 6), -1)
        col[indep] = np.arange(int(indep.sum()))
        rows, cols, vals = [], [], []
        free_nodes, free_dofs = np.nonzero(indep)
        rows.append(6 * free_nodes + free_dofs)
        cols.append(col[free_nodes, free_dofs])
        vals.append(np.ones(len(free_nodes)))
        slaves = np.flatnonzero(slave_of >= 0)
        if len(slaves):
            m = slave_of[slaves]
            r = xyz[slaves] - xyz[m]
            # u_s = u_m + θ_m × r: coefficient of θ_m[j] in u_s[i]
            cross = np.zeros((len(slaves), 3, 3))
            cross[:, 0, 1], cross[:, 0, 2] = r[:, 2], -r[:, 1]
            cross[:, 1, 0], cross[:, 1, 2] = -r[:, 2], r[:, 0]
            cross[:, 2, 0], cross[:, 2, 1] = r[:, 1], -r[:, 0]
            for i in range(6):
                for j in range(6):
                    if i < 3:
                        coef = np.full(len(slaves), 1.0) if j == i else (cross[:, i, j - 3] if j >= 3 else None)
                    else:
                        coef = np.full(len(slaves), 1.0) if j == i else None
                    if coef is None:
                        continue
                    c = col[m, j]
                    ok = (c >= 0) & (coef != 0)
                    rows.append(6 * slaves[ok] + i)
                    cols.append(c[ok])
                    vals.append(coef[ok])
        n_q = int(indep.sum())
        t = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(size, n_q))
        return t, fixed, slave_of, notes

    def solve_cases(self, cases: Sequence[dict[int, np.ndarray]]) -> list[StaticSolution]:
        """Solve several load cases on one factorisation: ``cases`` a list
        of {node: (6,) force and moment}; one StaticSolution each."""
        n_all = self.n_total
        size = 6 * n_all
        t, fixed, slave_of, notes = self.reduction()
        indep = (slave_of < 0)[:, None] & ~fixed
        n_q = t.shape[1]
        k_full = self.stiffness_matrix()
        f_full = np.zeros((size, len(cases)))
        for c, loads in enumerate(cases):
            for node, v in loads.items():
                f_full[6 * node : 6 * node + 6, c] += v
        kr = (t.T @ k_full @ t).tocsr()
        fr = t.T @ f_full
        diag = kr.diagonal()
        live = diag > 1e-12 * max(float(np.abs(diag).max(initial=0.0)), 1e-300)
        if not live.all():
            dead = np.flatnonzero(~live)
            if np.any(fr[dead] != 0.0):
                raise ValueError("a load acts on a degree of freedom without stiffness")
            used = np.zeros(n_all, bool)  # nodes of elements and rigid groups
            for dofs, _ in self._blocks:
                used[np.unique(dofs // 6)] = True
            used[self.n :] = True
            used |= slave_of >= 0
            dof_node = np.repeat(np.arange(n_all), 6)[indep.ravel()]
            n_dead = int(used[dof_node[dead]].sum())
            if n_dead:
                notes.append(f"{n_dead} degrees of freedom of the structure without stiffness held")
        keep = np.flatnonzero(live)
        kk = kr[keep][:, keep].tocsc()
        ff = fr[keep]
        if not len(keep):
            raise ValueError("nothing to solve: every degree of freedom is held")
        dof_node = np.repeat(np.arange(n_all), 6)[indep.ravel()][keep]
        q_live, residual = _factor_solve(kk, ff, dof_node)
        q = np.zeros((n_q, len(cases)))
        q[keep] = q_live.reshape(len(keep), len(cases))
        u = t @ q
        react = k_full @ u - f_full
        held = fixed.any(axis=1)  # supported nodes, and the members of fixed rigid groups
        held |= (slave_of >= 0) & held[np.maximum(slave_of, 0)]
        out = []
        for c in range(len(cases)):
            reaction = np.where(held[:, None], react[:, c].reshape(n_all, 6), 0.0)
            f_c = f_full[:, c].reshape(n_all, 6)
            total = f_c[:, :3].sum(axis=0) + reaction[:, :3].sum(axis=0)
            scale = max(float(np.abs(f_c).max(initial=0.0)), 1e-300)
            case_notes = list(notes)
            if np.abs(total).max() > 1e-6 * scale:
                case_notes.append(f"loads and reactions differ by {np.abs(total).max():.3g} (not in equilibrium)")
            out.append(StaticSolution(u[:, c].reshape(n_all, 6), reaction, f_c, len(keep), residual, case_notes))
        return out
