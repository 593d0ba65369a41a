"""Mass properties of a Model and a guess of its unit system."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from . import mass as mk


def _per_part(model, pids: np.ndarray, group: str, key: str, value, width: int = 0) -> np.ndarray:
    """``value(record)`` of each element's part section or material (0 where
    the part or the record is unknown), spread to the elements."""
    out = np.zeros((len(pids), width) if width else len(pids))
    for pid in np.unique(pids):
        part = model.parts.get(int(pid))
        rec = getattr(model, group).get(part.get(key)) if part is not None else None
        if rec is not None:
            out[pids == pid] = value(rec)
    return out


def _density(model, pids: np.ndarray) -> np.ndarray:
    """Density of each element's part material."""
    return _per_part(model, pids, "materials", "mid", lambda m: float(m.get("ro", 0.0)))


def _shell_t(sec) -> list[float]:
    t1 = float(sec.get("t1", 0.0))
    return [t1] + [float(sec.get(f"t{i}", 0.0)) or t1 for i in (2, 3, 4)]


def _section_thickness(model, pids: np.ndarray) -> np.ndarray:
    """(n, 4) section thicknesses T1..T4 of each shell's part (T2-T4 default to T1)."""
    return _per_part(model, pids, "sections", "secid", _shell_t, width=4)


def _beam_area(model, pids: np.ndarray) -> np.ndarray:
    """Cross-section area of each beam from its *SECTION_BEAM."""
    return _per_part(model, pids, "sections", "secid", section_area)


def section_area(sec) -> float:
    """A for resultant beams and trusses; from TS1/TT1 and the shape CST for
    integrated beams (0 rectangle, 1 tube by diameters, 2 solid circle)."""
    a = float(sec.get("a", 0.0))
    if a == 0.0 and sec.get("ts1") is not None:
        ts, tt = float(sec.get("ts1", 0.0)), float(sec.get("tt1", 0.0))
        cst = int(sec.get("cst", 0))
        if cst == 0:
            a = ts * tt
        elif cst == 1:
            a = math.pi / 4 * (ts**2 - tt**2)
        elif cst == 2:
            a = math.pi / 4 * ts**2
    return a


def _part_moments(model, pid_sel):
    """Raw moments of the elements of the selected parts."""
    xyz = model.nodes.xyz
    moments = []
    s = model.shells
    m = np.isin(s.pid, pid_sel)
    if m.any():
        t = s.thickness[m]
        t = np.where(np.isnan(t), _section_thickness(model, s.pid[m]), t)
        moments.append(mk.shell_moments(xyz, s.nodes[m], t, _density(model, s.pid[m])))
    so = model.solids
    m = np.isin(so.pid, pid_sel)
    if m.any():
        moments.append(mk.solid_moments(xyz, so.nodes[m], _density(model, so.pid[m])))
    b = model.beams
    m = np.isin(b.pid, pid_sel)
    if m.any():
        moments.append(mk.beam_moments(xyz, b.nodes[m][:, :2], _beam_area(model, b.pid[m]), _density(model, b.pid[m])))
    return moments


def _scaled(mo, f: float):
    return mk.Moments(mo.mass * f, mo.first * f, mo.second * f)


class MassPartRow(NamedTuple):
    """One row of *ELEMENT_MASS_PART(_SET): the parts it names, their mass
    before it (earlier rows included) and the mass it adds."""

    rec: object  # the card
    row: int  # its row
    pids: list  # parts (of the set, with _SET) that exist
    current: float  # their mass before this row [mass]
    added: float  # FINMASS - current when FINMASS > 0, else ADDMASS [mass]


def _given_inertia(part) -> bool:
    return "INERTIA" in part.options and float(part.get("tm", 0.0) or 0.0) > 0


def element_mass(model, pid: int) -> float:
    """Mass of a part's shells, solids and beams (ρ·t·A, ρ·V, ρ·A·L)."""
    return float(sum(x.mass.sum() for x in _part_moments(model, np.array([int(pid)]))))


def _mass_part_scaling(model, part_mass) -> tuple[list[MassPartRow], dict[int, float]]:
    """The rows of ``mass_part_rows`` and the factor each part ends with."""
    factor: dict[int, float] = {}
    out = []
    for rec in model.find("ELEMENT_MASS_PART"):
        rows = rec.rows or {}
        for k, ident in enumerate(rows.get("pid", [])):
            if "SET" in rec.options:
                try:
                    named = [int(p) for p in model.set_members("PART", int(ident))]
                except KeyError:
                    named = []
            else:
                named = [int(ident)]
            pids = [p for p in named if p in model.parts and not _given_inertia(model.parts[p])]
            current = sum(part_mass(p) * factor.get(p, 1.0) for p in pids)
            fm, am = float(rows["finmass"][k]), float(rows["addmass"][k])
            added = fm - current if fm > 0 else am
            if current > 0:
                for p in pids:
                    factor[p] = factor.get(p, 1.0) * (current + added) / current
            out.append(MassPartRow(rec, k, pids, current, added))
    return out, factor


