"""Field states of runs and their node-by-node comparison (e.g. firewall
intrusion): displacement difference field on the nodes both runs have."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from .errors import CompareError

if TYPE_CHECKING:
    from ..model.model import Model
    from ..results.history import History

_AXES = {"x": 0, "y": 1, "z": 2}


@dataclass
class FieldStates:
    """Coordinates of all nodes at the field-state times of a run.

    time (n_f,) [time]; x (n_f, n_nodes, 3) [length], state 0 the initial
    geometry; ids (n_nodes,) int64 deck node IDs or None when unknown;
    cells: connectivity rows (0-based node indices) for pictures, empty
    when unknown.
    """

    time: np.ndarray
    x: np.ndarray
    ids: np.ndarray | None = None
    cells: list = field(default_factory=list)
    source: str = ""

    def at(self, t: float) -> np.ndarray:
        """Coordinates (n_nodes, 3) at time t, linear between states."""
        if not self.time[0] - 1e-12 <= t <= self.time[-1] * (1 + 1e-9) + 1e-12:
            raise ValueError(
                f"{self.source}: time {t:.6g} is outside the field states [{self.time[0]:.6g}, {self.time[-1]:.6g}]"
            )
        k = int(np.clip(np.searchsorted(self.time, t), 1, len(self.time) - 1)) if len(self.time) > 1 else 0
        if len(self.time) == 1:
            return self.x[0]
        t0, t1 = self.time[k - 1], self.time[k]
        w = 0.0 if t1 == t0 else min(max((t - t0) / (t1 - t0), 0.0), 1.0)
        return (1 - w) * self.x[k - 1] + w * self.x[k]


def load_states(path: Path | str, deck: Path | str | Model | None = None) -> FieldStates | None:
    """Field states of a crashlite results folder (``states_time``,
    ``states_x`` of results.npz; cells from its states/ VTK files); node IDs
    from results.npz (``node_ids``) or, when absent, from ``deck`` (path or
    Model) with as many nodes. A folder without results.npz but with an
    LS-DYNA d3plot (an LS-DYNA run): its states through lasso-python. None
    when the run wrote no field states."""
    p = Path(path)
    npz = p / "results.npz" if p.is_dir() else p
    if not npz.is_file():
        return _d3plot_states(p)
    with np.load(npz) as z:
        if "states_time" not in z.files or len(z["states_time"]) == 0:
            return None
        t, x = np.array(z["states_time"], float), np.array(z["states_x"], float)
        ids = np.array(z["node_ids"], np.int64) if "node_ids" in z.files else None
    if ids is None and deck is not None:
        from .. import read_deck

        model = deck if hasattr(deck, "nodes") else read_deck(deck)
        if len(model.nodes.ids) != x.shape[1]:
            raise CompareError(
                f"{deck}: {len(model.nodes.ids)} nodes, but {p} holds states of {x.shape[1]}: not the deck of this run"
            )
        ids = np.asarray(model.nodes.ids, np.int64)
    vtk = npz.parent / "states" / "state_0000.vtk"
    cells = read_cells(vtk) if vtk.is_file() else []
    return FieldStates(t, x, ids, cells, str(p))


def _d3plot_states(p: Path) -> FieldStates | None:
    """Field states of an LS-DYNA d3plot family (LS-DYNA's run, or a
    crashlite run kept without its results.npz), through lasso-python."""
    from ..results.d3plot import read_states

    got = read_states(p)  # None without a d3plot
    if got is None or len(got[0]) == 0:
        return None
    t, x, ids, cells = got
    return FieldStates(t, x, ids, cells, f"{p} (d3plot)")


def history_states(history: History, deck: Path | str | Model | None = None) -> FieldStates | None:
    """Field states of the history nodes of a run (nodout of a crashlite
    or LS-DYNA run: ``load(path)``), for node-field comparisons of runs
    without field states, e.g. firewall intrusion from LS-DYNA ASCII
    output. Coordinates are the first state's coordinates (or the deck's)
    plus the displacements, so differences keep the displacements'
    precision (nodout has 5 digits). None without nodout displacements."""
    try:
        t = np.asarray(history.read("nodout", "time"), float)
        ids = np.asarray(history.read("nodout", "ids"), np.int64)
        u = np.stack([np.asarray(history.read("nodout", f"{a}_displacement"), float) for a in "xyz"], axis=2)
    except (KeyError, ValueError, TypeError):
        return None
    if len(t) == 0 or len(ids) == 0 or u.shape[:2] != (len(t), len(ids)):
        return None
    x0 = None
    try:
        c = np.stack([np.asarray(history.read("nodout", f"{a}_coordinate"), float)[0] for a in "xyz"], axis=1)
        if np.all(np.isfinite(c)):
            x0 = c - u[0]
    except (KeyError, ValueError, TypeError, IndexError):
        pass
    if x0 is None and deck is not None:
        from .. import read_deck

        model = deck if hasattr(deck, "nodes") else read_deck(deck)
        all_ids = np.asarray(model.nodes.ids, np.int64)
        if np.all(np.isin(ids, all_ids)):
            x0 = np.asarray(model.nodes.xyz, float)[_index(all_ids, ids)]
    if x0 is None:
        x0 = np.zeros((len(ids), 3))  # displacements only: comparisons hold, pictures show displacements
    if not np.all(np.isfinite(u)):
        return None
    return FieldStates(t, x0[None, :, :] + u, ids, [], f"{getattr(history, 'source', '')} (history nodes)")


def read_cells(path: Path | str) -> list[np.ndarray]:
    """Connectivity rows of a legacy VTK file's CELLS block."""
    lines = Path(path).read_text().splitlines()
    i = next((k for k, ln in enumerate(lines) if ln.startswith("CELLS")), None)
    if i is None:
        return []
    n = int(lines[i].split()[1])
    return [np.array(ln.split()[1:], np.int64) for ln in lines[i + 1 : i + 1 + n]]


