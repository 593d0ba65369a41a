"""Tied contacts as kinematic constraints: *CONTACT_TIED_NODES_TO_SURFACE
and *CONTACT_TIED_SHELL_EDGE_TO_SURFACE (each also _OFFSET; the shell edge
also _BEAM_OFFSET).

At set-up every slave node is projected on the nearest master segment;
nodes farther than the search distance stay free and are listed
(``TiedContact.untied``, with a warning) as LS-DYNA warns about them. A
tied slave then follows its master point: its velocity is the shape-function
interpolation of the segment nodes' velocities, and its force (and mass, at
set-up) goes to those nodes with the same weights, so momentum is kept and
the time step stays that of the elements.

Search distance: the larger of 0.6·(t_slave + t_master) and 5 % of the
segment's longest diagonal, t the contact thickness at the nodes, as
LS-DYNA's tied contacts: the shell thickness (scaled by the part's SFT,
*PART_CONTACT), |SST|·SFST, |MST|·SFMT when given, the part's OPTT over
both.

_OFFSET keeps the initial gap r as a rigid offset: v_s = v_m + ω × r, with
ω the master nodes' angular velocity where they have rotational DOFs, else
the spin of the segment (best fit of its nodes' velocities); the moment
r × f_s of the slave force goes to the segment. SHELL_EDGE_TO_SURFACE ties
the slave rotations as well (ω_s = ω, the slave moment and rotary inertia
go to the segment) and always carries the gap as a rigid offset. Without
_OFFSET, NODES_TO_SURFACE carries the gap as a translation (the slave is
not moved onto the surface as LS-DYNA does; the gap is within the search
distance) and leaves the slave rotations free.

SHELL_EDGE_TO_SURFACE_BEAM_OFFSET: LS-DYNA ties by penalty, with beams
across the gap whose stiffness follows the shells' and which carry the
moments. crashlite runs it as the shell-edge tie above, the gap kept as a
rigid offset and the rotations tied: the limit of infinitely stiff beams
(the penalty's compliance, small beside the shells', is left out), with
one warning per card saying so.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numba import njit

from ..keyword.errors import Problem
from ..model.contacts import interface_numbers
from ..model.model import Model
from .contact_build import part_contact
from .state import State

# hexahedron faces (LS-DYNA node order) for the exterior of solid parts
_HEX_FACES = np.array([[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]])


# --- kernels (time loop) -------------------------------------------------------------------------


@njit(cache=True)
def _solve3(a00, a01, a02, a11, a12, a22, b0, b1, b2):
    """Solution of the symmetric 3×3 system A y = b (zero if singular)."""
    c00 = a11 * a22 - a12 * a12
    c01 = a02 * a12 - a01 * a22
    c02 = a01 * a12 - a02 * a11
    det = a00 * c00 + a01 * c01 + a02 * c02
    if det == 0.0:
        return 0.0, 0.0, 0.0
    c11 = a00 * a22 - a02 * a02
    c12 = a01 * a02 - a00 * a12
    c22 = a00 * a11 - a01 * a01
    return (
        (c00 * b0 + c01 * b1 + c02 * b2) / det,
        (c01 * b0 + c11 * b1 + c12 * b2) / det,
        (c02 * b0 + c12 * b1 + c22 * b2) / det,
    )


@njit(cache=True)
def _segment_frame(x, seg, nn, j, p):
    """p[a] = x of segment node a minus the segment centroid; returns the
    inertia-like tensor Σ (|p|² I − p pᵀ) as 6 components."""
    c0 = 0.0
    c1 = 0.0
    c2 = 0.0
    for a in range(nn[j]):
        m = seg[j, a]
        c0 += x[m, 0]
        c1 += x[m, 1]
        c2 += x[m, 2]
    c0 /= nn[j]
    c1 /= nn[j]
    c2 /= nn[j]
    a00 = a01 = a02 = a11 = a12 = a22 = 0.0
    for a in range(nn[j]):
        m = seg[j, a]
        p[a, 0] = x[m, 0] - c0
        p[a, 1] = x[m, 1] - c1
        p[a, 2] = x[m, 2] - c2
        q = p[a, 0] ** 2 + p[a, 1] ** 2 + p[a, 2] ** 2
        a00 += q - p[a, 0] * p[a, 0]
        a11 += q - p[a, 1] * p[a, 1]
        a22 += q - p[a, 2] * p[a, 2]
        a01 -= p[a, 0] * p[a, 1]
        a02 -= p[a, 0] * p[a, 2]
        a12 -= p[a, 1] * p[a, 2]
    return a00, a01, a02, a11, a12, a22


@njit(cache=True)
def tie_forces(slave, seg, w, nn, offset, rotations, mrot, x, f, moment):
    """Move each slave's force (and with ``rotations`` its moment) to its
    segment nodes with the shape functions w; with ``offset`` the moment of
    the slave force about the master point goes to the segment too: as
    nodal moments where the masters rotate (mrot), else as the nodal forces
    a × p_a whose resultant is zero and whose moment is r × f_s.
    Serial over the ties: a fixed summation order on shared masters."""
    p = np.empty((4, 3))
    for j in range(slave.shape[0]):
        s = slave[j]
        f0, f1, f2 = f[s, 0], f[s, 1], f[s, 2]
        f[s, 0] = 0.0
        f[s, 1] = 0.0
        f[s, 2] = 0.0
        r0, r1, r2 = x[s, 0], x[s, 1], x[s, 2]
        for a in range(4):
            m, wa = seg[j, a], w[j, a]
            f[m, 0] += wa * f0
            f[m, 1] += wa * f1
            f[m, 2] += wa * f2
            r0 -= wa * x[m, 0]
            r1 -= wa * x[m, 1]
            r2 -= wa * x[m, 2]
        if not offset:
            continue
        q0 = r1 * f2 - r2 * f1
        q1 = r2 * f0 - r0 * f2
        q2 = r0 * f1 - r1 * f0
        if rotations:
            q0 += moment[s, 0]
            q1 += moment[s, 1]
            q2 += moment[s, 2]
            moment[s, 0] = 0.0
            moment[s, 1] = 0.0
            moment[s, 2] = 0.0
        if mrot[j]:
            for a in range(4):
                m, wa = seg[j, a], w[j, a]
                moment[m, 0] += wa * q0
                moment[m, 1] += wa * q1
                moment[m, 2] += wa * q2
        else:
            a00, a01, a02, a11, a12, a22 = _segment_frame(x, seg, nn, j, p)
            y0, y1, y2 = _solve3(a00, a01, a02, a11, a12, a22, q0, q1, q2)
            for a in range(nn[j]):
                m = seg[j, a]
                f[m, 0] += y1 * p[a, 2] - y2 * p[a, 1]
                f[m, 1] += y2 * p[a, 0] - y0 * p[a, 2]
                f[m, 2] += y0 * p[a, 1] - y1 * p[a, 0]


@njit(cache=True)
def tie_velocities(slave, seg, w, nn, offset, rotations, mrot, x, v, wang):
    """Slave velocities from their segments: v_s = Σ w_a v_a (+ ω × r with
    ``offset``); with ``rotations`` the slave angular velocity is ω."""
    p = np.empty((4, 3))
    for j in range(slave.shape[0]):
        s = slave[j]
        v0 = v1 = v2 = 0.0
        r0, r1, r2 = x[s, 0], x[s, 1], x[s, 2]
        for a in range(4):
            m, wa = seg[j, a], w[j, a]
            v0 += wa * v[m, 0]
            v1 += wa * v[m, 1]
            v2 += wa * v[m, 2]
            r0 -= wa * x[m, 0]
            r1 -= wa * x[m, 1]
            r2 -= wa * x[m, 2]
        if offset:
            if mrot[j]:
                o0 = o1 = o2 = 0.0
                for a in range(4):
                    m, wa = seg[j, a], w[j, a]
                    o0 += wa * wang[m, 0]
                    o1 += wa * wang[m, 1]
                    o2 += wa * wang[m, 2]
            else:  # spin of the segment: ω = A⁻¹ Σ p_a × (v_a − v̄)
                a00, a01, a02, a11, a12, a22 = _segment_frame(x, seg, nn, j, p)
                k = nn[j]
                b0 = b1 = b2 = 0.0
                m0 = m1 = m2 = 0.0
                for a in range(k):
                    m = seg[j, a]
                    m0 += v[m, 0] / k
                    m1 += v[m, 1] / k
                    m2 += v[m, 2] / k
                for a in range(k):
                    m = seg[j, a]
                    u0, u1, u2 = v[m, 0] - m0, v[m, 1] - m1, v[m, 2] - m2
                    b0 += p[a, 1] * u2 - p[a, 2] * u1
                    b1 += p[a, 2] * u0 - p[a, 0] * u2
                    b2 += p[a, 0] * u1 - p[a, 1] * u0
                o0, o1, o2 = _solve3(a00, a01, a02, a11, a12, a22, b0, b1, b2)
            v0 += o1 * r2 - o2 * r1
            v1 += o2 * r0 - o0 * r2
            v2 += o0 * r1 - o1 * r0
            if rotations:
                wang[s, 0] = o0
                wang[s, 1] = o1
                wang[s, 2] = o2
        v[s, 0] = v0
        v[s, 1] = v1
        v[s, 2] = v2


# --- the constraint ------------------------------------------------------------------------------


@dataclass
class TiedContact:
    """One tied-contact card: k tied slave nodes.

    slave (k,) node indices; seg (k, 4) segment node indices (triangles
    n1 n2 n3 n3); w (k, 4) shape functions at the projection (w[3] = 0 on
    triangles); nn (k,) distinct segment nodes (3 or 4); gap (k,) initial
    distance slave - master point [length]; mrot (k,) the segment nodes have
    rotational DOFs; untied (j,) deck IDs of slave nodes left free.
    """

    cid: int
    keyword: str
    slave: np.ndarray
    seg: np.ndarray
    w: np.ndarray
    nn: np.ndarray
    gap: np.ndarray
    offset: bool
    rotations: bool
    mrot: np.ndarray = field(default_factory=lambda: np.zeros(0, np.bool_))
    untied: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    warnings: list = field(default_factory=list)

    def __len__(self) -> int:
        return len(self.slave)

    def forces(self, st: State) -> None:
        if len(self.slave):
            tie_forces(
                self.slave, self.seg, self.w, self.nn, self.offset, self.rotations, self.mrot, st.x, st.f, st.moment
            )

    def velocities(self, st: State) -> None:
        if len(self.slave):
            tie_velocities(
                self.slave, self.seg, self.w, self.nn, self.offset, self.rotations, self.mrot, st.x, st.v, st.w
            )

    def lump(self, mass: np.ndarray, rot_inertia: np.ndarray, x: np.ndarray) -> None:
        """Move the slave masses (and, where the tie turns them, rotary
        inertias plus m·|r|²) to the segment nodes by the shape functions."""
        ms = mass[self.slave].copy()
        for a in range(4):
            np.add.at(mass, self.seg[:, a], self.w[:, a] * ms)
        mass[self.slave] = 0.0
        self.mrot = np.all(rot_inertia[self.seg] > 0, axis=1)
        if self.offset:
            r = x[self.slave] - np.einsum("ka,kaj->kj", self.w, x[self.seg])
            js = ms * np.einsum("kj,kj->k", r, r)
            if self.rotations:
                js += rot_inertia[self.slave]
                rot_inertia[self.slave] = 0.0
            js = np.where(self.mrot, js, 0.0)
            for a in range(4):
                np.add.at(rot_inertia, self.seg[:, a], self.w[:, a] * js)

    def start(self, v: np.ndarray, mass: np.ndarray, slave_mass: np.ndarray, x: np.ndarray, w: np.ndarray) -> None:
        """Initial velocities made consistent with the tie, keeping the
        momentum: each slave's momentum relative to the motion the tie
        gives it goes to the segment nodes (masses ``mass`` after ``lump``);
        a consistent start is left as it is."""
        if not len(self.slave):
            return
        target, w_t = v.copy(), w.copy()
        tie_velocities(self.slave, self.seg, self.w, self.nn, self.offset, self.rotations, self.mrot, x, target, w_t)
        dp = slave_mass[:, None] * (v[self.slave] - target[self.slave])
        dv = np.zeros_like(v)
        for a in range(4):
            np.add.at(dv, self.seg[:, a], self.w[:, a, None] * dp)
        on = mass > 0
        v[on] += dv[on] / mass[on, None]
        tie_velocities(self.slave, self.seg, self.w, self.nn, self.offset, self.rotations, self.mrot, x, v, w)


# --- from the Model ------------------------------------------------------------------------------


def _problem(rec, fld, msg) -> Problem:
    f, line = rec.where(fld) if hasattr(rec, "where") else ("", 0)
    return Problem(f, line, getattr(rec, "name", ""), fld.upper() if fld else None, msg)


def shell_thickness(model: Model) -> np.ndarray:
    """(n_shells,) element thickness: the mean of the nodal ones given on
    the element card, else T1 of the part's *SECTION_SHELL (0 unknown)."""
    sh = model.shells
    out = np.zeros(len(sh))
    sec_t = {}
    for pid, part in model.parts.items():
        sec = model.sections.get(part.get("secid"))
        if sec is not None and sec.keyword == "SECTION_SHELL":
            sec_t[pid] = float(sec.get("t1") or 0.0)
    ok = np.isfinite(sh.thickness) & (sh.thickness > 0)
    count = ok.sum(axis=1)
    mean = np.where(ok, sh.thickness, 0.0).sum(axis=1) / np.maximum(count, 1)
    for i in range(len(sh)):
        out[i] = mean[i] if count[i] else sec_t.get(int(sh.pid[i]), 0.0)
    return out


