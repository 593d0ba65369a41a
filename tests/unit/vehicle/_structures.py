"""Small shell structures with closed-form answers, as keyword Models."""

import numpy as np

from crashlite.model.mesh import Nodes, Shells
from crashlite.model.model import Model
from crashlite.vehicle.car.records import record

E, NU, RHO = 210000.0, 0.3, 7.85e-9  # MPa, -, t/mm³


def grid_quads(n_i: int, n_j: int, wrap: bool = False) -> np.ndarray:
    """Quads of an (n_i, n_j) node grid (row-major), j periodic with ``wrap``."""
    i, j = np.meshgrid(np.arange(n_i - 1), np.arange(n_j if wrap else n_j - 1), indexing="ij")
    i, j = i.ravel(), j.ravel()
    j1 = (j + 1) % n_j
    return np.stack([i * n_j + j, (i + 1) * n_j + j, (i + 1) * n_j + j1, i * n_j + j1], axis=1)


def square_ring(b: float, per_side: int) -> np.ndarray:
    """(4·per_side, 2) points (y, z) around a b x b square centred on the axis."""
    s = np.arange(4 * per_side) * b / per_side
    side, r = s // b, s % b
    h = b / 2
    y = np.select([side == 0, side == 1, side == 2], [-h + r, h, h - r], -h)
    z = np.select([side == 0, side == 1, side == 2], [-h, -h + r, h], h - r)
    return np.stack([y, z], axis=1)


def tube_mesh(b: float, length: float, per_side: int, n_len: int):
    """Closed square tube b x b (mid-line) along x from 0 to ``length``."""
    ring = square_ring(b, per_side)
    x = np.linspace(0.0, length, n_len + 1)
    xyz = np.empty((len(x), len(ring), 3))
    xyz[..., 0] = x[:, None]
    xyz[..., 1:] = ring[None]
    return xyz.reshape(-1, 3), grid_quads(len(x), len(ring), wrap=True)


def plate_mesh(length: float, width: float, n_len: int, n_wid: int, plane: str = "xy"):
    """Flat plate along x (0..length), across y or z (−width/2..width/2)."""
    x = np.linspace(0.0, length, n_len + 1)
    w = np.linspace(-width / 2, width / 2, n_wid + 1)
    xyz = np.zeros((len(x), len(w), 3))
    xyz[..., 0] = x[:, None]
    xyz[..., 1 if plane == "xy" else 2] = w[None]
    return xyz.reshape(-1, 3), grid_quads(len(x), len(w))


def box_mesh(a: float, b: float, c: float, n: int):
    """Closed box [0, a] x [−b/2, b/2] x [−c/2, c/2] of shells, n cells per
    edge, coincident nodes merged."""
    pts, quads = [], []
    g = np.linspace(0.0, 1.0, n + 1)
    lo, hi = np.array([0.0, -b / 2, -c / 2]), np.array([a, b / 2, c / 2])
    for axis in range(3):
        u, v = [k for k in range(3) if k != axis]
        for at in (lo[axis], hi[axis]):
            p = np.zeros((n + 1, n + 1, 3))
            p[..., axis] = at
            p[..., u] = (lo[u] + g * (hi[u] - lo[u]))[:, None]
            p[..., v] = (lo[v] + g * (hi[v] - lo[v]))[None, :]
            quads.append(grid_quads(n + 1, n + 1) + sum(len(x) for x in pts))
            pts.append(p.reshape(-1, 3))
    allp = np.concatenate(pts)
    key = np.round(allp, 9)
    uniq, inv = np.unique(key, axis=0, return_inverse=True)
    return uniq, inv.ravel()[np.concatenate(quads)]


def shell_model(xyz, quads, thickness=1.0, pids=None, young=E, poisson=NU, density=RHO) -> Model:
    """A Model of shells on ``xyz`` (node IDs from 1), MAT_ELASTIC, one part
    per distinct ``pids`` value (default all part 1)."""
    m = Model()
    n = len(xyz)
    m.nodes = Nodes(
        np.arange(1, n + 1, dtype=np.int64), np.asarray(xyz, float), np.zeros(n, np.int8), np.zeros(n, np.int8)
    )
    sh = Shells.zeros(len(quads))
    sh.ids = np.arange(1, len(quads) + 1, dtype=np.int64)
    sh.pid = np.ones(len(quads), np.int64) if pids is None else np.asarray(pids, np.int64)
    sh.nodes = np.asarray(quads, np.int32)
    m.shells = sh
    m.materials[1] = record("MAT_ELASTIC", mid=1, ro=density, e=young, pr=poisson)
    for p in np.unique(sh.pid):
        # the one-point shell of the generic car (the figures of these structures' tests were measured with it)
        m.sections[int(p)] = record(
            "SECTION_SHELL", secid=int(p), elform=2, t1=thickness, t2=thickness, t3=thickness, t4=thickness
        )
        m.parts[int(p)] = record("PART", heading=f"part {int(p)}", pid=int(p), secid=int(p), mid=1)
    return m