@dataclass
class FieldComparison:
    """Displacement fields of two runs on their common nodes at one time.

    ids (n,) int64 common node IDs; u_ref, u_cmp (n,) or (n, 3) [length]
    displacement from the first state (vector, or one component);
    difference (n,) |u_cmp − u_ref| [length]. Relative figures divide by
    the largest reference displacement of the compared nodes, so nodes that
    barely move do not blow them up.
    """

    time: float
    component: str  # "magnitude" or x, y, z
    ids: np.ndarray
    u_ref: np.ndarray
    u_cmp: np.ndarray
    difference: np.ndarray
    figures: dict
    only_ref: np.ndarray  # requested or present node IDs that only the reference run has
    only_cmp: np.ndarray

    def summary(self) -> dict:
        return {
            "time": self.time,
            "component": self.component,
            "n_common": int(len(self.ids)),
            **self.figures,
            "only_ref": _id_list(self.only_ref),
            "only_cmp": _id_list(self.only_cmp),
        }


def _id_list(ids: np.ndarray, limit: int = 50) -> dict:
    return {"count": int(len(ids)), "ids": [int(i) for i in ids[:limit]]}


def compare_fields(
    ref: FieldStates, cmp: FieldStates, time: float, nodes: ArrayLike | None = None, component: str | None = None
) -> FieldComparison:
    """Compare displacements (from the first state) of two runs at ``time``
    on the nodes both have (``nodes``: the node IDs to compare, default all
    common ones); component None compares vectors, "x"/"y"/"z" one
    component (e.g. intrusion along the vehicle axis). Node IDs one run
    lacks are listed (``only_ref``, ``only_cmp``), never matched by position."""
    for name, s in (("reference", ref), ("comparison", cmp)):
        if s.ids is None:
            raise CompareError(
                f"the {name} run's field states ({s.source}) carry no node IDs: give its deck, "
                "nodes are matched by ID, not by position"
            )
        if not s.time[0] - 1e-12 <= time <= s.time[-1] * (1 + 1e-9) + 1e-12:
            raise CompareError(
                f"time {time:.6g} is outside the {name} run's field states "
                f"[{s.time[0]:.6g}, {s.time[-1]:.6g}] ({s.source})"
            )
    if component is not None and component not in _AXES:
        raise ValueError(f"component must be None, 'x', 'y' or 'z', got {component!r}")
    want = None if nodes is None else np.unique(np.asarray(nodes, np.int64))
    ids_r = ref.ids if want is None else np.intersect1d(ref.ids, want)
    ids_c = cmp.ids if want is None else np.intersect1d(cmp.ids, want)
    common = np.intersect1d(ids_r, ids_c)
    only_r = np.setdiff1d(ids_r, ids_c)  # (requested and) in the reference only
    only_c = np.setdiff1d(ids_c, ids_r)
    if len(common) == 0:
        absent = 0 if want is None else len(np.setdiff1d(want, np.union1d(ids_r, ids_c)))
        raise CompareError(
            f"no node is in both runs{'' if want is None else ' among the requested ones'}: "
            f"{len(only_r)} only in the reference, {len(only_c)} only in the comparison"
            + (f", {absent} in neither" if absent else "")
        )
    ir = _index(ref.ids, common)
    ic = _index(cmp.ids, common)
    ur = ref.at(time)[ir] - ref.x[0][ir]
    uc = cmp.at(time)[ic] - cmp.x[0][ic]
    if component is not None:
        ur, uc = ur[:, _AXES[component]], uc[:, _AXES[component]]
        mag_r, mag_c, diff = np.abs(ur), np.abs(uc), np.abs(uc - ur)
    else:
        mag_r, mag_c, diff = (np.linalg.norm(ur, axis=1), np.linalg.norm(uc, axis=1), np.linalg.norm(uc - ur, axis=1))
    scale = float(mag_r.max())
    if scale == 0.0:
        raise CompareError(
            f"the compared nodes of the reference do not move up to t = {time:.6g}: no relative deviation"
        )
    k = int(np.argmax(diff))
    kr, kc = int(np.argmax(mag_r)), int(np.argmax(mag_c))
    figures = {
        "max_displacement_ref": scale,
        "node_of_max_ref": int(common[kr]),
        "max_displacement_cmp": float(mag_c.max()),
        "node_of_max_cmp": int(common[kc]),
        "max_displacement_deviation_percent": 100.0 * (float(mag_c.max()) - scale) / scale,
        "max_difference": float(diff[k]),
        "node_of_max_difference": int(common[k]),
        "mean_difference": float(diff.mean()),
        "max_relative_deviation_percent": 100.0 * float(diff[k]) / scale,
        "mean_relative_deviation_percent": 100.0 * float(diff.mean()) / scale,
    }
    return FieldComparison(float(time), component or "magnitude", common, ur, uc, diff, figures, only_r, only_c)


def _index(ids: np.ndarray, wanted: np.ndarray) -> np.ndarray:
    order = np.argsort(ids, kind="stable")
    return order[np.searchsorted(ids[order], wanted)]