def _node_thickness(model: Model) -> tuple[np.ndarray, np.ndarray]:
    """((n,) largest contact thickness of the shells at each node: the
    shell thickness scaled by the part's SFT, its OPTT where given
    (*PART_CONTACT) [length]; (n,) the node's thickness is an OPTT)."""
    t = np.zeros(len(model.nodes))
    optt = np.zeros(len(model.nodes), bool)
    sh = model.shells
    if len(sh):
        pc = part_contact(model)
        te = shell_thickness(model)
        given = np.zeros(len(sh), bool)
        for pid, v in pc.items():
            on = sh.pid == pid
            if v["optt"] > 0:
                te[on], given[on] = v["optt"], True
            elif v["sft"] > 0:
                te[on] *= v["sft"]
        conn = sh.nodes.astype(np.int64)
        for a in range(4):
            ok = conn[:, a] >= 0
            np.maximum.at(t, conn[ok, a], te[ok])
            optt[conn[ok & given, a]] = True
    return t, optt


def exterior_faces(conn: np.ndarray) -> np.ndarray:
    """(k, 4) node indices of the faces of hexahedra (n, 8) met once (the
    exterior); degenerate faces (fewer than 3 distinct nodes) dropped."""
    if not len(conn):
        return np.zeros((0, 4), np.int64)
    faces = conn[:, _HEX_FACES].reshape(-1, 4)
    key = np.sort(faces, axis=1)
    _, inv, count = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    faces = faces[count[inv.ravel()] == 1]
    out = []
    for f in faces:
        u = list(dict.fromkeys(int(a) for a in f))
        if len(u) == 4:
            out.append(u)
        elif len(u) == 3:
            out.append(u + [u[2]])
    return np.array(out, np.int64).reshape(-1, 4)


