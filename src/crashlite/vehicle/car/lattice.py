"""Structured quadrilateral meshing on a global rectilinear lattice.

The generic car is built from sheet-metal pieces whose edges run along the
global axes (plates, and tubes of axis-aligned profiles extruded along an
axis), plus a few sloped pieces (pillars, glass) ruled between lattice
lines. Every axis has one grid: the keypoints of all pieces (the
coordinates where a piece starts, ends or bends), each interval between
neighbouring keypoints divided into about ``size``-long cells. A piece
takes the grid points within its bounds, so two pieces that touch share
their nodes along the contact line: T-joints and corners are conforming by
construction and the mesh size changes the element count, not the
geometry. Ruled pieces interpolate between two rows (or rings) of lattice
nodes with the same number of points, computed by one expression, so where
two ruled pieces share an edge their nodes coincide bit for bit.

Merging is exact: nodes with identical coordinates are one node.
Everything is vectorised (no Python loop per element).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

AXES = "xyz"


def _others(axis: int) -> tuple[int, int]:
    """The two in-plane axes of a plane normal to ``axis``, in increasing order."""
    return tuple(a for a in range(3) if a != axis)  # type: ignore[return-value]


class Grid:
    """The lattice: per axis, the sorted grid coordinates through every
    keypoint, intervals divided into ``max(1, round(length / size))`` cells."""

    def __init__(self, keypoints: list[set[float]], size: float):
        if not size > 0:
            raise ValueError(f"mesh size must be > 0, got {size}")
        self.size = float(size)
        self.keys = [np.array(sorted(k), float) for k in keypoints]
        self.coords = []
        for k in self.keys:
            parts = [k[:1]]
            for a, b in zip(k[:-1], k[1:]):
                n = max(1, int(round((b - a) / size)))
                parts.append(np.linspace(a, b, n + 1)[1:])
            self.coords.append(np.concatenate(parts))

    def index(self, axis: int, value: float) -> int:
        c = self.coords[axis]
        i = int(np.searchsorted(c, value))
        if i >= len(c) or c[i] != value:
            raise ValueError(f"{AXES[axis]} = {value} is not a keypoint of the lattice")
        return i

    def span(self, axis: int, a: float, b: float) -> np.ndarray:
        """Grid coordinates from a to b (both keypoints), in that order."""
        i, j = self.index(axis, a), self.index(axis, b)
        return self.coords[axis][i : j + 1] if i <= j else self.coords[axis][j : i + 1][::-1]

    def smallest_gap(self) -> tuple[float, str]:
        """Smallest distance between neighbouring keypoints, and its axis."""
        out = (np.inf, "")
        for a, k in enumerate(self.keys):
            if len(k) > 1 and np.diff(k).min() < out[0]:
                out = (float(np.diff(k).min()), AXES[a])
        return out


@dataclass(frozen=True)
class Plate:
    """A rectangle in the plane ``axis = at``: ``lo``..``hi`` along the two
    other axes (in increasing axis order)."""

    axis: int
    at: float
    lo: tuple[float, float]
    hi: tuple[float, float]

    def keypoints(self) -> list[tuple[int, float]]:
        u, v = _others(self.axis)
        return [(self.axis, self.at), (u, self.lo[0]), (u, self.hi[0]), (v, self.lo[1]), (v, self.hi[1])]

    def mesh(self, g: Grid) -> tuple[np.ndarray, np.ndarray]:
        u, v = _others(self.axis)
        cu, cv = g.span(u, self.lo[0], self.hi[0]), g.span(v, self.lo[1], self.hi[1])
        xyz = np.empty((len(cu), len(cv), 3))
        xyz[..., self.axis] = self.at
        xyz[..., u] = cu[:, None]
        xyz[..., v] = cv[None, :]
        return xyz.reshape(-1, 3), _grid_quads(len(cu), len(cv))


@dataclass(frozen=True)
class Tube:
    """A profile in the plane normal to ``axis`` extruded from ``s0`` to
    ``s1``. ``profile``: vertices (u, v) in the two other axes (increasing
    axis order), consecutive vertices differing in one coordinate only;
    ``closed`` joins the last vertex to the first."""

    axis: int
    s0: float
    s1: float
    profile: tuple[tuple[float, float], ...]
    closed: bool = True

    def keypoints(self) -> list[tuple[int, float]]:
        u, v = _others(self.axis)
        return (
            [(self.axis, self.s0), (self.axis, self.s1)]
            + [(u, p[0]) for p in self.profile]
            + [(v, p[1]) for p in self.profile]
        )

    def ring(self, g: Grid) -> np.ndarray:
        """(m, 2) in-plane coordinates of the profile's grid points."""
        return profile_points(g, self.axis, self.profile, self.closed)

    def mesh(self, g: Grid) -> tuple[np.ndarray, np.ndarray]:
        u, v = _others(self.axis)
        ring = self.ring(g)
        s = g.span(self.axis, self.s0, self.s1)
        xyz = np.empty((len(s), len(ring), 3))
        xyz[..., self.axis] = s[:, None]
        xyz[..., u] = ring[None, :, 0]
        xyz[..., v] = ring[None, :, 1]
        return xyz.reshape(-1, 3), _grid_quads(len(s), len(ring), wrap=self.closed)


