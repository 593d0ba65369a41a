"""Per-part sums for matsum: internal, hourglass and kinetic energy,
momentum, and the rigid-body velocity of every part (its momentum over its
mass, as LS-DYNA writes it; the CoG velocity for rigid parts).

A node shared by parts lends its mass to each in proportion to the element
mass each part puts on it (equal shares where the elements carry none, as
for springs on lumped masses). Nodes of rigid bodies count through their
body, reported under the body's part ID.
"""

from __future__ import annotations

import numpy as np
from scipy import sparse

from .groups import part_energy


class PartAccount:
    def __init__(self, groups, bodies, n_nodes: int):
        self.groups = [g for g in groups if len(g) and getattr(g, "in_parts", True)]
        pids = [np.asarray(g.pid, np.int64) for g in self.groups] + [np.array([b.body_id for b in bodies], np.int64)]
        self.part_ids = np.unique(np.concatenate(pids)) if pids else np.zeros(0, np.int64)
        self.bodies = bodies
        self._mass = None  # (n_parts,) part masses, summed at the first rigid_velocity
        self.body_part = np.searchsorted(self.part_ids, [b.body_id for b in bodies]).astype(np.int64)
        in_body = np.zeros(n_nodes, bool)
        for b in bodies:
            in_body[b.nodes] = True
        rows, cols, vals = [], [], []
        for g in self.groups:
            conn = np.asarray(g.conn)
            k = conn.shape[1]
            part = np.repeat(np.searchsorted(self.part_ids, g.pid), k)
            share = np.asarray(
                getattr(g, "corner_mass", None) if getattr(g, "corner_mass", None) is not None else np.ones(conn.shape),
                float,
            ).ravel()
            nodes = conn.ravel()
            ok = nodes >= 0
            ok[ok] &= ~in_body[nodes[ok]]
            rows.append(part[ok]), cols.append(nodes[ok]), vals.append(share[ok] + 1e-300)
        if rows:
            w = sparse.csr_matrix(
                (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                shape=(len(self.part_ids), n_nodes),
            )
            col = np.asarray(w.sum(axis=0)).ravel()
            self.weights = w @ sparse.diags(np.where(col > 0, 1.0 / np.where(col > 0, col, 1.0), 0.0))
        else:
            self.weights = sparse.csr_matrix((len(self.part_ids), n_nodes))

    def internal(self) -> np.ndarray:
        return part_energy(self.groups, self.part_ids)

    def hourglass(self) -> np.ndarray:
        return part_energy(self.groups, self.part_ids, "hourglass")

    def deleted(self) -> np.ndarray:
        """(n_parts,) how many of each part's shells and solids are deleted
        (eroded, failed or collapsed): what a torn or crushed-flat part no
        longer carries."""
        out = np.zeros(len(self.part_ids), np.int64)
        for g in self.groups:
            alive = getattr(getattr(g, "st", None), "alive", None)
            if alive is not None and alive.min() != 1:
                gone = np.searchsorted(self.part_ids, np.asarray(g.pid)[alive != 1])
                out += np.bincount(gone, minlength=len(out))
        return out

    def kinetic(self, mass: np.ndarray, v: np.ndarray) -> np.ndarray:
        out = self.weights @ (0.5 * mass * np.einsum("ij,ij->i", v, v))
        for k, b in zip(self.body_part, self.bodies):
            out[k] += b.kinetic()
        return out

    def momentum(self, mass: np.ndarray, v: np.ndarray) -> np.ndarray:
        out = self.weights @ (mass[:, None] * v)
        for k, b in zip(self.body_part, self.bodies):
            out[k] += b.mass * b.velocity
        return np.asarray(out)

    def mass(self, mass: np.ndarray) -> np.ndarray:
        """(n_parts,) mass of each part (its share of the nodal masses)."""
        out = np.asarray(self.weights @ mass, float)
        for k, b in zip(self.body_part, self.bodies):
            out[k] += b.mass
        return out

    def rigid_velocity(self, mass: np.ndarray, momentum: np.ndarray) -> np.ndarray:
        """(n_parts, 3) rigid-body velocity from the parts' ``momentum``:
        momentum / mass, the CoG velocity (NaN for a part without mass).
        The part masses are summed once: the nodal masses do not change in
        the time loop."""
        if self._mass is None:
            self._mass = self.mass(mass)
        m = self._mass
        with np.errstate(divide="ignore", invalid="ignore"):
            return momentum / np.where(m > 0, m, np.nan)[:, None]
