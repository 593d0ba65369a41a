"""From part definitions to one conforming shell mesh.

Collects the keypoints of every piece, builds the lattice, meshes each
piece, shifts the pieces of shifted parts (doors), merges coincident nodes
and checks the result: no degenerate quadrilateral, no two elements on the
same four nodes (two parts laid over each other). The crash boxes get a
small geometric trigger (a bead pattern) so that they start folding at
their front.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from .body import PartDef
from .lattice import Grid, merge


@dataclass
class Mesh:
    grid: Grid
    xyz: np.ndarray  # (n, 3) float64 node coordinates [mm]
    quads: np.ndarray  # (m, 4) int64 node indices
    part: np.ndarray  # (m,) int64 index of each element's part in the part list
    names: list  # part names, in part-list order

    def part_index(self, name: str) -> int:
        try:
            return self.names.index(name)
        except ValueError:
            raise KeyError(f"no part named {name!r}") from None

    def nodes_of(self, names: Iterable[str]) -> np.ndarray:
        """Sorted unique node indices of the elements of the named parts."""
        k = [self.part_index(n) for n in names]
        return np.unique(self.quads[np.isin(self.part, k)])

    def areas(self) -> np.ndarray:
        """(m,) element areas [mm²] (half the cross product of the diagonals)."""
        x = self.xyz[self.quads]
        return 0.5 * np.linalg.norm(np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 1]), axis=1)


def build_mesh(parts: list[PartDef], size: float, trigger: float = 1.0) -> Mesh:
    """The merged mesh of ``parts`` with cells of about ``size`` mm; crash
    boxes get beads of depth ``trigger`` mm (0: none)."""
    keys: list[set] = [set(), set(), set()]
    for p in parts:
        for piece in p.pieces:
            for ax, v in piece.keypoints():
                keys[ax].add(float(v))
    g = Grid(keys, size)
    pts, quads, owner = [], [], []
    offset = 0
    for k, p in enumerate(parts):
        for piece in p.pieces:
            xyz, q = piece.mesh(g)
            if any(p.shift):
                xyz = xyz + np.asarray(p.shift, float)
            pts.append(xyz)
            quads.append(q + offset)
            owner.append(np.full(len(q), k, np.int64))
            offset += len(xyz)
    nodes, index = merge(np.concatenate(pts))
    conn = index[np.concatenate(quads)]
    part = np.concatenate(owner)
    mesh = Mesh(g, nodes, conn.astype(np.int64), part, [p.name for p in parts])
    _check(mesh)
    if trigger:
        _beads(mesh, parts, trigger)
    return mesh


def _check(mesh: Mesh) -> None:
    q = np.sort(mesh.quads, axis=1)
    bad = np.flatnonzero(np.any(q[:, 1:] == q[:, :-1], axis=1))
    if len(bad):
        raise ValueError(f"degenerate element in part {mesh.names[mesh.part[bad[0]]]!r}")
    key = np.ascontiguousarray(q).view(np.dtype((np.void, 32))).ravel()
    _, first, counts = np.unique(key, return_index=True, return_counts=True)
    if np.any(counts > 1):
        dup = np.flatnonzero(np.isin(key, key[first[counts > 1]]))
        names = sorted({mesh.names[i] for i in mesh.part[dup]})
        raise ValueError(f"parts laid over each other (elements on the same nodes): {names}")


def _beads(mesh: Mesh, parts: list[PartDef], depth: float) -> None:
    """Bead triggers of the crash boxes: near the front of each box its side
    walls are dented inwards and its top and bottom walls outwards (the
    first lobe of the progressive folding mode), a half sine across each
    wall and a Gaussian along the box, corners left straight. Only nodes of
    the crash boxes alone move, so neighbours stay attached."""
    for k, p in enumerate(parts):
        if not p.name.startswith("crash box"):
            continue
        piece = p.pieces[0]
        (y0, z0), (y1, _), (_, z1) = piece.profile[0], piece.profile[1], piece.profile[2]
        ylo, yhi, zlo, zhi = min(y0, y1), max(y0, y1), min(z0, z1), max(z0, z1)
        mine = mesh.part == k
        shared = np.zeros(len(mesh.xyz), bool)
        shared[mesh.quads[~mine].ravel()] = True
        own = np.unique(mesh.quads[mine])
        nodes = own[~shared[own]]
        x, y, z = mesh.xyz[nodes].T
        length = piece.s1 - piece.s0
        along = np.exp(-(((x - (piece.s1 - 0.25 * length)) / (0.1 * length)) ** 2))
        side = (y == ylo) | (y == yhi)
        flat = (z == zlo) | (z == zhi)
        across_z = np.sin(np.pi * (z - zlo) / (zhi - zlo))
        across_y = np.sin(np.pi * (y - ylo) / (yhi - ylo))
        inward = np.where(y == ylo, 1.0, -1.0)
        outward = np.where(z == zlo, -1.0, 1.0)
        mesh.xyz[nodes, 1] += np.where(side & ~flat, depth * along * across_z * inward, 0.0)
        mesh.xyz[nodes, 2] += np.where(flat & ~side, depth * along * across_y * outward, 0.0)
