"""Element groups: one per element family, all seen alike by the time loop.

A group owns its element arrays and state, computes its nodal forces (and
moments) into the loop's arrays, accounts its internal energy per element,
and exposes the per-corner forces that section forces and reports need.
New families (shells, solids) join the loop by being a group.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from .kernels.beam import beam_forces, energy_step6, gather_ends
from .kernels.discrete import discrete_forces, energy_step, gather, incidence
from .state import State


class ElementGroup:
    """Interface of an element family in the time loop.

    ids (ne,) deck element IDs; pid (ne,) part IDs; conn (ne, k) node
    indices (-1: none); energy (ne,) internal energy [energy]; hourglass
    (ne,) hourglass energy or None; refused (ne,) bool or None: elements of
    a part whose card was refused (the run is refused; they carry no mass
    and are not checked further).
    """

    kind = "element"
    ids: np.ndarray
    pid: np.ndarray
    conn: np.ndarray
    energy: np.ndarray
    hourglass: np.ndarray | None = None
    refused: np.ndarray | None = None

    def forces(self, st: State) -> None:
        """Add this group's forces ON the nodes to st.f (moments to st.moment)."""
        raise NotImplementedError

    def account(self) -> None:
        """Energy of the step just computed (after ``forces``)."""

    def corner_forces(self) -> np.ndarray:
        """(ne, k, 3) forces exerted ON the nodes at each element corner."""
        raise NotImplementedError

    def first_step(self, dt: float) -> None:
        """The run's first step, TSSFAC taken off (for limits relative to it)."""

    def corner_moments(self) -> np.ndarray | None:
        """(ne, k, 3) moments ON the nodes, or None for translational elements."""
        return None

    def plastic_strain(self) -> np.ndarray | None:
        """(ne,) effective plastic strain of each element (largest over its
        integration points), or None for a family without one. It never
        decreases, so at the end of a run it is the peak of the run."""
        return None

    def __len__(self) -> int:
        return len(self.ids)


class DiscreteGroup(ElementGroup):
    """*ELEMENT_DISCRETE springs and dampers (kernels.discrete)."""

    kind = "discrete"

    def __init__(self, d, n_nodes: int, pid: np.ndarray | None = None):
        self.d = d
        ne = len(d.ids)
        self.ids = d.ids
        self.pid = pid if pid is not None and len(pid) == ne else np.zeros(ne, np.int64)
        self.conn = np.stack([d.n1, d.n2], axis=1)
        self.fe = np.zeros((ne, 3))  # force on n1 [force]
        self.force = np.zeros(ne)  # axial force, tension positive [force]
        self.elong = np.zeros(ne)  # elongation δ [length]
        self._force_old = np.zeros(ne)
        self._elong_old = np.zeros(ne)
        self.plastic = np.zeros(ne)  # S08 plastic deflection [length]
        self.hist = np.zeros((ne, 4))  # S06 largest deflections and unloading shifts [length]
        zi, zf = np.zeros(ne, np.int64), np.zeros(ne)
        self._s06 = tuple(
            a if a is not None else z
            for a, z in ((d.ucurve_start, zi), (d.ucurve_stop, zi), (d.yield_t, zf), (d.yield_c, zf))
        )
        self.energy = np.zeros(ne)
        self._rows, self._ptr, self._elem, self._sign = incidence(d.n1, d.n2)

    def forces(self, st: State) -> None:
        d = self.d
        if not len(d.ids):
            return
        discrete_forces(
            st.x,
            st.v,
            d.n1,
            d.n2,
            d.kind,
            d.k,
            d.scale,
            d.offset,
            d.length0,
            d.direction,
            d.curve_start,
            d.curve_stop,
            d.curve_x,
            d.curve_y,
            d.ground,
            d.ctf,
            *self._s06,
            self.plastic,
            self.hist,
            self.fe,
            self.force,
            self.elong,
        )
        gather(self._rows, self._ptr, self._elem, self._sign, self.fe, st.f)

    def start(self) -> None:
        """Values at t = 0 are the reference of the energy account."""
        self._force_old[:] = self.force
        self._elong_old[:] = self.elong

    def account(self) -> None:
        if len(self.ids):
            energy_step(self._force_old, self.force, self._elong_old, self.elong, self.energy)

    def corner_forces(self) -> np.ndarray:
        return np.stack([self.fe, -self.fe], axis=1)


class BeamGroup(ElementGroup):
    """Elastic corotational beams (kernels.beam)."""

    kind = "beam"

    def __init__(self, bm, n_nodes: int, pid: np.ndarray | None = None):
        self.bm = bm
        nb = len(bm.ids)
        self.ids = bm.ids
        self.pid = pid if pid is not None and len(pid) == nb else np.zeros(nb, np.int64)
        self.conn = np.stack([bm.n1, bm.n2], axis=1)
        self.fe = np.zeros((nb, 2, 3))
        self.me = np.zeros((nb, 2, 3))
        self.gf, self.gd = np.zeros((nb, 6)), np.zeros((nb, 6))  # generalised resultants, deformations
        self._gf_old, self._gd_old = np.zeros((nb, 6)), np.zeros((nb, 6))
        self.energy = np.zeros(nb)
        corner_nodes = self.conn.ravel()
        self._corner_of = np.argsort(corner_nodes, kind="stable").astype(np.int64)
        ptr = np.zeros(n_nodes + 1, np.int64)
        np.add.at(ptr, corner_nodes + 1, 1)
        self._ptr = np.cumsum(ptr)

    def forces(self, st: State) -> None:
        bm = self.bm
        beam_forces(
            st.x,
            st.rot,
            bm.n1,
            bm.n2,
            bm.q1,
            bm.q2,
            bm.length0,
            bm.ea,
            bm.gj,
            bm.ei2,
            bm.ei3,
            self.fe,
            self.me,
            self.gf,
            self.gd,
        )
        gather_ends(self._ptr, self._corner_of, self.fe, st.f)
        gather_ends(self._ptr, self._corner_of, self.me, st.moment)

    def start(self) -> None:
        self._gf_old[:] = self.gf
        self._gd_old[:] = self.gd

    def account(self) -> None:
        energy_step6(self._gf_old, self.gf, self._gd_old, self.gd, self.energy)

    def corner_forces(self) -> np.ndarray:
        return self.fe

    def corner_moments(self) -> np.ndarray:
        return self.me


def part_energy(groups: Iterable[ElementGroup], part_ids: np.ndarray, attr: str = "energy") -> np.ndarray:
    """(n_parts,) sum of a per-element energy over the groups, per part."""
    out = np.zeros(len(part_ids))
    for g in groups:
        e = getattr(g, attr, None)
        if e is not None and len(g):
            out += np.bincount(np.searchsorted(part_ids, g.pid), e, len(part_ids))
    return out
