"""Free vibration modes of the replaced structure: what a rigid rear leaves out.

The surrogate carries the replaced structure as one rigid body (and the
springs' quasi-static stiffness). The structure itself rings: its lowest
free modes, with the interface a rigid body as in step 3, lie at
frequencies a crash pulse of 60–100 ms excites where they are below some
50 Hz. ``free_modes`` computes them on the step-3 static model (shells,
solids, beams and springs of the replaced structure; lumped masses of
``relief.replaced_node_masses``) by shift-invert Lanczos (scipy ``eigsh``)
about a small negative shift, so that the six rigid modes stay regular.

With the modes mass-normalised, the interface's compliance relative to the
structure's rigid motion (inertia relief, ``relief``) is Σ φφᵀ/ω² over the
elastic modes: each mode's term over the whole (the relieved flexibility of
step 3) is the share of the interface's axial, lateral, vertical, roll,
pitch or yaw compliance that the mode carries. A uniform free beam's first
bending mode carries 4·105/(4.730⁴) = 84 % of its end's lateral compliance
(test).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import eigsh

from .connection import DIRECTIONS, vehicle_frame
from .cut import Cut
from .relief import replaced_node_masses
from .stiffness import build_static


@dataclass
class FreeModes:
    frequencies: np.ndarray  # (k,) elastic modes [1/time, Hz in mm–t–s]
    interface: np.ndarray  # (k, 6) the rigid interface's [u; θ] in each mass-normalised mode
    rigid_modes: int  # modes found below the elastic ones (6 for one free structure)
    point: np.ndarray  # (3,) the interface's master
    where: list = field(default_factory=list)  # per mode: {part title: share of its kinetic energy}, the largest
    notes: list = field(default_factory=list)

    def shares(self, flexibility: np.ndarray, axis) -> dict:
        """direction -> (k,) share of the interface's relieved compliance
        (``flexibility``, 6×6 global, at ``point``) each mode carries."""
        r = vehicle_frame(axis)
        phi = self.interface @ r.T  # into the vehicle frame
        c = np.diag(r @ flexibility @ r.T)
        lam = (2.0 * np.pi * self.frequencies) ** 2
        return {name: phi[:, j] ** 2 / lam / c[j] for j, name in enumerate(DIRECTIONS)}

    def summary(self, flexibility=None, axis=(1.0, 0.0, 0.0)) -> dict:
        out = {"frequencies": self.frequencies.tolist(), "rigid_modes": self.rigid_modes,
               "kinetic_energy_share_percent": [{k: 100.0 * v for k, v in w.items()} for w in self.where],
               "notes": list(self.notes)}
        if flexibility is not None:
            out["compliance_share_percent"] = {k: (100.0 * v).tolist()
                                               for k, v in self.shares(flexibility, axis).items()}
        return out


def free_modes(cut: Cut, count: int = 8, interface_nodes=None, drill: float = 1e-3) -> FreeModes:
    """The ``count`` lowest elastic modes of the replaced structure of ``cut``,
    free, its interface nodes one rigid body (module docstring)."""
    model = cut.model
    ls, _, notes = build_static(model, cut.replaced, drill)
    nodes = cut.interface_nodes if interface_nodes is None else np.asarray(interface_nodes, np.int64)
    nodes = nodes[ls.in_structure[nodes]]
    if not len(nodes):
        raise ValueError("no interface node is a node of the replaced structure")
    master = ls.add_rigid(nodes)
    m, mnotes = replaced_node_masses(cut)
    m[~ls.in_structure] = 0.0
    t, fixed, slave_of, rnotes = ls.reduction()
    size = 6 * ls.n_total
    diag = np.zeros(size)
    for i in range(3):
        diag[6 * np.arange(ls.n) + i] = m
    k = (t.T @ ls.stiffness_matrix() @ t).tocsc()
    mm = (t.T @ sp.diags(diag) @ t).tocsc()
    live = k.diagonal() > 1e-12 * float(np.abs(k.diagonal()).max())
    keep = np.flatnonzero(live)
    k, mm = k[keep][:, keep], mm[keep][:, keep]
    total = float(m.sum())
    if not total > 0:
        raise ValueError("the replaced structure has no mass")
    want = min(count + 6 + max(4, count // 2), len(keep) - 2)  # a margin: the last Ritz pairs converge slowest
    shift = -1.0  # [1/time²]: K − σM stays regular with the rigid modes at 0
    lam, vec = eigsh(k, k=want, M=mm, sigma=shift, which="LM", v0=np.ones(len(keep)))  # v0: reproducible
    order = np.argsort(lam)
    lam, vec = lam[order], vec[:, order]
    # the rigid modes sit at round-off; the elastic ones far above (a mechanism would show as another ~0)
    scale = max(float(lam.max()), 1e-300)
    rigid = int((lam < 1e-8 * scale).sum())
    if rigid != 6:
        notes.append(f"{rigid} modes at zero frequency (six for one free rigid structure; more: a mechanism)")
    q = np.zeros((t.shape[1], vec.shape[1]))
    q[keep] = vec
    u = (t @ q).reshape(ls.n_total, 6, -1)
    el = slice(rigid, rigid + count)
    freq = np.sqrt(np.maximum(lam[el], 0.0)) / (2.0 * np.pi)
    where = _where(model, cut, m, u[:ls.n, :3, el])
    return FreeModes(freq, u[master, :, el].T.copy(), rigid, ls.position(master), where, notes + mnotes + rnotes)


def _where(model, cut: Cut, m: np.ndarray, u: np.ndarray, top: int = 3) -> list:
    """Per mode the parts holding most of its kinetic energy m·|φ|² (each
    node counted for the part of the first replaced element on it)."""
    part_of = np.full(len(m), -1, np.int64)
    for table in ("beams", "discretes", "solids", "shells"):  # shells last: they win a shared node
        tab = getattr(model, table)
        if not len(tab):
            continue
        sel = cut.replaced[table]
        conn = np.asarray(tab.nodes, np.int64)[sel]
        conn = conn[:, :2] if table in ("beams", "discretes") else conn
        pid = np.broadcast_to(np.asarray(tab.pid)[sel][:, None], conn.shape)
        ok = conn >= 0
        part_of[conn[ok]] = pid[ok]
    title = {int(p): str(model.parts.get(int(p), {}).get("heading", "") or f"part {int(p)}")
             for p in np.unique(part_of[part_of >= 0])}
    title[-1] = "point masses"
    out = []
    for j in range(u.shape[2]):
        e = m * (u[:, :, j] ** 2).sum(axis=1)
        total = float(e.sum())
        by = {}
        for p in np.unique(part_of[e > 0]):
            by[title[int(p)]] = by.get(title[int(p)], 0.0) + float(e[part_of == p].sum()) / total
        out.append(dict(sorted(by.items(), key=lambda kv: -kv[1])[:top]))
    return out
