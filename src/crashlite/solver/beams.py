"""Elastic beams from the Model: section resultants, frames, lumped masses."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..keyword.errors import Problem
from ..model.model import Model
from ..model.properties import section_area


@dataclass
class BeamSet:
    ids: np.ndarray  # (n,) element IDs
    n1: np.ndarray  # (n,) int64 node index
    n2: np.ndarray  # (n,) int64 node index
    q1: np.ndarray  # (n, 3, 3) element axes (columns) seen from node 1 at t = 0
    q2: np.ndarray  # (n, 3, 3) same from node 2
    length0: np.ndarray  # (n,) [length]
    ea: np.ndarray  # (n,) axial stiffness E·A [force]
    gj: np.ndarray  # (n,) torsional stiffness G·J [force·length²]
    ei2: np.ndarray  # (n,) E·ISS: bending with deflection along e3 [force·length²]
    ei3: np.ndarray  # (n,) E·ITT: bending with deflection along e2
    mass: np.ndarray  # (n,) ρ·A·L0 [mass]
    wave: np.ndarray  # (n,) axial wave speed sqrt(E/ρ) [length/time], of the (scaled) mass


def _properties(sec, mat):
    """A, ISS, ITT, J from a *SECTION_BEAM: given (ELFORM 2, 12, 13) or from
    the TS1/TT1 shape of integrated beams (CST 0 rectangle, 1 tube, 2 circle)."""
    elform = int(sec.get("elform", 1) or 1)
    if elform in (2, 12, 13):
        a = float(sec.get("a", 0.0))
        iss, itt = float(sec.get("iss", 0.0)), float(sec.get("itt", 0.0))
        j = float(sec.get("irr", 0.0)) or iss + itt
        return a, iss, itt, j
    ts, tt = float(sec.get("ts1", 0.0)), float(sec.get("tt1", 0.0))
    cst = int(sec.get("cst", 0) or 0)
    a = section_area(sec)
    if cst == 0:  # rectangle: ts along s, tt along t
        iss, itt = ts * tt**3 / 12.0, tt * ts**3 / 12.0
        k = min(ts, tt)
        big = max(ts, tt)
        j = big * k**3 * (1.0 / 3.0 - 0.21 * k / big * (1.0 - k**4 / (12.0 * big**4)))
    else:  # circle or tube by outer and inner diameter
        inner = tt if cst == 1 else 0.0
        iss = itt = np.pi / 64.0 * (ts**4 - inner**4)
        j = 2.0 * iss
    return a, iss, itt, j


def _frames(x, n1, n2, n3):
    """Initial element axes: e1 along the chord, e2 towards the orientation
    node (or the global axis least aligned with e1), e3 = e1 × e2."""
    d = x[n2] - x[n1]
    e1 = d / np.linalg.norm(d, axis=1)[:, None]
    ref = np.where((n3 >= 0)[:, None], x[np.maximum(n3, 0)] - x[n1], 0.0)
    no_ref = n3 < 0
    if no_ref.any():
        axis = np.eye(3)[np.argmin(np.abs(e1[no_ref]), axis=1)]
        ref[no_ref] = axis
    g = ref - np.einsum("ij,ij->i", ref, e1)[:, None] * e1
    e2 = g / np.linalg.norm(g, axis=1)[:, None]
    e3 = np.cross(e1, e2)
    return np.stack([e1, e2, e3], axis=2)  # (n, 3, 3), columns


def build_beams(model: Model, rigid_pids: np.ndarray, problems: list) -> BeamSet | None:
    b = model.beams
    sel = ~np.isin(b.pid, rigid_pids)
    if not sel.any():
        return None
    n = int(sel.sum())
    ids, pid, nodes = b.ids[sel], b.pid[sel], b.nodes[sel].astype(np.int64)
    props = np.zeros((n, 4))
    young, shear, rho = np.zeros(n), np.zeros(n), np.zeros(n)
    for p in np.unique(pid):
        m = pid == p
        part = model.parts.get(int(p))
        sec = model.sections.get(part.get("secid")) if part is not None else None
        mat = model.materials.get(part.get("mid")) if part is not None else None
        if sec is None or sec.keyword != "SECTION_BEAM" or mat is None or mat.keyword != "MAT_ELASTIC":
            problems.append(
                Problem(
                    model.source or "",
                    0,
                    "ELEMENT_BEAM",
                    "PID",
                    f"beams of part {int(p)}: the solver runs elastic beams "
                    "(*SECTION_BEAM with *MAT_ELASTIC) or rigid ones",
                )
            )
            continue
        if int(sec.get("elform", 1) or 1) in (3, 6, 9):
            problems.append(
                Problem(
                    *sec.where("elform"),
                    sec.name,
                    "ELFORM",
                    f"beam formulation {sec.get('elform')} is not supported yet",
                )
            )
            continue
        props[m] = _properties(sec, mat)
        e, nu = float(mat["e"]), float(mat.get("pr", 0.0) or 0.0)
        young[m], shear[m], rho[m] = e, e / (2.0 * (1.0 + nu)), float(mat["ro"])
    if np.any(props[:, 0] <= 0) and not problems:
        problems.append(Problem(model.source or "", 0, "SECTION_BEAM", "A", "beam section area is zero"))
    x = model.nodes.xyz
    frames = _frames(x, nodes[:, 0], nodes[:, 1], nodes[:, 2])
    length0 = np.linalg.norm(x[nodes[:, 1]] - x[nodes[:, 0]], axis=1)
    a, iss, itt, j = props.T
    return BeamSet(
        ids,
        nodes[:, 0],
        nodes[:, 1],
        frames,
        frames.copy(),
        length0,
        young * a,
        shear * j,
        young * iss,
        young * itt,
        rho * a * length0,
        np.sqrt(young / np.where(rho > 0, rho, 1.0)),
    )


def lumped(beams: BeamSet, n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodal masses (half of each element) and isotropic rotational
    inertias m·L²/24 per end (large enough that rotation does not set a
    smaller time step than the axial wave for ordinary proportions)."""
    mass = np.zeros(n_nodes)
    inertia = np.zeros(n_nodes)
    half = 0.5 * beams.mass
    rot = half * beams.length0**2 / 12.0
    for nodes in (beams.n1, beams.n2):
        np.add.at(mass, nodes, half)
        np.add.at(inertia, nodes, rot)
    return mass, inertia


