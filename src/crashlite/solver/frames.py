"""Local coordinate systems (*DEFINE_COORDINATE_...) as rotation matrices."""

from __future__ import annotations

import numpy as np

from ..model.model import Model


def _orthonormal(ex: np.ndarray, in_plane: np.ndarray) -> np.ndarray:
    """Rows e_x, e_y, e_z: x along ``ex``, y in the plane of ex and in_plane."""
    ex = ex / np.linalg.norm(ex)
    ez = np.cross(ex, in_plane)
    if np.linalg.norm(ez) == 0:
        raise ValueError("the points or vectors defining the system are collinear")
    ez /= np.linalg.norm(ez)
    return np.stack([ex, np.cross(ez, ex), ez])


def axes(model: Model, cid: int) -> np.ndarray:
    """(3, 3) local axes of system ``cid`` in global components (rows x, y, z)."""
    rec = model.coordinate_systems.get(int(cid))
    if rec is None:
        raise KeyError(f"coordinate system {cid} is not defined")
    kw = rec.keyword
    g = lambda *names: np.array([float(rec.get(n, 0.0) or 0.0) for n in names])  # noqa: E731
    if kw == "DEFINE_COORDINATE_SYSTEM":
        if int(rec.get("cidl", 0) or 0):
            raise ValueError("systems defined in another local system (CIDL) are not supported yet")
        o = g("xo", "yo", "zo")
        return _orthonormal(g("xl", "yl", "zl") - o, g("xp", "yp", "zp") - o)
    if kw == "DEFINE_COORDINATE_VECTOR":
        return _orthonormal(g("xx", "yx", "zx"), g("xv", "yv", "zv"))
    if kw == "DEFINE_COORDINATE_NODES":
        if int(rec.get("flag", 0) or 0):
            raise ValueError("FLAG = 1 (system following its nodes) is not supported for constraints")
        x = model.nodes.xyz[model.node_index([rec["n1"], rec["n2"], rec["n3"]])]
        first, plane = x[1] - x[0], x[2] - x[0]
        d = str(rec.get("dir", "X") or "X").strip().upper()
        r = _orthonormal(first, plane)  # rows: the axis along N1-N2 first
        order = {"X": (0, 1, 2), "Y": (2, 0, 1), "Z": (1, 2, 0)}[d]  # N1-N2 along DIR, right-handed
        return r[list(order)]
    raise ValueError(f"*{kw} is not supported")


def project_out(v: np.ndarray, nodes: np.ndarray, held: np.ndarray) -> None:
    """Remove from v[nodes] (k, 3) its components along the held unit
    directions ``held`` (k, 3, 3), rows of zeros for free directions."""
    if len(nodes):
        vn = v[nodes]
        v[nodes] = vn - np.einsum("kd,kdj->kj", np.einsum("kj,kdj->kd", vn, held), held)
