"""Linear elastic element stiffness matrices for the static solve of step 3,
vectorised over elements (global axes, 6 DOFs per node: ux uy uz rx ry rz,
except solids: 3 translations per node).

Shell: a flat four-node shell in the element's mean plane (nodes projected
on it; warped quads are approximated), triangles as quads with nodes 3 and
4 equal (collapsed, somewhat stiffer):

- membrane: bilinear plane stress with Wilson–Taylor incompatible modes
  (QM6: 1−ξ², 1−η² condensed per element, Jacobian at the centre, passes
  the patch test and bends in plane exactly on rectangles);
- bending: Reissner–Mindlin plate, 2x2 Gauss points; transverse shear by
  MITC4 (Bathe–Dvorkin: covariant shear strains tied at the edge
  midpoints), so thin plates do not lock; shear factor 5/6;
- drilling: the penalty γ ∫ (θz − ω)² dA, ω = ½(∂v/∂x − ∂u/∂y) the
  in-plane rotation (Hughes–Brezzi), 2x2 points, γ = ``drill``·G·t; zero
  for rigid motions, it only gives θz a stiffness where the shells meet in
  one plane.

Beam: Euler–Bernoulli frame (EA, GJ, EI about both section axes).
Spring: axial k on the three translations of both ends.
Solid: trilinear hexahedron, 2x2x2 Gauss points (degenerate forms by
repeated nodes).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

_GP = 1.0 / np.sqrt(3.0)
_XI = np.array([-_GP, _GP, _GP, -_GP])
_ETA = np.array([-_GP, -_GP, _GP, _GP])
_XN = np.array([-1.0, 1.0, 1.0, -1.0])  # corner ξ of nodes 1..4
_EN = np.array([-1.0, -1.0, 1.0, 1.0])  # corner η
BLOCK = 4096  # elements per vectorised block


def _shape(xi, eta):
    """N (4,), dN/dξ (4,), dN/dη (4,) at one point."""
    n = 0.25 * (1 + xi * _XN) * (1 + eta * _EN)
    return n, 0.25 * _XN * (1 + eta * _EN), 0.25 * (1 + xi * _XN) * _EN


def shell_frames(x: np.ndarray) -> np.ndarray:
    """(n, 3, 3) rotation from global to element axes (rows e1, e2, e3 = normal)
    of quads ``x`` (n, 4, 3): normal from the diagonals, e1 along the ξ
    mid-line projected on the mean plane."""
    nrm = np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 1])
    ln = np.linalg.norm(nrm, axis=1)
    if np.any(ln <= 0):
        raise ValueError(f"{int((ln <= 0).sum())} shell(s) have no area")
    e3 = nrm / ln[:, None]
    g1 = 0.5 * (x[:, 1] + x[:, 2] - x[:, 0] - x[:, 3])
    g1 = g1 - np.einsum("ij,ij->i", g1, e3)[:, None] * e3
    e1 = g1 / np.linalg.norm(g1, axis=1)[:, None]
    e2 = np.cross(e3, e1)
    return np.stack([e1, e2, e3], axis=1)


def _membrane(xl, D):
    """(n, 8, 8) QM6 membrane stiffness, DOFs u1 v1 u2 v2 ..."""
    n = len(xl)
    kuu = np.zeros((n, 8, 8))
    kua = np.zeros((n, 8, 4))
    kaa = np.zeros((n, 4, 4))
    _, ds0, de0 = _shape(0.0, 0.0)
    j0 = np.stack([ds0 @ xl, de0 @ xl], axis=1)  # (n, 2, 2) rows d/dξ, d/dη of (x, y)
    det0 = np.linalg.det(j0)
    j0inv = np.linalg.inv(j0)
    for xi, eta in zip(_XI, _ETA):
        _, ds, de = _shape(xi, eta)
        j = np.stack([ds @ xl, de @ xl], axis=1)
        det = np.linalg.det(j)
        if np.any(det <= 0):
            raise ValueError("a shell has a non-positive Jacobian (inverted or degenerate in two corners)")
        d = np.linalg.solve(j, np.broadcast_to(np.stack([ds, de]), (n, 2, 4)))  # (n, 2, 4): d/dx, d/dy
        b = np.zeros((n, 3, 8))
        b[:, 0, 0::2] = d[:, 0]
        b[:, 1, 1::2] = d[:, 1]
        b[:, 2, 0::2] = d[:, 1]
        b[:, 2, 1::2] = d[:, 0]
        dp = np.array([[-2.0 * xi, 0.0], [0.0, -2.0 * eta]])  # rows d/dξ, d/dη; columns modes 1−ξ², 1−η²
        g = (det0 / det)[:, None, None] * (j0inv @ dp)  # (n, 2, 2) rows d/dx, d/dy
        ba = np.zeros((n, 3, 4))
        ba[:, 0, 0:2] = g[:, 0]
        ba[:, 1, 2:4] = g[:, 1]
        ba[:, 2, 0:2] = g[:, 1]
        ba[:, 2, 2:4] = g[:, 0]
        w = det[:, None, None]
        db = D @ b
        kuu += w * (b.transpose(0, 2, 1) @ db)
        kua += w * (db.transpose(0, 2, 1) @ ba)
        kaa += w * (ba.transpose(0, 2, 1) @ (D @ ba))
    return kuu - kua @ np.linalg.solve(kaa, kua.transpose(0, 2, 1))


def _plate(xl, Db, ks):
    """(n, 12, 12) MITC4 plate stiffness, DOFs w1 rx1 ry1 w2 ...;
    ``Db`` (n, 3, 3) bending, ``ks`` (n,) shear stiffness κ·G·t."""
    n = len(xl)
    k = np.zeros((n, 12, 12))

    def covariant(xi, eta, along):
        """(n, 12) row of the covariant shear strain along ξ (0) or η (1) at a point."""
        nn, ds, de = _shape(xi, eta)
        dd = ds if along == 0 else de
        dx = dd @ xl  # (n, 2): dx/dξ, dy/dξ (or /dη)
        row = np.zeros((n, 12))
        row[:, 0::3] = dd
        row[:, 1::3] = -dx[:, 1:2] * nn
        row[:, 2::3] = dx[:, 0:1] * nn
        return row

    ga, gc = covariant(0.0, -1.0, 0), covariant(0.0, 1.0, 0)
    gd, gb = covariant(-1.0, 0.0, 1), covariant(1.0, 0.0, 1)
    for xi, eta in zip(_XI, _ETA):
        _, ds, de = _shape(xi, eta)
        j = np.stack([ds @ xl, de @ xl], axis=1)
        det = np.linalg.det(j)
        d = np.linalg.solve(j, np.broadcast_to(np.stack([ds, de]), (n, 2, 4)))
        bb = np.zeros((n, 3, 12))
        bb[:, 0, 2::3] = d[:, 0]
        bb[:, 1, 1::3] = -d[:, 1]
        bb[:, 2, 2::3] = d[:, 1]
        bb[:, 2, 1::3] = -d[:, 0]
        gxi = 0.5 * (1 - eta) * ga + 0.5 * (1 + eta) * gc
        geta = 0.5 * (1 - xi) * gd + 0.5 * (1 + xi) * gb
        bs = np.linalg.solve(j, np.stack([gxi, geta], axis=1))  # (n, 2, 12): γxz, γyz
        w = det[:, None, None]
        k += w * (bb.transpose(0, 2, 1) @ (Db @ bb) + ks[:, None, None] * (bs.transpose(0, 2, 1) @ bs))
    return k


def _drill(xl, gamma):
    """(n, 24, 24) drilling penalty on the local 6-DOF layout."""
    n = len(xl)
    k = np.zeros((n, 24, 24))
    for xi, eta in zip(_XI, _ETA):
        nn, ds, de = _shape(xi, eta)
        j = np.stack([ds @ xl, de @ xl], axis=1)
        det = np.linalg.det(j)
        d = np.linalg.solve(j, np.broadcast_to(np.stack([ds, de]), (n, 2, 4)))
        r = np.zeros((n, 24))
        r[:, 0::6] = 0.5 * d[:, 1]
        r[:, 1::6] = -0.5 * d[:, 0]
        r[:, 5::6] = nn
        k += (gamma * det)[:, None, None] * (r[:, :, None] * r[:, None, :])
    return k


def _to_global(kl, rot, n_nodes):
    """K_g = Tᵀ K_l T with T = blockdiag(rot) over 2·n_nodes 3-vectors."""
    n = len(kl)
    m = 2 * n_nodes
    k = kl.reshape(n, m, 3, m, 3)
    k = np.einsum("npi,napbq,nqj->naibj", rot, k, rot, optimize=True)
    return k.reshape(n, 3 * m, 3 * m)


def _local(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(rot (n, 3, 3), xl (n, 4, 2)): quads ``x`` (n, 4, 3) in their element
    frames (``shell_frames``) about their centroids."""
    rot = shell_frames(x)
    xl = np.einsum("nij,nkj->nki", rot, x - x.mean(axis=1, keepdims=True))[:, :, :2]
    return rot, xl