def _parts(model: Model, rec, typ: int, sid: int, fld: str, problems: list):
    """Part IDs of a part set (2) or part (3), or None (Problem added)."""
    if typ == 3:
        if sid not in model.parts:
            problems.append(_problem(rec, fld, f"part {sid} is not defined"))
            return None
        return np.array([sid], np.int64)
    try:
        return model.set_members("PART", sid)
    except KeyError:
        problems.append(_problem(rec, fld, f"*SET_PART {sid} is not defined"))
        return None


def _segments(model: Model, rec, problems: list) -> np.ndarray | None:
    """(k, 4) node indices of the master segments (triangles n1 n2 n3 n3)."""
    sid, typ = int(rec.get("msid") or 0), int(rec.get("mstyp") or 0)
    if sid <= 0:
        problems.append(_problem(rec, "msid", "a master surface (MSID > 0) is needed"))
        return None
    if typ == 0:
        if ("SEGMENT", sid) not in model.sets:
            problems.append(_problem(rec, "msid", f"*SET_SEGMENT {sid} is not defined"))
            return None
        ids = model.set_members("SEGMENT", sid)
        ids = ids.copy()
        ids[:, 3] = np.where(ids[:, 3] <= 0, ids[:, 2], ids[:, 3])
        seg = model.node_index(ids.ravel()).reshape(-1, 4)
    elif typ == 1:
        if ("SHELL", sid) not in model.sets:
            problems.append(_problem(rec, "msid", f"*SET_SHELL {sid} is not defined"))
            return None
        sel = np.isin(model.shells.ids, model.set_members("SHELL", sid))
        seg = model.shells.nodes[sel].astype(np.int64)
    elif typ in (2, 3):
        pids = _parts(model, rec, typ, sid, "msid", problems)
        if pids is None:
            return None
        seg = model.shells.nodes[np.isin(model.shells.pid, pids)].astype(np.int64)
        solids = model.solids.nodes[np.isin(model.solids.pid, pids)].astype(np.int64)
        seg = np.concatenate([seg.reshape(-1, 4), exterior_faces(solids)])
    else:
        problems.append(
            _problem(
                rec,
                "mstyp",
                f"MSTYP {typ} is not supported for tied contacts (0 segment set, 1 shell set, 2 part set, 3 part)",
            )
        )
        return None
    if len(seg) == 0:
        problems.append(_problem(rec, "msid", f"the master surface {sid} (MSTYP {typ}) has no segments"))
        return None
    seg = seg.copy()
    seg[:, 3] = np.where(seg[:, 3] < 0, seg[:, 2], seg[:, 3])
    if np.any(seg < 0):
        problems.append(_problem(rec, "msid", "a master segment names an undefined node"))
        return None
    return seg