def mass_part_rows(model, part_mass: Callable[[int], float] | None = None) -> list[MassPartRow]:
    """*ELEMENT_MASS_PART rows in deck order. A _SET row acts on its parts
    as a whole (FINMASS is the set's final mass) and scales each by the same
    factor, so the mass goes to every node in proportion to its mass and the
    CoG stays; a later row sees the mass earlier rows added. ``part_mass``:
    a part's own mass (default: its elements' mass). Parts given by
    *PART_INERTIA keep their TM and are left out."""
    return _mass_part_scaling(model, part_mass or (lambda p: element_mass(model, p)))[0]


def mass_part_factors(model, part_mass: Callable[[int], float] | None = None) -> dict[int, float]:
    """Part ID -> the factor *ELEMENT_MASS_PART scales its own mass by
    (``part_mass`` as in ``mass_part_rows``)."""
    return _mass_part_scaling(model, part_mass or (lambda p: element_mass(model, p)))[1]


def mass_properties(model, parts=None) -> mk.MassProperties:
    """Mass, CoG and inertia about the CoG of the whole model or of parts.

    Shells integrate ρ·t over the mid-surface (nodal thickness or section
    T1..T4), solids ρ over the volume, beams ρ·A along the axis; *ELEMENT_MASS
    and *ELEMENT_INERTIA add point masses; a part with *PART_INERTIA (TM > 0)
    counts with its given mass, CoG and tensor; *ELEMENT_MASS_PART adds mass
    to a part in proportion to its element mass (CoG unchanged; see
    ``mass_part_rows``).
    """
    pids = model.part_ids_of(parts)
    whole = parts is None
    factor = mass_part_factors(model) if model.find("ELEMENT_MASS_PART") else {}
    moments = []
    for pid in pids:
        part = model.parts[int(pid)]
        if _given_inertia(part):
            c = np.array([part.get("xc", 0.0), part.get("yc", 0.0), part.get("zc", 0.0)], float)
            tensor = np.array(
                [
                    [part.get("ixx", 0.0), part.get("ixy", 0.0), part.get("ixz", 0.0)],
                    [part.get("ixy", 0.0), part.get("iyy", 0.0), part.get("iyz", 0.0)],
                    [part.get("ixz", 0.0), part.get("iyz", 0.0), part.get("izz", 0.0)],
                ],
                float,
            )
            moments.append(mk.point_moments(c[None], np.array([part.get("tm")], float), tensor[None]))
            continue
        pm = _part_moments(model, np.array([pid]))
        if int(pid) in factor:
            pm = [_scaled(x, factor[int(pid)]) for x in pm]
        moments += pm
    ms = model.masses
    sel = np.ones(len(ms), bool) if whole else np.isin(ms.pid, pids)
    if sel.any():
        moments.append(mk.point_moments(model.nodes.xyz[ms.node[sel]], ms.mass[sel]))
    it = model.inertias
    if whole and len(it):
        pos = model.nodes.xyz[it.node] + np.nan_to_num(it.offset)
        t = it.tensor
        tensor = np.stack(
            [
                np.stack([t[:, 0], t[:, 1], t[:, 2]], 1),
                np.stack([t[:, 1], t[:, 3], t[:, 4]], 1),
                np.stack([t[:, 2], t[:, 4], t[:, 5]], 1),
            ],
            1,
        )
        moments.append(mk.point_moments(pos, it.mass, tensor))
    return mk.combine(*moments)


_UNITS = [  # steel density in each system
    (7.85e-9, "mm-t-s (N, MPa)"),
    (7.85e-6, "mm-kg-ms (kN, GPa)"),
    (7.85e-3, "mm-g-ms (N, MPa)"),
    (7.85e3, "m-kg-s (N, Pa)"),
    (7.85, "cm-g-s / mm-mg-... (density ~ g/cm³)"),
]


def guess_units(model) -> str:
    """Unit system whose steel density is closest (in log scale) to the
    model's median density; metals and foams both sit within ~2 decades."""
    ro = [float(m.get("ro", 0.0)) for m in model.materials.values() if float(m.get("ro", 0.0) or 0) > 0]
    if not ro:
        return "unknown (no densities)"
    med = float(np.median(ro))
    best = min(_UNITS, key=lambda u: abs(math.log10(med) - math.log10(u[0])))
    return best[1]
