"""Where to put the interface: the structure behind it must stay elastic.

The springs of the surrogate are elastic: whatever the replaced structure
would dissipate in the crash is lost, and whatever of it would fold
changes the load paths. ``propose_interface`` therefore rates every shell
of a full run by two measures:

- its effective plastic strain εp at the end of the run, the peak over its
  integration points (a crashlite run records it). Where a run lacks it,
  an estimate from the field states: the largest relative length change of
  its four edges and two diagonals between the first state and any later
  one, less the yield strain σy/E (a membrane measure: the bending of a
  flat element is missed);
- the internal energy it holds at the end of the run (a crashlite run
  records it per element: plastic work plus what elastic energy is left);
  where a run lacks it, the plastic work σy·εp·V, a lower bound.

It scans candidate planes normal to the vehicle axis from the front to the
rear and proposes the foremost one behind which (a) the shells hold at most
a share ``energy`` of the energy all shells absorbed and (b) at most a
share ``allowed`` of the shell area reaches the plastic strain ``strain``:
the paper's criterion (the replaced structure stays elastic) with the most
reduction. (a) is what the reduction loses; (b) keeps a plane from being
proposed ahead of a part that folds with little energy. Neither is
upset by thin skins that yield a little while they ring, nor by the odd
element around a lumped mass or a spot weld, which a criterion on every
element yielding is (a car's door skins and floor all yield somewhere).

For every candidate it reports both shares, the largest and the 99th
percentile plastic strain behind it, the parts holding most of the energy
behind it, and the mass and the share of the elements the reduction would
replace: with the time step unchanged, the run time scales with the
elements kept, so the share replaced is the expected time saving. Where
the run has field states, also how far the cut's nodes bend along the axis
out of the rigid motion that best fits them (largest value and largest
root mean square over the run): elastic as the structure behind may be, a
rigid interface holds the cut flat, and the kept structure's deformation
(the firewall's intrusion) cannot follow the full model's closer than that.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from ...model.model import Model

_EDGES = ((0, 1), (1, 2), (2, 3), (3, 0), (0, 2), (1, 3))


@dataclass
class InterfaceProposal:
    x: float | None  # proposed interface position along the axis [length]; None: no candidate is elastic behind
    strain: float  # plastic strain that counts as strained
    allowed: float  # share of the shell area behind allowed to reach it
    energy: float  # share of the shells' absorbed energy allowed behind
    candidates: list  # dicts: x, energy_behind_percent, strained_area_percent_behind, ... (module docstring)
    plastic_strain: np.ndarray  # (n_shells,) effective plastic strain of each shell
    absorbed: np.ndarray  # (n_shells,) energy each shell holds at the end of the run [energy]
    measured: dict = field(default_factory=dict)  # how each measure was obtained: "recorded" or "estimated"
    notes: list = field(default_factory=list)

    def summary(self) -> dict:
        return {
            "proposed_x": self.x,
            "criteria": {
                "plastic_strain": self.strain,
                "strained_area_allowed_percent": 100.0 * self.allowed,
                "energy_allowed_percent": 100.0 * self.energy,
            },
            "measures": dict(self.measured),
            "candidates": list(self.candidates),
            "shells_beyond_strain": int((self.plastic_strain >= self.strain).sum()),
            "notes": list(self.notes),
        }


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


def _shell_material(model: Model) -> tuple[np.ndarray, np.ndarray]:
    """(n_shells,) σy/E and σy of each shell's material (inf and 0 where it
    has none: rigid, elastic)."""
    s = model.shells
    ey, sy = np.full(len(s), np.inf), np.zeros(len(s))
    for pid in np.unique(s.pid):
        part = model.parts.get(int(pid))
        mat = model.materials.get(part.get("mid")) if part is not None else None
        if mat is None or mat.keyword == "MAT_RIGID":
            continue
        e, y = float(mat.get("e", 0.0) or 0.0), float(mat.get("sigy", 0.0) or 0.0)
        if e > 0 and y > 0:
            ey[s.pid == pid], sy[s.pid == pid] = y / e, y
    return ey, sy


def _aligned_states(model: Model, results) -> np.ndarray | None:
    """(m, n_nodes, 3) field states of ``results`` in the deck's node order
    (nodes matched by ID), the first the initial one; None without states."""
    from ...verify.fields import load_states

    st = load_states(results, model) if results is not None else None
    if st is None:
        return None
    idx = {int(n): k for k, n in enumerate(st.ids)}
    missing = [int(n) for n in model.nodes.ids if int(n) not in idx]
    if missing:
        raise ValueError(
            f"{results}: {len(missing)} node(s) of the deck are not in the field states "
            f"(e.g. {missing[:5]}): not a run of this deck"
        )
    return st.x[:, np.array([idx[int(n)] for n in model.nodes.ids])]


def _membrane_strain(model: Model, results, xs=None) -> np.ndarray:
    """(n_shells,) largest edge or diagonal strain over the field states of
    ``results`` (nodes matched by ID; ``xs``: those already aligned)."""
    xs = _aligned_states(model, results) if xs is None else xs
    if xs is None:
        raise ValueError(
            f"{results}: neither plastic strains nor field states (*DATABASE_BINARY_D3PLOT) to rate the shells by"
        )
    return shell_strain(xs[0], xs[1:], model.shells.nodes.astype(np.int64))


def _shell_field(model: Model, results, name: str) -> np.ndarray | None:
    """(n_shells,) the per-shell array ``name`` of a crashlite results.npz,
    rows matched by element ID (0 for shells it lacks: rigid ones), or None
    when the run did not record it."""
    path = Path(results) / "results.npz" if Path(results).is_dir() else Path(results)
    if not path.is_file():
        return None
    with np.load(path) as z:
        if name not in z.files or "shell_ids" not in z.files or not len(z["shell_ids"]):
            return None
        ids, values = z["shell_ids"], z[name]
    from ...model.mesh import index_map

    k = index_map(ids)(model.shells.ids)
    return np.where(k >= 0, values[np.maximum(k, 0)], 0.0)


def shell_plastic_strain(model: Model, results: Path | str) -> np.ndarray | None:
    """(n_shells,) effective plastic strain of every shell of ``model`` at the
    end of the run in the crashlite results folder ``results`` (0 for rigid
    shells, matched by element ID), or None when the run did not record it."""
    return _shell_field(model, results, "shell_plastic_strain")


def shell_areas(model: Model) -> np.ndarray:
    """(n_shells,) initial area of every shell (degenerate quads as triangles)."""
    from ...solver.shells import element_areas

    conn = model.shells.nodes.astype(np.int64)
    return element_areas(model.nodes.xyz, conn, (conn[:, 3] == conn[:, 2]).astype(np.int8))


def shell_volumes(model: Model) -> np.ndarray:
    """(n_shells,) initial area x section thickness of every shell."""
    from ...solver.tied import shell_thickness

    return shell_areas(model) * shell_thickness(model)


def shell_measures(
    model: Model, results: Path | str, states: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, dict]:
    """(plastic strain, absorbed energy, how each was obtained) of every
    shell in the run ``results`` (module docstring); ``states``: its field
    states already in the deck's node order (``_aligned_states``)."""
    ey, sy = _shell_material(model)
    eps = shell_plastic_strain(model, results)
    how = {"plastic_strain": "recorded", "energy": "recorded"}
    if eps is None:
        eps = np.maximum(_membrane_strain(model, results, states) - ey, 0.0)  # inf yield strain: 0
        how["plastic_strain"] = "estimated from the field states' membrane strain"
    energy = _shell_field(model, results, "shell_internal_energy")
    if energy is None:
        energy = sy * eps * shell_volumes(model)
        how["energy"] = "estimated: plastic work σy·εp·V (a lower bound)"
    return eps, energy, how


