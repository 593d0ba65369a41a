"""Spot welds as constraints: *CONSTRAINED_SPOTWELD (a rigid massless
link between two nodes) and *CONSTRAINED_GENERALIZED_WELD_SPOT (the nodes
of a set).

Until it fails, a weld's nodes move as one rigid body: ``forces`` sums
their forces and moments into the weld and hands each node its share of
the rigid-body acceleration (a + α × r, and α for nodes with rotational
DOFs), the difference being the weld force; ``velocities`` then projects
the nodes' velocities on the rigid motion of the same total momentum and
angular momentum (so both are kept exactly, and no drift builds up).

Failure: at the time TF (TFAIL), or when the weld force on a node, split
into the normal part fn (along the weld, node 1 → node 2; for coincident
nodes along the mean normal of the shells at the nodes) and the shear
part fs, reaches (|fn|/SN)^N + (|fs|/SS)^M ≥ 1 (a term with SN or SS = 0
is left out). A failed weld lets its nodes go; the failure time and cause
are kept in ``SpotWelds.log``.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from ..keyword.errors import Problem
from ..model.model import Model
from .state import State
from .tied import _solve3

_LOG = logging.getLogger(__name__)
_REG = 1e-10  # relative regularisation of the weld inertia (collinear nodes without rotations)


@njit(cache=True)
def _inertia(ptr, nodes, k, x, mass, jrot, c, inert):
    """Mass of weld k, its centre into c (3,) and its inertia about c,
    nodal rotary inertia included, into inert (6,: xx yy zz xy xz yz),
    regularised; returns (M, trace)."""
    m_tot = 0.0
    c[0] = c[1] = c[2] = 0.0
    for q in range(ptr[k], ptr[k + 1]):
        i = nodes[q]
        m_tot += mass[i]
        for d in range(3):
            c[d] += mass[i] * x[i, d]
    if m_tot > 0.0:
        for d in range(3):
            c[d] /= m_tot
    for d in range(6):
        inert[d] = 0.0
    for q in range(ptr[k], ptr[k + 1]):
        i = nodes[q]
        r0, r1, r2 = x[i, 0] - c[0], x[i, 1] - c[1], x[i, 2] - c[2]
        rr = r0 * r0 + r1 * r1 + r2 * r2
        m = mass[i]
        inert[0] += m * (rr - r0 * r0) + jrot[i]
        inert[1] += m * (rr - r1 * r1) + jrot[i]
        inert[2] += m * (rr - r2 * r2) + jrot[i]
        inert[3] -= m * r0 * r1
        inert[4] -= m * r0 * r2
        inert[5] -= m * r1 * r2
    tr = inert[0] + inert[1] + inert[2]
    for d in range(3):
        inert[d] += _REG * tr
    return m_tot, tr


@njit(cache=True)
def _solve(inert, tr, b0, b1, b2):
    """inert⁻¹ b (zero for a weld without rotary inertia of any kind)."""
    if tr <= 0.0:
        return 0.0, 0.0, 0.0
    return _solve3(inert[0], inert[3], inert[4], inert[1], inert[5], inert[2], b0, b1, b2)


@njit(cache=True)
def weld_forces(
    ptr,
    nodes,
    alive,
    x,
    f,
    moment,
    mass,
    jrot,
    normal0,
    along,
    sn,
    ss,
    en,
    em,
    t,
    tfail,
    fn_out,
    fs_out,
    crit_out,
    cause,
):
    """Rigid-body share of the summed force and moment for each live weld,
    the weld force on its nodes split into normal fn and shear fs (the
    node with the largest failure measure), and that measure crit_out.
    A weld past its failure time (cause 1) or whose measure reaches 1
    (cause 2) fails here and keeps its nodes' own forces. Returns the
    number that failed (the caller logs them; nothing else to do per cycle)."""
    c = np.empty(3)
    inert = np.empty(6)
    failed = 0
    for k in range(len(alive)):
        if not alive[k]:
            continue
        if t >= tfail[k]:
            alive[k], cause[k] = False, 1
            failed += 1
            continue
        m_tot, tr = _inertia(ptr, nodes, k, x, mass, jrot, c, inert)
        if m_tot <= 0.0:
            continue
        f0 = f1 = f2 = 0.0
        q0 = q1 = q2 = 0.0
        for q in range(ptr[k], ptr[k + 1]):
            i = nodes[q]
            r0, r1, r2 = x[i, 0] - c[0], x[i, 1] - c[1], x[i, 2] - c[2]
            f0 += f[i, 0]
            f1 += f[i, 1]
            f2 += f[i, 2]
            q0 += r1 * f[i, 2] - r2 * f[i, 1]
            q1 += r2 * f[i, 0] - r0 * f[i, 2]
            q2 += r0 * f[i, 1] - r1 * f[i, 0]
            if jrot[i] > 0.0:
                q0 += moment[i, 0]
                q1 += moment[i, 1]
                q2 += moment[i, 2]
        a0, a1, a2 = f0 / m_tot, f1 / m_tot, f2 / m_tot
        al0, al1, al2 = _solve(inert, tr, q0, q1, q2)
        # weld direction: along the nodes (first to last) or the given normal
        n0, n1, n2 = normal0[k, 0], normal0[k, 1], normal0[k, 2]
        if along[k]:
            i1, i2 = nodes[ptr[k]], nodes[ptr[k + 1] - 1]
            d0, d1, d2 = x[i2, 0] - x[i1, 0], x[i2, 1] - x[i1, 1], x[i2, 2] - x[i1, 2]
            ln = np.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
            if ln > 0.0:
                n0, n1, n2 = d0 / ln, d1 / ln, d2 / ln
        worst, wn, ws = 0.0, 0.0, 0.0
        for q in range(ptr[k], ptr[k + 1]):
            i = nodes[q]
            r0, r1, r2 = x[i, 0] - c[0], x[i, 1] - c[1], x[i, 2] - c[2]
            g0 = mass[i] * (a0 + al1 * r2 - al2 * r1) - f[i, 0]
            g1 = mass[i] * (a1 + al2 * r0 - al0 * r2) - f[i, 1]
            g2 = mass[i] * (a2 + al0 * r1 - al1 * r0) - f[i, 2]
            fn = g0 * n0 + g1 * n1 + g2 * n2
            fs = np.sqrt(max(g0 * g0 + g1 * g1 + g2 * g2 - fn * fn, 0.0))
            crit = 0.0
            if sn[k] > 0.0:
                crit += (abs(fn) / sn[k]) ** en[k]
            if ss[k] > 0.0:
                crit += (fs / ss[k]) ** em[k]
            if q == ptr[k] or crit > worst:
                worst, wn, ws = crit, fn, fs
        fn_out[k], fs_out[k], crit_out[k] = wn, ws, worst
        if worst >= 1.0:
            alive[k], cause[k] = False, 2
            failed += 1
            continue
        for q in range(ptr[k], ptr[k + 1]):
            i = nodes[q]
            r0, r1, r2 = x[i, 0] - c[0], x[i, 1] - c[1], x[i, 2] - c[2]
            f[i, 0] = mass[i] * (a0 + al1 * r2 - al2 * r1)
            f[i, 1] = mass[i] * (a1 + al2 * r0 - al0 * r2)
            f[i, 2] = mass[i] * (a2 + al0 * r1 - al1 * r0)
            if jrot[i] > 0.0:
                moment[i, 0] = jrot[i] * al0
                moment[i, 1] = jrot[i] * al1
                moment[i, 2] = jrot[i] * al2
    return failed


@njit(cache=True)
def weld_velocities(ptr, nodes, alive, x, v, w, mass, jrot):
    """Velocities of each live weld's nodes: the rigid motion with their
    total momentum and angular momentum about the mass centre."""
    c = np.empty(3)
    inert = np.empty(6)
    for k in range(len(alive)):
        if not alive[k]:
            continue
        m_tot, tr = _inertia(ptr, nodes, k, x, mass, jrot, c, inert)
        if m_tot <= 0.0:
            continue
        p0 = p1 = p2 = 0.0
        l0 = l1 = l2 = 0.0
        for q in range(ptr[k], ptr[k + 1]):
            i = nodes[q]
            m = mass[i]
            r0, r1, r2 = x[i, 0] - c[0], x[i, 1] - c[1], x[i, 2] - c[2]
            p0 += m * v[i, 0]
            p1 += m * v[i, 1]
            p2 += m * v[i, 2]
            l0 += m * (r1 * v[i, 2] - r2 * v[i, 1])
            l1 += m * (r2 * v[i, 0] - r0 * v[i, 2])
            l2 += m * (r0 * v[i, 1] - r1 * v[i, 0])
            if jrot[i] > 0.0:
                l0 += jrot[i] * w[i, 0]
                l1 += jrot[i] * w[i, 1]
                l2 += jrot[i] * w[i, 2]
        v0, v1, v2 = p0 / m_tot, p1 / m_tot, p2 / m_tot
        o0, o1, o2 = _solve(inert, tr, l0, l1, l2)
        for q in range(ptr[k], ptr[k + 1]):
            i = nodes[q]
            r0, r1, r2 = x[i, 0] - c[0], x[i, 1] - c[1], x[i, 2] - c[2]
            v[i, 0] = v0 + o1 * r2 - o2 * r1
            v[i, 1] = v1 + o2 * r0 - o0 * r2
            v[i, 2] = v2 + o0 * r1 - o1 * r0
            if jrot[i] > 0.0:
                w[i, 0] = o0
                w[i, 1] = o1
                w[i, 2] = o2


@dataclass
class SpotWelds:
    """k welds. ids (k,) weld IDs; keyword (k,) the card of each; ptr
    (k+1,), nodes (m,) CSR member node indices; sn, ss [force], en, em
    failure criterion; tfail (k,) failure time [time]; normal0 (k, 3) weld
    normal where the nodes coincide; along (k,) the normal runs along the
    nodes; alive (k,) bool; fail_time (k,) (inf while intact); fn, fs
    (k,) last normal and shear weld force [force]; crit (k,) last failure
    measure; log: (weld ID, time, cause) of each failure, in order."""

    ids: np.ndarray
    keyword: list
    ptr: np.ndarray
    nodes: np.ndarray
    sn: np.ndarray
    ss: np.ndarray
    en: np.ndarray
    em: np.ndarray
    tfail: np.ndarray
    normal0: np.ndarray
    along: np.ndarray
    alive: np.ndarray = None
    fail_time: np.ndarray = None
    fn: np.ndarray = None
    fs: np.ndarray = None
    crit: np.ndarray = None
    log: list = field(default_factory=list)
    _jrot: np.ndarray | None = None

    def __post_init__(self):
        k = len(self.ids)
        self.alive = np.ones(k, np.bool_)
        self.fail_time = np.full(k, np.inf)
        self.fn, self.fs, self.crit = np.zeros(k), np.zeros(k), np.zeros(k)
        self._cause = np.zeros(k, np.int8)  # set by weld_forces where a weld fails: 1 time, 2 force

    def __len__(self) -> int:
        return len(self.ids)

    def _rot(self, st) -> np.ndarray:
        if self._jrot is None or len(self._jrot) != len(st.mass):
            self._jrot = np.asarray(st.rot_inertia, float)
        return self._jrot

    def forces(self, st: State) -> None:
        t = float(getattr(st, "t", 0.0))
        failed = weld_forces(
            self.ptr,
            self.nodes,
            self.alive,
            st.x,
            st.f,
            st.moment,
            st.mass,
            self._rot(st),
            self.normal0,
            self.along,
            self.sn,
            self.ss,
            self.en,
            self.em,
            t,
            self.tfail,
            self.fn,
            self.fs,
            self.crit,
            self._cause,
        )
        if failed:  # logged in the order they are checked: by time, then by force
            for code, why in ((1, "time"), (2, "force")):
                for k in np.flatnonzero(self._cause == code):
                    self._fail(k, t, why)
            self._cause[:] = 0

    def velocities(self, st: State) -> None:
        # dead welds are skipped there: no check of its own here
        weld_velocities(self.ptr, self.nodes, self.alive, st.x, st.v, st.w, st.mass, self._rot(st))

    def start(self, v: np.ndarray, w: np.ndarray, mass: np.ndarray, rot_inertia: np.ndarray, x: np.ndarray) -> None:
        """Initial velocities made rigid per weld, momentum and angular
        momentum kept (the kinetic energy of the relative motion is lost,
        as in a plastic impact)."""
        if self.alive.any():
            weld_velocities(
                self.ptr, self.nodes, self.alive & (self.tfail > 0), x, v, w, mass, np.asarray(rot_inertia, float)
            )

    def _fail(self, k: int, t: float, cause: str) -> None:
        self.alive[k] = False  # (the kernel has cleared it already where it failed the weld)
        self.fail_time[k] = t
        self.log.append((int(self.ids[k]), t, cause))
        _LOG.info(
            "*%s %d failed at t = %.6g (%s; fn = %.4g, fs = %.4g)",
            self.keyword[k],
            int(self.ids[k]),
            t,
            cause,
            self.fn[k],
            self.fs[k],
        )


# --- from the Model ------------------------------------------------------------------------------


def _problem(rec, fld, msg) -> Problem:
    f, line = rec.where(fld) if hasattr(rec, "where") else ("", 0)
    return Problem(f, line, getattr(rec, "name", ""), fld.upper() if fld else None, msg)


def _shell_normals(model: Model) -> np.ndarray:
    """(n, 3) sum of the unit normals of the shells at each node."""
    out = np.zeros((len(model.nodes), 3))
    sh = model.shells
    if not len(sh):
        return out
    x = model.nodes.xyz
    c = sh.nodes.astype(np.int64)
    c4 = np.where(c[:, 3] < 0, c[:, 2], c[:, 3])
    nrm = np.cross(x[c[:, 2]] - x[c[:, 0]], x[c4] - x[c[:, 1]])
    tri = c4 == c[:, 2]
    nrm[tri] = np.cross(x[c[tri, 1]] - x[c[tri, 0]], x[c[tri, 2]] - x[c[tri, 0]])
    nrm /= np.maximum(np.linalg.norm(nrm, axis=1), 1e-300)[:, None]
    for a in range(4):
        sel = (a < 3) | ~tri
        np.add.at(out, c[sel, a], nrm[sel])
    return out


def build_spotwelds(model: Model, problems: list) -> SpotWelds | None:
    """The spot welds of a deck (None without any)."""
    rows = []  # (id, keyword, node indices, sn, ss, n, m, tfail, rec)
    for rec in model.find("CONSTRAINED_SPOTWELD"):
        r = rec.rows if rec.rows else None
        entries = [{k: r[k][i] for k in r} for i in range(len(r["n1"]))] if r else [rec]
        for _i, e in enumerate(entries):
            get = (lambda k, d=None, e=e: e.get(k, d)) if isinstance(e, dict) else e.get
            n1, n2 = int(get("n1") or 0), int(get("n2") or 0)
            idx = model.node_index([n1, n2])
            if n1 <= 0 or n2 <= 0 or np.any(idx < 0) or n1 == n2:
                problems.append(_problem(rec, "n1", f"a spot weld needs two distinct defined nodes (N1 {n1}, N2 {n2})"))
                continue
            if float(get("ep", 1e20) or 1e20) < 1e20:
                problems.append(_problem(rec, "ep", "plastic-strain failure (EP) of spot welds is not supported yet"))
                continue
            wid = int(get("wid") or 0) or len(rows) + 1
            rows.append(
                (
                    wid,
                    rec.keyword,
                    idx.astype(np.int64),
                    get("sn", 0.0),
                    get("ss", 0.0),
                    get("n", 0.0),
                    get("m", 0.0),
                    get("tf", 1e20),
                    rec,
                )
            )
    for rec in model.find("CONSTRAINED_GENERALIZED_WELD"):
        if rec.keyword != "CONSTRAINED_GENERALIZED_WELD_SPOT":
            problems.append(_problem(rec, None, f"*{rec.keyword} is not supported (GENERALIZED_WELD_SPOT is)"))
            continue
        nsid = int(rec.get("nsid") or 0)
        if ("NODE", nsid) not in model.sets:
            problems.append(_problem(rec, "nsid", f"*SET_NODE {nsid} is not defined"))
            continue
        idx = model.node_index(model.set_members("NODE", nsid))
        if len(idx) < 2 or np.any(idx < 0):
            problems.append(
                _problem(
                    rec,
                    "nsid",
                    f"a generalized spot weld needs at least 2 defined nodes; "
                    f"*SET_NODE {nsid} has {int((idx >= 0).sum())}",
                )
            )
            continue
        if int(rec.get("cid") or 0):
            problems.append(_problem(rec, "cid", "failure forces in a local system (CID) are not supported yet"))
            continue
        if float(rec.get("epsf", 1e20) or 1e20) < 1e20:
            problems.append(_problem(rec, "epsf", "plastic-strain failure (EPSF) is not supported yet"))
            continue
        wid = int(rec.get("wid") or 0) or len(rows) + 1
        rows.append(
            (
                wid,
                rec.keyword,
                idx.astype(np.int64),
                rec.get("sn", 0.0),
                rec.get("ss", 0.0),
                rec.get("n", 0.0),
                rec.get("m", 0.0),
                rec.get("tfail", 1e20),
                rec,
            )
        )
    if not rows:
        return None
    x = model.nodes.xyz
    normals = None
    k = len(rows)
    sn, ss, en, em, tf = (np.zeros(k) for _ in range(5))
    normal0, along = np.zeros((k, 3)), np.zeros(k, np.bool_)
    owner: dict[int, int] = {}
    for j, (wid, kw, idx, a_sn, a_ss, a_n, a_m, a_tf, rec) in enumerate(rows):
        sn[j], ss[j] = float(a_sn or 0.0), float(a_ss or 0.0)
        en[j], em[j] = float(a_n or 0.0), float(a_m or 0.0)
        tf[j] = float(a_tf if a_tf not in (None, 0.0) else 1e20)
        for fld, s_, e_ in (("n", sn[j], en[j]), ("m", ss[j], em[j])):
            if s_ < 0 or (s_ > 0 and e_ <= 0):
                problems.append(
                    _problem(rec, fld, f"weld {wid}: SN/SS >= 0 and exponents N, M > 0 with them are needed")
                )
        for i in idx:
            if int(i) in owner:
                problems.append(
                    _problem(
                        rec,
                        "n1" if kw == "CONSTRAINED_SPOTWELD" else "nsid",
                        f"node {int(model.nodes.ids[i])} is in two welds ({owner[int(i)]} and "
                        f"{wid}); join them in one generalized weld instead",
                    )
                )
            owner[int(i)] = wid
        d = x[idx[-1]] - x[idx[0]]
        if np.linalg.norm(d) > 1e-9 * max(1.0, float(np.abs(x[idx]).max())):
            along[j] = True
        elif sn[j] > 0 or ss[j] > 0:
            if normals is None:
                normals = _shell_normals(model)
            nrm = normals[idx].sum(axis=0)
            if np.linalg.norm(nrm) == 0:
                problems.append(
                    _problem(
                        rec,
                        "n1" if kw == "CONSTRAINED_SPOTWELD" else "nsid",
                        f"weld {wid}: the nodes coincide and no shell gives a normal for the failure forces",
                    )
                )
            else:
                normal0[j] = nrm / np.linalg.norm(nrm)
    ptr = np.zeros(k + 1, np.int64)
    ptr[1:] = np.cumsum([len(r[2]) for r in rows])
    return SpotWelds(
        np.array([r[0] for r in rows], np.int64),
        [r[1] for r in rows],
        ptr,
        np.concatenate([r[2] for r in rows]).astype(np.int64),
        sn,
        ss,
        en,
        em,
        tf,
        normal0,
        along,
    )
