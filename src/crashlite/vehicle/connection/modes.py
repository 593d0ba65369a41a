"""Vibration modes of the replaced structure: what a rigid rear leaves out.

The surrogate carries the replaced structure as one rigid body (and the
springs' quasi-static stiffness). The structure itself rings, and a crash
pulse of 60–100 ms excites what rings below some 30 Hz. Both solves run on
the step-3 static model (shells, solids, beams and springs of the replaced
structure; lumped masses of ``relief.replaced_node_masses``) by
shift-invert Lanczos (scipy ``eigsh``) about a small negative shift, so
that rigid modes stay regular:

- ``held_modes``: clamped at the interface, as a rear joined to the front
  there rings (Craig–Bampton's interior modes), with each mode's effective
  mass along and inertia about the vehicle axes: how much of the rear
  would not move with the interface at that frequency;
- ``free_modes``: free, the interface one rigid body as in step 3. With
  the modes mass-normalised, the interface's compliance relative to the
  structure's rigid motion (inertia relief, ``relief``) is Σ φφᵀ/ω² over
  the elastic modes: each mode's term over the whole (the relieved
  flexibility of step 3) is its share of the interface's axial, lateral,
  vertical, roll, pitch or yaw compliance. A uniform free beam's first
  bending mode carries 4·105/(4.730⁴) = 84 % of its end's lateral
  compliance (test).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike
from scipy.sparse.linalg import eigsh

from ..steps.cut import Cut
from ..steps.massprops import NodeSelection
from ..steps.relief import mass_matrix, static_masses
from ..steps.stiffness import build_static
from .connection import DIRECTIONS, vehicle_frame


@dataclass
class FreeModes:
    frequencies: np.ndarray  # (k,) elastic modes [1/time, Hz in mm–t–s]
    interface: np.ndarray  # (k, 6) the rigid interface's [u; θ] in each mass-normalised mode
    rigid_modes: int  # modes found below the elastic ones (6 for one free structure)
    point: np.ndarray  # (3,) the interface's master
    where: list = field(default_factory=list)  # per mode: {part title: share of its kinetic energy}, the largest
    notes: list = field(default_factory=list)

    def shares(self, flexibility: np.ndarray, axis: ArrayLike) -> dict:
        """direction -> (k,) share of the interface's relieved compliance
        (``flexibility``, 6×6 global, at ``point``) each mode carries."""
        r = vehicle_frame(axis)
        phi = self.interface @ r.T  # into the vehicle frame
        c = np.diag(r @ flexibility @ r.T)
        lam = (2.0 * np.pi * self.frequencies) ** 2
        return {name: phi[:, j] ** 2 / lam / c[j] for j, name in enumerate(DIRECTIONS)}

    def summary(self, flexibility: np.ndarray | None = None, axis: ArrayLike = (1.0, 0.0, 0.0)) -> dict:
        out = {
            "frequencies": self.frequencies.tolist(),
            "rigid_modes": self.rigid_modes,
            "kinetic_energy_share_percent": [{k: 100.0 * v for k, v in w.items()} for w in self.where],
            "notes": list(self.notes),
        }
        if flexibility is not None:
            out["compliance_share_percent"] = {
                k: (100.0 * v).tolist() for k, v in self.shares(flexibility, axis).items()
            }
        return out


def free_modes(
    cut: Cut, count: int = 8, interface_nodes: NodeSelection | None = None, drill: float = 1e-3
) -> FreeModes:
    """The ``count`` lowest elastic modes of the replaced structure of ``cut``,
    free, its interface nodes one rigid body (module docstring)."""
    ls, master, _, m, u, lam, rigid, notes = _eigen(cut, count, "rigid", interface_nodes, drill)
    if rigid != 6:
        notes.append(f"{rigid} modes at zero frequency (six for one free rigid structure; more: a mechanism)")
    el = slice(rigid, rigid + count)
    freq = np.sqrt(np.maximum(lam[el], 0.0)) / (2.0 * np.pi)
    where = _where(cut, m, u[: ls.n, :3, el])
    return FreeModes(freq, u[master, :, el].T.copy(), rigid, ls.position(master), where, notes)


@dataclass
class HeldModes:
    """Modes of the replaced structure clamped at its interface (the
    Craig–Bampton interior modes of a rear joined to the front there)."""

    frequencies: np.ndarray  # (k,) [1/time]
    effective: np.ndarray  # (k, 6) effective mass along axis, lateral, vertical [mass] and inertia about them
    #                        through the interface centre [mass·length²], of each mass-normalised mode
    totals: np.ndarray  # (6,) the structure's mass (three times) and its inertia about those axes
    participation: np.ndarray | None = None  # (k, 6) L = Ψᵀ M φ, signed (effective = L²), vehicle frame
    point: np.ndarray | None = None  # (3,) the interface centre the rotations are about
    where: list = field(default_factory=list)
    notes: list = field(default_factory=list)

    def summary(self) -> dict:
        pct = 100.0 * self.effective / self.totals
        return {
            "frequencies": self.frequencies.tolist(),
            "effective_mass_percent": {d: pct[:, j].tolist() for j, d in enumerate(DIRECTIONS)},
            "kinetic_energy_share_percent": [{k: 100.0 * v for k, v in w.items()} for w in self.where],
            "notes": list(self.notes),
        }


def held_modes(
    cut: Cut, count: int = 8, interface_nodes: NodeSelection | None = None, drill: float = 1e-3
) -> HeldModes:
    """The ``count`` lowest modes of the replaced structure of ``cut`` with
    its interface nodes held, and each mode's effective mass: with L = Ψᵀ M φ
    (Ψ the six rigid motions about the interface centre, in the vehicle
    frame) the share L² of the mass (or inertia) that rings in that mode
    when the interface is shaken; the shares of all modes add up to the
    mass less what sits on the interface itself. A uniform cantilever's
    first bending mode holds 61.3 % of its mass, its first axial mode
    8/π² = 81 % (test): where the modes below the crash's frequencies hold
    little, a rigid rear is right."""
    ls, _, nodes, m, u, lam, rigid, notes = _eigen(cut, count, "held", interface_nodes, drill)
    el = slice(rigid, rigid + count)
    xyz = cut.model.nodes.xyz
    p = xyz[nodes].mean(axis=0)
    f = vehicle_frame(cut.axis)[:3, :3]
    r = (xyz - p) @ f.T  # node positions in the vehicle frame about the interface centre
    phi = np.einsum("ab,nbk->nak", f, u[: ls.n, :3, el])  # translations in the vehicle frame
    lt = np.einsum("n,nak->ka", m, phi)  # Ψ_translationᵀ M φ
    lr = np.einsum("n,nak->ka", m, np.cross(r[:, :, None], phi, axis=1))  # rotation e about p: (e × r)·φ = e·(r × φ)
    eff = np.hstack([lt**2, lr**2])
    inertia = np.array([(m * (r**2).sum(axis=1) - m * r[:, j] ** 2).sum() for j in range(3)])
    totals = np.concatenate([np.full(3, float(m.sum())), inertia])
    freq = np.sqrt(np.maximum(lam[el], 0.0)) / (2.0 * np.pi)
    if rigid:
        notes.append(f"{rigid} modes at zero frequency with the interface held: a part not joined to it")
    return HeldModes(freq, eff, totals, np.hstack([lt, lr]), p, _where(cut, m, u[: ls.n, :3, el]), notes)


def _eigen(cut: Cut, count: int, interface: str, interface_nodes, drill: float, shells: str = "static"):
    """Eigen solve on the step-3 static model, the interface "held", one
    "rigid" body or "free" (its nodes as any other): (model, the rigid
    interface's master or None, the interface nodes in it, node masses,
    mode shapes (n_total, 6, k) mass-normalised, eigenvalues, number at
    zero, notes)."""
    model = cut.model
    ls, _, notes = build_static(model, cut.replaced, drill, shells=shells)
    nodes = cut.interface_nodes if interface_nodes is None else np.asarray(interface_nodes, np.int64)
    nodes = nodes[ls.in_structure[nodes]]
    if not len(nodes):
        raise ValueError("no interface node is a node of the replaced structure")
    master = None
    if interface == "held":
        ls.fix(nodes)
    elif interface == "rigid":
        master = ls.add_rigid(nodes)
    m, _, _, _, mnotes = static_masses(cut, ls)
    t, _, _, rnotes = ls.reduction()
    k = (t.T @ ls.stiffness_matrix() @ t).tocsc()
    mm = (t.T @ mass_matrix(ls, m) @ t).tocsc()
    keep = np.flatnonzero(k.diagonal() > 1e-12 * float(np.abs(k.diagonal()).max()))
    k, mm = k[keep][:, keep], mm[keep][:, keep]
    want = min(count + 6 + max(4, count // 2), len(keep) - 2)  # a margin: the last Ritz pairs converge slowest
    shift = -1.0  # [1/time²]: K − σM stays regular with the rigid modes at 0
    lam, vec = eigsh(k, k=want, M=mm, sigma=shift, which="LM", v0=np.ones(len(keep)))  # v0: reproducible
    order = np.argsort(lam)
    lam, vec = lam[order], vec[:, order]
    # rigid modes sit at round-off, the elastic ones far above (a mechanism would show as another ~0)
    rigid = int((lam < 1e-8 * max(float(lam.max()), 1e-300)).sum())
    q = np.zeros((t.shape[1], vec.shape[1]))
    q[keep] = vec
    return ls, master, nodes, m, (t @ q).reshape(ls.n_total, 6, -1), lam, rigid, notes + mnotes + rnotes


def _where(cut: Cut, m: np.ndarray, u: np.ndarray, top: int = 3) -> list:
    """Per mode the parts holding most of its kinetic energy m·|φ|² (each
    node counted for the part of the first replaced element on it)."""
    model = cut.model
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
    title = {
        int(p): str(model.parts.get(int(p), {}).get("heading", "") or f"part {int(p)}")
        for p in np.unique(part_of[part_of >= 0])
    }
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