def propose_interface(
    model: Model,
    results: Path | str,
    strain: float = 0.01,
    allowed: float = 0.01,
    energy: float = 0.03,
    axis: ArrayLike = (1.0, 0.0, 0.0),
    step: float | None = None,
    also: Iterable[float] = (),
    measures: tuple[ArrayLike, ArrayLike] | None = None,
) -> InterfaceProposal:
    """Candidate planes at the multiples of ``step`` (default: four element
    sizes) along ``axis`` over the model's length, and at the positions
    ``also`` (e.g. the interface in use); the proposal (module docstring).
    ``measures``: (plastic strain, absorbed energy) per shell instead of
    reading them from ``results``."""
    from ..steps.cut import cut_behind
    from ..steps.massprops import element_moments, replaced_mass
    from .rigidfit import warping_history

    a = np.asarray(axis, float)
    a = a / np.linalg.norm(a)
    xs = _aligned_states(model, results)  # read once: the estimated measures and the cut's bending
    if measures is None:
        eps, absorbed, how = shell_measures(model, results, xs)
    else:
        eps, absorbed = (np.asarray(m, float) for m in measures)
        how = {"plastic_strain": "given", "energy": "given"}
    xyz = model.nodes.xyz
    conn = model.shells.nodes.astype(np.int64)
    area = shell_areas(model)
    centre = xyz[conn].mean(axis=1) @ a
    size = float(np.median(np.linalg.norm(xyz[conn[:, 2]] - xyz[conn[:, 0]], axis=1))) / np.sqrt(2.0)
    step = 4.0 * size if step is None else float(step)
    lo, hi = float(centre.min()), float(centre.max())
    full_mass = model.mass_properties().mass
    n_el = sum(len(getattr(model, t)) for t in ("shells", "solids", "beams", "discretes"))
    total = float(absorbed.sum())
    titles = np.array(
        [str(model.parts.get(int(p), {}).get("heading", "") or f"part {int(p)}") for p in model.shells.pid]
    )
    moments = element_moments(model)  # once: every candidate sums its own share of them
    out, proposed = [], None
    first = np.ceil(hi / step) * step - step  # candidates on multiples of the step
    planes = np.concatenate([np.arange(first, lo, -step), [float(x) for x in also if lo < float(x) < hi]])
    for x in np.unique(planes)[::-1]:
        behind = centre < x
        cut = cut_behind(model, x=float(x), axis=a)
        n_rep = sum(int(m.sum()) for m in cut.replaced.values())
        e_share = float(absorbed[behind].sum()) / total if total > 0 else 0.0
        a_share = float(area[behind & (eps >= strain)].sum() / area[behind].sum()) if behind.any() else 0.0
        parts = {}
        for t in np.unique(titles[behind]):
            parts[str(t)] = float(absorbed[behind & (titles == t)].sum())
        top = sorted(parts.items(), key=lambda kv: -kv[1])[:3]
        out.append(
            {
                "x": float(x),
                "energy_behind_percent": 100.0 * e_share,
                "strained_area_percent_behind": 100.0 * a_share,
                "max_plastic_strain_behind": float(eps[behind].max()) if behind.any() else 0.0,
                "p99_plastic_strain_behind": float(np.percentile(eps[behind], 99)) if behind.any() else 0.0,
                "most_energy_behind": {t: 100.0 * v / total for t, v in top if total > 0},
                "replaced_mass_percent": 100.0 * replaced_mass(cut, moments=moments).structure.mass / full_mass,
                "replaced_elements_percent": 100.0 * n_rep / max(n_el, 1),
            }
        )
        if xs is not None:  # how far the cut bends out of a rigid motion: what a rigid interface cannot follow
            wh = warping_history(xs[1:], xs[0], cut.interface_nodes, a)
            out[-1].update(interface_warping_max=wh["max"], interface_warping_rms=wh["rms"])
        if proposed is None and e_share <= energy and a_share <= allowed:
            proposed = float(x)
    notes = [f"{k.replace('_', ' ')}: {v}" for k, v in how.items() if v != "recorded"]
    if proposed is None:
        notes.append(
            f"behind every candidate plane the shells hold more than {100 * energy:g} % of the absorbed "
            f"energy or more than {100 * allowed:g} % of their area reaches {100 * strain:g} % plastic "
            "strain: the structure does not stay elastic anywhere"
        )
    return InterfaceProposal(proposed, float(strain), float(allowed), float(energy), out, eps, absorbed, how, notes)


