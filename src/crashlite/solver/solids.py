"""Solid elements from the Model: 8-node hexahedra (LS-DYNA ELFORM 1 and 2).

Builds the struct-of-arrays set the kernels in ``kernels.solid`` (one
point) and ``kernels.solid_full`` (fully integrated) run: element
connectivity, material tables and curves, hourglass and bulk viscosity
settings per element, initial volumes and material axes; plus lumped
masses, the element time step and the state arrays.

Section formulations: ELFORM 1 (one point, hourglass control) and 2 (fully
integrated, selectively reduced: 2×2×2 points, B-bar volumetric strain, no
hourglass modes) run as they are; -1 and -2 (LS-DYNA's fully integrated
variants for poor aspect ratios) run as 2, 0 (one-point corotational) as
1, each with a warning; any other ELFORM is refused. The elements of both
formulations live in one set, in the deck's order: ``full`` marks those of
ELFORM 2, whose per-point state sits in the ``*8`` arrays of SolidState and
whose element values (stress, plastic strain: mean of the points; energy:
their sum) fill the element arrays as the one-point ones do. Hourglass
types IHQ 1–5 run; IHQ 6 runs as 5 with a warning; others are refused
(ELFORM 2 parts have no hourglass control: their IHQ is not used).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ..keyword.errors import Problem
from ..model.model import Model
from .curve_store import CurveStore
from .groups import ElementGroup
from .kernels import solid_materials as sm
from .kernels.solid import (
    N_CHUNKS,
    N_WORK,
    corner_incidence,
    gather_corners,
    solid_forces,
    solid_timestep,
    solid_volumes,
)
from .kernels.solid_full import N_WORK_FULL, point_jacobians, solid_full_forces
from .state import State

_AS_ONE_POINT = (0,)  # one-point corotational: runs as ELFORM 1
_AS_FULL = (-1, -2)  # fully integrated for poor aspect ratios: run as ELFORM 2


@dataclass
class SolidSet:
    """Solid elements (n) and their materials (n_mat), see kernels.solid."""

    ids: np.ndarray  # (n,) int64 element IDs
    pid: np.ndarray  # (n,) int64 part IDs
    conn: np.ndarray  # (n, 8) int64 node indices (LS-DYNA order, tetrahedra as n1 n2 n3 n3 n4 n4 n4 n4)
    mat_of: np.ndarray  # (n,) int64 row of the material tables
    mat_ids: np.ndarray  # (n_mat,) int64 deck material IDs
    mtype: np.ndarray  # (n_mat,) int64 material kind (solid_materials.ELASTIC ...)
    props: np.ndarray  # (n_mat, N_PROPS) float64 material parameters (solid_materials P_*)
    mcurve: np.ndarray  # (n_mat, N_CURVES) int64 curve slots (-1: none)
    curve_start: np.ndarray  # (n_curves,) int64
    curve_stop: np.ndarray  # (n_curves,) int64
    curve_x: np.ndarray  # (m,) float64 abscissae (strain) [-]
    curve_y: np.ndarray  # (m,) float64 ordinates [stress]
    rho0: np.ndarray  # (n,) float64 initial density [mass/length³]
    vol0: np.ndarray  # (n,) float64 initial volume [length³]
    axes0: np.ndarray  # (n, 3, 3) float64 initial material axes a, b, c (columns)
    hg_type: np.ndarray  # (n,) int64 IHQ
    hg_qm: np.ndarray  # (n,) float64 QM
    q1: np.ndarray  # (n,) float64 quadratic bulk viscosity coefficient
    q2: np.ndarray  # (n,) float64 linear bulk viscosity coefficient
    warnings: list = field(default_factory=list)  # Problem: options run in an approximated way
    # *CONTROL_TIMESTEP ERODE = 1: an inverted solid, or one whose step falls below DTMIN (of
    # *CONTROL_TERMINATION) x the solids' first step, is deleted instead of stopping the run
    erode: bool = False
    erode_dtmin: float = 0.0
    full: np.ndarray | None = None  # (n,) int8 1: fully integrated (ELFORM 2); None: none
    detj0: np.ndarray | None = None  # (nf, 8) float64 det J at the Gauss points of those, at t = 0 [length³]

    def __len__(self) -> int:
        return len(self.ids)


@dataclass
class SolidState:
    """Per-element state of the solids (kernels.solid documents each)."""

    sig: np.ndarray  # (n, 6) float64 stress [stress]
    sv: np.ndarray  # (n, 6) float64 viscous stress [stress]
    epsp: np.ndarray  # (n,) float64 effective plastic strain
    hist: np.ndarray  # (n, N_HIST) float64
    axes: np.ndarray  # (n, 3, 3) float64 material axes
    hgq: np.ndarray  # (n, 3, 4) float64 hourglass generalized forces [force]
    hg_kappa: np.ndarray  # (n,) float64 hourglass stiffness of the last step (kernels.solid) [force/length]
    alive: np.ndarray  # (n,) int8 1 active, 0 eroded, -1 inverted
    vol: np.ndarray  # (n,) float64 [length³]
    rate: np.ndarray  # (n,) float64 volumetric strain rate [1/time]
    cmod: np.ndarray  # (n,) float64 wave modulus [stress]
    energy: np.ndarray  # (n,) float64 internal energy [energy]
    hg_energy: np.ndarray  # (n,) float64 hourglass energy [energy]
    fe: np.ndarray  # (n, 8, 3) float64 corner forces ON the nodes [force]
    work: np.ndarray  # (N_CHUNKS, N_WORK) float64 scratch
    node_ptr: np.ndarray  # (n_nodes + 1,) int64 CSR node -> corners
    corner_of: np.ndarray  # (8n,) int64
    # the fully integrated elements (kernels.solid_full): their rows, and their state at the 8 Gauss
    # points (sig, sv, epsp above then hold the mean of the points, energy their sum)
    full_idx: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))  # (nf,) int64
    sig8: np.ndarray = field(default_factory=lambda: np.zeros((0, 8, 6)))  # (nf, 8, 6) [stress]
    sv8: np.ndarray = field(default_factory=lambda: np.zeros((0, 8, 6)))  # (nf, 8, 6) viscous [stress]
    epsp8: np.ndarray = field(default_factory=lambda: np.zeros((0, 8)))  # (nf, 8)
    hist8: np.ndarray = field(default_factory=lambda: np.zeros((0, 8, sm.N_HIST)))  # (nf, 8, N_HIST)
    axes8: np.ndarray = field(default_factory=lambda: np.zeros((0, 8, 3, 3)))  # (nf, 8, 3, 3)
    work8: np.ndarray = field(default_factory=lambda: np.zeros((N_CHUNKS, N_WORK_FULL)))  # scratch
    full_alive: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int8))  # (nf,) scratch


def new_state(s: SolidSet, n_nodes: int) -> SolidState:
    n = len(s)
    ptr, corner_of = corner_incidence(n_nodes, s.conn)
    idx = np.flatnonzero(s.full).astype(np.int64) if s.full is not None else np.zeros(0, np.int64)
    nf = len(idx)
    return SolidState(
        np.zeros((n, 6)),
        np.zeros((n, 6)),
        np.zeros(n),
        np.zeros((n, sm.N_HIST)),
        s.axes0.copy(),
        np.zeros((n, 3, 4)),
        np.zeros(n),
        np.ones(n, np.int8),
        s.vol0.copy(),
        np.zeros(n),
        s.props[s.mat_of, sm.P_WAVE].copy(),
        np.zeros(n),
        np.zeros(n),
        np.zeros((n, 8, 3)),
        np.zeros((N_CHUNKS, N_WORK)),
        ptr,
        corner_of,
        idx,
        np.zeros((nf, 8, 6)),
        np.zeros((nf, 8, 6)),
        np.zeros((nf, 8)),
        np.zeros((nf, 8, sm.N_HIST)),
        np.repeat(s.axes0[idx][:, None], 8, axis=1),
        np.zeros((N_CHUNKS, N_WORK_FULL)),
        np.zeros(nf, np.int8),
    )


def compute_forces(s: SolidSet, st: SolidState, x: np.ndarray, v: np.ndarray, dt: float) -> None:
    """Advance the solids' state to t(n+1) and fill st.fe: the one-point
    elements (kernels.solid), then the fully integrated ones
    (kernels.solid_full)."""
    idx = st.full_idx
    if len(idx) < len(s):
        keep = st.full_alive
        np.take(st.alive, idx, out=keep)
        np.put(st.alive, idx, 2)  # not the one-point kernel's: it zeroes their rows, the full kernel fills them
        _one_point(s, st, x, v, dt)
        np.put(st.alive, idx, keep)
    if len(idx):
        solid_full_forces(
            x,
            v,
            float(dt),
            idx,
            s.conn,
            s.mat_of,
            s.mtype,
            s.props,
            s.mcurve,
            s.curve_start,
            s.curve_stop,
            s.curve_x,
            s.curve_y,
            s.rho0,
            s.vol0,
            s.q1,
            s.q2,
            s.detj0,
            st.sig8,
            st.sv8,
            st.epsp8,
            st.hist8,
            st.axes8,
            st.alive,
            st.vol,
            st.rate,
            st.cmod,
            st.energy,
            st.sig,
            st.sv,
            st.epsp,
            st.work8,
            st.fe,
        )


def _one_point(s: SolidSet, st: SolidState, x: np.ndarray, v: np.ndarray, dt: float) -> None:
    solid_forces(
        x,
        v,
        float(dt),
        s.conn,
        s.mat_of,
        s.mtype,
        s.props,
        s.mcurve,
        s.curve_start,
        s.curve_stop,
        s.curve_x,
        s.curve_y,
        s.rho0,
        s.vol0,
        s.hg_type,
        s.hg_qm,
        s.q1,
        s.q2,
        st.sig,
        st.sv,
        st.epsp,
        st.hist,
        st.axes,
        st.hgq,
        st.hg_kappa,
        st.alive,
        st.vol,
        st.rate,
        st.cmod,
        st.energy,
        st.hg_energy,
        st.work,
        st.fe,
    )


def lumped_mass(s: SolidSet, n_nodes: int) -> np.ndarray:
    """(n_nodes,) nodal masses [mass]: ρ·V0 shared equally by the distinct
    nodes of each element (1/8 for a hexahedron; 1/6 for a wedge and 1/4
    for a tetrahedron given with repeated nodes, their row-sum lumping)."""
    srt = np.sort(s.conn, axis=1)
    first = np.ones(srt.shape, bool)
    first[:, 1:] = srt[:, 1:] != srt[:, :-1]
    share = s.rho0 * s.vol0 / first.sum(axis=1)
    mass = np.zeros(n_nodes)
    np.add.at(mass, srt[first], np.repeat(share, first.sum(axis=1)))
    return mass


def element_dt(s: SolidSet, x: np.ndarray, st: SolidState | None = None) -> np.ndarray:
    """(n,) critical time step of each solid [time] (LS-DYNA rule, before
    TSSFAC): at the initial state without ``st``, else at the current one."""
    out = np.empty(len(s))
    if st is None:
        vol = np.empty(len(s))
        solid_volumes(x, s.conn, np.zeros((N_CHUNKS, N_WORK)), vol)
        solid_timestep(
            x,
            s.conn,
            np.ones(len(s), np.int8),
            vol,
            s.rho0,
            s.vol0,
            s.props[s.mat_of, sm.P_WAVE],
            np.zeros(len(s)),
            s.q1,
            s.q2,
            out,
        )
    else:
        solid_timestep(x, s.conn, st.alive, st.vol, s.rho0, s.vol0, np.maximum(st.cmod, 0.0), st.rate, s.q1, s.q2, out)
    return out


# --- from the Model -------------------------------------------------------------------------------


def _where(rec, fld):
    return rec.where(fld) if rec is not None and hasattr(rec, "where") else ("", 0)


def _problem(rec, fld, msg) -> Problem:
    f, line = _where(rec, fld)
    return Problem(f, line, getattr(rec, "name", ""), fld.upper() if fld else None, msg)


def _elastic_constants(mat, row, problems) -> bool:
    e, nu, ro = float(mat.get("e", 0.0)), float(mat.get("pr", 0.0)), float(mat.get("ro", 0.0))
    if e <= 0 or ro <= 0 or not -1.0 < nu < 0.5:
        bad, value = ("ro", ro) if ro <= 0 else ("e", e) if e <= 0 else ("pr", nu)
        problems.append(
            _problem(
                mat,
                bad,
                f"material {mat.get('mid')}: RO > 0, E > 0 and -1 < PR < 0.5 "
                f"are needed for solids ({bad.upper()} = {value:g})",
            )
        )
        return False
    k, g = e / (3.0 * (1.0 - 2.0 * nu)), e / (2.0 * (1.0 + nu))
    row[sm.P_RO], row[sm.P_E], row[sm.P_PR], row[sm.P_K], row[sm.P_G] = ro, e, nu, k, g
    row[sm.P_WAVE] = k + 4.0 * g / 3.0
    row[sm.P_BULKQ] = 1.0
    return True


def _curve_ok(model, mat, fld, problems, required=True) -> bool:
    lc = int(mat.get(fld, 0) or 0)
    if lc == 0 and not required:
        return True
    if lc not in model.curves:
        problems.append(_problem(mat, fld, f"curve {lc} is not defined (a *DEFINE_CURVE is needed)"))
        return False
    return True


def _material(model: Model, mat, curves: CurveStore, problems: list):
    """(kind, props row, curve slots) of one material, or None if refused."""
    row = np.zeros(sm.N_PROPS)
    mc = np.full(sm.N_CURVES, -1, np.int64)
    kw = mat.keyword
    if kw not in (
        "MAT_ELASTIC",
        "MAT_PIECEWISE_LINEAR_PLASTICITY",
        "MAT_HONEYCOMB",
        "MAT_MODIFIED_HONEYCOMB",
        "MAT_CRUSHABLE_FOAM",
    ):
        problems.append(
            _problem(
                mat, None, f"*{kw} is not supported for solids (supported: MAT_001, MAT_024, MAT_026, MAT_063, MAT_126)"
            )
        )
        return None
    if not _elastic_constants(mat, row, problems):
        return None
    if kw == "MAT_ELASTIC":
        if float(mat.get("da", 0.0) or 0.0) or float(mat.get("db", 0.0) or 0.0):
            problems.append(_problem(mat, "da", "axial/bending damping DA, DB apply to beams only"))
        return sm.ELASTIC, row, mc
    if kw == "MAT_PIECEWISE_LINEAR_PLASTICITY":
        ok = True
        for fld, what in (("lcsr", "strain-rate curve LCSR"), ("lcf", "LCF"), ("tdel", "TDEL")):
            if float(mat.get(fld, 0) or 0) != 0:
                problems.append(_problem(mat, fld, f"{what} is not supported for solids yet"))
                ok = False
        if float(mat.get("vp", 0.0) or 0.0) != 0.0:
            problems.append(_problem(mat, "vp", "VP = 1 (viscoplastic rate formulation) is not supported yet"))
            ok = False
        fail = float(mat.get("fail", 1e21) or 1e21)
        if fail < 0:
            problems.append(_problem(mat, "fail", "FAIL < 0 (user failure subroutine) is not supported"))
            ok = False
        e, etan = row[sm.P_E], float(mat.get("etan", 0.0) or 0.0)
        row[sm.P_SIGY] = float(mat.get("sigy", 0.0) or 0.0)
        row[sm.P_HARD] = e * etan / (e - etan) if etan < e else 0.0
        row[sm.P_FAIL] = fail if fail > 0 else 1e21
        row[sm.P_CS_C], row[sm.P_CS_P] = float(mat.get("c", 0.0) or 0.0), float(mat.get("p", 0.0) or 0.0)
        eps = np.array([float(mat.get(f"eps{i}", 0.0) or 0.0) for i in range(1, 9)])
        es = np.array([float(mat.get(f"es{i}", 0.0) or 0.0) for i in range(1, 9)])
        lcss, table, why = curves.yield_slots(mat, "lcss")
        if why is not None:
            problems.append(_problem(mat, "lcss", why))
            ok = False
        elif table >= 0:  # yield curves by strain rate: C and P do not apply
            mc[sm.C_TABLE] = table
            row[sm.P_CS_C] = row[sm.P_CS_P] = 0.0
        elif lcss >= 0:
            mc[sm.C_LCSS] = lcss
        elif np.any(es > 0):
            n = int(np.flatnonzero(es > 0)[-1]) + 1
            if n < 2:
                problems.append(_problem(mat, "es1", "EPS/ES need at least two points"))
                ok = False
            else:
                mc[sm.C_LCSS] = curves.add(eps[:n], es[:n], ("mat", mat.get("mid")))
        elif row[sm.P_SIGY] <= 0:
            problems.append(_problem(mat, "sigy", "SIGY > 0 (or a curve LCSS / EPS-ES points) is needed"))
            ok = False
        return (sm.PLASTIC, row, mc) if ok else None
    if kw == "MAT_CRUSHABLE_FOAM":
        if not _curve_ok(model, mat, "lcid", problems):
            return None
        mc[sm.C_FOAM] = curves.get(int(mat["lcid"]))
        row[sm.P_TSC] = max(float(mat.get("tsc", 0.0) or 0.0), 0.0)
        row[sm.P_DAMP] = float(mat.get("damp", 0.1) or 0.0)
        return sm.FOAM, row, mc
    return _honeycomb(model, mat, curves, row, mc, problems)


def _honeycomb(model, mat, curves, row, mc, problems):
    ok = True
    vf = float(mat.get("vf", 0.0) or 0.0)
    if not 0.0 < vf < 1.0:
        problems.append(_problem(mat, "vf", "VF (relative volume at full compaction) must lie in (0, 1)"))
        ok = False
    if float(mat.get("lcsr", 0) or 0):
        problems.append(_problem(mat, "lcsr", "strain-rate scaling LCSR is not supported yet"))
        ok = False
    if int(mat.get("macf", 1) or 1) != 1:
        problems.append(_problem(mat, "macf", "MACF other than 1 (material axes change) is not supported"))
        ok = False
    if float(mat.get("aopt", 0.0) or 0.0) not in (0.0, 2.0):
        problems.append(_problem(mat, "aopt", "AOPT 0 (element nodes 1, 2, 4) and 2 (vectors A, D) are supported"))
        ok = False
    modified = mat.keyword == "MAT_MODIFIED_HONEYCOMB"
    transverse = modified and int(mat.get("lca", 0) or 0) < 0
    if modified:
        for fld, what in (("vref", "relative volume"), ("tref", "time step")):
            if float(mat.get(fld, 0.0) or 0.0) != 0.0:
                problems.append(
                    _problem(mat, fld, f"{fld.upper()} (reset to the reference geometry at a {what}) is not supported")
                )
                ok = False
        if float(mat.get("eccu", 0.0) or 0.0) < 0.0:
            problems.append(_problem(mat, "eccu", "ECCU < 0 (the hydrostatic/shear yield surface) is not supported"))
            ok = False
    lc = _honeycomb_curves(model, mat, transverse, problems)
    if lc is None or not ok:
        return None
    for slot, fld in (
        (sm.C_A, "lca"),
        (sm.C_B, "lcb"),
        (sm.C_C, "lcc"),
        (sm.C_AB, "lcab"),
        (sm.C_BC, "lcbc"),
        (sm.C_CA, "lcca"),
    ):
        mc[slot] = curves.get(lc[fld]) if lc[fld] else -1
    row[sm.P_FORM] = 2.0 if transverse else 1.0
    row[sm.P_SHDFLG] = float(mat.get("shdflg", 0.0) or 0.0)
    row[sm.P_SIGY], row[sm.P_VF] = float(mat.get("sigy", 0.0) or 0.0), vf
    # BULK = 1: artificial bulk viscosity instead of the material viscosity MU (LS-DYNA sets μ = 0)
    bulk = float(mat.get("bulk", 0.0) or 0.0) != 0.0
    row[sm.P_BULKQ] = 1.0 if bulk else 0.0
    row[sm.P_DAMP] = 0.0 if bulk else float(mat.get("mu", 0.05) or 0.0)
    for i, fld in enumerate(("eaau", "ebbu", "eccu", "gabu", "gbcu", "gcau")):
        row[sm.P_EAAU + i] = float(mat.get(fld, 0.0) or 0.0)
    row[sm.P_TSEF] = float(mat.get("tsef", 0.0) or 0.0)
    row[sm.P_SSEF] = float(mat.get("ssef", 0.0) or 0.0)
    # the time step follows the stiffest state (compacted, or a stiffer uncompacted modulus)
    row[sm.P_WAVE] = max(row[sm.P_WAVE], *row[sm.P_EAAU : sm.P_EAAU + 6])
    return sm.HONEYCOMB, row, mc


def _honeycomb_curves(model, mat, transverse, problems):
    """Curve IDs of a honeycomb by field (0: none), or None if one is
    missing. MAT_026's form: LCB, LCC, LCS default to LCA and LCAB, LCBC,
    LCCA to LCS. The transversely isotropic form (MAT_126, LCA < 0): |LCA|
    the yield stress by the angle off the cell axis [degrees], LCB and LCC
    the strong and weak axes' hardening (both needed), LCAB, LCBC, LCCA
    the shear damage curves, all three LCS's where only LCS is given, none
    if neither is."""
    lca = abs(int(mat.get("lca", 0) or 0))
    if lca not in model.curves:
        problems.append(_problem(mat, "lca", f"curve {lca} is not defined (a *DEFINE_CURVE is needed)"))
        return None
    lc, ok = {"lca": lca}, True
    for fld in ("lcb", "lcc", "lcs", "lcab", "lcbc", "lcca"):
        lc[fld] = int(mat.get(fld, 0) or 0)
        if lc[fld] and not _curve_ok(model, mat, fld, problems):
            ok = False
    if transverse:
        for fld in ("lcb", "lcc"):
            if not lc[fld]:
                problems.append(
                    _problem(mat, fld, f"{fld.upper()} is needed with LCA < 0 (hardening of the strong and weak axes)")
                )
                ok = False
        if lc["lcs"] and not (lc["lcab"] or lc["lcbc"] or lc["lcca"]):
            lc["lcab"] = lc["lcbc"] = lc["lcca"] = lc["lcs"]
        return lc if ok else None
    for fld, default in (
        ("lcb", "lca"),
        ("lcc", "lca"),
        ("lcs", "lca"),
        ("lcab", "lcs"),
        ("lcbc", "lcs"),
        ("lcca", "lcs"),
    ):
        lc[fld] = lc[fld] or lc[default]
    return lc if ok else None


def _bulk_viscosity(model: Model) -> tuple[float, float]:
    """Q1, Q2 of *CONTROL_BULK_VISCOSITY (LS-DYNA defaults 1.5, 0.06, also for a 0)."""
    recs = model.find("CONTROL_BULK_VISCOSITY")
    if not recs:
        return 1.5, 0.06
    return float(recs[-1].get("q1", 1.5)), float(recs[-1].get("q2", 0.06))


def _axes(x, conn, aopt, a_vec, d_vec):
    """(n, 3, 3) material axes: AOPT 0 from element nodes 1, 2, 4; AOPT 2
    from vectors A and D (c = a × d, b = c × a)."""
    if aopt == 2.0:
        a = np.broadcast_to(a_vec, (len(conn), 3)).astype(float)
        d = np.broadcast_to(d_vec, (len(conn), 3)).astype(float)
    else:
        a = x[conn[:, 1]] - x[conn[:, 0]]
        d = x[conn[:, 3]] - x[conn[:, 0]]
    c = np.cross(a, d)
    b = np.cross(c, a)
    with np.errstate(invalid="ignore", divide="ignore"):
        q = np.stack([u / np.linalg.norm(u, axis=1)[:, None] for u in (a, b, c)], axis=2)
    return q


def build_solids(model: Model, rigid_pids: ArrayLike, problems: list, warnings: list | None = None) -> SolidSet | None:
    """Solids of the deformable parts, or None if there are none. Problems
    (unsupported options, missing data) are appended to ``problems``;
    options run in an approximated way are reported in ``warnings`` (and
    the set's ``warnings``)."""
    so = model.solids
    sel = ~np.isin(so.pid, np.asarray(rigid_pids, np.int64))
    warns: list[Problem] = []
    if not sel.any():
        return None
    ids, pid = so.ids[sel].astype(np.int64), so.pid[sel].astype(np.int64)
    conn = so.nodes[sel].astype(np.int64)
    n = len(ids)
    src = model.source or ""
    # 4-node input (n5..n8 blank) and LS-DYNA's tetrahedron n1 n2 n3 n4 n4 n4 n4 n4 -> n1 n2 n3 n3 n4 n4 n4 n4
    blank = conn[:, 4:] < 0
    conn[:, 4:] = np.where(blank, conn[:, 3:4], conn[:, 4:])
    tet = np.all(conn[:, 4:] == conn[:, 3:4], axis=1) & (conn[:, 2] != conn[:, 3])
    conn[tet] = conn[tet][:, [0, 1, 2, 2, 3, 3, 3, 3]]
    if np.any(conn < 0):
        problems.append(Problem(src, 0, "ELEMENT_SOLID", None, "solid elements need their nodes N1-N4 defined"))
        return None
    x = model.nodes.xyz
    ctrl = model.find("CONTROL_HOURGLASS")
    ihq0 = int(ctrl[0].get("ihq", 1) or 1) if ctrl else 1
    qh0 = float(ctrl[0].get("qh", 0.1)) if ctrl else 0.1
    bq1, bq2 = _bulk_viscosity(model)
    curves = CurveStore(model)
    mat_rows: dict[int, int] = {}
    mtypes, props, mcurves, mat_ids = [], [], [], []
    mat_of = np.zeros(n, np.int64)
    rho0 = np.zeros(n)
    hg_type, hg_qm = np.zeros(n, np.int64), np.zeros(n)
    q1, q2 = np.full(n, bq1), np.full(n, bq2)
    full = np.zeros(n, np.int8)
    axes = np.zeros((n, 3, 3))
    axes[:] = np.eye(3)
    for p in np.unique(pid):
        m = pid == p
        part = model.parts.get(int(p))
        sec = model.sections.get(part.get("secid")) if part is not None else None
        mat = model.materials.get(part.get("mid")) if part is not None else None
        if part is None or sec is None or sec.keyword != "SECTION_SOLID" or mat is None:
            problems.append(
                Problem(
                    src,
                    0,
                    "ELEMENT_SOLID",
                    "PID",
                    f"solids of part {int(p)} need a *PART with a *SECTION_SOLID and a material",
                )
            )
            continue
        elform = int(sec.get("elform", 1) if sec.get("elform") is not None else 1)
        if elform in _AS_ONE_POINT:
            warns.append(
                _problem(
                    sec,
                    "elform",
                    f"ELFORM {elform} of part {int(p)} runs as ELFORM 1 (one-point integration with hourglass control)",
                )
            )
        elif elform in _AS_FULL:
            warns.append(
                _problem(
                    sec,
                    "elform",
                    f"ELFORM {elform} of part {int(p)} runs as ELFORM 2 (fully integrated, selectively reduced; "
                    "no correction for poor aspect ratios)",
                )
            )
        elif elform not in (1, 2):
            problems.append(
                _problem(
                    sec, "elform", f"solid formulation {elform} is not supported (1, 2; 0 runs as 1, -1 and -2 as 2)"
                )
            )
            continue
        is_full = elform == 2 or elform in _AS_FULL
        full[m] = is_full
        mid = int(mat.get("mid"))
        if mid not in mat_rows:
            got = _material(model, mat, curves, problems)
            if got is None:
                continue
            mat_rows[mid] = len(mtypes)
            mtypes.append(got[0])
            props.append(got[1])
            mcurves.append(got[2])
            mat_ids.append(mid)
        row = mat_rows[mid]
        mat_of[m] = row
        rho0[m] = props[row][sm.P_RO]
        if mtypes[row] == sm.HONEYCOMB:
            a_vec = np.array([float(mat.get(k, 0.0) or 0.0) for k in ("a1", "a2", "a3")])
            d_vec = np.array([float(mat.get(k, 0.0) or 0.0) for k in ("d1", "d2", "d3")])
            aopt = float(mat.get("aopt", 0.0) or 0.0)
            if aopt == 2.0 and np.linalg.norm(np.cross(a_vec, d_vec)) == 0.0:
                problems.append(_problem(mat, "a1", "AOPT 2 needs vectors A and D that are not parallel"))
                continue
            q = _axes(x, conn[m], aopt, a_vec, d_vec)
            if not np.all(np.isfinite(q)):
                problems.append(
                    _problem(
                        mat,
                        "aopt",
                        f"part {int(p)}: material axes from element nodes 1, 2, 4 "
                        "are undefined for a collapsed element",
                    )
                )
                continue
            axes[m] = q
        hgid = int(part.get("hgid", 0) or 0)
        hg = model.hourglasses.get(hgid) if hgid else None
        if hgid and hg is None:
            problems.append(_problem(part, "hgid", f"*HOURGLASS {hgid} is not defined"))
            continue
        ihq = int(hg.get("ihq", 0) or 0) if hg is not None else 0
        ihq = ihq or ihq0
        qm = float(hg.get("qm", 0.1)) if hg is not None else qh0
        if ihq == 6 and not is_full:
            warns.append(
                _problem(
                    hg if hg is not None else part,
                    "ihq",
                    f"IHQ 6 of part {int(p)} runs as IHQ 5 (Flanagan-Belytschko stiffness)",
                )
            )
            ihq = 5
        elif not 1 <= ihq <= 5 and not is_full:
            problems.append(
                _problem(
                    hg if hg is not None else part,
                    "ihq",
                    f"hourglass type {ihq} is not supported for solids (1-5, 6 as 5)",
                )
            )
            continue
        hg_type[m], hg_qm[m] = (0, 0.0) if is_full else (ihq, qm)
        if hg is not None:
            q1[m], q2[m] = float(hg.get("q1", 1.5)), float(hg.get("q2", 0.06))
    if not mtypes:
        return None
    vol0 = np.empty(n)
    solid_volumes(x, conn, np.zeros((N_CHUNKS, N_WORK)), vol0)
    bad = np.flatnonzero(vol0 <= 0)
    for i in bad[:10]:
        problems.append(
            Problem(
                src,
                0,
                "ELEMENT_SOLID",
                None,
                f"solid {int(ids[i])} has volume {vol0[i]:.4g} <= 0 (inverted node order?)",
            )
        )
    fidx = np.flatnonzero(full)
    detj0 = np.empty((len(fidx), 8))
    point_jacobians(x, fidx, conn, np.zeros((1, N_WORK_FULL)), detj0)
    for k in np.flatnonzero((detj0 <= 0).any(axis=1) & (vol0[fidx] > 0))[:10]:
        problems.append(
            Problem(
                src,
                0,
                "ELEMENT_SOLID",
                None,
                f"solid {int(ids[fidx[k]])} (ELFORM 2) has a Jacobian <= 0 at an integration point "
                "(too distorted for full integration)",
            )
        )
    cs, ce, cx, cy = curves.arrays()
    if warnings is not None:
        warnings.extend(warns)
    ts, term = model.find("CONTROL_TIMESTEP"), model.find("CONTROL_TERMINATION")
    erode = bool(ts) and int(ts[0].get("erode", 0) or 0) == 1
    dtmin = float(term[0].get("dtmin", 0.0) or 0.0) if term else 0.0
    return SolidSet(
        ids,
        pid,
        conn,
        mat_of,
        np.array(mat_ids, np.int64),
        np.array(mtypes, np.int64),
        np.array(props),
        np.array(mcurves, np.int64).reshape(-1, sm.N_CURVES),
        cs,
        ce,
        cx,
        cy,
        rho0,
        vol0,
        axes,
        hg_type,
        hg_qm,
        q1,
        q2,
        warns,
        erode,
        dtmin if erode else 0.0,
        full if fidx.size else None,
        detj0 if fidx.size else None,
    )


# --- in the time loop ----------------------------------------------------------------------------


class SolidGroup(ElementGroup):
    """The solids as an element group of the time loop (groups.ElementGroup)."""

    kind = "solid"

    def __init__(self, s: SolidSet, n_nodes: int):
        self.s = s
        self.st = new_state(s, n_nodes)
        self.ids, self.pid, self.conn = s.ids, s.pid, s.conn
        self.energy = self.st.energy  # internal energy, viscous work included [energy]
        self.hourglass = self.st.hg_energy
        self.warnings = s.warnings  # Problem: options run in an approximated way (ELFORM 0, -1, -2, IHQ 6)
        self._rows = self.st.fe.reshape(-1, 3)
        self._dt = np.empty(len(s))
        self._dt_first = 0.0
        self.erosions = 0  # elements deleted by ERODE (inverted or below the step limit)

    def forces(self, st: State) -> None:
        compute_forces(self.s, self.st, st.x, st.v, st.dt)
        if self.s.erode and self.st.alive.min() < 0:  # deleted: its mass stays, it carries no more force
            self.erosions += int(np.count_nonzero(self.st.alive < 0))
            self.st.alive[self.st.alive < 0] = 0
        if self.st.alive.min() < 0:  # LS-DYNA stops on a negative volume too (unless ERODE = 1)
            bad = np.flatnonzero(self.st.alive < 0)
            more = f" ({len(bad)} elements)" if len(bad) > 1 else ""
            raise FloatingPointError(
                f"solid element {int(self.ids[bad[0]])} turned inside out (negative volume) at "
                f"t = {getattr(st, 't', 0.0):.6g}{more}: the run is stopped"
            )
        gather_corners(self.st.node_ptr, self.st.corner_of, self._rows, st.f)

    def corner_forces(self) -> np.ndarray:
        return self.st.fe

    def plastic_strain(self) -> np.ndarray:
        return self.st.epsp.copy()

    def lumped(self, n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
        return lumped_mass(self.s, n_nodes), np.zeros(n_nodes)

    def critical_dt(self, st: State) -> float:
        s, g = self.s, self.st
        solid_timestep(st.x, s.conn, g.alive, g.vol, s.rho0, s.vol0, g.cmod, g.rate, s.q1, s.q2, self._dt)
        if not len(self._dt):
            return np.inf
        if s.erode_dtmin > 0.0 and self._dt_first > 0.0:  # ERODE's limit, once the run has set it
            small = self._dt < s.erode_dtmin * self._dt_first  # eroded ones report an infinite step
            if small.any():
                self.erosions += int(np.count_nonzero(small))
                g.alive[small] = 0
                self._dt[small] = np.inf
        return float(self._dt.min())

    def first_step(self, dt: float) -> None:
        """ERODE deletes a solid whose step falls below DTMIN times the run's
        first step (LS-DYNA's TSMIN, the step the run stops at), not the
        solids' own first step (a honeycomb reports its compacted modulus
        before its first update, a step four times shorter than its real
        one)."""
        self._dt_first = dt

    @property
    def eroded(self) -> int:
        return int(np.count_nonzero(self.st.alive != 1))


def build_solid_group(
    model: Model, rigid_pids: ArrayLike, problems: list, warnings: list | None = None
) -> SolidGroup | None:
    """The solids of a Model as a time-loop group (see build_solids), or None."""
    s = build_solids(model, rigid_pids, problems, warnings)
    return SolidGroup(s, len(model.nodes.xyz)) if s is not None and len(s) else None
