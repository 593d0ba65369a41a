"""Model-to-model comparison of two runs (crashlite or LS-DYNA results).

A reference run (e.g. the detailed model) and a comparison run (e.g. the
simplified one) are matched entity by entity, by ID or, with the decks, by
part title or part set: global energies, internal energy per part, section
forces, rigid-wall forces, displacements and CFC-filtered accelerations of
history nodes. Each pair gets its deviation figures and ISO/TS 18571 rating
(``curves.make_pair``); field states are compared node by node on the common
nodes (``fields.compare_fields``); each run's crash pulse and time accounting
come along. Entities only one run has are listed, never matched by guess;
a request that matches nothing, or runs without a common time range, raise
CompareError.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .curves import CurvePair, make_pair, relative_percent
from .errors import CompareError
from .fields import FieldComparison, FieldStates, compare_fields, history_states, load_states
from .filters import filter_signal
from .pulse import crash_pulse
from .rating import RatingError, common_interval
from .timing import RunInfo, run_info, timing_table

if TYPE_CHECKING:
    from ..model.model import Model

# glstat quantities compared, with the names the report shows
ENERGIES = (
    ("total_energy", "total"),
    ("kinetic_energy", "kinetic"),
    ("internal_energy", "internal"),
    ("hourglass_energy", "hourglass"),
    ("sliding_interface_energy", "sliding"),
)
GROUPS = ("energy", "part", "section", "wall", "node_displacement", "node_acceleration")
AXES = "xyz"
FLAT = 1e-3  # relative variation below which a reference curve is not rated


@dataclass
class Options:
    """What to compare and how.

    parts: part IDs (int or digits), part titles or ``set:<id>`` part sets
    (titles and sets need the decks), default the parts both runs report;
    nodes, sections, walls: history node, cross-section and rigid-wall IDs,
    default the common ones; field_nodes: node IDs of the field comparison
    (default all common nodes); times: times of the field comparisons and
    pictures [time] (default the last field state both runs have); at: time
    of the "value at" figures [time] (default the end of each common range);
    cfc: J211 class of the accelerations (None: unfiltered); time_scale:
    seconds per time unit; pulse_node: history node of the crash pulse
    (default the common history node with the smallest peak deceleration,
    i.e. the most body-like one); axis: direction of travel;
    component: field comparison of one component ("x", "y", "z") or of
    the displacement vector (None).
    """

    parts: list | None = None
    nodes: list[int] | None = None
    sections: list[int] | None = None
    walls: list[int] | None = None
    field_nodes: list[int] | None = None
    times: list[float] | None = None
    at: float | None = None
    cfc: float | None = 60.0
    time_scale: float = 1.0
    pulse_node: int | None = None
    axis: str = "x"
    component: str | None = None

    def as_dict(self) -> dict:
        return {k: (list(v) if isinstance(v, tuple) else v) for k, v in self.__dict__.items()}


@dataclass
class Run:
    """One run opened for comparison: its histories, optional deck (Model),
    field states and run facts."""

    name: str
    path: str
    history: object  # crashlite.results.History
    model: object | None = None  # crashlite Model of its deck
    states: FieldStates | None = None
    info: RunInfo | None = None
    notes: list[str] = field(default_factory=list)

    def read(self, category: str, *quantity: str) -> np.ndarray | None:
        """The array, or None when the run has no such history."""
        try:
            return np.asarray(self.history.read(category, *quantity))
        except (KeyError, ValueError, TypeError):
            return None

    def settings(self) -> dict:
        """Run settings for the report: source, title, times, counts and,
        with the deck, the fields of its *CONTROL cards."""
        out = {
            "name": self.name,
            "path": self.path,
            "history": type(self.history).__name__,
            "categories": list(self.history.categories()),
        }
        t = self.read("glstat", "time")
        if t is not None and len(t):
            out.update(states=int(len(t)), start_time=float(t[0]), end_time=float(t[-1]))
        ts = self.read("glstat", "time_step")
        if ts is not None and np.any(ts > 0):  # the state at t = 0 may carry no step yet
            out.update(time_step_min=float(np.min(ts[ts > 0])), time_step_last=float(ts[-1]))
        if self.info is not None:
            out["run"] = self.info.as_dict()
        if self.model is not None:
            m = self.model
            out.update(deck=str(m.source), title=m.title, nodes=len(m.nodes), parts=len(m.parts))
            controls = {}
            for rec in m.find("CONTROL"):
                controls[rec.name] = {k: _plain(v) for k, v in rec.values.items() if v is not None}
            out["controls"] = controls
        if self.states is not None:
            out["field_states"] = {
                "count": int(len(self.states.time)),
                "end": float(self.states.time[-1]),
                "nodes": int(self.states.x.shape[1]),
                "source": self.states.source,
            }
        return out


def _plain(v):
    if isinstance(v, (np.integer,)):
        return int(v)
    if isinstance(v, (np.floating,)):
        return float(v)
    if isinstance(v, (int, float, str, bool)) or v is None:
        return v
    return str(v)


def open_run(path: Path | str, name: str | None = None, deck: Path | str | Model | None = None) -> Run:
    """A run from a crashlite results folder (or results.npz), an LS-DYNA
    output folder (binout or ASCII files), with its deck (path or Model)
    when given: the deck supplies part titles and sets, node IDs of the
    field states and element counts."""
    from .. import Model, read_deck
    from ..results import load

    p = Path(path)
    if not p.exists():
        raise CompareError(f"{p}: no such results folder or file")
    try:
        hist = load(p)
    except FileNotFoundError as e:
        raise CompareError(str(e)) from None
    model = None if deck is None else (deck if isinstance(deck, Model) else read_deck(deck))
    run = Run(
        name or (p.name if p.name not in ("out", "results.npz") else p.resolve().parent.name), str(p), hist, model
    )
    try:
        run.states = load_states(p, model)
    except CompareError:
        raise
    except (OSError, ValueError, KeyError) as e:
        run.notes.append(f"field states not read: {e}")
    if run.states is None or run.states.ids is None:
        # no field states with node IDs (LS-DYNA ASCII output, a run without
        # d3plot states): the history nodes' displacements are the field
        nodal = history_states(hist, model)
        if nodal is not None:
            run.notes.append(
                f"{run.name}: node field from its {len(nodal.ids)} history nodes (nodout)"
                + ("" if run.states is None else "; its field states carry no node IDs (give its deck)")
            )
            run.states = nodal
        elif run.states is not None:
            run.notes.append("field states without node IDs (give the deck): no field comparison")
    try:
        run.info = run_info(p, run.name, model)
    except (FileNotFoundError, ValueError, KeyError) as e:
        run.notes.append(f"no run facts: {e}")
    return run


@dataclass
class Comparison:
    """Everything compared; ``summary()`` holds every figure (JSON-ready)."""

    ref: Run
    cmp: Run
    options: Options
    t0: float
    t1: float
    pairs: list[CurvePair] = field(default_factory=list)
    fields: list[FieldComparison] = field(default_factory=list)
    pulse: dict = field(default_factory=dict)
    pulse_curves: dict = field(default_factory=dict)  # run name -> (t, forward velocity)
    timing: list[dict] = field(default_factory=list)
    mismatches: dict = field(default_factory=dict)  # what -> {only_ref, only_cmp, missing}
    notes: list[str] = field(default_factory=list)

    def group(self, name: str) -> list[CurvePair]:
        return [p for p in self.pairs if p.group == name]

    def overall(self) -> dict:
        rated = [p.rating.overall for p in self.pairs if p.rating is not None]
        return {
            "pairs": len(self.pairs),
            "rated": len(rated),
            "mean_rating": float(np.mean(rated)) if rated else None,
            "min_rating": float(np.min(rated)) if rated else None,
            "worst": (
                min((p for p in self.pairs if p.rating is not None), key=lambda p: p.rating.overall).name
                if rated
                else None
            ),
        }

    def summary(self) -> dict:
        from .. import __version__

        return {
            "crashlite": __version__,
            "reference": self.ref.settings(),
            "comparison": self.cmp.settings(),
            "options": self.options.as_dict(),
            "time_range": [self.t0, self.t1],
            "overall": self.overall(),
            "curves": {g: [p.summary() for p in self.group(g)] for g in GROUPS},
            "fields": [f.summary() for f in self.fields],
            "pulse": self.pulse,
            "timing": self.timing,
            "mismatches": self.mismatches,
            "notes": self.notes + self.ref.notes + self.cmp.notes,
        }


# --- matching ---------------------------------------------------------------


def _id_list(ids, limit: int = 100) -> dict:
    ids = [int(i) if isinstance(i, (int, np.integer)) else i for i in ids]
    return {"count": len(ids), "ids": ids[:limit]}


def _match(c: Comparison, what: str, ids_ref, ids_cmp, wanted=None) -> np.ndarray:
    """Common IDs of two runs (among ``wanted`` when given); the others are
    recorded in ``c.mismatches[what]``. A request that matches nothing in
    both runs is a CompareError."""
    r = np.unique(np.asarray([] if ids_ref is None else ids_ref, np.int64))
    k = np.unique(np.asarray([] if ids_cmp is None else ids_cmp, np.int64))
    if wanted is not None:
        w = np.unique(np.asarray(wanted, np.int64))
        missing = np.setdiff1d(w, np.union1d(r, k))
        r, k = np.intersect1d(r, w), np.intersect1d(k, w)
    else:
        missing = np.zeros(0, np.int64)
    common = np.intersect1d(r, k)
    only_r, only_c = np.setdiff1d(r, k), np.setdiff1d(k, r)
    if len(only_r) or len(only_c) or len(missing):
        c.mismatches[what] = {
            "only_ref": _id_list(only_r),
            "only_cmp": _id_list(only_c),
            "in_neither": _id_list(missing),
        }
    if wanted is not None and len(common) == 0:
        raise CompareError(
            f"no requested {what} ID is in both runs: {len(only_r)} only in {c.ref.name}, "
            f"{len(only_c)} only in {c.cmp.name}, {len(missing)} in neither "
            f"(asked for {_short(wanted)})"
        )
    return common


def _short(ids, n: int = 10) -> str:
    ids = list(ids)
    return ", ".join(map(str, ids[:n])) + (f" … ({len(ids)} in all)" if len(ids) > n else "")


def _col(ids: np.ndarray, wanted: int) -> int:
    return int(np.flatnonzero(np.asarray(ids).astype(np.int64) == wanted)[0])


def _add(c: Comparison, group: str, name: str, unit: str, tr, yr, tk, yk) -> None:
    """One pair; pairs that are zero in both runs carry no information and
    are only noted."""
    yr, yk = np.asarray(yr, float), np.asarray(yk, float)
    if not np.any(yr) and not np.any(yk):
        c.notes.append(f"{name}: zero in both runs, not compared")
        return
    try:
        common_interval(tr, tk)
    except RatingError as e:
        raise CompareError(f"{name}: {e}") from None
    at = c.options.at
    if at is not None and not max(tr[0], tk[0]) <= at <= min(tr[-1], tk[-1]):
        raise CompareError(
            f"{name}: time {at:.6g} of the 'value at' figures is outside the common range "
            f"[{max(tr[0], tk[0]):.6g}, {min(tr[-1], tk[-1]):.6g}]"
        )
    # ISO/TS 18571 scores of a curve that hardly varies (e.g. a conserved
    # total energy) measure its round-off, not the model: not rated
    flat = float(np.ptp(yr)) <= FLAT * float(np.max(np.abs(yr)))
    p = make_pair(group, name, unit, tr, yr, tk, yk, at=at, time_scale=c.options.time_scale, rate=not flat)
    if flat:
        p.note = f"not rated: the reference varies by less than {FLAT:.0e} of its magnitude"
    c.pairs.append(p)


# --- quantities -------------------------------------------------------------


def _energies(c: Comparison) -> None:
    tr, tk = c.ref.read("glstat", "time"), c.cmp.read("glstat", "time")
    if tr is None or tk is None:
        c.notes.append(
            "global energies: glstat missing in "
            + " and ".join(r.name for r, t in ((c.ref, tr), (c.cmp, tk)) if t is None)
        )
        return
    missing = {"only_ref": [], "only_cmp": []}
    for q, label in ENERGIES:
        yr, yk = c.ref.read("glstat", q), c.cmp.read("glstat", q)
        if yr is None and yk is None:
            continue
        if yr is None or yk is None:
            missing["only_ref" if yk is None else "only_cmp"].append(label)
            continue
        _add(c, "energy", f"{label} energy", "energy", tr, yr, tk, yk)
    if missing["only_ref"] or missing["only_cmp"]:
        c.mismatches["energies"] = {k: _id_list(v) for k, v in missing.items()}


def _part_ids(run: Run, spec) -> tuple[np.ndarray | None, str]:
    """Part IDs a spec names in a run (None where the run lacks it) and a label."""
    s = str(spec).strip()
    if isinstance(spec, (int, np.integer)) or s.lstrip("-").isdigit():
        pid = int(s)
        title = ""
        if run.model is not None and pid in run.model.parts:
            title = str(run.model.parts[pid].get("heading", "") or "").strip()
        return np.array([pid], np.int64), f"part {pid}" + (f" ({title})" if title else "")
    if run.model is None:
        raise CompareError(f"part {s!r}: part titles and sets need the deck of run {run.name!r} ({run.path})")
    if s.lower().startswith("set:"):
        try:
            sid = int(s[4:])
        except ValueError:
            raise CompareError(f"part set {s!r}: write set:<ID>, e.g. set:7") from None
        try:
            ids = np.asarray(run.model.set_members("PART", sid), np.int64)
        except (KeyError, ValueError):
            return None, f"part set {sid}"
        return (ids if len(ids) else None), f"part set {sid} (parts {_short(ids, 6)})"
    try:
        ids = run.model.part_ids_of([s])
    except KeyError:
        return None, s
    return ids, f"{s} (part {', '.join(map(str, ids))})"


def _parts(c: Comparison) -> None:
    ids_r, ids_k = c.ref.read("matsum", "ids"), c.cmp.read("matsum", "ids")
    er, ek = c.ref.read("matsum", "internal_energy"), c.cmp.read("matsum", "internal_energy")
    if ids_r is None or ids_k is None or er is None or ek is None:
        if c.options.parts:
            raise CompareError(
                "part energies asked for, but matsum is missing in "
                + " and ".join(r.name for r, e in ((c.ref, er), (c.cmp, ek)) if e is None)
            )
        c.notes.append("part energies: matsum missing in one run")
        return
    tr, tk = c.ref.read("matsum", "time"), c.cmp.read("matsum", "time")
    if not c.options.parts:
        for pid in _match(c, "part", ids_r, ids_k):
            _, lr = _part_ids(c.ref, pid)
            _add(c, "part", f"{lr} internal energy", "energy", tr, er[:, _col(ids_r, pid)], tk, ek[:, _col(ids_k, pid)])
        return
    only_r, only_k, neither, found = [], [], [], 0
    for spec in c.options.parts:
        (pr, lr), (pk, lk) = _part_ids(c.ref, spec), _part_ids(c.cmp, spec)
        # a part (or member of a set) the run reports no energy for is missing there
        pr = None if pr is None or not np.all(np.isin(pr, ids_r)) else pr
        pk = None if pk is None or not np.all(np.isin(pk, ids_k)) else pk
        if pr is None or pk is None:
            (only_r if pr is not None else only_k if pk is not None else neither).append(str(spec))
            continue
        found += 1
        label = lr if lr == lk else f"{lr} | {lk}"
        yr = er[:, [_col(ids_r, p) for p in pr]].sum(axis=1)
        yk = ek[:, [_col(ids_k, p) for p in pk]].sum(axis=1)
        _add(c, "part", f"{label} internal energy", "energy", tr, yr, tk, yk)
    if only_r or only_k or neither:
        c.mismatches["part"] = {
            "only_ref": _id_list(only_r),
            "only_cmp": _id_list(only_k),
            "in_neither": _id_list(neither),
        }
    if not found:
        raise CompareError(
            f"no requested part is in both runs: {_short(c.options.parts)}"
            f" ({len(only_r)} only in {c.ref.name}, {len(only_k)} only in {c.cmp.name}, "
            f"{len(neither)} in neither)"
        )


def _sections(c: Comparison) -> None:
    ids_r, ids_k = c.ref.read("secforc", "ids"), c.cmp.read("secforc", "ids")
    if ids_r is None or ids_k is None:
        if c.options.sections:
            raise CompareError("section forces asked for, but secforc is missing in a run")
        return
    tr, tk = c.ref.read("secforc", "time"), c.cmp.read("secforc", "time")
    for sid in _match(c, "section", ids_r, ids_k, c.options.sections):
        for a in AXES:
            yr, yk = c.ref.read("secforc", f"{a}_force"), c.cmp.read("secforc", f"{a}_force")
            if yr is not None and yk is not None:
                _add(
                    c,
                    "section",
                    f"section {sid} {a}-force",
                    "force",
                    tr,
                    yr[:, _col(ids_r, sid)],
                    tk,
                    yk[:, _col(ids_k, sid)],
                )


def _walls(c: Comparison) -> None:
    ids_r, ids_k = c.ref.read("rwforc", "forces", "ids"), c.cmp.read("rwforc", "forces", "ids")
    if ids_r is None or ids_k is None:
        if c.options.walls:
            raise CompareError("rigid-wall forces asked for, but rwforc is missing in a run")
        return
    tr, tk = c.ref.read("rwforc", "forces", "time"), c.cmp.read("rwforc", "forces", "time")
    yr, yk = c.ref.read("rwforc", "forces", "normal_force"), c.cmp.read("rwforc", "forces", "normal_force")
    for wid in _match(c, "wall", ids_r, ids_k, c.options.walls):
        _add(
            c,
            "wall",
            f"rigid wall {wid} normal force",
            "force",
            tr,
            yr[:, _col(ids_r, wid)],
            tk,
            yk[:, _col(ids_k, wid)],
        )


def _acceleration(run: Run, axis: str, col: int) -> tuple[np.ndarray, np.ndarray, bool]:
    """(t, a, derived): nodout acceleration, or the derivative of its velocity."""
    t = run.read("nodout", "time")
    a = run.read("nodout", f"{axis}_acceleration")
    if a is not None:
        return t, a[:, col], False
    v = run.read("nodout", f"{axis}_velocity")
    return t, np.gradient(v[:, col], t), True


def _filtered(c: Comparison, name: str, t, y):
    if c.options.cfc is None:
        return t, y
    try:
        return filter_signal(t, y, c.options.cfc, time_scale=c.options.time_scale)
    except ValueError as e:
        c.notes.append(f"{name}: not CFC-filtered ({e})")
        return t, y


def _nodes(c: Comparison) -> None:
    ids_r, ids_k = c.ref.read("nodout", "ids"), c.cmp.read("nodout", "ids")
    if ids_r is None or ids_k is None:
        if c.options.nodes:
            raise CompareError("history nodes asked for, but nodout is missing in a run")
        return
    tr, tk = c.ref.read("nodout", "time"), c.cmp.read("nodout", "time")
    cfc = "" if c.options.cfc is None else f" CFC {c.options.cfc:g}"
    for nid in _match(c, "node", ids_r, ids_k, c.options.nodes):
        jr, jk = _col(ids_r, nid), _col(ids_k, nid)
        for a in AXES:
            yr, yk = c.ref.read("nodout", f"{a}_displacement"), c.cmp.read("nodout", f"{a}_displacement")
            if yr is not None and yk is not None:
                _add(c, "node_displacement", f"node {nid} {a}-displacement", "length", tr, yr[:, jr], tk, yk[:, jk])
        for a in AXES:
            if c.ref.read("nodout", f"{a}_velocity") is None or c.cmp.read("nodout", f"{a}_velocity") is None:
                continue
            name = f"node {nid} {a}-acceleration{cfc}"
            t1, y1, d1 = _acceleration(c.ref, a, jr)
            t2, y2, d2 = _acceleration(c.cmp, a, jk)
            if d1 or d2:
                c.notes.append(
                    f"{name}: derived from the velocity in "
                    + " and ".join(r.name for r, d in ((c.ref, d1), (c.cmp, d2)) if d)
                )
            if not np.any(y1) and not np.any(y2):
                c.notes.append(f"{name}: zero in both runs, not compared")
                continue
            _add(c, "node_acceleration", name, "acceleration", *_filtered(c, name, t1, y1), *_filtered(c, name, t2, y2))


def _pulse(c: Comparison) -> None:
    ax = c.options.axis
    ids_r, ids_k = c.ref.read("nodout", "ids"), c.cmp.read("nodout", "ids")
    vr, vk = c.ref.read("nodout", f"{ax}_velocity"), c.cmp.read("nodout", f"{ax}_velocity")
    if ids_r is None or ids_k is None or vr is None or vk is None:
        if c.options.pulse_node is not None:
            raise CompareError("a crash pulse node was given, but nodout is missing in a run")
        c.notes.append("crash pulse: no nodout velocities in both runs")
        return
    tr, tk = c.ref.read("nodout", "time"), c.cmp.read("nodout", "time")
    nid = c.options.pulse_node
    if nid is None:
        common = np.intersect1d(ids_r, ids_k)
        moving = [n for n in common if vr[0, _col(ids_r, n)] != 0.0]
        if not moving:
            c.notes.append("crash pulse: no common history node has an initial velocity")
            return

        # the most body-like node: the smallest peak deceleration
        def peak(n):
            _, a, _ = _acceleration(c.ref, ax, _col(ids_r, n))
            return float(np.max(np.abs(_filtered(c, "pulse", tr, a)[1])))

        nid = int(min(moving, key=peak))
    c.pulse = {"node": int(nid), "axis": ax, "cfc": c.options.cfc}
    for key, run, t, ids, v in (("reference", c.ref, tr, ids_r, vr), ("comparison", c.cmp, tk, ids_k, vk)):
        if int(nid) not in ids.astype(np.int64):
            raise CompareError(f"crash pulse node {nid} is not a history node of {run.name}")
        vel = v[:, _col(ids, int(nid))]
        try:
            p = crash_pulse(t, velocity=vel, cfc=c.options.cfc, time_scale=c.options.time_scale)
        except ValueError as e:
            c.pulse[key] = None
            c.notes.append(f"crash pulse of {run.name}: {e}")
            continue
        c.pulse[key] = p.as_dict()
        c.pulse_curves[run.name] = (t, math.copysign(1.0, vel[0]) * vel)
    pr, pk = c.pulse.get("reference"), c.pulse.get("comparison")
    if pr and pk:
        c.pulse["deviation_percent"] = {
            k: (relative_percent(pr[k], pk[k]) if pr[k] is not None and pk[k] is not None else None)
            for k in ("peak_deceleration", "mean_deceleration", "dynamic_crush", "time_to_zero_velocity", "olc")
        }


def _fields(c: Comparison) -> None:
    sr, sk = c.ref.states, c.cmp.states
    usable = sr is not None and sk is not None and sr.ids is not None and sk.ids is not None
    if not usable:
        if c.options.field_nodes is not None or c.options.times:
            why = [
                f"{r.name}: "
                + ("no field states" if r.states is None else "field states without node IDs (give its deck)")
                for r in (c.ref, c.cmp)
                if r.states is None or r.states.ids is None
            ]
            raise CompareError("field comparison asked for, but " + "; ".join(why))
        c.notes.append("field comparison: field states with node IDs (or history nodes) are needed in both runs")
        return
    end = min(float(sr.time[-1]), float(sk.time[-1]))
    asked = c.options.field_nodes is not None or bool(c.options.times)
    times = list(c.options.times) if c.options.times else [end]
    for t in times:
        try:
            c.fields.append(compare_fields(sr, sk, float(t), c.options.field_nodes, c.options.component))
        except CompareError as e:
            if asked:  # what was asked for cannot be compared: say so, never a NaN figure
                raise
            c.notes.append(f"field comparison: {e}")  # not asked for: the rest is still compared
            return
    f = c.fields[-1]
    if len(f.only_ref) or len(f.only_cmp):
        c.mismatches["field node"] = {
            "only_ref": _id_list(f.only_ref),
            "only_cmp": _id_list(f.only_cmp),
            "in_neither": _id_list([]),
        }


def _timing(c: Comparison) -> None:
    if c.ref.info is None or c.cmp.info is None:
        c.notes.append(
            "time accounting: run facts missing in " + " and ".join(r.name for r in (c.ref, c.cmp) if r.info is None)
        )
        return
    c.timing = timing_table([c.ref.info, c.cmp.info])


def compare(ref: Run, cmp: Run, options: Options | None = None) -> Comparison:
    """Compare ``cmp`` against ``ref`` (see the module text)."""
    o = options or Options()
    if o.axis not in AXES:
        raise CompareError(f"axis must be x, y or z, got {o.axis!r}")
    if not o.time_scale > 0:
        raise CompareError(f"time_scale must be positive seconds per time unit, got {o.time_scale!r}")
    tr, tk = ref.read("glstat", "time"), cmp.read("glstat", "time")
    if tr is None or tk is None or len(tr) < 2 or len(tk) < 2:
        raise CompareError(
            "both runs need a glstat history of at least two states: "
            f"{ref.name} has {0 if tr is None else len(tr)}, {cmp.name} {0 if tk is None else len(tk)}"
        )
    try:
        t0, t1 = common_interval(tr, tk)
    except RatingError:
        raise CompareError(
            f"no common time range: {ref.name} covers [{tr[0]:.6g}, {tr[-1]:.6g}], "
            f"{cmp.name} [{tk[0]:.6g}, {tk[-1]:.6g}]"
        ) from None
    c = Comparison(ref, cmp, o, t0, t1)
    for step in (_energies, _parts, _sections, _walls, _nodes, _pulse, _fields, _timing):
        step(c)
    if not c.pairs and not c.fields:
        raise CompareError(
            f"nothing to compare: {ref.name} and {cmp.name} share no energy, part, section, wall "
            "or node history and no field states" + _mismatch_text(c)
        )
    return c


def _mismatch_text(c: Comparison) -> str:
    parts = [
        f"{what}: {m['only_ref']['count']} only in {c.ref.name}, {m['only_cmp']['count']} only in {c.cmp.name}"
        for what, m in c.mismatches.items()
    ]
    return (" (" + "; ".join(parts) + ")") if parts else ""


def compare_paths(
    ref: Path | str,
    cmp: Path | str,
    options: Options | None = None,
    names: tuple[str | None, str | None] = (None, None),
    decks: tuple = (None, None),
) -> Comparison:
    """``compare`` of two results paths (crashlite or LS-DYNA), with their decks when given."""
    a = open_run(ref, names[0], decks[0])
    b = open_run(cmp, names[1], decks[1])
    if a.name == b.name:
        a.name, b.name = f"{a.name} (reference)", f"{b.name} (comparison)"
    return compare(a, b, options)
