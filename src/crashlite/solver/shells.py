"""Shell elements from the Model: Belytschko–Lin–Tsay quads, C0 triangles and
fully integrated quads (ELFORM 16).

Builds the struct-of-arrays set the kernels in ``kernels.shell`` and
``kernels.shell_full`` run
(connectivity, thickness, integration rule, material table and curves,
hourglass settings), the lumped masses and rotary inertias, and the shell
group the time loop drives.

Section formulations: ELFORM 2 (and blank/0) runs as is; 16 and -16 run as
the fully integrated shell (kernels.shell_full; its triangles, n3 = n4, as
the C0 triangle); 1, 4, 6, 7, 8, 10, 11, 17, 18, 20 (other one-point and
fully integrated shells and triangles) run as ELFORM 2 with a warning;
membranes (5, 9) and any other form are refused. Degenerate quadrilaterals
(n3 = n4) are C0 triangles. The hourglass control applies to the one-point
quadrilaterals only.
NIP 0 means 2; 1–10 Gauss points (Lobatto for *CONTROL_SHELL INTGRD = 1,
NIP ≥ 3). Hourglass IHQ 1–3 run viscous, 4–5 stiffness; 6 and 8 run as
stiffness with a warning. *CONTROL_SHELL: ISTUPD (1, 3, 4: thickness
change), BWC (1: Belytschko–Wong–Chiang warping correction; 2, LS-DYNA's
default: none), INTGRD, ROTASCL.

Masses: ρ·t·A (+ MAREA·A) shared equally by the element's nodes; rotary
inertia m_node·A/8 (Kennedy–Belytschko–Lin scaling, large enough that the
rotations never set the time step) times ROTASCL.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import ArrayLike

from ..keyword.errors import Problem
from ..model.model import Model
from .curve_store import CurveStore
from .groups import ElementGroup
from .kernels import plane_stress as ps
from .kernels.shell import scratch, shell_forces, shell_timestep
from .kernels.shell_full import full_forces
from .kernels.solid import corner_incidence, gather_corner_pair
from .shell_materials import num as _num
from .shell_materials import problem as _problem
from .shell_materials import shell_material
from .state import State

_AS_BT = (0, 1, 2, 4, 6, 7, 8, 10, 11, 17, 18, 20)
FULL = (16, -16)  # fully integrated (kernels.shell_full)
VISCOUS, STIFFNESS = 1, 2


@dataclass
class ShellSet:
    """Shell elements (n) and their materials (n_mat), see kernels.shell."""

    ids: np.ndarray  # (n,) int64 element IDs
    pid: np.ndarray  # (n,) int64 part IDs
    conn: np.ndarray  # (n, 4) int64 node indices (triangles n1 n2 n3 n3)
    tri: np.ndarray  # (n,) int8 1: triangle
    mat_of: np.ndarray  # (n,) int64 row of the material tables
    mat_ids: np.ndarray  # (n_mat,) int64 deck material IDs
    mtype: np.ndarray  # (n_mat,) int64 plane_stress.ELASTIC, KINEMATIC, PIECEWISE, DAMAGE
    props: np.ndarray  # (n_mat, N_PROPS) float64 (plane_stress P_*)
    mcurve: np.ndarray  # (n_mat, N_CURVES) int64 curve slots (-1: none)
    curve_start: np.ndarray  # (n_curves,) int64
    curve_stop: np.ndarray  # (n_curves,) int64
    curve_x: np.ndarray  # (m,) float64 abscissae (plastic strain or strain rate)
    curve_y: np.ndarray  # (m,) float64 ordinates (stress or scale factor)
    thick0: np.ndarray  # (n,) float64 initial thickness, mean of the nodal ones [length]
    area0: np.ndarray  # (n,) float64 initial area [length²]
    nip: np.ndarray  # (n,) int64 integration points through the thickness
    rule: np.ndarray  # (n,) int64 0 Gauss, 1 Lobatto
    shrf: np.ndarray  # (n,) float64 transverse shear correction factor
    hg_kind: np.ndarray  # (n,) int64 0 none, 1 viscous, 2 stiffness
    hg_qm: np.ndarray  # (n,) float64 membrane hourglass coefficient QM
    hg_qb: np.ndarray  # (n,) float64 bending coefficient QB
    hg_qw: np.ndarray  # (n,) float64 out-of-plane (warping) coefficient QW
    rho: np.ndarray  # (n,) float64 density incl. MAREA/t [mass/length³]
    marea: np.ndarray  # (n,) float64 non-structural mass per area [mass/length²]
    istupd: int = 0  # 1: thickness follows the normal strain
    bwc: int = 2  # 1: warping correction
    rotascl: float = 1.0  # rotary inertia scale factor
    warnings: list = field(default_factory=list)  # Problem: options run in an approximated way
    isdo: int = 0  # *CONTROL_TIMESTEP ISDO: the characteristic length of the time step (0, 1, 2)
    full: np.ndarray | None = None  # (n,) int8 1: fully integrated quadrilateral (ELFORM 16)
    # (n,) bool: shells of a part whose section, material or hourglass card is refused (the run is
    # refused: they have no thickness and no mass, and are not checked further); None: none
    refused: np.ndarray | None = None

    def __len__(self) -> int:
        return len(self.ids)

    PER_ELEMENT = (
        "ids", "pid", "conn", "tri", "mat_of", "thick0", "area0", "nip", "rule", "shrf",
        "hg_kind", "hg_qm", "hg_qb", "hg_qw", "rho", "marea", "full", "refused",
    )  # fmt: skip

    def subset(self, rows: np.ndarray) -> ShellSet:
        """The elements ``rows`` (per-element arrays taken; material and curve tables shared)."""
        return replace(self, **{f: getattr(self, f)[rows] for f in self.PER_ELEMENT if getattr(self, f) is not None})


@dataclass
class ShellState:
    """Per-element state of the shells (kernels.shell documents each)."""

    sig: np.ndarray  # (n, nip_max, 5) float64 stress in the element frame [stress]
    back: np.ndarray  # (n, nip_max, 5) float64 back stress [stress]
    epsp: np.ndarray  # (n, nip_max) float64 effective plastic strain
    ipfail: np.ndarray  # (n, nip_max) int8 1: failed point
    thick: np.ndarray  # (n,) float64 [length]
    alive: np.ndarray  # (n,) int8 1 active, 0 eroded, -1 collapsed
    hgq: np.ndarray  # (n, 5) float64 hourglass generalized stresses
    energy: np.ndarray  # (n,) float64 internal energy [energy]
    hg_energy: np.ndarray  # (n,) float64 hourglass energy [energy]
    fe: np.ndarray  # (n, 4, 3) float64 corner forces ON the nodes [force]
    me: np.ndarray  # (n, 4, 3) float64 corner moments ON the nodes [force·length]
    step: np.ndarray  # (n,) float64 critical step of each element at the last forces' positions [time]
    points: np.ndarray  # scratch of kernels.shell (``scratch``)
    geometry: np.ndarray
    point_k: np.ndarray
    node_ptr: np.ndarray  # (n_nodes + 1,) int64 CSR node -> corners
    corner_of: np.ndarray  # (4n,) int64
    # the fully integrated elements (kernels.shell_full): their rows, and their state at the four
    # Gauss points (sig, back, epsp, ipfail above then hold the element-averaged layers)
    full_idx: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))  # (nf,) int64
    sig4: np.ndarray = field(default_factory=lambda: np.zeros((0, 4, 5)))  # (nf, 4·nip_max, 5) [stress]
    back4: np.ndarray = field(default_factory=lambda: np.zeros((0, 4, 5)))  # (nf, 4·nip_max, 5) [stress]
    epsp4: np.ndarray = field(default_factory=lambda: np.zeros((0, 4)))  # (nf, 4·nip_max)
    ipfail4: np.ndarray = field(default_factory=lambda: np.zeros((0, 4), np.int8))  # (nf, 4·nip_max)


def new_state(s: ShellSet, n_nodes: int) -> ShellState:
    n = len(s)
    k = int(s.nip.max()) if n else 1
    ptr, corner_of = corner_incidence(n_nodes, s.conn)
    idx = np.flatnonzero(s.full) if s.full is not None else np.zeros(0, np.int64)
    nf = len(idx)
    back4 = np.zeros((nf, 4 * k, 5))
    # MAT_081 counts NUMINT failed points per in-plane point: the layers' in-plane point (plane_stress)
    dmg = s.mtype[s.mat_of[idx]] == ps.DAMAGE if nf else np.zeros(0, bool)
    back4[dmg, :, 1] = np.repeat(np.arange(4.0), k)
    return ShellState(
        np.zeros((n, k, 5)),
        np.zeros((n, k, 5)),
        np.zeros((n, k)),
        np.zeros((n, k), np.int8),
        s.thick0.copy(),
        np.ones(n, np.int8),
        np.zeros((n, 5)),
        np.zeros(n),
        np.zeros(n),
        np.zeros((n, 4, 3)),
        np.zeros((n, 4, 3)),
        np.full(n, np.inf),
        *scratch(k),
        ptr,
        corner_of,
        idx.astype(np.int64),
        np.zeros((nf, 4 * k, 5)),
        back4,
        np.zeros((nf, 4 * k)),
        np.zeros((nf, 4 * k), np.int8),
    )


def compute_forces(s: ShellSet, st: ShellState, x: np.ndarray, v: np.ndarray, w: np.ndarray, dt: float) -> float | None:
    """Advance the shells' state to t(n+1) and fill st.fe, st.me: the
    one-point elements and triangles (kernels.shell), then the fully
    integrated ones (kernels.shell_full). Returns the smallest element step
    where the one-point kernel had them all (else None: st.step has them)."""
    idx = st.full_idx
    if not len(idx):
        return _one_point(s, st, x, v, w, dt)
    elif len(idx) < len(s):
        keep = st.alive[idx].copy()
        st.alive[idx] = 2  # not the one-point kernel's: it leaves them as they are
        _one_point(s, st, x, v, w, dt)
        st.alive[idx] = keep
    if len(idx):
        full_forces(
            x,
            v,
            w,
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
            s.nip,
            s.rule,
            s.shrf,
            int(s.istupd == 1),
            s.isdo,
            st.sig4,
            st.back4,
            st.epsp4,
            st.ipfail4,
            st.thick,
            st.alive,
            st.energy,
            st.sig,
            st.epsp,
            st.ipfail,
            st.fe,
            st.me,
            st.step,
        )


def _one_point(s: ShellSet, st: ShellState, x, v, w, dt: float) -> float:
    return shell_forces(
        x,
        v,
        w,
        float(dt),
        s.conn,
        s.tri,
        s.mat_of,
        s.mtype,
        s.props,
        s.mcurve,
        s.curve_start,
        s.curve_stop,
        s.curve_x,
        s.curve_y,
        s.nip,
        s.rule,
        s.shrf,
        s.hg_kind,
        s.hg_qm,
        s.hg_qb,
        s.hg_qw,
        s.rho,
        int(s.istupd == 1),
        int(s.bwc == 1),
        s.isdo,
        st.sig,
        st.back,
        st.epsp,
        st.ipfail,
        st.thick,
        st.alive,
        st.hgq,
        st.energy,
        st.hg_energy,
        st.points,
        st.geometry,
        st.point_k,
        st.fe,
        st.me,
        st.step,
    )


def element_areas(x: np.ndarray, conn: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """(n,) areas ½|d13 × d24| (quads) or ½|d12 × d13| (triangles) [length²]."""
    quad = tri == 0
    u = np.where(quad[:, None], x[conn[:, 2]] - x[conn[:, 0]], x[conn[:, 1]] - x[conn[:, 0]])
    s = np.where(quad[:, None], x[conn[:, 3]] - x[conn[:, 1]], x[conn[:, 2]] - x[conn[:, 0]])
    return 0.5 * np.linalg.norm(np.cross(u, s), axis=1)


def lumped(s: ShellSet, n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """(mass (n_nodes,) [mass], rotary inertia (n_nodes,) [mass·length²]):
    each element's ρ·t·A + MAREA·A shared equally by its distinct nodes,
    with m_node·A/8·ROTASCL of rotary inertia."""
    nn = np.where(s.tri == 1, 3, 4)
    m_node = (s.rho * s.thick0 * s.area0) / nn
    j_node = m_node * s.area0 / 8.0 * s.rotascl
    mass = np.zeros(n_nodes)
    inertia = np.zeros(n_nodes)
    for a in range(4):
        sel = (a < 3) | (s.tri == 0)
        np.add.at(mass, s.conn[sel, a], m_node[sel])
        np.add.at(inertia, s.conn[sel, a], j_node[sel])
    return mass, inertia


def element_dt(s: ShellSet, x: np.ndarray, alive: np.ndarray | None = None) -> np.ndarray:
    """(n,) critical step of each shell at positions x (LS-DYNA rule, before TSSFAC)."""
    out = np.empty(len(s))
    shell_timestep(
        x, s.conn, s.tri, np.ones(len(s), np.int8) if alive is None else alive, s.mat_of, s.props, s.isdo, out
    )
    return out


# --- from the Model -------------------------------------------------------------------------------


def _control_shell(model: Model, problems: list, warns: list) -> tuple[int, int, int, float]:
    """(ISTUPD as 0/1, BWC, INTGRD, ROTASCL) of *CONTROL_SHELL."""
    recs = model.find("CONTROL_SHELL")
    if not recs:
        return 0, 2, 0, 1.0
    r = recs[0]
    istupd = int(_num(r, "istupd"))
    if istupd in (2,):
        istupd = 0  # thick shells only
    elif istupd == 4:
        warns.append(_problem(r, "istupd", "ISTUPD 4 runs as 1 (elastic strains also change the thickness)"))
        istupd = 1
    elif istupd in (1, 3):
        istupd = 1
    elif istupd != 0:
        problems.append(_problem(r, "istupd", f"ISTUPD {istupd} is not supported (0-4)"))
    bwc = int(_num(r, "bwc", 2))
    intgrd = int(_num(r, "intgrd"))
    if intgrd not in (0, 1):
        problems.append(_problem(r, "intgrd", "INTGRD must be 0 (Gauss) or 1 (Lobatto)"))
    return istupd, (1 if bwc == 1 else 2), intgrd, _num(r, "rotascl", 1.0) or 1.0


def _isdo(model: Model, problems: list) -> int:
    """*CONTROL_TIMESTEP ISDO: 0 longest side, 1 longest diagonal, 2 shortest side and bar wave speed."""
    ts = model.find("CONTROL_TIMESTEP")
    isdo = int(_num(ts[0], "isdo")) if ts else 0
    if isdo not in (0, 1, 2):
        problems.append(_problem(ts[0], "isdo", f"ISDO {isdo} is not one of 0, 1, 2"))
        return 0
    return isdo


def _section(sec, part, p, intgrd, problems, warns):
    """(nip, rule, shrf, (t1..t4), marea, fully integrated) of a *SECTION_SHELL, or None."""
    ok = True
    elform = int(sec.get("elform") if sec.get("elform") is not None else 2)
    if elform in _AS_BT or elform in FULL:
        if elform not in (0, 2) + FULL:
            warns.append(
                _problem(
                    sec,
                    "elform",
                    f"ELFORM {elform} of part {p} runs as ELFORM 2 (Belytschko-Lin-Tsay, one point, hourglass control)",
                )
            )
    else:
        problems.append(
            _problem(
                sec,
                "elform",
                f"shell formulation {elform} is not supported (2, 16, -16; 0, 1, 4, 6-8, 10, 11, 17, 18, 20 run as 2)",
            )
        )
        ok = False
    nip = int(_num(sec, "nip", 2)) or 2
    if not 1 <= nip <= 10:
        problems.append(_problem(sec, "nip", f"NIP {nip}: 1 to 10 points through the thickness are supported"))
        ok = False
    for fld, what in (
        ("qr", "QR/IRID (user integration rule)"),
        ("icomp", "ICOMP = 1 (composite layers)"),
        ("nloc", "NLOC (reference surface offset)"),
        ("idof", "IDOF"),
        ("edgset", "EDGSET"),
    ):
        if _num(sec, fld) != 0:
            problems.append(_problem(sec, fld, f"{what} is not supported for shells"))
            ok = False
    t = [_num(sec, f"t{i}") for i in range(1, 5)]
    t = [ti if ti > 0 else t[0] for ti in t]
    shrf = _num(sec, "shrf", 1.0) or 1.0
    rule = 1 if intgrd == 1 and nip >= 3 else 0
    return (nip, rule, shrf, np.array(t), _num(sec, "marea"), elform in FULL) if ok else None


def _hourglass(model, part, p, ihq0, qh0, problems, warns, full=False):
    """(kind, QM, QB, QW) of a part, or None; ``full``: its shells are fully
    integrated (no hourglass modes: only IHQ 8's warping stiffness would act)."""
    hgid = int(part.get("hgid", 0) or 0)
    hg = model.hourglasses.get(hgid) if hgid else None
    if hgid and hg is None:
        problems.append(_problem(part, "hgid", f"*HOURGLASS {hgid} is not defined"))
        return None
    ihq = (int(hg.get("ihq", 0) or 0) if hg is not None else 0) or ihq0
    qm = _num(hg, "qm", 0.1) if hg is not None else qh0
    qb = _num(hg, "qb", 0.0) if hg is not None else 0.0
    qw = _num(hg, "qw", 0.0) if hg is not None else 0.0
    if full and ihq == 8:
        warns.append(
            _problem(
                hg if hg is not None else part,
                "ihq",
                f"IHQ 8 of part {p}: LS-DYNA adds warping stiffness to its fully integrated shells; crashlite's "
                "ELFORM 16 has no warping terms (its other hourglass settings do not act on it)",
            )
        )
        ihq = 4
    elif ihq in (6, 8):
        warns.append(
            _problem(
                hg if hg is not None else part,
                "ihq",
                f"IHQ {ihq} of part {p} runs as IHQ 4 (Belytschko-Tsay stiffness form)",
            )
        )
        ihq = 4
    if not 1 <= ihq <= 5:
        problems.append(
            _problem(
                hg if hg is not None else part,
                "ihq",
                f"hourglass type {ihq} is not supported for shells (1-5; 6, 8 as 4)",
            )
        )
        return None
    return (VISCOUS if ihq <= 3 else STIFFNESS), qm, (qb or qm), (qw or qm)


def build_shell_set(
    model: Model, rigid_pids: ArrayLike, problems: list, warnings: list | None = None
) -> ShellSet | None:
    """Shells of the deformable parts, or None if there are none. Problems
    (unsupported options, missing data) go to ``problems``; options run in
    an approximated way to ``warnings`` (and the set's ``warnings``)."""
    sh = model.shells
    sel = ~np.isin(sh.pid, np.asarray(rigid_pids, np.int64))
    if not sel.any():
        return None
    warns: list[Problem] = []
    src = model.source or ""
    ids, pid = sh.ids[sel].astype(np.int64), sh.pid[sel].astype(np.int64)
    conn = sh.nodes[sel].astype(np.int64)
    n = len(ids)
    conn[:, 3] = np.where(conn[:, 3] < 0, conn[:, 2], conn[:, 3])  # 3-node input
    if np.any(conn < 0):
        problems.append(Problem(src, 0, "ELEMENT_SHELL", None, "shell elements need their nodes N1-N3 defined"))
        return None
    tri = (conn[:, 2] == conn[:, 3]).astype(np.int8)
    if np.any(
        (conn[:, 0] == conn[:, 1])
        | (conn[:, 1] == conn[:, 2])
        | (conn[:, 0] == conn[:, 2])
        | ((tri == 0) & ((conn[:, 3] == conn[:, 0]) | (conn[:, 3] == conn[:, 1])))
    ):
        problems.append(
            Problem(src, 0, "ELEMENT_SHELL", None, "degenerate shells must repeat node 3 as node 4 (n1 n2 n3 n3)")
        )
        return None
    offset = sh.offset[sel]
    if np.any(np.nan_to_num(offset) != 0.0):
        problems.append(Problem(src, 0, "ELEMENT_SHELL_OFFSET", "OFFSET", "shell offsets are not supported yet"))
    ctrl = model.find("CONTROL_HOURGLASS")
    ihq0 = int(ctrl[0].get("ihq", 1) or 1) if ctrl else 1
    qh0 = _num(ctrl[0], "qh", 0.1) if ctrl else 0.1
    istupd, bwc, intgrd, rotascl = _control_shell(model, problems, warns)
    curves = CurveStore(model)
    mat_rows: dict[int, int] = {}
    mtypes, props, mcurves, mat_ids = [], [], [], []
    mat_of = np.zeros(n, np.int64)
    nip, rule, shrf = np.full(n, 2, np.int64), np.zeros(n, np.int64), np.ones(n)
    tnode = np.zeros((n, 4))
    marea = np.zeros(n)
    full = np.zeros(n, np.int8)
    hg_kind, hg_qm, hg_qb, hg_qw = np.zeros(n, np.int64), np.zeros(n), np.zeros(n), np.zeros(n)
    refused = np.zeros(n, bool)
    for p in np.unique(pid):
        m = pid == p
        part = model.parts.get(int(p))
        sec = model.sections.get(part.get("secid")) if part is not None else None
        mat = model.materials.get(part.get("mid")) if part is not None else None
        if part is None or sec is None or sec.keyword != "SECTION_SHELL" or mat is None:
            problems.append(
                Problem(
                    src,
                    0,
                    "ELEMENT_SHELL",
                    "PID",
                    f"shells of part {int(p)} need a *PART with a *SECTION_SHELL and a material",
                )
            )
            refused[m] = True
            continue
        got = _section(sec, part, int(p), intgrd, problems, warns)
        hg = _hourglass(model, part, int(p), ihq0, qh0, problems, warns, full=got is not None and got[5])
        mid = int(mat.get("mid"))
        if mid not in mat_rows:
            mm = shell_material(model, mat, curves, problems, warns)
            if mm is not None:
                mat_rows[mid] = len(mtypes)
                mtypes.append(mm[0])
                props.append(mm[1])
                mcurves.append(mm[2])
                mat_ids.append(mid)
        if got is None or hg is None or mid not in mat_rows:
            refused[m] = True  # the card's refusal is the problem: not their thickness or nodes' mass
            continue
        mat_of[m] = mat_rows[mid]
        nip[m], rule[m], shrf[m], tnode[m], marea[m], full[m] = got
        hg_kind[m], hg_qm[m], hg_qb[m], hg_qw[m] = hg
    if not mtypes:
        return None
    given = sh.thickness[sel]
    tn = np.where(np.isfinite(given) & (given > 0), given, tnode)
    thick0 = np.where(tri == 1, tn[:, :3].mean(axis=1), tn.mean(axis=1))
    for i in np.flatnonzero((thick0 <= 0) & ~refused)[:10]:
        problems.append(Problem(src, 0, "SECTION_SHELL", "T1", f"shell {int(ids[i])} has thickness <= 0"))
    x = model.nodes.xyz
    area0 = element_areas(x, conn, tri)
    for i in np.flatnonzero(area0 <= 0)[:10]:
        problems.append(Problem(src, 0, "ELEMENT_SHELL", None, f"shell {int(ids[i])} has zero area"))
    # a quadrilateral with two different nodes at one point: a collapsed edge the element's
    # one-point rule cannot carry (a triangle is written N3 = N4)
    edge = np.linalg.norm(x[conn] - x[np.roll(conn, -1, axis=1)], axis=2)
    size = np.sqrt(np.maximum(area0, 0.0))
    collapsed = (tri == 0) & np.any(edge <= 1e-9 * np.maximum(size, 1e-300)[:, None], axis=1) & (area0 > 0)
    for i in np.flatnonzero(collapsed)[:10]:
        a = int(np.argmin(edge[i]))
        n1, n2 = model.nodes.ids[conn[i, a]], model.nodes.ids[conn[i, (a + 1) % 4]]
        problems.append(
            Problem(
                src,
                0,
                "ELEMENT_SHELL",
                f"N{a + 1}",
                f"shell {int(ids[i])}: nodes {int(n1)} and {int(n2)} lie at one point (a collapsed "
                "edge): merge them, or write the element as a triangle (N3 = N4)",
            )
        )
    props_a = np.array(props)
    rho = props_a[mat_of, ps.P_RO] + np.where(thick0 > 0, marea / np.where(thick0 > 0, thick0, 1.0), 0.0)
    cs, ce, cx, cy = curves.arrays()
    s = ShellSet(
        ids,
        pid,
        conn,
        tri,
        mat_of,
        np.array(mat_ids, np.int64),
        np.array(mtypes, np.int64),
        props_a,
        np.array(mcurves, np.int64).reshape(-1, ps.N_CURVES),
        cs,
        ce,
        cx,
        cy,
        thick0,
        area0,
        nip,
        rule,
        shrf,
        hg_kind,
        hg_qm,
        hg_qb,
        hg_qw,
        rho,
        marea,
        istupd,
        bwc,
        rotascl,
        warns,
        _isdo(model, problems),
        full * (1 - tri),  # an ELFORM 16 triangle runs as the C0 triangle
        refused if refused.any() else None,
    )
    if warnings is not None:
        warnings.extend(warns)
    return s


# --- in the time loop ----------------------------------------------------------------------------


class ShellGroup(ElementGroup):
    """The shells as an element group of the time loop (groups.ElementGroup)."""

    kind = "shell"

    def __init__(self, s: ShellSet, n_nodes: int):
        self.s = s
        self.st = new_state(s, n_nodes)
        self.ids, self.pid, self.conn = s.ids, s.pid, s.conn
        self.refused = s.refused
        self.energy = self.st.energy  # internal energy [energy]
        self.hourglass = self.st.hg_energy
        self.warnings = s.warnings
        self._frows = self.st.fe.reshape(-1, 3)
        self._mrows = self.st.me.reshape(-1, 3)
        self._dt = self.st.step
        self._fresh = False  # the kernel's steps are those of the current positions
        self._dt_min = None  # their smallest, where the kernel returned it

    def forces(self, st: State) -> None:
        self._dt_min = compute_forces(self.s, self.st, st.x, st.v, st.w, st.dt)
        self._fresh = True
        gather_corner_pair(self.st.node_ptr, self.st.corner_of, self._frows, st.f, self._mrows, st.moment)

    def corner_forces(self) -> np.ndarray:
        return self.st.fe

    def corner_moments(self) -> np.ndarray:
        return self.st.me

    def plastic_strain(self) -> np.ndarray:
        return self.st.epsp.max(axis=1) if self.st.epsp.size else np.zeros(len(self.ids))

    def lumped(self, n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
        return lumped(self.s, n_nodes)

    def critical_dt(self, st: State) -> float:
        """The smallest element step at st.x: the one the forces just
        computed (the time loop asks right after them), else computed."""
        fresh, self._fresh = self._fresh, False
        if fresh and self._dt_min is not None:  # the one-point kernel returned it
            return float(self._dt_min)
        if not fresh:
            s = self.s
            shell_timestep(st.x, s.conn, s.tri, self.st.alive, s.mat_of, s.props, s.isdo, self._dt)
        return float(self._dt.min()) if len(self._dt) else np.inf

    @property
    def eroded(self) -> int:
        return int(np.count_nonzero(self.st.alive != 1))


def build_shells(
    model: Model, rigid_pids: ArrayLike, problems: list, warnings: list | None = None
) -> ShellGroup | None:
    """The shell group of a Model (None without deformable shells); see
    ``build_shell_set`` for ``problems`` and ``warnings``."""
    s = build_shell_set(model, rigid_pids, problems, warnings)
    if s is None:
        return None
    return ShellGroup(s, len(model.nodes))