def drilling_stiffness(
    x: np.ndarray, thickness: ArrayLike, young: ArrayLike, poisson: ArrayLike, drill: float
) -> np.ndarray:
    """(n, 24, 24) global: the drilling penalty ``shell_stiffness`` adds
    (``drill`` · G·t on the in-plane rotation against the membrane's)."""
    x = np.asarray(x, float)
    n = len(x)
    t = np.broadcast_to(np.asarray(thickness, float), (n,))
    g = np.broadcast_to(np.asarray(young, float), (n,)) / (2 * (1 + np.broadcast_to(np.asarray(poisson, float), (n,))))
    out = np.empty((n, 24, 24))
    for lo in range(0, n, BLOCK):
        sl = slice(lo, lo + BLOCK)
        rot, xl = _local(x[sl])
        out[sl] = _to_global(_drill(xl, drill * g[sl] * t[sl]), rot, 4)
    return out


def shell_stiffness(
    x: np.ndarray,
    thickness: ArrayLike,
    young: ArrayLike,
    poisson: ArrayLike,
    drill: float = 1e-3,
    shear_factor: float = 5.0 / 6.0,
) -> np.ndarray:
    """(n, 24, 24) global stiffness of flat shells.

    x          (n, 4, 3) node coordinates (triangles: node 4 = node 3) [length]
    thickness  (n,) [length];  young (n,) [stress];  poisson (n,)
    drill      drilling penalty as a fraction of G·t
    DOF order: node 1 ux uy uz rx ry rz, node 2 ..., node 4.
    """
    x = np.asarray(x, float)
    n = len(x)
    t = np.broadcast_to(np.asarray(thickness, float), (n,))
    e = np.broadcast_to(np.asarray(young, float), (n,))
    nu = np.broadcast_to(np.asarray(poisson, float), (n,))
    out = np.empty((n, 24, 24))
    for lo in range(0, n, BLOCK):
        sl = slice(lo, lo + BLOCK)
        rot, xl = _local(x[sl])
        tb, eb, nb = t[sl], e[sl], nu[sl]
        base = np.array([[1.0, 0, 0], [0, 1.0, 0], [0, 0, 0]])
        cross = np.array([[0, 1.0, 0], [1.0, 0, 0], [0, 0, 0]])
        shear = np.array([[0, 0, 0], [0, 0, 0], [0, 0, 1.0]])
        iso = base + nb[:, None, None] * cross + 0.5 * (1 - nb)[:, None, None] * shear
        c0 = eb / (1 - nb**2)
        g = eb / (2 * (1 + nb))
        km = _membrane(xl, (c0 * tb)[:, None, None] * iso)
        kp = _plate(xl, (c0 * tb**3 / 12.0)[:, None, None] * iso, shear_factor * g * tb)
        kl = _drill(xl, drill * g * tb)
        mi = (6 * np.arange(4)[:, None] + np.array([0, 1])).ravel()
        pi = (6 * np.arange(4)[:, None] + np.array([2, 3, 4])).ravel()
        kl[:, mi[:, None], mi[None, :]] += km
        kl[:, pi[:, None], pi[None, :]] += kp
        out[sl] = _to_global(kl, rot, 4)
    return out