def _slaves(model: Model, rec, problems: list) -> np.ndarray | None:
    sid, typ = int(rec.get("ssid") or 0), int(rec.get("sstyp") or 0)
    if sid <= 0:
        problems.append(_problem(rec, "ssid", "slave nodes (SSID > 0) are needed"))
        return None
    kinds = {4: "NODE", 0: "SEGMENT", 1: "SHELL"}
    if typ in kinds:
        if (kinds[typ], sid) not in model.sets:
            problems.append(_problem(rec, "ssid", f"*SET_{kinds[typ]} {sid} is not defined (SSTYP {typ})"))
            return None
        ids = model.set_members(kinds[typ], sid)
        if typ == 4:
            nodes = model.node_index(ids)
        elif typ == 0:
            nodes = model.node_index(ids[ids > 0])
        else:
            nodes = model.shells.nodes[np.isin(model.shells.ids, ids)].ravel().astype(np.int64)
    elif typ in (2, 3):
        pids = _parts(model, rec, typ, sid, "ssid", problems)
        if pids is None:
            return None
        nodes = np.concatenate(
            [
                t.nodes[np.isin(t.pid, pids)][:, :k].ravel().astype(np.int64)
                for t, k in ((model.shells, 4), (model.solids, 8), (model.beams, 2))
            ]
        )
    else:
        problems.append(
            _problem(
                rec,
                "sstyp",
                f"SSTYP {typ} is not supported for tied contacts (4 node set, "
                "0 segment set, 1 shell set, 2 part set, 3 part)",
            )
        )
        return None
    if np.any(nodes < -1) or (typ == 4 and np.any(nodes < 0)):
        problems.append(_problem(rec, "ssid", "the slave set names an undefined node"))
        return None
    return np.unique(nodes[nodes >= 0])


