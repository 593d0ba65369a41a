"""The material rows of the shells (kernels.plane_stress): kind, props row
and curve slots of MAT_001, MAT_003, MAT_024 and MAT_081, or the Problems
that refuse a material.

MAT_024 and MAT_081 take a yield curve LCSS that may be a *DEFINE_TABLE of
curves by strain rate (C, P and LCSR then do not apply: the table holds the
rate effect). MAT_081 adds the damage of plane_stress: softening from EPPF,
rupture at EPPFR (P_FAIL, the erosion of MAT_024's FAIL), the damage curve
LCDM if given, NUMINT.
"""

from __future__ import annotations

import numpy as np

from ..keyword.errors import Problem
from ..model.model import Model
from .curve_store import CurveStore
from .kernels import plane_stress as ps

PLASTIC = ("MAT_PIECEWISE_LINEAR_PLASTICITY", "MAT_PLASTICITY_WITH_DAMAGE")
SUPPORTED = ("MAT_ELASTIC", "MAT_PLASTIC_KINEMATIC", *PLASTIC)
NO_SOFTENING = 1e12  # EPPF read from a blank or 0 (the manual's default)


def problem(rec, fld, msg) -> Problem:
    """A Problem naming the card (file, line, keyword) and field of ``rec``."""
    f, line = rec.where(fld) if rec is not None and hasattr(rec, "where") else ("", 0)
    return Problem(f, line, getattr(rec, "name", ""), fld.upper() if fld else None, msg)


def num(rec, fld: str, default: float = 0.0) -> float:
    v = rec.get(fld)
    return default if v is None else float(v)


def _curve(model, mat, fld, curves, problems):
    """Curve slot of field ``fld`` (-1: none), None if refused."""
    lc = int(num(mat, fld))
    if lc == 0:
        return -1
    if lc not in model.curves:
        problems.append(problem(mat, fld, f"curve {lc} is not defined (a *DEFINE_CURVE is needed)"))
        return None
    return curves.get(lc)


def shell_material(model: Model, mat, curves: CurveStore, problems: list, warns: list | None = None):
    """(kind, props row, curve slots) of one material, or None if refused;
    options run in an approximated way go to ``warns``."""
    kw = mat.keyword
    if kw not in SUPPORTED:
        problems.append(
            problem(
                mat,
                None,
                f"*{kw} is not supported for shells (supported: MAT_001, MAT_003, MAT_024, MAT_081, MAT_020 rigid)",
            )
        )
        return None
    e, nu, ro = num(mat, "e"), num(mat, "pr"), num(mat, "ro")
    if e <= 0 or ro <= 0 or not 0.0 <= nu < 0.5:
        bad = "ro" if ro <= 0 else "e" if e <= 0 else "pr"
        problems.append(
            problem(
                mat,
                bad,
                f"material {mat.get('mid')}: RO > 0, E > 0 and 0 <= PR < 0.5 are "
                f"needed for shells ({bad.upper()} = {num(mat, bad):g})",
            )
        )
        return None
    row = np.zeros(ps.N_PROPS)
    mc = np.full(ps.N_CURVES, -1, np.int64)
    row[ps.P_RO], row[ps.P_E], row[ps.P_PR] = ro, e, nu
    row[ps.P_G], row[ps.P_C1] = e / (2.0 * (1.0 + nu)), e / (1.0 - nu * nu)
    row[ps.P_WAVE] = e / (ro * (1.0 - nu * nu))
    row[ps.P_FAIL] = 1e21
    row[ps.P_BETA] = 1.0
    row[ps.P_EPPF], row[ps.P_EPPFR] = 1e21, 1e21
    if kw == "MAT_ELASTIC":
        return ps.ELASTIC, row, mc
    ok = True
    etan = num(mat, "etan")
    if not 0.0 <= etan < e:
        problems.append(problem(mat, "etan", "ETAN must lie in [0, E)"))
        ok = False
    row[ps.P_SIGY] = num(mat, "sigy")
    row[ps.P_EP] = e * etan / (e - etan) if 0.0 <= etan < e else 0.0
    if num(mat, "vp") != 0.0:
        problems.append(problem(mat, "vp", "VP = 1 (viscoplastic rate formulation) is not supported yet"))
        ok = False
    if kw == "MAT_PLASTIC_KINEMATIC":
        beta = num(mat, "beta")
        if not 0.0 <= beta <= 1.0:
            problems.append(problem(mat, "beta", "BETA must lie in [0, 1]"))
            ok = False
        row[ps.P_BETA] = beta
        row[ps.P_CS_C], row[ps.P_CS_P] = num(mat, "src"), num(mat, "srp")
        fs = num(mat, "fs", 1e20)
        row[ps.P_FAIL] = fs if fs > 0 else 1e21
        if row[ps.P_SIGY] <= 0:
            problems.append(problem(mat, "sigy", "SIGY > 0 is needed"))
            ok = False
        return (ps.KINEMATIC, row, mc) if ok else None
    ok = _piecewise(model, mat, curves, row, mc, problems, warns) and ok
    if kw == "MAT_PLASTICITY_WITH_DAMAGE":
        ok = _damage(model, mat, curves, row, mc, problems) and ok
        return (ps.DAMAGE, row, mc) if ok else None
    return (ps.PIECEWISE, row, mc) if ok else None