def beam_stiffness(
    x1: np.ndarray,
    x2: np.ndarray,
    frames: np.ndarray,
    ea: ArrayLike,
    gj: ArrayLike,
    ei2: ArrayLike,
    ei3: ArrayLike,
) -> np.ndarray:
    """(n, 12, 12) global Euler–Bernoulli frame stiffness.

    x1, x2   (n, 3) end coordinates [length]
    frames   (n, 3, 3) element axes as columns e1 (along), e2, e3
    ea [force]; gj, ei2 (deflection along e3), ei3 (along e2) [force·length²]
    DOF order: node 1 ux uy uz rx ry rz, node 2 ...
    """
    length = np.linalg.norm(np.asarray(x2, float) - np.asarray(x1, float), axis=1)
    n = len(length)
    k = np.zeros((n, 12, 12))
    L = length

    def put(i, j, v):
        k[:, i, j] += v
        if i != j:
            k[:, j, i] += v

    a, t = ea / L, gj / L
    for i, j, s in ((0, 0, 1), (6, 6, 1), (0, 6, -1)):
        put(i, j, s * a)
    for i, j, s in ((3, 3, 1), (9, 9, 1), (3, 9, -1)):
        put(i, j, s * t)
    # deflection v along e2 with rotation rz (EI about e3)
    c = ei3
    for i, j, v in (
        (1, 1, 12 * c / L**3),
        (7, 7, 12 * c / L**3),
        (1, 7, -12 * c / L**3),
        (1, 5, 6 * c / L**2),
        (1, 11, 6 * c / L**2),
        (7, 5, -6 * c / L**2),
        (7, 11, -6 * c / L**2),
        (5, 5, 4 * c / L),
        (11, 11, 4 * c / L),
        (5, 11, 2 * c / L),
    ):
        put(i, j, v)
    # deflection w along e3 with rotation ry (EI about e2)
    c = ei2
    for i, j, v in (
        (2, 2, 12 * c / L**3),
        (8, 8, 12 * c / L**3),
        (2, 8, -12 * c / L**3),
        (2, 4, -6 * c / L**2),
        (2, 10, -6 * c / L**2),
        (8, 4, 6 * c / L**2),
        (8, 10, 6 * c / L**2),
        (4, 4, 4 * c / L),
        (10, 10, 4 * c / L),
        (4, 10, 2 * c / L),
    ):
        put(i, j, v)
    rot = np.asarray(frames, float).transpose(0, 2, 1)  # rows e1, e2, e3
    return _to_global(k, rot, 2)