def _closest_quad(p, xs):
    """Closest points of points p (P, 3) on bilinear quads xs (P, 4, 3):
    (ξ, η) in [-1, 1]² by projected Gauss-Newton."""
    xi = np.zeros(len(p))
    eta = np.zeros(len(p))
    for _ in range(25):
        n, dxi, deta = _quad_n(xi, eta)
        X = np.einsum("pa,paj->pj", n, xs)
        t1 = np.einsum("pa,paj->pj", dxi, xs)
        t2 = np.einsum("pa,paj->pj", deta, xs)
        d = p - X
        a11, a12, a22 = (t1 * t1).sum(1), (t1 * t2).sum(1), (t2 * t2).sum(1)
        b1, b2 = (t1 * d).sum(1), (t2 * d).sum(1)
        det = a11 * a22 - a12 * a12
        det = np.where(det == 0, 1.0, det)
        xi = np.clip(xi + (a22 * b1 - a12 * b2) / det, -1.0, 1.0)
        eta = np.clip(eta + (a11 * b2 - a12 * b1) / det, -1.0, 1.0)
    return _quad_n(xi, eta)[0]


def _quad_n(xi, eta):
    n = 0.25 * np.stack([(1 - xi) * (1 - eta), (1 + xi) * (1 - eta), (1 + xi) * (1 + eta), (1 - xi) * (1 + eta)], 1)
    dxi = 0.25 * np.stack([-(1 - eta), (1 - eta), (1 + eta), -(1 + eta)], 1)
    deta = 0.25 * np.stack([-(1 - xi), -(1 + xi), (1 + xi), (1 - xi)], 1)
    return n, dxi, deta


