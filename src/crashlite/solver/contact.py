"""Penalty contact in the time loop: one ContactGroup (kind "contact": its
energy counts as sliding energy) per interface, built from the Model's
*CONTACT_AUTOMATIC_... cards by ``contact_build`` (segments, slave entries,
penalty stiffness, options refused).

A Surface holds the segments of one side of an interface and an Interface
the slave entries and master segments the kernels (kernels.contact) take.
Each cycle the group computes the penalty forces of the entries facing a
segment: SOFT = 1 takes the larger of the SOFT = 0 stiffness and
0.5·SOFSCL·m*/Δt0², with m* the reduced mass of the node and the mean node
mass of the segment and Δt0 the initial element time step (DTSTIF when
given). Friction: μ = FSF·(FD + (FS − FD)·exp(−DC·|v_t|)), elastic-plastic
tangential spring of the same stiffness; VDC adds normal damping in percent
of critical (of 2·min(m)·ω, ω² = k/m*). Segments of eroded shells and solids
drop out; BT/DT switch the interface on and off. The rcforc resultant is the
force on the slave side (for a single surface, on all its nodes: it
cancels).

The search is a bucket sort (kernels.contact.find_candidates) with boxes
grown by the contact reach plus a margin; it is redone every BSORT cycles
(default 100) or as soon as a node may have moved half the margin, so the
candidate lists stay conservative.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .groups import ElementGroup
from .kernels import contact as kc
from .state import State

BSORT_DEFAULT = 100  # cycles between bucket sorts (BSORT)


@dataclass
class Surface:
    """Segments of one side of an interface."""

    seg: np.ndarray  # (k, 4) int64 node indices (triangles n1 n2 n3 n3)
    thick: np.ndarray  # (k,) float64 contact thickness [length]
    k: np.ndarray  # (k,) float64 penalty stiffness (SOFT = 0) [force/length]
    onesided: np.ndarray  # (k,) int8 1: solid face
    depth: np.ndarray  # (k,) float64 deepest penetration accepted behind a solid face [length]
    size: np.ndarray  # (k,) float64 √area [length]
    owner: np.ndarray  # (k,) int64 row of the element in model.shells (solid faces: model.solids)
    solid: np.ndarray  # (k,) int8 1: the owner is a solid
    partner: np.ndarray  # (k,) int64 row in model.solids of the solid across an inner face (-1: none)

    @staticmethod
    def empty() -> Surface:
        return Surface(
            np.zeros((0, 4), np.int64),
            np.zeros(0),
            np.zeros(0),
            np.zeros(0, np.int8),
            np.zeros(0),
            np.zeros(0),
            np.zeros(0, np.int64),
            np.zeros(0, np.int8),
            np.zeros(0, np.int64),
        )

    def nodes(self) -> np.ndarray:
        return np.unique(self.seg)

    def node_values(self, nodes: np.ndarray, n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
        """(thickness, stiffness) of ``nodes``: the largest shell thickness and
        the largest stiffness of this surface's segments holding them (0
        and inf for none; the largest, so that a thin side face of a solid
        does not soften the contact of the face it borders)."""
        t, k = np.zeros(n_nodes), np.zeros(n_nodes)
        for a in range(4):
            np.maximum.at(t, self.seg[:, a], self.thick)
            np.maximum.at(k, self.seg[:, a], self.k)
        return t[nodes], np.where(k > 0, k, np.inf)[nodes]


def concat(*surfs: Surface) -> Surface:
    return Surface(
        *(
            np.concatenate([getattr(s, f) for s in surfs])
            for f in ("seg", "thick", "k", "onesided", "depth", "size", "owner", "solid", "partner")
        )
    )


@dataclass
class Interface:
    """One contact interface as the kernels see it (kernels.contact)."""

    cid: int
    name: str
    snode: np.ndarray  # (ns,) int64 slave entry nodes
    sside: np.ndarray  # (ns,) int64 side of the entry (-1: single surface)
    sthick: np.ndarray  # (ns,) float64 [length]
    sk: np.ndarray  # (ns,) float64 [force/length]
    node_side: np.ndarray  # (ns,) int64 1: the node is on the slave side (rcforc), 0: the segment is
    seg: np.ndarray  # (nm, 4) int64
    mside: np.ndarray  # (nm,) int64
    mthick: np.ndarray  # (nm,) float64
    mk: np.ndarray  # (nm,) float64
    onesided: np.ndarray  # (nm,) int8
    depth: np.ndarray  # (nm,) float64
    msize: np.ndarray  # (nm,) float64
    owner: np.ndarray  # (nm,) int64 element row in model.shells or model.solids
    solid: np.ndarray  # (nm,) int8 1: owner in model.solids
    partner: np.ndarray  # (nm,) int64 solid across an inner face, model.solids row (-1: none)
    fs: float = 0.0
    fd: float = 0.0
    dc: float = 0.0
    vdc: float = 0.0
    fsf: float = 1.0
    soft: int = 0
    sofscl: float = 0.1
    dt0: float = np.inf  # initial time step for SOFT = 1 (inf: the first step of the run)
    birth: float = 0.0
    death: float = 1e20
    bsort: int = BSORT_DEFAULT
    ignore: int = 0  # initial penetrations: 0 moved out at set-up, 1 and 2 tracked (IGNORE)


class ContactGroup(ElementGroup):
    """One contact interface in the time loop (groups.ElementGroup, kind
    "contact"): forces ON the nodes into st.f, the work of the contact
    forces as ``energy`` (1,) [energy], the force on the slave side as
    ``resultant`` (3,) [force]."""

    kind = "contact"

    def __init__(self, c: Interface, n_nodes: int, links=()):
        self.c = c
        # eroded elements drop their segments, expose the inner faces of the solids beside them:
        # (segment rows, the group's alive array, element rows in it, across); a group's owner links
        # come before its links across (contact_build._links), which only narrow them
        self.links = list(links)
        self.alive = np.ones(len(c.seg), np.int8)
        self.cid, self.name = c.cid, c.name
        self.ids = np.zeros(0, np.int64)  # no elements: parts and element counts leave contacts out
        self.pid = np.zeros(0, np.int64)
        self.conn = np.zeros((0, 5), np.int64)
        self.energy = np.zeros(1)
        self.resultant = np.zeros(3)
        ns = len(c.snode)
        self.ft = np.zeros((ns, 3))
        self.prev = np.full(ns, -1, np.int64)  # segment of each entry in the last cycle
        self.side = np.zeros(ns, np.int8)  # the side of that (shell) segment it is on
        self.rows = np.zeros((ns, 5, 3))
        self.rnode = np.full((ns, 5), -1, np.int64)
        self._box = np.empty((len(c.seg), 6))  # the segments' bounding boxes of the cycle, grown by their reach
        # how far from a segment a slave node's mid-surface may be in contact, less the node's half thickness
        self._reach = 0.5 * c.mthick + np.where(c.onesided != 0, c.depth + 1e-2 * c.msize, 0.0)
        self.gap = np.zeros(ns)
        self.offset = np.zeros(ns)  # tracked initial penetration of each entry (IGNORE 1, 2) [length]
        self.max_gap = 0.0  # largest penetration met so far [length]
        self.sorts = 0  # bucket sorts done
        self.prm = np.zeros(kc.N_PRM)
        self.prm[[kc.P_FS, kc.P_FD, kc.P_DC, kc.P_VDC, kc.P_FSF]] = c.fs, c.fd, c.dc, c.vdc, c.fsf
        self.involved = np.unique(np.concatenate([c.snode, c.seg.ravel()])).astype(np.int64)
        self.x_sort = np.zeros((len(self.involved), 3))
        # search margin: half a mean segment; boxes grow by the reach of a contact plus the margin
        self.margin = 0.5 * float(c.msize.mean()) if len(c.msize) else 0.0
        tmax = float(c.sthick.max()) if ns else 0.0
        self.grow = 0.5 * (c.mthick + tmax) + np.where(c.onesided == 1, c.depth, 0.0) + self.margin
        self._cptr, self._cand = np.zeros(ns + 1, np.int64), np.zeros(0, np.int64)
        self._since = 0
        self._smass = self._mmass = None
        self._soft_set = False  # the SOFT = 1 stiffness is in prm
        self._active = False  # prm's P_ACTIVE (between BT and DT)

    def lumped(self, n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
        return np.zeros(n_nodes), np.zeros(n_nodes)

    def critical_dt(self, st: State) -> float:
        return np.inf  # the penalty is sized to the elements' step (SOFT = 1: to the initial step)

    def _sort(self, x) -> None:
        c = self.c
        self._cptr, self._cand = kc.find_candidates(x, c.snode, c.sside, c.seg, c.mside, self.grow)
        self.x_sort[:] = x[self.involved]
        self._since = 0
        self.sorts += 1

    def _first(self, st) -> None:
        c = self.c
        mass = np.asarray(st.mass, float)
        self._smass = mass[c.snode]
        nn = np.where(c.seg[:, 2] == c.seg[:, 3], 3, 4)
        self._mmass = (
            mass[c.seg[:, 0]] + mass[c.seg[:, 1]] + mass[c.seg[:, 2]] + np.where(nn == 4, mass[c.seg[:, 3]], 0.0)
        ) / nn
        self._sort(st.x)

    def forces(self, st: State) -> None:
        c = self.c
        if self._smass is None:
            self._first(st)
        if c.soft == 1 and not self._soft_set:
            dt0 = c.dt0 if np.isfinite(c.dt0) else st.dt
            if dt0 > 0:
                self.prm[kc.P_SOFT_K] = 0.5 * c.sofscl / dt0**2
                self._soft_set = True
        active = c.birth <= st.t <= c.death
        if active != self._active:  # written where it changes only: an array write a cycle is not free
            self.prm[kc.P_ACTIVE] = 1.0 if active else 0.0
            self._active = active
        for rows, alive, el, across in self.links:
            kc.link_alive(rows, alive, el, across, self.alive)
        self._since += 1
        if self._since >= c.bsort or 2.0 * kc.max_displacement(st.x, self.x_sort, self.involved) > self.margin:
            self._sort(st.x)
        p_old = kc.power(self.rows, self.rnode, self.gap, st.v)  # forces of t(n) at v(n+½)
        kc.segment_boxes(st.x, c.seg, self._reach, self._box)
        kc.contact_forces(
            st.x,
            st.v,
            float(st.dt),
            c.snode,
            c.sthick,
            c.sk,
            self._smass,
            c.seg,
            c.mthick,
            c.mk,
            self._mmass,
            c.onesided,
            c.depth,
            c.msize,
            self.alive,
            self._box,
            self._cptr,
            self._cand,
            self.prm,
            self.ft,
            self.prev,
            self.side,
            self.rows,
            self.rnode,
            self.gap,
            self.offset,
        )
        p_new, deepest = kc.scatter(self.rows, self.rnode, self.gap, st.v, c.node_side, st.f, self.resultant)
        # work of the contact forces over the step (trapezoid); stored and dissipated energy count positive
        self.energy[0] -= 0.5 * float(st.dt) * (p_old + p_new)
        self.max_gap = max(self.max_gap, deepest)

    def corner_forces(self) -> np.ndarray:
        return np.zeros((0, 5, 3))

    def penetrations(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(normal (ns, 3), gap (ns,), segment nodes (ns, 4)) of every slave
        entry at positions x, at rest and without friction: the contact
        normal (from the segment to the node), the penetration (0: none) and
        the nodes of the segment it penetrates (-1: none). The candidate lists
        are sorted anew at x; the contact state of the time loop (forces,
        friction, segments held) is left as it was
        (penetrations.remove_initial_penetrations)."""
        c = self.c
        ns, nm = len(c.snode), len(c.seg)
        self._sort(x)
        box = np.empty((nm, 6))
        kc.segment_boxes(x, c.seg, self._reach, box)
        prm = self.prm.copy()
        prm[[kc.P_FS, kc.P_FD, kc.P_VDC, kc.P_SOFT_K]] = 0.0
        prm[kc.P_ACTIVE] = 1.0
        rows, rnode, gap = np.zeros((ns, 5, 3)), np.full((ns, 5), -1, np.int64), np.zeros(ns)
        kc.contact_forces(
            x,
            np.zeros_like(x),
            0.0,
            c.snode,
            c.sthick,
            c.sk,
            np.zeros(ns),
            c.seg,
            c.mthick,
            c.mk,
            np.zeros(nm),
            c.onesided,
            c.depth,
            c.msize,
            self.alive,
            box,
            self._cptr,
            self._cand,
            prm,
            np.zeros((ns, 3)),
            np.full(ns, -1, np.int64),
            np.zeros(ns, np.int8),
            rows,
            rnode,
            gap,
            np.zeros(ns),
        )
        f = rows[:, 0, :]
        size = np.linalg.norm(f, axis=1)
        normal = np.where(size[:, None] > 0, f / np.where(size > 0, size, 1.0)[:, None], 0.0)
        return normal, np.where(size > 0, gap, 0.0), rnode[:, 1:]