PASSENGER_CELL = ("A-pillar", "door sill", "floor", "tunnel", "door", "roof", "B-pillars", "rear floor")


def _strain_and_area(model: Model, results) -> tuple[np.ndarray, np.ndarray]:
    """(n_shells,) plastic strain at the end of the run and initial area of every shell."""
    eps = shell_plastic_strain(model, results)
    if eps is None:
        raise ValueError(f"{results}: the run did not record the shells' plastic strain (a crashlite run does)")
    return eps, shell_areas(model)


def _yielded_percent(eps: np.ndarray, area: np.ndarray, limit: float) -> float:
    return 100.0 * float(area[eps > limit].sum() / area.sum()) if area.sum() > 0 else 0.0


def part_plastic_strain(
    model: Model, results: Path | str, yield_strain: float = 0.002, _ea: tuple[np.ndarray, np.ndarray] | None = None
) -> dict:
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
        out[title] = {
            "part": int(pid),
            "max": float(e.max()),
            "p95": float(np.percentile(e, 95)),
            "mean": float((e * a).sum() / a.sum()) if a.sum() > 0 else 0.0,
            "yielded_area_percent": _yielded_percent(e, a, yield_strain),
            "shells": int(m.sum()),
        }
    return out


def assembly_parts(model: Model, names: Iterable[str] = PASSENGER_CELL) -> np.ndarray:
    """Part IDs of the assemblies ``names`` (their sides included) from the
    part sets titled "assembly <name>" (as the generic car writes them)."""
    want = {n.strip().lower() for n in names}
    out = set()
    for (kind, sid), rec in model.sets.items():
        title = str(rec.title or "").strip().lower()
        if kind != "PART" or not title.startswith("assembly "):
            continue
        name = title[len("assembly ") :]
        for side in (" left", " right"):
            if name.endswith(side):
                name = name[: -len(side)]
        if name in want:
            out.update(int(p) for p in model.set_members("PART", sid))
    if not out:
        raise KeyError(f"no part set titled 'assembly <name>' for any of {sorted(want)}")
    return np.array(sorted(out), np.int64)


def cell_plastic_strain(
    model: Model, results: Path | str, names: Iterable[str] = PASSENGER_CELL, yield_strain: float = 0.002
) -> dict:
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
    return {
        "shells": int(m.sum()),
        "max": float(e.max()),
        "p95": float(np.percentile(e, 95)),
        "p99": float(np.percentile(e, 99)),
        "yield_strain": yield_strain,
        "yielded_area_percent": _yielded_percent(e, area[m], yield_strain),
        "parts": dict(sorted(cell.items(), key=lambda kv: -kv[1]["max"])),
    }
