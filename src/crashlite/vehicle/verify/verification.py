"""Verification of a simplified vehicle against its full model (the paper's section 4).

``verify_vehicle`` compares two runs of the same load case (crashlite
results folders; LS-DYNA output where it has the quantities) on what the
paper checks, each figure under a self-explaining key:

- global energies (total, kinetic, internal): ISO/TS 18571 rating and the
  deviation at the end of the *deceleration phase* (from the start to the
  time the full model's cell reference node stops moving forward);
- internal energy of the crash boxes (parts by title, summed), rating and
  deviation in % at the end of the deceleration phase (paper: ≈ 1 %);
- firewall intrusion: displacement of every firewall node along the vehicle
  axis in the passenger cell's own frame (the rigid motion that best fits
  the cell's frame nodes: rear seats and B-pillar sills, so that the cell's
  pitch and yaw are not counted as intrusion, as a local coordinate system
  on the cell does in a crash test), at the field state of the full
  model's largest intrusion; per-node |difference| relative to the full
  model's largest intrusion, max and mean in % (paper: < 5 %), with a
  contour picture; where the simplified deck names its interface nodes,
  the split into what the interface's motion carries and the kept
  structure's own deformation, and how far the full model's interface
  bends out of a rigid motion (which a rigid interface cannot follow);
- the engine-top acceleration along the axis, CFC 60: rating and peak;
- the computational time of both runs and its reduction in %.

The generic comparison of ``crashlite.verify.compare`` (every common
energy, part, section, wall and node curve) comes along in ``comparison``.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...model.model import Model
from ...verify.curves import make_pair, relative_percent
from ...verify.errors import CompareError
from ...verify.fields import load_states
from ...verify.filters import filter_signal
from ...verify.timing import reduction, run_info
from ..connection.rigidfit import rearward_in_frame, warping
from ..steps.massprops import node_indices
from .verdict import intrusion_bound, verdict

FLAT = 0.02  # an energy curve varying less than this share of its magnitude (the total) is not rated
ENERGY_KEYS = (("total_energy", "total"), ("kinetic_energy", "kinetic"), ("internal_energy", "internal"))
# history nodes of the passenger cell that carry its frame: apart along x and y, so pitch and yaw show
CELL_FRAME = ("rear seat left", "rear seat right", "B-pillar sill left", "B-pillar sill right")


@dataclass
class VehicleVerification:
    """The figures (``figures``, JSON-ready) and the curves behind them."""

    names: tuple  # (full, simplified)
    figures: dict
    pairs: list  # CurvePair: energies, crash boxes, engine top
    intrusion: dict | None = None  # ids, y, z, full, simplified, difference [length]
    notes: list = field(default_factory=list)

    def write(self, directory: Path | str) -> dict:
        """summary.json and index.html in ``directory``."""
        from ...report.build import jsonable
        from .verification_report import verification_page

        out = Path(directory)
        out.mkdir(parents=True, exist_ok=True)
        (out / "summary.json").write_text(
            json.dumps(jsonable({**self.figures, "notes": self.notes}), indent=1, allow_nan=False) + "\n"
        )
        (out / "index.html").write_text(verification_page(self))
        return {"summary": out / "summary.json", "html": out / "index.html"}


def _model(deck) -> Model | None:
    if deck is None or isinstance(deck, Model):
        return deck
    from ...keyword.reader import read_deck

    return read_deck(deck)


def history_node(model: Model, heading: str) -> int:
    """Deck node ID of the *DATABASE_HISTORY_NODE_ID row with ``heading``."""
    for rec in model.find("DATABASE_HISTORY_NODE"):
        heads = (rec.rows or {}).get("heading")
        if heads is None:
            continue
        for nid, h in zip(rec.rows["id"], heads):
            if str(h).strip().lower() == heading.strip().lower():
                return int(nid)
    raise KeyError(f"no history node titled {heading!r} in the deck")


def _hourglass_share(h) -> float | None:
    """Hourglass energy at the end of a run over its internal energy [%]
    (glstat; None where the run did not record it)."""
    hg, ie = _read(h, "glstat", "hourglass_energy"), _read(h, "glstat", "internal_energy")
    if hg is None or ie is None or not len(ie) or ie[-1] <= 0:
        return None
    return 100.0 * float(hg[-1]) / float(ie[-1])


def _read(h, cat, q):
    try:
        return np.asarray(h.read(cat, q))
    except (KeyError, ValueError, TypeError):
        return None


def _window(t, y, t_end):
    keep = t <= t_end * (1 + 1e-9)
    return t[keep], y[keep]


def _deceleration_end(h, node: int, axis: int, cfc: float = 60.0) -> float:
    """Time the node stops moving forward (its CFC-filtered velocity along
    the axis turns ≤ 0: a sheet node's ringing is no stop), or the last time."""
    t = _read(h, "nodout", "time")
    ids = list(np.asarray(h.read("nodout", "ids")).astype(np.int64))
    if node not in ids:
        raise CompareError(f"{getattr(h, 'source', 'run')}: node {node} is not a history node")
    v = np.asarray(h.read("nodout", f"{'xyz'[axis]}_velocity"))[:, ids.index(node)]
    sign = np.sign(v[0]) or 1.0
    try:
        t, v = filter_signal(t, v, cfc)
    except ValueError:
        pass  # too few samples to filter: the raw velocity
    stop = np.flatnonzero(sign * v <= 0.0)
    return float(t[stop[0]]) if len(stop) else float(t[-1])


def _part_sum(h, model: Model, titles) -> tuple[np.ndarray, np.ndarray]:
    pids = model.part_ids_of(list(titles))
    t = _read(h, "matsum", "time")
    ids = np.asarray(h.read("matsum", "ids")).astype(np.int64)
    ie = np.asarray(h.read("matsum", "internal_energy"))
    cols = [int(np.flatnonzero(ids == p)[0]) for p in pids if np.any(ids == p)]
    if len(cols) != len(pids):
        raise CompareError(
            f"{getattr(h, 'source', 'run')}: no internal energy of part(s) "
            f"{sorted(set(pids.tolist()) - set(ids.tolist()))}"
        )
    return t, ie[:, cols].sum(axis=1)


def _acceleration(h, node: int, axis: int, cfc: float | None):
    t = _read(h, "nodout", "time")
    ids = list(np.asarray(h.read("nodout", "ids")).astype(np.int64))
    k = ids.index(node)
    a = _read(h, "nodout", f"{'xyz'[axis]}_acceleration")
    a = np.gradient(np.asarray(h.read("nodout", f"{'xyz'[axis]}_velocity"))[:, k], t) if a is None else a[:, k]
    return filter_signal(t, a, cfc) if cfc else (t, a)


def intrusion_split(
    x: np.ndarray, x0: np.ndarray, nodes: np.ndarray, frame: np.ndarray, interface: np.ndarray, axis: int
) -> tuple[np.ndarray, np.ndarray]:
    """The rearward displacement of ``nodes`` in the cell frame split in two:
    (carried, own). ``own`` is the displacement in the frame of the
    ``interface`` nodes (their best-fitting rigid motion): the kept
    structure's own deformation between the interface and the firewall;
    ``carried`` = total − own: what the interface's motion in the cell frame
    (the replaced structure's compliance, or the surrogate's springs)
    carries the nodes by."""
    total = rearward_in_frame(x, x0, nodes, frame, axis)
    own = rearward_in_frame(x, x0, nodes, interface, axis)
    return total - own, own


def _deviation(full: np.ndarray, cmp: np.ndarray, scale: float) -> dict:
    d = np.abs(cmp - full)
    return {
        "max_full": float(full.max()),
        "max_simplified": float(cmp.max()),
        "mean_full": float(full.mean()),
        "mean_simplified": float(cmp.mean()),
        "max_deviation_percent": 100.0 * float(d.max()) / scale,
        "mean_deviation_percent": 100.0 * float(d.mean()) / scale,
    }


def _warping(x_r, x0_r, ir, x_c, x0_c, ic, axis: int, scale: float) -> dict:
    """How far the interface nodes of each run are from moving as one rigid
    body along the axis (``rigidfit.warping``), at the compared state: the
    full model's elastic rear bends its cut, which a rigid interface holds
    flat; max and root mean square [length] and in % of the full model's
    largest intrusion."""
    out = {}
    for name, (x, x0, nodes) in (("full", (x_r, x0_r, ir)), ("simplified", (x_c, x0_c, ic))):
        w = warping(x, x0, nodes, axis)
        out[f"max_{name}"], out[f"rms_{name}"] = float(np.abs(w).max()), float(np.sqrt((w * w).mean()))
    out["max_full_percent"] = 100.0 * out["max_full"] / scale
    out["rms_full_percent"] = 100.0 * out["rms_full"] / scale
    return out


def _intrusion(
    ref_path,
    cmp_path,
    decks,
    firewall: np.ndarray,
    frame_ids: np.ndarray,
    axis: int,
    t_end: float,
    interface_ids=None,
    at: float | None = None,
    scale: float | None = None,
    loaded: dict | None = None,
):
    """Firewall intrusion (rearwards, in the cell frame of the ``frame_ids``
    nodes) of both runs at the reference run's field state of largest
    intrusion up to t_end (its state nearest ``at`` where given), deviations
    relative to its largest intrusion (or ``scale``); with ``interface_ids``
    (nodes of the interface in both runs) its split into what the interface
    carries and the kept structure's own deformation (``intrusion_split``).
    ``loaded``: field states by results path, read once for several calls."""
    loaded = {} if loaded is None else loaded
    for p, d in zip((ref_path, cmp_path), decks):
        if str(p) not in loaded:
            loaded[str(p)] = load_states(p, d)
    states = [loaded[str(p)] for p in (ref_path, cmp_path)]
    if any(s is None for s in states):
        raise CompareError("firewall intrusion needs field states of both runs (*DATABASE_BINARY_D3PLOT)")
    out = []
    for s in states:
        idx = {int(n): k for k, n in enumerate(s.ids)}
        missing = [int(n) for n in np.append(firewall, frame_ids) if int(n) not in idx]
        if missing:
            raise CompareError(f"{s.source}: firewall or cell frame node(s) {missing[:10]} not in the field states")
        out.append((s, idx, np.array([idx[int(n)] for n in firewall]), np.array([idx[int(n)] for n in frame_ids])))
    (s_r, idx_r, fw_r, fr_r), (s_c, idx_c, fw_c, fr_c) = out
    if at is None:
        i_r = np.array([rearward_in_frame(x, s_r.x[0], fw_r, fr_r, axis) for x in s_r.x])
        usable = np.flatnonzero(s_r.time <= t_end * (1 + 1e-9))
        k = int(usable[np.argmax(i_r[usable].max(axis=1))])
        full = i_r[k]
    else:
        k = int(np.argmin(np.abs(s_r.time - at)))
        full = rearward_in_frame(s_r.x[k], s_r.x[0], fw_r, fr_r, axis)
    t = float(s_r.time[k])
    x_c = s_c.at(t)
    i_c = rearward_in_frame(x_c, s_c.x[0], fw_c, fr_c, axis)
    scale = float(full.max()) if scale is None else float(scale)
    if not scale > 0:
        raise CompareError("the firewall of the full model does not intrude: no relative deviation")
    diff = np.abs(i_c - full)
    y, z = s_r.x[0, fw_r, 1], s_r.x[0, fw_r, 2]
    figs = {
        "time": t,
        "max_intrusion_full": scale,
        "max_intrusion_simplified": float(i_c.max()),
        "max_intrusion_deviation_percent": relative_percent(scale, float(i_c.max())),
        "max_deviation_percent": 100.0 * float(diff.max()) / scale,
        "mean_deviation_percent": 100.0 * float(diff.mean()) / scale,
        "nodes": int(len(firewall)),
        "cell_frame_nodes": [int(n) for n in frame_ids],
    }
    if interface_ids is not None:
        both = [int(n) for n in interface_ids if int(n) in idx_r and int(n) in idx_c]
        if len(both) >= 3:
            ir, ic = np.array([idx_r[n] for n in both]), np.array([idx_c[n] for n in both])
            car_r, own_r = intrusion_split(s_r.x[k], s_r.x[0], fw_r, fr_r, ir, axis)
            car_c, own_c = intrusion_split(x_c, s_c.x[0], fw_c, fr_c, ic, axis)
            figs["split"] = {
                "interface_nodes": len(both),
                "carried_by_interface": _deviation(car_r, car_c, scale),
                "own_deformation": _deviation(own_r, own_c, scale),
                "interface_warping": _warping(s_r.x[k], s_r.x[0], ir, x_c, s_c.x[0], ic, axis, scale),
            }
    return figs, {"ids": np.asarray(firewall), "y": y, "z": z, "full": full, "simplified": i_c, "difference": diff}


def _twin_split(
    full,
    simplified,
    twin,
    decks,
    twin_deck,
    figures: dict,
    crash_boxes,
    fw,
    frame,
    axis: int,
    t_stop: float,
    loaded: dict,
) -> dict:
    """Crash-box energy and firewall intrusion deviations split by the
    elastic twin's run: full vs twin (what the elastic premise costs at this
    interface; no elastic surrogate comes closer) and twin vs simplified
    (the surrogate's own), relative to the same full-model figures."""
    from ...results import load

    if twin_deck is None:
        raise CompareError("the elastic twin's deck is needed with its results")
    cb = _part_sum(load(twin), twin_deck, crash_boxes)
    if cb[0][-1] < t_stop * (1 - 1e-6):
        raise CompareError(
            f"the elastic twin's run ends at {cb[0][-1]:.4g}, before the deceleration phase (to {t_stop:.4g})"
        )
    e_twin = float(np.interp(t_stop, *cb))
    box = figures["crash_box_internal_energy"]
    out = {
        "premise": {"crash_box_internal_energy_deviation_percent": relative_percent(box["full"], e_twin)},
        "surrogate": {"crash_box_internal_energy_deviation_percent": relative_percent(e_twin, box["simplified"])},
    }
    fi = figures.get("firewall_intrusion")
    if fi is not None:
        at, scale = fi["time"], fi["max_intrusion_full"]
        for key, ref, cmp, dd in (
            ("premise", full, twin, (decks[0], twin_deck)),
            ("surrogate", twin, simplified, (twin_deck, decks[1])),
        ):
            f, _ = _intrusion(ref, cmp, dd, fw, frame, axis, t_stop, at=at, scale=scale, loaded=loaded)
            out[key]["firewall_intrusion_max_deviation_percent"] = f["max_deviation_percent"]
            out[key]["firewall_intrusion_mean_deviation_percent"] = f["mean_deviation_percent"]
            out[key]["time"] = f["time"]
    return out


def split_text(intrusion: dict) -> str:
    """ " (of it: own deformation max a % mean b %, carried by the interface
    max c % mean d %)" for a firewall-intrusion figure with its split, else ""."""
    sp = (intrusion or {}).get("split")
    if not sp:
        return ""
    own, car = sp["own_deformation"], sp["carried_by_interface"]
    warp = sp.get("interface_warping")
    bent = (
        f"; the full model's interface bends {warp['max_full_percent']:.1f} % out of a rigid motion, rms "
        f"{warp['rms_full_percent']:.1f} %"
        if warp
        else ""
    )
    return (
        f" (of it: own deformation max {own['max_deviation_percent']:.1f} % mean "
        f"{own['mean_deviation_percent']:.1f} %, carried by the interface max {car['max_deviation_percent']:.1f} "
        f"% mean {car['mean_deviation_percent']:.1f} %{bent})"
    )


def interface_nodes(model: Model, prefix: str = "surrogate interface") -> np.ndarray | None:
    """Deck IDs of the nodes in every *SET_NODE whose title starts with
    ``prefix`` (the interface bodies a reduction writes), or None."""
    ids = [
        model.set_members("NODE", sid)
        for (kind, sid), rec in model.sets.items()
        if kind == "NODE" and str(rec.title or "").strip().lower().startswith(prefix)
    ]
    return np.unique(np.concatenate(ids)).astype(np.int64) if ids else None


def verify_vehicle(
    full: Path | str,
    simplified: Path | str,
    full_deck: Model | Path | str,
    simplified_deck: Model | Path | str,
    load_case: str = "US NCAP",
    crash_boxes: Iterable[str] = ("crash box left", "crash box right"),
    firewall: str = "firewall nodes",
    reference: str = "rear seat left",
    engine: str = "engine top",
    cfc: float = 60.0,
    axis: int = 0,
    names: Sequence[str] = ("full", "simplified"),
    cell_frame: Iterable[str] = CELL_FRAME,
    twin: Path | str | None = None,
    twin_deck: Model | Path | str | None = None,
) -> VehicleVerification:
    """Compare the simplified run with the full one (module docstring).
    ``full``, ``simplified``: results folders; the decks name the parts,
    the firewall node set and the history nodes (by their titles):
    ``reference`` the cell node whose stop ends the deceleration phase,
    ``cell_frame`` the cell nodes whose rigid motion the intrusion is
    measured in (the reference node alone where a deck lacks them: then the
    cell's rotation counts as intrusion, and a note says so). ``twin``,
    ``twin_deck``: a run of the full model's elastic twin
    (``vehicle.connection.twin``) in the same load case: the crash-box energy and
    intrusion deviations split into the premise's (full vs twin) and the
    surrogate's (twin vs simplified), under ``elastic_twin``."""
    from ...results import load

    decks = (_model(full_deck), _model(simplified_deck))
    hist = (load(full), load(simplified))
    notes = []
    ref_node = history_node(decks[0], reference)
    t_stop = _deceleration_end(hist[0], ref_node, axis)
    figures: dict = {
        "load_case": load_case,
        "names": list(names),
        "deceleration_phase_end": t_stop,
        "reference_node": ref_node,
    }
    pairs = []
    energies = {}
    figures["hourglass_share_percent"] = {n: _hourglass_share(h) for n, h in zip(names, hist)}
    for key, label in ENERGY_KEYS:
        c = [(_read(h, "glstat", "time"), _read(h, "glstat", key)) for h in hist]
        if any(y is None for _, y in c):
            notes.append(f"{label} energy: not in both runs")
            continue
        tr, yr = _window(*c[0], t_stop)
        flat = float(np.ptp(yr)) <= FLAT * float(np.max(np.abs(yr)))
        p = make_pair("energy", f"{label} energy", "energy", tr, yr, *_window(*c[1], t_stop), rate=not flat)
        if flat:
            p.note = f"not rated: varies by less than {100 * FLAT:g} % (conserved); see its deviation"
        pairs.append(p)
        energies[label] = {
            "rating": None if p.rating is None else p.rating.overall,
            "deviation_at_end_percent": p.deviation.get("value_deviation_percent"),
            "max_difference_percent": 100.0 * p.deviation["max_abs_difference"] / float(np.abs(yr).max()),
            "note": p.note,
        }
    figures["energy_ratings_deceleration_phase"] = {k: v["rating"] for k, v in energies.items()}
    figures["energies"] = energies
    rated = [v for v in figures["energy_ratings_deceleration_phase"].values() if v is not None]
    figures["energy_rating_min"] = min(rated) if rated else None
    cb = [_part_sum(h, d, crash_boxes) for h, d in zip(hist, decks)]
    p = make_pair("part", "crash boxes internal energy", "energy", *_window(*cb[0], t_stop), *_window(*cb[1], t_stop))
    pairs.append(p)
    e_full = float(np.interp(t_stop, *cb[0]))
    e_sim = float(np.interp(t_stop, *cb[1]))
    figures["crash_box_internal_energy"] = {
        "parts": list(crash_boxes),
        "full": e_full,
        "simplified": e_sim,
        "deviation_percent": relative_percent(e_full, e_sim),
        "max_full": float(cb[0][1].max()),
        "max_simplified": float(cb[1][1].max()),
        "max_deviation_percent": relative_percent(float(cb[0][1].max()), float(cb[1][1].max())),
        "rating": None if p.rating is None else p.rating.overall,
    }
    figures["crash_box_internal_energy_deviation_percent"] = figures["crash_box_internal_energy"]["deviation_percent"]
    try:
        eng = history_node(decks[0], engine)
        acc = [_acceleration(h, eng, axis, cfc) for h in hist]
        p = make_pair(
            "node_acceleration",
            f"{engine} acceleration (CFC {cfc:g})",
            "acceleration",
            *_window(*acc[0], t_stop),
            *_window(*acc[1], t_stop),
        )
        pairs.append(p)
        figures["engine_top_acceleration"] = {
            "node": eng,
            "cfc": cfc,
            "peak_full": p.deviation.get("peak_ref"),
            "peak_simplified": p.deviation.get("peak_cmp"),
            "peak_deviation_percent": p.deviation.get("peak_deviation_percent"),
            "rating": None if p.rating is None else p.rating.overall,
        }
    except (KeyError, ValueError, CompareError) as e:
        notes.append(f"engine acceleration not compared: {e}")
    intrusion = None
    loaded: dict = {}  # field states by results path, read once for the twin's comparisons too
    try:
        fw = decks[0].nodes.ids[node_indices(decks[0], firewall)]
        try:
            frame = np.array([history_node(decks[0], name) for name in cell_frame], np.int64)
        except KeyError as e:
            frame = np.array([ref_node], np.int64)
            notes.append(
                f"intrusion relative to the {reference} node alone (no cell frame: {e}): the cell's "
                "rotation counts as intrusion"
            )
        figs, intrusion = _intrusion(
            full, simplified, decks, fw, frame, axis, t_stop, interface_nodes(decks[1]), loaded=loaded
        )
        figures["firewall_intrusion"] = figs
        figures["firewall_intrusion_max_deviation_percent"] = figs["max_deviation_percent"]
        figures["firewall_intrusion_mean_deviation_percent"] = figs["mean_deviation_percent"]
    except (KeyError, CompareError) as e:
        fw = None
        notes.append(f"firewall intrusion not compared: {e}")
    if twin is not None:
        try:
            figures["elastic_twin"] = _twin_split(
                full,
                simplified,
                twin,
                decks,
                _model(twin_deck),
                figures,
                crash_boxes,
                fw,
                frame if fw is not None else None,
                axis,
                t_stop,
                loaded,
            )
        except (KeyError, CompareError) as e:
            notes.append(f"elastic twin not compared: {e}")
    info = [run_info(p, n, d) for p, n, d in zip((full, simplified), names, decks)]
    figures["time"] = {
        "full": info[0].as_dict(),
        "simplified": info[1].as_dict(),
        "reduction_percent": reduction(info[0].wall_time, info[1].wall_time),
        "elements_full": info[0].n_elements,
        "elements_simplified": info[1].n_elements,
    }
    figures["time_reduction_percent"] = figures["time"]["reduction_percent"]
    figures["firewall_intrusion_bound_percent"] = intrusion_bound(figures)
    figures["verdict"] = [v.as_dict() for v in verdict(figures)]
    return VehicleVerification(tuple(names), figures, pairs, intrusion, notes)