def element_dt(beams: BeamSet, mass: np.ndarray, inertia: np.ndarray) -> np.ndarray:
    """Critical step of each beam: axial wave L/c, and the axial, bending
    and rotation modes with the lumped masses and inertias (2/ω with ω²
    from the end stiffnesses)."""
    L = beams.length0
    ei = np.maximum(beams.ei2, beams.ei3)
    m_end = np.minimum(mass[beams.n1], mass[beams.n2])
    j_end = np.minimum(inertia[beams.n1], inertia[beams.n2])
    with np.errstate(divide="ignore", invalid="ignore"):
        dts = np.stack(
            [
                L / beams.wave,
                2.0 * np.sqrt(j_end / (2.0 * 6.0 * ei / L)),
                2.0 * np.sqrt(m_end / (2.0 * 2.0 * 12.0 * ei / L**3)),
                2.0 * np.sqrt(m_end / (2.0 * beams.ea / L)),
            ]
        )
    return np.nanmin(np.where(np.isfinite(dts), dts, np.nan), axis=0)


def scale_beams(beams: BeamSet, mass: np.ndarray, inertia: np.ndarray, target: float) -> np.ndarray:
    """Mass scaling of the beams whose step is below ``target``: their mass
    (and rotational inertia) grows by (target/dt)², split to their nodes,
    and their wave speed drops accordingly. Returns the mass added per beam."""
    added = np.zeros(len(beams.ids))
    for _ in range(3):  # nodes share elements: a few passes settle the steps
        dt = element_dt(beams, mass, inertia)
        need = dt < target * (1 - 1e-9)
        if not need.any():
            break
        factor = np.where(need, (target / dt) ** 2, 1.0)
        extra = (factor - 1.0) * beams.mass
        for nodes in (beams.n1, beams.n2):
            np.add.at(mass, nodes, 0.5 * extra)
            np.add.at(inertia, nodes, 0.5 * extra * beams.length0**2 / 12.0)
        beams.mass = beams.mass * factor
        beams.wave = beams.wave / np.sqrt(factor)
        added += extra
    return added
