"""Where to put the interface: the structure behind it must stay elastic.

Every shell of a full run gets a *yield ratio*: its largest strain over
the run divided by its material's yield strain σy/E; above 1 it has
yielded. The strain is the larger of two measures: from the field states,
the largest relative length change of its four edges and two diagonals
between the first state and each later one (a membrane measure: pure
bending of a flat element is missed); and, where the run recorded it (a
crashlite run), its effective plastic strain εp at the end of the run, the
peak over its integration points and the run, counted as a strain of
σy/E + εp (the uniaxial total strain at that plastic strain).

``propose_interface`` scans candidate planes normal to the vehicle axis
from the front to the rear and proposes the foremost one behind which at
most a share ``allowed`` of the shells (solids and beams are not rated)
reach ``threshold`` times their yield strain: the paper's criterion (the
replaced structure stays elastic), with the most reduction; ``allowed``
forgives the odd element around a lumped mass or a spot weld. For every
candidate it reports that share, the largest and the 99th-percentile
ratio behind it, and the mass and the share of the elements the reduction
would replace: with the time step unchanged, the run time scales with the
elements kept, so the share replaced is the expected time saving.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..model.model import Model

_EDGES = ((0, 1), (1, 2), (2, 3), (3, 0), (0, 2), (1, 3))


@dataclass
class InterfaceProposal:
    x: float | None  # proposed interface position along the axis [length]; None: no candidate is elastic behind
    threshold: float
    allowed: float  # share of the shells behind allowed to reach the threshold
    candidates: list  # dicts: x, yielded_percent_behind, max/p99 yield ratio behind, replaced mass/elements %
    yield_ratio: np.ndarray  # (n_shells,) largest strain / yield strain of each shell
    notes: list = field(default_factory=list)

    def summary(self) -> dict:
        return {"proposed_x": self.x, "threshold": self.threshold, "allowed": self.allowed,
                "candidates": list(self.candidates),
                "yielded_shells": int((self.yield_ratio >= 1.0).sum()), "notes": list(self.notes)}


def shell_strain(x0: np.ndarray, states: np.ndarray, quads: np.ndarray) -> np.ndarray:
    """(n_shells,) largest |Δl/l| of edges and diagonals over the states.
    x0 (n, 3) initial, states (k, n, 3) coordinates, quads (m, 4) 0-based."""
    out = np.zeros(len(quads))
    for a, b in _EDGES:
        l0 = np.linalg.norm(x0[quads[:, b]] - x0[quads[:, a]], axis=1)
        ok = l0 > 0
        for xs in states:
            ln = np.linalg.norm(xs[quads[:, b]] - xs[quads[:, a]], axis=1)
            out[ok] = np.maximum(out[ok], np.abs(ln[ok] / l0[ok] - 1.0))
    return out


def _yield_strain(model: Model) -> np.ndarray:
    """(n_shells,) σy/E of each shell's material (inf where it has none: rigid, elastic)."""
    s = model.shells
    out = np.full(len(s), np.inf)
    for pid in np.unique(s.pid):
        part = model.parts.get(int(pid))
        mat = model.materials.get(part.get("mid")) if part is not None else None
        if mat is None or mat.keyword == "MAT_RIGID":
            continue
        e, sy = float(mat.get("e", 0.0) or 0.0), float(mat.get("sigy", 0.0) or 0.0)
        if e > 0 and sy > 0:
            out[s.pid == pid] = sy / e
    return out