def _closest_tri(p, a, b, c):
    """Weights (P, 4) of the closest points of p on triangles abc (w[3] = 0)."""
    e1, e2 = b - a, c - a
    d = p - a
    m11, m12, m22 = (e1 * e1).sum(1), (e1 * e2).sum(1), (e2 * e2).sum(1)
    r1, r2 = (e1 * d).sum(1), (e2 * d).sum(1)
    det = m11 * m22 - m12 * m12
    det = np.where(det == 0, 1.0, det)
    s = (m22 * r1 - m12 * r2) / det
    t = (m11 * r2 - m12 * r1) / det
    inside = (s >= 0) & (t >= 0) & (s + t <= 1)
    best_w = np.stack([1 - s - t, s, t, np.zeros_like(s)], 1)
    best_d = np.full(len(p), np.inf)
    best_d[inside] = 0.0
    corners = (a, b, c)
    for i, k in ((0, 1), (1, 2), (2, 0)):
        u, q = corners[i], corners[k]
        e = q - u
        lam = np.clip(((p - u) * e).sum(1) / np.maximum((e * e).sum(1), 1e-300), 0.0, 1.0)
        dist = np.linalg.norm(p - (u + lam[:, None] * e), axis=1)
        better = ~inside & (dist < best_d)
        w = np.zeros((len(p), 4))
        w[:, i], w[:, k] = 1 - lam, lam
        best_w[better] = w[better]
        best_d[better] = dist[better]
    return best_w


