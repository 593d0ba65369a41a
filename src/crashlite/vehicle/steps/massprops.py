"""Step 2 of the simplified vehicle: mass properties of the replaced structure.

The replaced structure of a ``Cut`` is its replaced elements (shells,
solids, beams, with their density, thickness and area as the deck gives
them, *ELEMENT_MASS_PART scaling included) and the point masses and point
inertias (*ELEMENT_MASS, *ELEMENT_INERTIA) on its removed nodes; a rigid
part with *PART_INERTIA counts with its given mass, CoG and tensor instead
of its elements. Masses on interface nodes stay with the kept model, so
kept + replaced = the whole model.

The paper's table 2 adds the centre of the rear-axle attachment points
(the bearing of step 3 and the anchor of the anti-rotation beam of
step 4) and the rear axle's own mass.

Units are the model's (mm–t: t, mm, t·mm²); ``table`` converts for print.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ...model import mass as mk
from ...model.mass import MassProperties
from ...model.model import Model
from ...model.properties import mass_part_factors, section_area
from .cut import Cut

# a selection of nodes (``node_indices``): node indices, ("set", SID) or a *SET_NODE title
NodeSelection = ArrayLike | tuple[str, int] | str


@dataclass
class ReplacedMass:
    """Mass properties of the replaced structure (step 2)."""

    structure: MassProperties  # everything replaced: elements + lumped
    elements: MassProperties  # replaced elements only
    lumped: MassProperties  # point masses and inertias on removed nodes
    axle_points: np.ndarray | None = None  # (3,) centre of the rear-axle attachment points [length]
    axle_nodes: np.ndarray | None = None  # (k,) int64 node indices of those points
    axle: MassProperties | None = None  # the rear-axle parts, whole [mass, length]
    notes: list = field(default_factory=list)

    def table(self, mass_scale: float = 1e3, mass_unit: str = "kg", length_unit: str = "mm") -> dict:
        """The paper's table 2: CoG x, y, z and mass of the replaced
        structure and of the rear axle (attachment-point centre), masses
        times ``mass_scale`` (t -> kg by default)."""
        out = {
            "replaced structure": {
                "x": float(self.structure.cog[0]),
                "y": float(self.structure.cog[1]),
                "z": float(self.structure.cog[2]),
                "mass": float(self.structure.mass * mass_scale),
            }
        }
        if self.axle_points is not None:
            out["rear axle"] = {
                "x": float(self.axle_points[0]),
                "y": float(self.axle_points[1]),
                "z": float(self.axle_points[2]),
                "mass": float(self.axle.mass * mass_scale) if self.axle is not None else None,
            }
        out["units"] = {"length": length_unit, "mass": mass_unit}
        return out


def _per_element(model, pids, fn, width: int = 0) -> np.ndarray:
    """``fn(part)`` of each element's part (0 where unknown)."""
    out = np.zeros((len(pids), width) if width else len(pids))
    for pid in np.unique(pids):
        part = model.parts.get(int(pid))
        if part is not None:
            v = fn(part)
            if v is not None:
                out[pids == pid] = v
    return out


def _density(model, part):
    mat = model.materials.get(part.get("mid"))
    return float(mat.get("ro", 0.0) or 0.0) if mat is not None else None


def _thickness(model, part):
    sec = model.sections.get(part.get("secid"))
    if sec is None:
        return None
    t1 = float(sec.get("t1", 0.0) or 0.0)
    return [t1] + [float(sec.get(f"t{i}", 0.0) or 0.0) or t1 for i in (2, 3, 4)]


def _area(model, part):
    sec = model.sections.get(part.get("secid"))
    return section_area(sec) if sec is not None else None


def element_moments(model: Model) -> dict:
    """Raw moments (``model.mass.Moments``) of every shell, solid and beam,
    table name -> Moments with one row per element, *ELEMENT_MASS_PART
    scaling applied per part."""
    xyz = model.nodes.xyz
    out = {}
    s = model.shells
    if len(s):
        t = s.thickness
        t = np.where(np.isnan(t), _per_element(model, s.pid, lambda p: _thickness(model, p), 4), t)
        out["shells"] = mk.shell_moments(xyz, s.nodes, t, _per_element(model, s.pid, lambda p: _density(model, p)))
    so = model.solids
    if len(so):
        out["solids"] = mk.solid_moments(xyz, so.nodes, _per_element(model, so.pid, lambda p: _density(model, p)))
    b = model.beams
    if len(b):
        out["beams"] = mk.beam_moments(
            xyz,
            b.nodes[:, :2],
            _per_element(model, b.pid, lambda p: _area(model, p)),
            _per_element(model, b.pid, lambda p: _density(model, p)),
        )
    _scale_parts(model, out)
    return out