def _piecewise(model, mat, curves: CurveStore, row, mc, problems, warns) -> bool:
    """MAT_024's fields (and MAT_081's, which are the same but FAIL and LCF)."""
    ok = True
    for fld, what in (("lcf", "LCF"), ("tdel", "TDEL (deletion by time step)")):
        if num(mat, fld) != 0:
            problems.append(problem(mat, fld, f"{what} is not supported for shells yet"))
            ok = False
    fail = num(mat, "fail", 1e21)
    if fail < 0:
        problems.append(problem(mat, "fail", "FAIL < 0 (user failure subroutine) is not supported"))
        ok = False
    row[ps.P_FAIL] = fail if fail > 0 else 1e21
    row[ps.P_CS_C], row[ps.P_CS_P] = num(mat, "c"), num(mat, "p")
    lcsr = _curve(model, mat, "lcsr", curves, problems)
    lcss, table, why = curves.yield_slots(mat, "lcss")
    if why is not None:
        problems.append(problem(mat, "lcss", why))
        return False
    if lcsr is None:
        return False
    if table >= 0:
        mc[ps.C_TABLE] = table
        given = [f.upper() for f in ("c", "p", "lcsr") if num(mat, f) != 0]
        if given and warns is not None:
            warns.append(
                problem(
                    mat,
                    "lcss",
                    f"material {mat.get('mid')}: LCSS is a table of yield curves by strain rate: "
                    f"{', '.join(given)} do not apply (as in LS-DYNA)",
                )
            )
        row[ps.P_CS_C] = row[ps.P_CS_P] = 0.0
        return ok
    mc[ps.C_LCSR] = lcsr
    if lcss >= 0:
        mc[ps.C_LCSS] = lcss
        return ok
    es = np.array([num(mat, f"es{i}") for i in range(1, 9)])
    eps = np.array([num(mat, f"eps{i}") for i in range(1, 9)])
    if np.any(es > 0):
        n = int(np.flatnonzero(es > 0)[-1]) + 1
        if n < 2 or np.any(np.diff(eps[:n]) <= 0):
            problems.append(problem(mat, "eps1", "EPS1-EPS8 / ES1-ES8 need at least two points with rising strains"))
            return False
        mc[ps.C_LCSS] = curves.add(eps[:n], es[:n], ("mat", mat.get("mid")))
    elif row[ps.P_SIGY] <= 0:
        problems.append(problem(mat, "sigy", "SIGY > 0 (or a curve LCSS / EPS-ES points) is needed"))
        return False
    return ok


def _damage(model, mat, curves: CurveStore, row, mc, problems) -> bool:
    """MAT_081: EPPF, EPPFR (the rupture strain: P_FAIL), LCDM, NUMINT."""
    eppf, eppfr = num(mat, "eppf", NO_SOFTENING), num(mat, "eppfr", 1e14)
    lcdm = _curve(model, mat, "lcdm", curves, problems)
    if lcdm is None:
        return False
    if lcdm >= 0 and eppf >= NO_SOFTENING:
        eppf = 0.0  # the manual lets EPPF be 0 with a damage curve: the curve from ε̄p = 0
    if eppf < 0 or eppfr <= 0:
        problems.append(problem(mat, "eppf" if eppf < 0 else "eppfr", "EPPF >= 0 and EPPFR > 0 are needed"))
        return False
    numint = int(num(mat, "numint"))
    if numint < 0:
        problems.append(problem(mat, "numint", f"NUMINT {numint}: a number of points >= 0 is needed"))
        return False
    row[ps.P_EPPF], row[ps.P_EPPFR], row[ps.P_NUMINT] = eppf, eppfr, numint
    row[ps.P_FAIL] = eppfr
    mc[ps.C_LCDM] = lcdm
    return True
