"""Superelement mass matrices solved as given (not lumped) in the time loop.

A reduced structure's mass matrix (a Craig–Bampton or Guyan reduction, a
DMIG ``MASS``) is dense: the motion of one boundary DOF carries mass that
sits on the structure's interior, and the interior's modes couple to the
boundary. Lumping it by row sums keeps the total mass but loses the
coupling and the rotational inertia of mass away from the boundary nodes.
Here the superelements' DOFs (their union, over all superelements) are
integrated with the full matrix: with D the rest of their nodes' lumped
mass (the elements beside them, point masses, mass scaling) and M the sum
of the superelements' mass matrices, the acceleration is (D + M)⁻¹ f.
The loop's diagonal update has already added f/m_l (m_l the lumped mass
it knows); the correction adds (A − diag 1/m_l) f, A = (D + M)⁻¹ formed
once: one dense matrix–vector product a cycle, as the stiffness is.

Kinetic energy: ½ vᵀ(D + M)v on these DOFs, the loop's ½ m_l v² plus
½ vᵀ(M − diag m_M)v (m_M the superelements' share of m_l). Body loads
(gravity, base acceleration) −(D + M)·e a likewise. DOFs that are held
(SPC) or ride a rigid body keep the lumped mass; the coupling of their
mass to the rest is then lost, and said.
"""

from __future__ import annotations

import numpy as np

from .kernels.matrix import matrix_kick


class ConsistentMass:
    """The superelements' DOFs integrated with their full mass matrix (module docstring)."""

    def __init__(self, nodes: np.ndarray, comps: np.ndarray, mass: np.ndarray, lumped: np.ndarray):
        self.nodes = np.ascontiguousarray(nodes, np.int64)  # (k,) node index of each DOF
        self.comps = np.ascontiguousarray(comps, np.int64)  # (k,) component 0–2
        self.m = mass  # (k, k) the superelements' mass matrix on these DOFs
        self.m_l = lumped  # (k,) its share of the loop's lumped nodal mass at each DOF
        self.b = None  # (k, k) A − diag(1/m_l), once the loop's masses are known (``start``)
        self.notes: list = []

    def start(self, mass: np.ndarray, fixed: np.ndarray, in_body: np.ndarray) -> None:
        """Form the correction from the loop's lumped nodal ``mass`` (after
        mass scaling); ``fixed`` (n, 3) and ``in_body`` (n,) DOFs keep the
        lumped mass."""
        live = ~fixed[self.nodes, self.comps] & ~in_body[self.nodes]
        if not live.all():
            self.notes.append(f"{int((~live).sum())} superelement DOF(s) held or on rigid bodies keep a lumped mass")
        self.nodes, self.comps = self.nodes[live], self.comps[live]
        self.m, self.m_l = self.m[np.ix_(live, live)], self.m_l[live]
        self._g = np.zeros(len(self.nodes))
        self._fs = np.zeros(len(self.nodes))
        m_node = mass[self.nodes]
        d = m_node - self.m_l  # the rest of the nodes' mass: elements beside them, point masses, scaling
        full = self.m + np.diag(d)
        try:
            np.linalg.cholesky(full)
        except np.linalg.LinAlgError:
            raise FloatingPointError(
                "*ELEMENT_DIRECT_MATRIX_INPUT: the superelements' mass matrix with the rest of their nodes' "
                "mass is not positive definite (a DOF without mass, or a matrix that is not a mass): the run "
                "cannot integrate it"
            ) from None
        a = np.linalg.inv(full)
        self.b = np.ascontiguousarray(0.5 * (a + a.T) - np.diag(1.0 / m_node))

    def kick(self, f: np.ndarray, v: np.ndarray, dt: float) -> None:
        """After the loop's v += dt f/m_l: v += dt (A − diag 1/m_l) f on these DOFs."""
        if len(self.nodes):
            matrix_kick(self.b, f, self.nodes, self.comps, self._fs, self._g, v, dt)

    def kinetic(self, v: np.ndarray) -> float:
        """What ½ vᵀMv adds to the loop's lumped ½ m_l v² on these DOFs."""
        u = v[self.nodes, self.comps]
        return 0.5 * float(u @ (self.m @ u) - (self.m_l * u) @ u)

    def body_force(self, out: np.ndarray, axis: np.ndarray, acc: float) -> None:
        """Correct the loop's −m_l e a on these DOFs to −(D + M) e a."""
        e = np.asarray(axis, float)[self.comps]
        extra = self.m @ e - self.m_l * e
        np.add.at(out, (self.nodes, self.comps), -acc * extra)
