"""Step 1 of the simplified vehicle: load paths through the interface.

The force through the interface cross section of each assembly (secforc of
a crashlite run, an LS-DYNA ASCII folder or a binout, through
``crashlite.results.load``) is reduced to its axial component; its time
integral, the impulse I(t) = ∫₀ᵗ F dt (trapezoidal rule on the output
states), gives the load path of the assembly; the share of assembly i is

    share_i = max_t I_i(t) / Σ_j max_t I_j(t)

(the paper's figures 10–12). The impulse starts at 0, so its maximum is
never negative: an assembly that only pulls gets share 0.

Sign convention. crashlite and LS-DYNA (secforc) report the internal force
of the cut elements at their corners on the side the section normal points
to: F·n > 0 in tension, F·n < 0 in compression, whichever way the normal
points (LS-DYNA R10.1 on a compressed solid: tests/parity). The axial force
used here is

    F_ax = -(F·a) · sign(n·a)

with ``a`` the unit vehicle axis (default +x, the driving direction) and
``n`` the section normal (taken from the deck when given, else assumed
along ``a``): positive when the assembly is compressed along the vehicle
axis, i.e. when the front structure pushes it rearwards.

Units are those of the run (mm–t–s: N and N·s); plots convert only what
their scale arguments say.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

if TYPE_CHECKING:
    from ...model.model import Model
    from ...results.history import History


@dataclass
class LoadPaths:
    """Axial force and impulse through the interface, per assembly, of one load case."""

    names: tuple  # (n,) assembly names
    section_ids: np.ndarray  # (n,) int64 cross-section IDs (0: not from a deck section)
    time: np.ndarray  # (n_states,) float64 [time]
    force: np.ndarray  # (n_states, n) float64 axial force, compression positive [force]
    impulse: np.ndarray  # (n_states, n) float64 ∫ force dt from the first state [force·time]
    load_case: str = ""
    notes: list = field(default_factory=list)  # what the reduction assumed or left out

    @property
    def max_impulse(self) -> np.ndarray:
        """(n,) maximum impulse of each assembly over the run [force·time] (≥ 0)."""
        if not len(self.time):
            return np.zeros(len(self.names))
        return np.maximum(self.impulse.max(axis=0), 0.0)

    @property
    def max_force(self) -> np.ndarray:
        """(n,) largest compressive force of each assembly [force]."""
        if not len(self.time):
            return np.zeros(len(self.names))
        return np.maximum(self.force.max(axis=0), 0.0)

    @property
    def share(self) -> np.ndarray:
        """(n,) load-path shares, max impulse over the sum of max impulses (sum 1)."""
        m = self.max_impulse
        total = m.sum()
        if not total > 0:
            raise ValueError(f"load case {self.load_case!r}: no assembly carries a compressive impulse")
        return m / total

    def shares(self) -> dict:
        """Assembly name -> share (fraction)."""
        return dict(zip(self.names, self.share.tolist()))

    def table(self) -> list[dict]:
        """One row per assembly: name, section, peak force, max impulse, share [%]."""
        s = self.share
        return [
            {
                "assembly": n,
                "section": int(c),
                "max_force": float(f),
                "max_impulse": float(i),
                "share_percent": float(100.0 * p),
            }
            for n, c, f, i, p in zip(self.names, self.section_ids, self.max_force, self.max_impulse, s)
        ]

    def to_dict(self) -> dict:
        return {"load_case": self.load_case, "assemblies": self.table(), "notes": list(self.notes)}


def cumulative_impulse(time: ArrayLike, force: ArrayLike) -> np.ndarray:
    """∫₀ᵗ F dt at every state by the trapezoidal rule: ``time`` (n_states,),
    ``force`` (n_states, ...) -> same shape as ``force``, 0 at the first state."""
    t = np.asarray(time, float)
    f = np.asarray(force, float)
    if f.shape[:1] != t.shape:
        raise ValueError(f"force has {f.shape[0] if f.ndim else 0} states, time {len(t)}")
    if len(t) and np.any(np.diff(t) < 0):
        raise ValueError("time must not decrease")
    out = np.zeros_like(f)
    if len(t) > 1:
        dt = np.diff(t).reshape((-1,) + (1,) * (f.ndim - 1))
        out[1:] = np.cumsum(0.5 * dt * (f[1:] + f[:-1]), axis=0)
    return out


def axial_force(
    force_xyz: ArrayLike, axis: ArrayLike = (1.0, 0.0, 0.0), normals: ArrayLike | None = None
) -> np.ndarray:
    """Axial force, compression positive (module docstring): ``force_xyz``
    (n_states, n, 3) section forces, ``axis`` the vehicle axis, ``normals``
    (n, 3) section normals or None (taken along ``axis``)."""
    f = np.asarray(force_xyz, float)
    a = _unit(axis, "axis")
    fa = -(f @ a)  # secforc: tension along the normal positive
    if normals is None:
        return fa
    n = np.asarray(normals, float).reshape(-1, 3)
    if len(n) != f.shape[1]:
        raise ValueError(f"{len(n)} section normals for {f.shape[1]} sections")
    side = np.sign(n @ a)
    if np.any(side == 0):
        raise ValueError("a section normal is perpendicular to the vehicle axis")
    return fa * side


def load_paths(
    time: ArrayLike,
    force: ArrayLike,
    names: Sequence[str],
    section_ids: ArrayLike | None = None,
    load_case: str = "",
    notes: Iterable[str] | None = None,
) -> LoadPaths:
    """LoadPaths of axial forces already reduced: ``force`` (n_states, n)
    compression positive, ``names`` the n assemblies."""
    t = np.asarray(time, float)
    f = np.asarray(force, float)
    if f.ndim != 2 or f.shape[1] != len(names):
        raise ValueError(f"force must be (n_states, {len(names)}), got {f.shape}")
    ids = np.zeros(len(names), np.int64) if section_ids is None else np.asarray(section_ids, np.int64)
    return LoadPaths(tuple(names), ids, t, f, cumulative_impulse(t, f), load_case, list(notes or []))


def deck_sections(model: Model) -> dict:
    """The cross sections of a deck: title (or ``section <ID>``) -> (ID,
    unit normal (3,) or None). Planes give the normal from (XCT, YCT, ZCT)
    to (XCH, YCH, ZCH); set sections have none."""
    out = {}
    for rec in model.find("DATABASE_CROSS_SECTION"):
        csid = int(rec.get("csid", 0) or 0)
        title = str(rec.get("title", "") or "").strip() or f"section {csid}"
        normal = None
        if rec.keyword == "DATABASE_CROSS_SECTION_PLANE":
            d = np.array([float(rec.get(f"{a}ch", 0.0) or 0.0) - float(rec.get(f"{a}ct", 0.0) or 0.0) for a in "xyz"])
            normal = d / np.linalg.norm(d) if np.linalg.norm(d) > 0 else None
        if title in out:
            raise ValueError(f"two cross sections titled {title!r} (IDs {out[title][0]} and {csid})")
        out[title] = (csid, normal)
    return out


def from_history(
    history: History | Path | str,
    sections: dict[str, int] | None = None,
    axis: ArrayLike = (1.0, 0.0, 0.0),
    normals: dict[int, np.ndarray | None] | None = None,
    load_case: str = "",
    t_end: float | None = None,
) -> LoadPaths:
    """LoadPaths from the secforc of a run.

    history   a ``crashlite.results.History``, or a path for ``crashlite.results.load``
              (crashlite results folder, LS-DYNA ASCII folder or secforc file, binout)
    sections  assembly name -> cross-section ID; None: every section of the
              run, named ``section <ID>``
    axis      vehicle axis (3,), the driving direction
    normals   section ID -> normal (3,), or None (normals along ``axis``)
    t_end     ignore states after this time [time] (e.g. the rebound)
    """
    if not hasattr(history, "read"):
        from ...results import load

        history = load(history)
    t = np.asarray(history.read("secforc", "time"), float)
    ids = np.asarray(history.read("secforc", "ids")).astype(np.int64).ravel()
    f = np.stack(
        [np.asarray(history.read("secforc", f"{c}_force"), float).reshape(len(t), len(ids)) for c in "xyz"], axis=2
    )
    if sections is None:
        sections = {f"section {int(i)}": int(i) for i in ids}
    names = list(sections)
    where = {int(i): k for k, i in enumerate(ids)}
    missing = [f"{n} ({int(sections[n])})" for n in names if int(sections[n]) not in where]
    if missing:
        raise KeyError(
            f"{getattr(history, 'source', 'run')}: no section force for {', '.join(missing)} "
            f"(sections in the run: {sorted(where)})"
        )
    cols = [where[int(sections[n])] for n in names]
    notes = []
    nrm = None
    if normals is not None:
        nrm = np.array(
            [
                normals.get(int(sections[n])) if normals.get(int(sections[n])) is not None else _unit(axis, "axis")
                for n in names
            ],
            float,
        )
    else:
        notes.append("section normals not given: taken along the vehicle axis")
    keep = np.ones(len(t), bool) if t_end is None else t <= t_end
    fa = axial_force(f[keep][:, cols], axis, nrm)
    return load_paths(t[keep], fa, names, [int(sections[n]) for n in names], load_case, notes)


def from_run(
    results: History | Path | str,
    deck: Model | Path | str | None = None,
    sections: dict[str, int] | None = None,
    axis: ArrayLike = (1.0, 0.0, 0.0),
    load_case: str = "",
    t_end: float | None = None,
) -> LoadPaths:
    """LoadPaths of a run with the section titles and normals of its deck.

    results   results folder or file (``crashlite.results.load``) or a History
    deck      the Model or deck path that defines the sections (titles name
              the assemblies, planes give the normals); None: ``sections``
    sections  assembly name -> section ID (a subset of the deck's, or all
              of them when there is no deck)
    """
    normals = None
    if deck is not None:
        if isinstance(deck, (str, Path)):
            from ...keyword.reader import read_deck

            deck = read_deck(deck)
        found = deck_sections(deck)
        if sections is None:
            sections = {name: csid for name, (csid, _) in found.items()}
        normals = {csid: n for csid, n in found.values()}
    return from_history(results, sections, axis, normals, load_case, t_end)


def combined_shares(paths: Iterable[LoadPaths], weights: ArrayLike | None = None) -> dict:
    """One set of shares for several load cases: the weighted mean of their
    shares (equal weights by default) over the assemblies all of them have,
    and per load case the largest absolute difference from it.

    Returns {"shares": {name: share}, "deviation": {load case: max |Δshare|}}.
    """
    paths = list(paths)
    if not paths:
        raise ValueError("no load cases")
    names = [n for n in paths[0].names if all(n in p.names for p in paths[1:])]
    w = np.ones(len(paths)) if weights is None else np.asarray(weights, float)
    if len(w) != len(paths) or np.any(w < 0) or not w.sum() > 0:
        raise ValueError("weights: one non-negative weight per load case, not all zero")
    per = np.array([[p.shares()[n] for n in names] for p in paths])
    per = per / per.sum(axis=1, keepdims=True)
    mean = (w / w.sum()) @ per
    dev = {p.load_case or f"case {k + 1}": float(np.abs(per[k] - mean).max()) for k, p in enumerate(paths)}
    return {"shares": dict(zip(names, mean.tolist())), "deviation": dev}


def _unit(v, name: str) -> np.ndarray:
    a = np.asarray(v, float).reshape(3)
    n = np.linalg.norm(a)
    if not n > 0:
        raise ValueError(f"{name} has zero length")
    return a / n


# --- figures (the paper's figures 10–12) -----------------------------------------------------------


def _curves(
    lp: LoadPaths, data: np.ndarray, ylabel: str, title: str, time_scale: float, time_unit: str, scale: float
) -> bytes:
    from ...report.plots import _pyplot, png

    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 3.6))
    cmap = plt.get_cmap("tab20")
    for k, name in enumerate(lp.names):
        ax.plot(lp.time * time_scale, data[:, k] * scale, lw=1.2, color=cmap(k % 20), label=name)
    ax.axhline(0.0, color="0.5", lw=0.5)
    ax.set_title(title + (f" ({lp.load_case})" if lp.load_case else ""), fontsize=9)
    ax.set_xlabel(f"time [{time_unit}]", fontsize=8)
    ax.set_ylabel(ylabel, fontsize=8)
    ax.tick_params(labelsize=7)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=6, ncol=2, loc="best")
    return png(fig)


def plot_forces(
    lp: LoadPaths, time_scale: float = 1e3, time_unit: str = "ms", force_scale: float = 1e-3, force_unit: str = "kN"
) -> bytes:
    """Figure 10: axial force (compression positive) of every assembly
    against time, PNG bytes. Defaults convert mm–t–s (s, N) to ms and kN."""
    return _curves(
        lp, lp.force, f"axial force [{force_unit}]", "force through the interface", time_scale, time_unit, force_scale
    )


def plot_impulses(
    lp: LoadPaths, time_scale: float = 1e3, time_unit: str = "ms", impulse_scale: float = 1.0, impulse_unit: str = "N·s"
) -> bytes:
    """Figure 11: impulse ∫F dt of every assembly against time, PNG bytes."""
    return _curves(
        lp,
        lp.impulse,
        f"impulse [{impulse_unit}]",
        "impulse through the interface",
        time_scale,
        time_unit,
        impulse_scale,
    )


def plot_shares(paths: LoadPaths | Iterable[LoadPaths]) -> bytes:
    """Figure 12: load-path shares [%] per assembly, one bar per load case
    (a LoadPaths or a list of them), PNG bytes."""
    from ...report.plots import _pyplot, png

    paths = [paths] if isinstance(paths, LoadPaths) else list(paths)
    names = []
    for p in paths:
        names += [n for n in p.names if n not in names]
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 3.6))
    width = 0.8 / len(paths)
    x = np.arange(len(names))
    for k, p in enumerate(paths):
        s = p.shares()
        vals = np.array([100.0 * s.get(n, 0.0) for n in names])
        bars = ax.bar(x + (k - 0.5 * (len(paths) - 1)) * width, vals, width, label=p.load_case or f"case {k + 1}")
        for b, v in zip(bars, vals):
            if v > 0:
                ax.text(b.get_x() + b.get_width() / 2, v, f"{v:.1f}", ha="center", va="bottom", fontsize=5)
    ax.set_xticks(x)
    ax.set_xticklabels(names, rotation=45, ha="right", fontsize=7)
    ax.set_ylabel("share of the max impulse [%]", fontsize=8)
    ax.set_title("load-path distribution in the interface", fontsize=9)
    ax.tick_params(labelsize=7)
    ax.grid(True, axis="y", lw=0.3)
    ax.legend(fontsize=7)
    return png(fig)
