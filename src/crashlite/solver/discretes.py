"""Discrete springs and dampers from the Model: *ELEMENT_DISCRETE with
*MAT_SPRING_ELASTIC, _DAMPER_VISCOUS, _NONLINEAR_ELASTIC, _INELASTIC and
_GENERAL_NONLINEAR (MAT_S01, S02, S04, S06, S08) and *DEFINE_SD_ORIENTATION
as the struct-of-arrays the discrete kernels take (kernels.discrete).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..keyword.errors import Problem
from ..model.model import Model
from .kernels.discrete import CURVE, DAMPER, GENERAL, INELASTIC, LINEAR
from .records import _curve, _problem

# spring and damper constants that must not be negative, by field
_SPRING_CONSTANTS = {"k": ("MAT_SPRING_ELASTIC",), "dc": ("MAT_DAMPER_VISCOUS",), "ku": ("MAT_SPRING_INELASTIC",)}


@dataclass
class Discrete:
    """Struct-of-arrays of discrete elements (see kernels.discrete)."""

    ids: np.ndarray  # (n,) int64 element IDs
    n1: np.ndarray  # (n,) int64 node index
    n2: np.ndarray  # (n,) int64 node index (-1: grounded)
    kind: np.ndarray  # (n,) int64 LINEAR, DAMPER or CURVE
    k: np.ndarray  # (n,) float64 stiffness [force/length] or damping [force·time/length]
    scale: np.ndarray  # (n,) float64
    offset: np.ndarray  # (n,) float64 [length]
    length0: np.ndarray  # (n,) float64 initial length (or projection) [length]
    direction: np.ndarray  # (n, 3) float64 fixed unit direction, zeros: along the axis
    ground: np.ndarray  # (n, 3) float64 ground point of grounded elements
    curve_start: np.ndarray  # (n,) int64
    curve_stop: np.ndarray  # (n,) int64
    curve_x: np.ndarray  # (m,) float64 deflection [length]
    curve_y: np.ndarray  # (m,) float64 force [force]
    ctf: np.ndarray  # (n,) int64 S08 sign restriction (1 compression only, -1 tension only)
    ucurve_start: np.ndarray | None = None  # (n,) int64 S06 unloading curve in curve_x/y (None: none)
    ucurve_stop: np.ndarray | None = None  # (n,) int64
    yield_t: np.ndarray | None = None  # (n,) S06 initial yield force in tension (> 0) [force]
    yield_c: np.ndarray | None = None  # (n,) S06 initial yield force in compression (< 0) [force]


def build_discrete(model: Model, problems: list) -> Discrete:
    d = model.discretes
    n = len(d)
    kind = np.zeros(n, np.int64)
    k = np.zeros(n)
    starts, stops = np.zeros(n, np.int64), np.zeros(n, np.int64)
    ctf = np.zeros(n, np.int64)
    ustart, ustop = np.zeros(n, np.int64), np.zeros(n, np.int64)
    yield_t, yield_c = np.zeros(n), np.zeros(n)
    cx, cy = [np.zeros(0)], [np.zeros(0)]
    used = 0

    def add_curve(lcid):
        nonlocal used
        a, o = _curve(model, lcid)
        cx.append(a)
        cy.append(o)
        used += len(a)
        return used - len(a), used

    for pid in np.unique(d.pid):
        sel = d.pid == pid
        part = model.parts.get(int(pid))
        mat = model.materials.get(part.get("mid")) if part is not None else None
        sec = model.sections.get(part.get("secid")) if part is not None else None
        if sec is not None and int(sec.get("dro", 0)) != 0:
            problems.append(_problem(sec, "dro", "rotational discrete elements are not supported yet"))
        if mat is None:
            problems.append(_problem(part, "mid", "discrete elements need a *MAT_SPRING/_DAMPER material"))
            continue
        for fld, what in (("k", "stiffness K"), ("dc", "damping constant DC"), ("ku", "unloading stiffness KU")):
            if mat.keyword in _SPRING_CONSTANTS.get(fld, ()) and float(mat.get(fld, 0.0) or 0.0) < 0:
                problems.append(
                    _problem(
                        mat,
                        fld,
                        f"material {mat.get('mid')}: {what} = {float(mat[fld]):g} < 0 "
                        "gives energy instead of storing it: it must be >= 0",
                    )
                )
        if mat.keyword == "MAT_SPRING_ELASTIC":
            kind[sel], k[sel] = LINEAR, float(mat["k"])
        elif mat.keyword == "MAT_DAMPER_VISCOUS":
            kind[sel], k[sel] = DAMPER, float(mat["dc"])
        elif mat.keyword in ("MAT_SPRING_NONLINEAR_ELASTIC", "MAT_SPRING_INELASTIC"):
            lc = "lcd" if mat.keyword == "MAT_SPRING_NONLINEAR_ELASTIC" else "lcfd"
            if int(mat.get(lc, 0)) not in model.curves:
                problems.append(_problem(mat, lc, f"curve {mat.get(lc)} is not defined"))
                continue
            if lc == "lcd":
                kind[sel] = CURVE
            else:
                kind[sel], k[sel], ctf[sel] = INELASTIC, float(mat["ku"]), int(mat.get("ctf", 0))
            starts[sel], stops[sel] = add_curve(int(mat[lc]))
        elif mat.keyword == "MAT_SPRING_GENERAL_NONLINEAR":
            bad = [f for f in ("lcdl", "lcdu") if mat.get(f) and int(mat[f]) not in model.curves]
            if not mat.get("lcdl") or bad:
                problems.append(
                    _problem(mat, (bad or ["lcdl"])[0], f"curve {mat.get((bad or ['lcdl'])[0])} is not defined")
                )
                continue
            if float(mat.get("beta", 0.0) or 0.0) != 0.0:
                problems.append(_problem(mat, "beta", "BETA other than 0 (coupled hardening) is not supported yet"))
                continue
            kind[sel] = GENERAL
            starts[sel], stops[sel] = add_curve(int(mat["lcdl"]))
            if mat.get("lcdu"):
                ustart[sel], ustop[sel] = add_curve(int(mat["lcdu"]))
            yield_t[sel] = abs(float(mat.get("tyi", 0.0) or 0.0))
            yield_c[sel] = -abs(float(mat.get("cyi", 0.0) or 0.0))
        else:
            problems.append(
                _problem(
                    mat,
                    None,
                    f"*{mat.keyword} is not supported by the solver yet "
                    "(supported: MAT_S01, MAT_S02, MAT_S04, MAT_S06, MAT_S08)",
                )
            )
    x = model.nodes.xyz
    n1 = d.nodes[:, 0].astype(np.int64)
    n2 = d.nodes[:, 1].astype(np.int64)
    direction = np.zeros((n, 3))
    orient = {int(r["vid"]): r for r in model.find("DEFINE_SD_ORIENTATION")}
    for vid in np.unique(d.vid[d.vid > 0]):
        rec = orient.get(int(vid))
        if rec is None:
            problems.append(
                Problem(
                    model.source or "",
                    0,
                    "ELEMENT_DISCRETE",
                    "VID",
                    f"*DEFINE_SD_ORIENTATION {int(vid)} is not defined",
                )
            )
            continue
        if int(rec.get("iop", 0)) != 0:
            problems.append(_problem(rec, "iop", "only IOP = 0 (a fixed vector) is supported yet"))
            continue
        u = np.array([rec.get("xt", 0.0), rec.get("yt", 0.0), rec.get("zt", 0.0)], float)
        if not np.linalg.norm(u):
            problems.append(_problem(rec, "xt", "the orientation vector has zero length"))
            continue
        direction[d.vid == vid] = u / np.linalg.norm(u)
    ground = x[n1].copy()
    other = np.where(n2[:, None] >= 0, x[np.maximum(n2, 0)], ground)
    rel = other - x[n1]
    fixed_dir = np.any(direction != 0, axis=1)
    length0 = np.where(fixed_dir, np.einsum("ij,ij->i", rel, direction), np.linalg.norm(rel, axis=1))
    # two nodes at one point and no orientation: the element has no direction to act along
    for e in np.flatnonzero((n2 >= 0) & ~fixed_dir & (np.linalg.norm(rel, axis=1) == 0))[:10]:
        problems.append(
            Problem(
                model.source or "",
                0,
                "ELEMENT_DISCRETE",
                "VID",
                f"discrete element {int(d.ids[e])}: nodes {int(model.nodes.ids[n1[e]])} and "
                f"{int(model.nodes.ids[n2[e]])} lie at one point and no orientation (VID, "
                "*DEFINE_SD_ORIENTATION) gives its direction",
            )
        )
    return Discrete(
        d.ids,
        n1,
        n2,
        kind,
        k,
        d.scale.astype(float),
        d.offset.astype(float),
        length0,
        direction,
        ground,
        starts,
        stops,
        np.concatenate(cx),
        np.concatenate(cy),
        ctf,
        ustart,
        ustop,
        yield_t,
        yield_c,
    )