def yield_ratio(model: Model, results) -> np.ndarray:
    """(n_shells,) largest strain over yield strain of every shell of
    ``model`` in the run ``results`` (a crashlite results folder with field
    states, nodes matched by ID)."""
    from ..verify.fields import load_states

    st = load_states(results, model)
    if st is None:
        raise ValueError(f"{results}: no field states (*DATABASE_BINARY_D3PLOT) to rate the strains")
    idx = {int(n): k for k, n in enumerate(st.ids)}
    missing = [int(n) for n in model.nodes.ids if int(n) not in idx]
    if missing:
        raise ValueError(f"{results}: {len(missing)} node(s) of the deck are not in the field states "
                         f"(e.g. {missing[:5]}): not a run of this deck")
    order = np.array([idx[int(n)] for n in model.nodes.ids])
    xs = st.x[:, order]
    ey = _yield_strain(model)
    ratio = shell_strain(xs[0], xs[1:], model.shells.nodes.astype(np.int64)) / ey
    eps = shell_plastic_strain(model, results)
    if eps is not None:
        plastic = eps > 0
        ratio[plastic] = np.maximum(ratio[plastic], 1.0 + eps[plastic] / ey[plastic])
    return ratio


def shell_plastic_strain(model: Model, results) -> np.ndarray | None:
    """(n_shells,) effective plastic strain of every shell of ``model`` at the
    end of the run in the crashlite results folder ``results`` (0 for rigid
    shells, matched by element ID), or None when the run did not record it."""
    path = Path(results) / "results.npz" if Path(results).is_dir() else Path(results)
    if not path.is_file():
        return None
    with np.load(path) as z:
        if "shell_plastic_strain" not in z.files or not len(z["shell_ids"]):
            return None
        ids, eps = z["shell_ids"], z["shell_plastic_strain"]
    from ..model.mesh import index_map

    k = index_map(ids)(model.shells.ids)
    return np.where(k >= 0, eps[np.maximum(k, 0)], 0.0)


def propose_interface(model: Model, results, threshold: float = 1.0, allowed: float = 0.01,
                      axis=(1.0, 0.0, 0.0), step: float | None = None,
                      ratio: np.ndarray | None = None) -> InterfaceProposal:
    """Candidate planes at the multiples of ``step`` (default: four element sizes) along
    ``axis`` over the model's length; the proposal (module docstring)."""
    from .cut import cut_behind
    from .massprops import element_moments, replaced_mass

    a = np.asarray(axis, float)
    a = a / np.linalg.norm(a)
    r = yield_ratio(model, results) if ratio is None else np.asarray(ratio, float)
    r = np.nan_to_num(r, nan=0.0, posinf=0.0)  # rigid and elastic materials do not yield
    xyz = model.nodes.xyz
    conn = model.shells.nodes.astype(np.int64)
    centre = xyz[conn].mean(axis=1) @ a
    size = float(np.median(np.linalg.norm(xyz[conn[:, 2]] - xyz[conn[:, 0]], axis=1))) / np.sqrt(2.0)
    step = 4.0 * size if step is None else float(step)
    lo, hi = float(centre.min()), float(centre.max())
    full_mass = model.mass_properties().mass
    n_el = sum(len(getattr(model, t)) for t in ("shells", "solids", "beams", "discretes"))
    moments = element_moments(model)  # once: every candidate sums its own share of them
    out, proposed = [], None
    first = np.ceil(hi / step) * step - step  # candidates on multiples of the step
    for x in np.arange(first, lo, -step):
        behind = centre < x
        share = float(np.mean(r[behind] >= threshold)) if behind.any() else 0.0
        cut = cut_behind(model, x=float(x), axis=a)
        n_rep = sum(int(m.sum()) for m in cut.replaced.values())
        rep = replaced_mass(cut, moments=moments).structure.mass
        out.append({"x": float(x), "yielded_percent_behind": 100.0 * share,
                    "max_yield_ratio_behind": float(r[behind].max()) if behind.any() else 0.0,
                    "p99_yield_ratio_behind": float(np.percentile(r[behind], 99)) if behind.any() else 0.0,
                    "replaced_mass_percent": 100.0 * rep / full_mass,
                    "replaced_elements_percent": 100.0 * n_rep / max(n_el, 1)})
        if proposed is None and share <= allowed:
            proposed = float(x)
    notes = []
    if proposed is None:
        notes.append(f"behind every candidate plane more than {100 * allowed:g} % of the shells reach "
                     f"{threshold:g} x their yield strain: the structure does not stay elastic anywhere")
    return InterfaceProposal(proposed, float(threshold), float(allowed), out, r, notes)