def profile_points(g: Grid, axis: int, profile: Sequence[tuple[float, float]], closed: bool) -> np.ndarray:
    """Grid points along an axis-aligned polyline in the plane normal to ``axis``."""
    u, v = _others(axis)
    pts = list(profile) + ([profile[0]] if closed else [])
    out = []
    for (a0, b0), (a1, b1) in zip(pts[:-1], pts[1:]):
        if a0 != a1 and b0 != b1:
            raise ValueError(f"profile segment {(a0, b0)} -> {(a1, b1)} is not along a lattice axis")
        if a0 != a1:
            c = g.span(u, a0, a1)
            seg = np.stack([c, np.full(len(c), b0)], axis=1)
        else:
            c = g.span(v, b0, b1)
            seg = np.stack([np.full(len(c), a0), c], axis=1)
        out.append(seg[:-1])
    if not closed:
        out.append(np.array([pts[-1]], float))
    return np.concatenate(out)


def lattice_line(g: Grid, vertices: Sequence[tuple[float, float, float]]) -> np.ndarray:
    """(m, 3) grid points along a 3D polyline whose segments each run along
    one axis between keypoints."""
    out = []
    for p, q in zip(vertices[:-1], vertices[1:]):
        d = [a for a in range(3) if p[a] != q[a]]
        if len(d) != 1:
            raise ValueError(f"line segment {p} -> {q} is not along a lattice axis")
        c = g.span(d[0], p[d[0]], q[d[0]])
        seg = np.tile(np.asarray(p, float), (len(c), 1))
        seg[:, d[0]] = c
        out.append(seg[:-1])
    out.append(np.asarray([vertices[-1]], float))
    return np.concatenate(out)


@dataclass(frozen=True)
class Ruled:
    """A sloped piece ruled between two lattice polylines ``a`` and ``b``
    (same number of grid points), ``closed`` for rings (tubes). The number
    of cells across is set by ``length`` (pieces sharing a ruled edge give
    the same length so their edge nodes coincide)."""

    a: tuple[tuple[float, float, float], ...]
    b: tuple[tuple[float, float, float], ...]
    length: float
    closed: bool = False

    def keypoints(self) -> list[tuple[int, float]]:
        return [(ax, p[ax]) for p in self.a + self.b for ax in range(3)]

    def mesh(self, g: Grid) -> tuple[np.ndarray, np.ndarray]:
        ra, rb = lattice_line(g, self.a), lattice_line(g, self.b)
        if self.closed:
            ra, rb = ra[:-1], rb[:-1]
        if ra.shape != rb.shape:
            raise ValueError(
                f"ruled piece between lines of {len(ra)} and {len(rb)} grid points: the "
                "lattice intervals on both ends must match"
            )
        n = max(1, int(round(self.length / g.size)))
        t = np.linspace(0.0, 1.0, n + 1)
        xyz = ra[None, :, :] + (rb - ra)[None, :, :] * t[:, None, None]
        xyz[0], xyz[-1] = ra, rb  # the ends are the lattice nodes themselves
        return xyz.reshape(-1, 3), _grid_quads(n + 1, len(ra), wrap=self.closed)


def _grid_quads(n_i: int, n_j: int, wrap: bool = False) -> np.ndarray:
    """Quads of an (n_i, n_j) node grid (row-major), j periodic with ``wrap``."""
    i, j = np.meshgrid(np.arange(n_i - 1), np.arange(n_j if wrap else n_j - 1), indexing="ij")
    i, j = i.ravel(), j.ravel()
    j1 = (j + 1) % n_j
    return np.stack([i * n_j + j, (i + 1) * n_j + j, (i + 1) * n_j + j1, i * n_j + j1], axis=1)


def merge(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unique nodes of ``points`` (m, 3) by exact coordinates, numbered in
    order of first appearance: (nodes (n, 3), index (m,) of each point)."""
    p = np.ascontiguousarray(points + 0.0)  # -0.0 -> 0.0
    key = p.view(np.dtype((np.void, 24))).ravel()
    _, first, inverse = np.unique(key, return_index=True, return_inverse=True)
    order = np.argsort(first, kind="stable")
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    return p[first[order]], rank[inverse.ravel()]