def spring_stiffness(direction: np.ndarray, k: ArrayLike) -> np.ndarray:
    """(n, 6, 6) axial spring k along unit ``direction`` (n, 3) on the
    translations of its two ends (ux uy uz of node 1, then node 2)."""
    d = np.asarray(direction, float)
    dd = np.asarray(k, float)[:, None, None] * (d[:, :, None] * d[:, None, :])
    return np.block([[dd, -dd], [-dd, dd]])


def hex_stiffness(x: np.ndarray, young: ArrayLike, poisson: ArrayLike) -> np.ndarray:
    """(n, 24, 24) global stiffness of trilinear hexahedra ``x`` (n, 8, 3),
    DOFs ux uy uz per node, 2x2x2 Gauss points."""
    x = np.asarray(x, float)
    n = len(x)
    e = np.broadcast_to(np.asarray(young, float), (n,))
    nu = np.broadcast_to(np.asarray(poisson, float), (n,))
    lam = e * nu / ((1 + nu) * (1 - 2 * nu))
    mu = e / (2 * (1 + nu))
    D = np.zeros((n, 6, 6))
    D[:, :3, :3] = lam[:, None, None]
    D[:, [0, 1, 2], [0, 1, 2]] += 2 * mu[:, None]
    D[:, [3, 4, 5], [3, 4, 5]] = mu[:, None]
    corners = np.array(
        [[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1], [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], float
    )
    k = np.zeros((n, 24, 24))
    for g in np.array(np.meshgrid([-_GP, _GP], [-_GP, _GP], [-_GP, _GP], indexing="ij")).reshape(3, -1).T:
        f = 1 + g[None, :] * corners  # (8, 3)
        dn = np.empty((3, 8))
        for d in range(3):
            o = [a for a in range(3) if a != d]
            dn[d] = 0.125 * corners[:, d] * f[:, o[0]] * f[:, o[1]]
        j = dn @ x  # (n, 3, 3)
        det = np.linalg.det(j)
        dx = np.linalg.solve(j, np.broadcast_to(dn, (n, 3, 8)))
        b = np.zeros((n, 6, 24))
        for a in range(3):
            b[:, a, a::3] = dx[:, a]
        b[:, 3, 0::3], b[:, 3, 1::3] = dx[:, 1], dx[:, 0]
        b[:, 4, 1::3], b[:, 4, 2::3] = dx[:, 2], dx[:, 1]
        b[:, 5, 0::3], b[:, 5, 2::3] = dx[:, 2], dx[:, 0]
        k += np.abs(det)[:, None, None] * (b.transpose(0, 2, 1) @ (D @ b))
    return k
