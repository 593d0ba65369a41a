"""Mass-property contributions of elements, vectorised over elements.

Each element type yields its raw moments about the origin: mass, first
moment ∫ρ r dV and second moment ∫ρ r⊗r dV. Summing them and shifting to the
centre of gravity gives the inertia tensor. Gauss quadrature with 3 points
per direction integrates polynomials up to degree 5 per direction exactly:
the integrands here (r⊗r times the Jacobian of a bilinear or trilinear map)
are at most degree 4 per direction, so planar quads, triangles, hexahedra
and their degenerate forms are integrated exactly.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

_G = np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)])
_W = np.array([5.0, 8.0, 5.0]) / 9.0


class Moments(NamedTuple):
    """Raw moments about the origin, per element."""

    mass: np.ndarray  # (n,) [mass]
    first: np.ndarray  # (n, 3) ∫ρ r dV [mass·length]
    second: np.ndarray  # (n, 3, 3) ∫ρ r⊗r dV [mass·length²]


@dataclass(frozen=True)
class MassProperties:
    mass: float  # total mass [mass]
    cog: np.ndarray  # (3,) centre of gravity [length]
    inertia: np.ndarray  # (3, 3) inertia tensor about the CoG [mass·length²]

    @property
    def principal(self) -> tuple[np.ndarray, np.ndarray]:
        """Principal moments (ascending) and axes (columns)."""
        w, v = np.linalg.eigh(self.inertia)
        return w, v

    def __add__(self, other: "MassProperties") -> "MassProperties":
        if self.mass == 0:
            return other
        if other.mass == 0:
            return self
        m = self.mass + other.mass
        c = (self.mass * self.cog + other.mass * other.cog) / m
        inertia = np.zeros((3, 3))
        for b in (self, other):
            d = b.cog - c
            inertia += b.inertia + b.mass * (d @ d * np.eye(3) - np.outer(d, d))
        return MassProperties(m, c, inertia)


def _empty(n: int = 0) -> Moments:
    return Moments(np.zeros(n), np.zeros((n, 3)), np.zeros((n, 3, 3)))


def shell_moments(xyz, conn, thickness, density) -> Moments:
    """Shells as mid-surface sheets of thickness t.

    xyz (n_nodes, 3) float64; conn (n, 4) int node indices (triangles repeat
    node 3); thickness (n,) or (n, 4) nodal values, interpolated
    bilinearly; density (n,). Includes the through-thickness term
    ∫ρ t³/12 n⊗n dA so a flat plate's inertia is that of the solid plate.
    """
    conn = np.asarray(conn)
    n = len(conn)
    if n == 0:
        return _empty()
    x = xyz[conn]  # (n, 4, 3)
    t = np.asarray(thickness, float)
    t = np.repeat(t[:, None], 4, axis=1) if t.ndim == 1 else t
    rho = np.asarray(density, float)
    out = _empty(n)
    for gi, wi in zip(_G, _W):
        for gj, wj in zip(_G, _W):
            N = 0.25 * np.array([(1 - gi) * (1 - gj), (1 + gi) * (1 - gj), (1 + gi) * (1 + gj), (1 - gi) * (1 + gj)])
            dNs = 0.25 * np.array([-(1 - gj), (1 - gj), (1 + gj), -(1 + gj)])
            dNt = 0.25 * np.array([-(1 - gi), -(1 + gi), (1 + gi), (1 - gi)])
            p = np.einsum("a,nak->nk", N, x)
            a = np.cross(np.einsum("a,nak->nk", dNs, x), np.einsum("a,nak->nk", dNt, x))
            da = np.linalg.norm(a, axis=1)
            unit = a / np.where(da > 0, da, 1.0)[:, None]
            tp = t @ N
            w = wi * wj * rho * da  # mass per unit thickness at this point
            out.mass[:] += w * tp
            out.first[:] += (w * tp)[:, None] * p
            out.second[:] += (w * tp)[:, None, None] * p[:, :, None] * p[:, None, :]
            out.second[:] += (w * tp**3 / 12.0)[:, None, None] * unit[:, :, None] * unit[:, None, :]
    return out


def solid_moments(xyz, conn, density) -> Moments:
    """8-node solids (wedges and tetrahedra as repeated nodes), trilinear map."""
    conn = np.asarray(conn)
    n = len(conn)
    if n == 0:
        return _empty()
    x = xyz[conn]  # (n, 8, 3)
    rho = np.asarray(density, float)
    sgn = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                    [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], float)
    out = _empty(n)
    for gi, wi in zip(_G, _W):
        for gj, wj in zip(_G, _W):
            for gk, wk in zip(_G, _W):
                q = np.array([gi, gj, gk])
                f = 1 + sgn * q  # (8, 3)
                N = 0.125 * f.prod(axis=1)
                dN = np.stack([0.125 * sgn[:, d] * np.prod(np.delete(f, d, axis=1), axis=1)
                               for d in range(3)], axis=1)  # (8, 3)
                p = np.einsum("a,nak->nk", N, x)
                jac = np.einsum("ad,nak->ndk", dN, x)
                w = wi * wj * wk * rho * np.abs(np.linalg.det(jac))
                out.mass[:] += w
                out.first[:] += w[:, None] * p
                out.second[:] += w[:, None, None] * p[:, :, None] * p[:, None, :]
    return out


def beam_moments(xyz, conn, area, density) -> Moments:
    """Beams as uniform line masses ρ·A between their two end nodes."""
    conn = np.asarray(conn)
    if len(conn) == 0:
        return _empty()
    a, b = xyz[conn[:, 0]], xyz[conn[:, 1]]
    m = np.asarray(density, float) * np.asarray(area, float) * np.linalg.norm(b - a, axis=1)
    second = (m / 3.0)[:, None, None] * (np.einsum("ni,nj->nij", a, a) + np.einsum("ni,nj->nij", b, b)
                                          + 0.5 * (np.einsum("ni,nj->nij", a, b) + np.einsum("ni,nj->nij", b, a)))
    return Moments(m, (m / 2.0)[:, None] * (a + b), second)


def point_moments(xyz_points, mass, inertia=None) -> Moments:
    """Point masses, optionally with their own inertia tensors (about the point)."""
    p = np.asarray(xyz_points, float).reshape(-1, 3)
    m = np.asarray(mass, float).reshape(-1)
    second = m[:, None, None] * p[:, :, None] * p[:, None, :]
    if inertia is not None:
        # ∫ r⊗r of the body about its point: S = tr(I)/2 · 1 − I
        inertia = np.asarray(inertia, float).reshape(-1, 3, 3)
        second = second + 0.5 * np.trace(inertia, axis1=1, axis2=2)[:, None, None] * np.eye(3) - inertia
    return Moments(m, m[:, None] * p, second)


def combine(*moments: Moments) -> MassProperties:
    """Total mass, CoG and inertia about the CoG: I = tr(S)·1 − S with
    S = Σ second − m c⊗c."""
    mass = float(sum(mo.mass.sum() for mo in moments))
    if mass == 0.0:
        return MassProperties(0.0, np.zeros(3), np.zeros((3, 3)))
    first = sum(mo.first.sum(axis=0) for mo in moments)
    second = sum(mo.second.sum(axis=0) for mo in moments)
    c = first / mass
    s = second - mass * np.outer(c, c)
    return MassProperties(mass, c, np.trace(s) * np.eye(3) - s)