def _scale_parts(model, moments: dict) -> None:
    """*ELEMENT_MASS_PART: each part's element moments scaled by the factor
    the solver gives it (``model.properties.mass_part_factors``: ADDMASS
    added, or FINMASS reached, in proportion to the element masses, so the
    CoG stays; a _SET row acts on its parts as a whole)."""
    for pid, f in mass_part_factors(model).items():
        for t, mo in moments.items():
            sel = getattr(model, t).pid == pid
            mo.mass[sel] *= f
            mo.first[sel] *= f
            mo.second[sel] *= f


def _given_inertia(part) -> tuple[float, np.ndarray, np.ndarray] | None:
    if "INERTIA" not in part.options or not float(part.get("tm", 0.0) or 0.0) > 0:
        return None
    g = {k: float(part.get(k, 0.0) or 0.0) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
    c = np.array([part.get("xc", 0.0), part.get("yc", 0.0), part.get("zc", 0.0)], float)
    tensor = np.array([[g["ixx"], g["ixy"], g["ixz"]], [g["ixy"], g["iyy"], g["iyz"]], [g["ixz"], g["iyz"], g["izz"]]])
    return float(part["tm"]), c, tensor


def replaced_rows(cut: Cut, moments: dict | None = None) -> tuple[list, list, list, list, list]:
    """Raw moments of everything ``cut`` replaces, row by row: (element
    Moments per table and *PART_INERTIA bodies, their weights (bool masks
    of the replaced rows, None: all), point-mass Moments, notes, the table
    name of each element Moments (None for a *PART_INERTIA body)).
    ``moments``: ``element_moments`` of the model when already at hand
    (several cuts of one model); the given-inertia parts are zeroed in it."""
    model = cut.model
    notes = []
    moments = element_moments(model) if moments is None else moments
    given = []
    for pid, part in model.parts.items():
        g = _given_inertia(part)
        if g is None:
            continue
        sel = {t: getattr(model, t).pid == pid for t in moments}
        n_rep = sum(int((cut.replaced[t] & s).sum()) for t, s in sel.items())
        n_all = sum(int(s.sum()) for s in sel.values())
        for t, s in sel.items():  # the given values replace the elements
            moments[t].mass[s] = 0.0
            moments[t].first[s] = 0.0
            moments[t].second[s] = 0.0
        if n_all and n_rep * 2 > n_all:
            given.append(mk.point_moments(g[1][None], np.array([g[0]]), g[2][None]))
            if n_rep < n_all:
                notes.append(f"part {pid} (*PART_INERTIA) lies across the interface: counted whole")
    elems = [moments[t] for t in moments] + given
    masks = [cut.replaced[t] for t in moments] + [None] * len(given)
    tables = list(moments) + [None] * len(given)
    lumped_m = []
    ms = model.masses
    if len(ms):
        sel = cut.removed_nodes[ms.node]
        if sel.any():
            lumped_m.append(mk.point_moments(model.nodes.xyz[ms.node[sel]], ms.mass[sel]))
    it = model.inertias
    if len(it):
        sel = cut.removed_nodes[it.node]
        if sel.any():
            pos = model.nodes.xyz[it.node[sel]] + np.nan_to_num(it.offset[sel])
            t = it.tensor[sel]
            tensor = np.stack([t[:, [0, 1, 2]], t[:, [1, 3, 4]], t[:, [2, 4, 5]]], axis=1)
            if np.any(it.csid[sel] != 0):
                notes.append("*ELEMENT_INERTIA in a local system taken as global")
            lumped_m.append(mk.point_moments(pos, it.mass[sel], tensor))
    if any("INERTIA" in r.options for r in model.find("CONSTRAINED_NODAL_RIGID_BODY")):
        notes.append("*CONSTRAINED_NODAL_RIGID_BODY_INERTIA mass and inertia are not counted (node masses are)")
    return elems, masks, lumped_m, notes, tables


def split_replaced(
    cut: Cut,
    far_point: ArrayLike,
    only: Iterable[int] | None = None,
    without: Iterable[int] | None = None,
    moments: dict | None = None,
) -> tuple[MassProperties, MassProperties]:
    """The replaced mass shared between the interface and a point behind it
    (the rear-axle point) as a two-node bar lumps its mass: each element
    and point mass goes to the far share by ξ, its distance behind the
    interface over the far point's (clipped to [0, 1]), to the interface
    share by 1 − ξ. Each share keeps its own CoG and inertia, so the two
    together have exactly the mass, CoG and inertia of the whole.

    only     part IDs: the elements of these parts alone (no point masses,
             no *PART_INERTIA bodies)
    without  part IDs: everything but the elements of these parts
    (so the shares of disjoint ``only`` sets and of ``without`` their union
    add up to the whole); ``moments``: ``element_moments`` of the model, to
    reuse over several splits. Returns (interface share, far share)."""
    elems, masks, lumped, _, tables = replaced_rows(cut, moments)
    span = float((cut.point - np.asarray(far_point, float)) @ cut.axis)
    if not span > 0:
        raise ValueError("the far point of the mass split must lie behind the interface")
    keep_points = only is None
    rows, weights = [], []
    for mo, w, t in zip(elems, masks, tables):
        base = np.ones(len(mo.mass)) if w is None else np.asarray(w, float)
        if t is None:  # a *PART_INERTIA body
            if not keep_points:
                continue
        elif only is not None or without is not None:
            pid = getattr(cut.model, t).pid
            base = base * (np.isin(pid, list(only)) if only is not None else ~np.isin(pid, list(without)))
        rows.append(mo)
        weights.append(base)
    if keep_points:
        rows += lumped
        weights += [np.ones(len(mo.mass)) for mo in lumped]
    near_w, far_w = [], []
    for mo, base in zip(rows, weights):
        with np.errstate(invalid="ignore", divide="ignore"):
            c = np.where(mo.mass[:, None] > 0, mo.first / mo.mass[:, None], 0.0)
        xi = np.clip(((cut.point - c) @ cut.axis) / span, 0.0, 1.0)
        near_w.append(base * (1.0 - xi))
        far_w.append(base * xi)
    return mk.combine(*rows, weights_mask=near_w), mk.combine(*rows, weights_mask=far_w)


def replaced_mass(
    cut: Cut,
    axle_nodes: NodeSelection | None = None,
    axle_parts: int | str | Iterable[int | str] | None = None,
    moments: dict | None = None,
) -> ReplacedMass:
    """Mass, CoG and inertia (about the CoG) of the structure ``cut`` replaces.

    axle_nodes  node indices, or ("set", SID) / a *SET_NODE title of the
                rear-axle attachment points: their mean position is the
                rear-axle point of table 2 (None: not computed)
    axle_parts  part IDs or titles of the rear axle (None: not computed)
    moments     ``element_moments`` of the model, to reuse over several cuts
    """
    model = cut.model
    elems, masks, lumped_m, notes, _ = replaced_rows(cut, moments)
    elements = mk.combine(*elems, weights_mask=masks)
    lumped = mk.combine(*lumped_m)
    structure = elements + lumped
    out = ReplacedMass(structure, elements, lumped, notes=notes + list(cut.notes))
    if axle_nodes is not None:
        idx = node_indices(model, axle_nodes)
        if not len(idx):
            raise ValueError("no rear-axle attachment nodes")
        out.axle_nodes = idx
        out.axle_points = model.nodes.xyz[idx].mean(axis=0)
    if axle_parts is not None:
        out.axle = model.mass_properties(axle_parts)
    return out


def node_indices(model: Model, spec: NodeSelection) -> np.ndarray:
    """Node indices from indices, ("set", SID) or a *SET_NODE title."""
    if isinstance(spec, str):
        for (kind, sid), rec in model.sets.items():
            if kind == "NODE" and str(rec.title or "").strip().lower() == spec.strip().lower():
                spec = ("set", sid)
                break
        else:
            raise KeyError(f"no *SET_NODE titled {spec!r}")
    if isinstance(spec, tuple) and len(spec) == 2 and spec[0] == "set":
        idx = model.node_index(model.set_members("NODE", int(spec[1])))
    else:
        idx = np.asarray(spec, np.int64).ravel()
    idx = np.asarray(idx, np.int64)
    if np.any(idx < 0) or np.any(idx >= len(model.nodes)):
        raise KeyError("a node of the selection is not in the model")
    return np.unique(idx)