PASSENGER_CELL = ("A-pillar", "door sill", "floor", "tunnel", "door", "roof", "B-pillars", "rear floor")


def _strain_and_area(model: Model, results) -> tuple[np.ndarray, np.ndarray]:
    """(n_shells,) plastic strain at the end of the run and initial area of every shell."""
    from ..solver.shells import element_areas

    eps = shell_plastic_strain(model, results)
    if eps is None:
        raise ValueError(f"{results}: the run did not record the shells' plastic strain (a crashlite run does)")
    s = model.shells
    tri = (s.nodes[:, 3] == s.nodes[:, 2]).astype(np.int8)
    return eps, element_areas(model.nodes.xyz, s.nodes.astype(np.int64), tri)


def _yielded_percent(eps: np.ndarray, area: np.ndarray, limit: float) -> float:
    return 100.0 * float(area[eps > limit].sum() / area.sum()) if area.sum() > 0 else 0.0


def part_plastic_strain(model: Model, results, yield_strain: float = 0.002, _ea=None) -> dict:
    """Effective plastic strain of every shell part at the end of a
    crashlite run (``shell_plastic_strain``): part title -> largest, 95th
    percentile, area-weighted mean and the share of its area beyond
    ``yield_strain`` (0.2 %: the offset that defines a proof stress)."""
    eps, area = _ea if _ea is not None else _strain_and_area(model, results)
    pid_of = model.shells.pid
    out = {}
    for pid in np.unique(pid_of):
        m = pid_of == pid
        e, a = eps[m], area[m]
        title = str(model.parts.get(int(pid), {}).get("heading", "") or f"part {int(pid)}")
        out[title] = {"part": int(pid), "max": float(e.max()), "p95": float(np.percentile(e, 95)),
                      "mean": float((e * a).sum() / a.sum()) if a.sum() > 0 else 0.0,
                      "yielded_area_percent": _yielded_percent(e, a, yield_strain), "shells": int(m.sum())}
    return out


def assembly_parts(model: Model, names=PASSENGER_CELL) -> np.ndarray:
    """Part IDs of the assemblies ``names`` (their sides included) from the
    part sets titled "assembly <name>" (as the generic car writes them)."""
    want = {n.strip().lower() for n in names}
    out = set()
    for (kind, sid), rec in model.sets.items():
        title = str(rec.title or "").strip().lower()
        if kind != "PART" or not title.startswith("assembly "):
            continue
        name = title[len("assembly "):]
        for side in (" left", " right"):
            if name.endswith(side):
                name = name[: -len(side)]
        if name in want:
            out.update(int(p) for p in model.set_members("PART", sid))
    if not out:
        raise KeyError(f"no part set titled 'assembly <name>' for any of {sorted(want)}")
    return np.array(sorted(out), np.int64)


def cell_plastic_strain(model: Model, results, names=PASSENGER_CELL, yield_strain: float = 0.002) -> dict:
    """The passenger cell's plastic strain at the end of a run (issue 7's
    "stays nearly elastic"): over all shells of the assemblies ``names``,
    the largest, 95th and 99th percentile plastic strain, the share of
    their area beyond ``yield_strain``, and the parts by their largest."""
    eps, area = _strain_and_area(model, results)
    pids = assembly_parts(model, names)
    m = np.isin(model.shells.pid, pids)
    e = eps[m]
    parts = part_plastic_strain(model, results, yield_strain, _ea=(eps, area))
    cell = {k: v for k, v in parts.items() if v["part"] in set(pids.tolist())}
    return {"shells": int(m.sum()), "max": float(e.max()), "p95": float(np.percentile(e, 95)),
            "p99": float(np.percentile(e, 99)), "yield_strain": yield_strain,
            "yielded_area_percent": _yielded_percent(e, area[m], yield_strain),
            "parts": dict(sorted(cell.items(), key=lambda kv: -kv[1]["max"]))}