def project(
    points: np.ndarray, x: np.ndarray, seg: np.ndarray, tol: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Nearest segment of each point: (segment index (-1: none within
    reach), weights (P, 4), distance (P,)). ``tol`` (n_seg,) the search
    distance of each segment."""
    from scipy.spatial import cKDTree

    npt = len(points)
    best = np.full(npt, -1, np.int64)
    best_w = np.zeros((npt, 4))
    best_d = np.full(npt, np.inf)
    if not npt or not len(seg):
        return best, best_w, best_d
    xs = x[seg]
    cen = xs.mean(axis=1)
    reach = float(np.max(np.linalg.norm(xs - cen[:, None], axis=2)) + tol.max()) * 1.0001
    tree = cKDTree(cen)
    lists = tree.query_ball_point(points, reach)
    pi = np.repeat(np.arange(npt), [len(c) for c in lists])
    si = np.fromiter((s for c in lists for s in c), np.int64, len(pi))
    if not len(pi):
        return best, best_w, best_d
    tri = seg[si, 2] == seg[si, 3]
    w = np.zeros((len(pi), 4))
    if (~tri).any():
        q = ~tri
        w[q] = _closest_quad(points[pi[q]], xs[si[q]])
    if tri.any():
        w[tri] = _closest_tri(points[pi[tri]], xs[si[tri], 0], xs[si[tri], 1], xs[si[tri], 2])
    d = np.linalg.norm(points[pi] - np.einsum("pa,paj->pj", w, xs[si]), axis=1)
    order = np.lexsort((si, d, pi))  # per point: nearest first, ties by segment index
    first = np.ones(len(order), bool)
    first[1:] = pi[order][1:] != pi[order][:-1]
    k = order[first]
    best[pi[k]], best_w[pi[k]], best_d[pi[k]] = si[k], w[k], d[k]
    return best, best_w, best_d


def build_tied(model: Model, problems: list, warnings: list | None = None) -> list[TiedContact]:
    """The tied contacts of a deck (projection done; masses not yet moved:
    see ``TiedContact.lump``)."""
    out = []
    x = model.nodes.xyz
    node_t = None
    taken: dict[int, int] = {}
    numbers = interface_numbers(model)  # as rcforc numbers the deck's contacts (model.contacts)
    for rec in model.find("CONTACT_TIED_"):
        kw = rec.keyword
        if kw not in ("CONTACT_TIED_NODES_TO_SURFACE", "CONTACT_TIED_SHELL_EDGE_TO_SURFACE") or (
            "BEAM" in rec.options and "OFFSET" not in rec.options
        ):
            problems.append(
                _problem(
                    rec,
                    None,
                    f"*{rec.name} is not supported (TIED_NODES_TO_SURFACE and TIED_SHELL_EDGE_TO_SURFACE, with "
                    "_OFFSET, and TIED_SHELL_EDGE_TO_SURFACE_BEAM_OFFSET are)",
                )
            )
            continue
        slaves, seg = _slaves(model, rec, problems), _segments(model, rec, problems)
        if slaves is None or seg is None:
            continue
        if node_t is None:
            node_t, node_optt = _node_thickness(model)
        sst, mst = abs(float(rec.get("sst") or 0.0)), abs(float(rec.get("mst") or 0.0))
        on_master = np.isin(slaves, seg)  # already joined to the surface by a shared node
        cand = slaves[~on_master]
        # SST/MST replace the shells' thickness, a part's OPTT replaces both (LS-DYNA's order)
        t_s = np.where(node_optt[cand] | (sst == 0), node_t[cand], sst * float(rec.get("sfst") or 1.0))
        t_m = np.where(
            node_optt[seg].any(axis=1) | (mst == 0), node_t[seg].max(axis=1), mst * float(rec.get("sfmt") or 1.0)
        )
        xs = x[seg]
        diag = np.maximum(np.linalg.norm(xs[:, 2] - xs[:, 0], axis=1), np.linalg.norm(xs[:, 3] - xs[:, 1], axis=1))
        reach = np.maximum(0.6 * (t_s.max(initial=0.0) + t_m), 0.05 * diag)
        idx, w, dist = project(x[cand], x, seg, reach)
        ok = idx >= 0
        j = idx[ok]
        ok[ok] = dist[ok] <= np.maximum(0.6 * (t_s[ok] + t_m[j]), 0.05 * diag[j]) * (1 + 1e-9)
        cid = numbers[id(rec)]
        for s in cand[ok]:
            if int(s) in taken:
                problems.append(
                    _problem(
                        rec, "ssid", f"node {int(model.nodes.ids[s])} is tied twice (also by contact {taken[int(s)]})"
                    )
                )
            taken[int(s)] = cid
        untied = model.nodes.ids[cand[~ok]].astype(np.int64)
        tie = TiedContact(
            cid,
            kw,
            cand[ok].astype(np.int64),
            seg[idx[ok]].astype(np.int64),
            w[ok],
            np.where(seg[idx[ok], 2] == seg[idx[ok], 3], 3, 4).astype(np.int64),
            dist[ok],
            offset="OFFSET" in rec.options or kw == "CONTACT_TIED_SHELL_EDGE_TO_SURFACE",
            rotations=kw == "CONTACT_TIED_SHELL_EDGE_TO_SURFACE",
            untied=untied,
        )
        if "BEAM" in rec.options:
            tie.warnings.append(
                _problem(
                    rec,
                    None,
                    "BEAM_OFFSET: LS-DYNA ties by penalty beams across the gap; crashlite ties the shell edge "
                    "kinematically, the gap kept as a rigid offset and the rotations tied (the limit of stiff "
                    f"beams): {len(tie)} slave node(s) tied",
                )
            )
        if len(untied):
            more = f" and {len(untied) - 10} more" if len(untied) > 10 else ""
            tie.warnings.append(
                _problem(
                    rec,
                    "ssid",
                    f"{len(untied)} slave node(s) not tied (farther from the "
                    "master surface than the search distance): " + " ".join(str(int(i)) for i in untied[:10]) + more,
                )
            )
        if warnings is not None:
            warnings.extend(tie.warnings)
        out.append(tie)
    masters = set()
    for t in out:
        masters.update(np.unique(t.seg).tolist())
    for t in out:
        both = [int(s) for s in t.slave if int(s) in masters]
        if both:
            problems.append(
                Problem(
                    model.source or "",
                    0,
                    t.keyword,
                    "SSID",
                    f"contact {t.cid}: node {int(model.nodes.ids[both[0]])} is both a tied slave "
                    "and a master node of a tied contact (chained ties are not supported)",
                )
            )
    return out
