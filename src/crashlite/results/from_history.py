"""A run's time histories (``results.load``: an LS-DYNA folder or binout)
as crashlite's ``Results``, so code written for crashlite runs (the study
responses) reads LS-DYNA runs too: the inverse of
``solver.results.categories``.

What an LS-DYNA history output cannot give stays empty: field states
(``states_x``), element results (plastic strain, element energy),
moving-wall velocities (zero). ``final_x`` and ``node_ids`` hold the
history nodes only (their last nodout coordinates); the final state of
every node is in the d3plot (``results.d3plot.read_final_state``).
Contact forces are rcforc's slave lines (the force on each interface's
slave side, as crashlite's ``contact_force``).

LS-DYNA writes each history file at its own interval; every history is
put on the time axis of the one with the most states (linear
interpolation; identical axes are taken as they are).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..model.model import Model
    from ..solver.results import Results
    from .history import History

# category -> its time quantity
_TIME = {
    "glstat": ("time",),
    "nodout": ("time",),
    "matsum": ("time",),
    "rwforc": ("forces", "time"),
    "deforc": ("time",),
    "secforc": ("time",),
    "spcforc": ("time",),
    "rcforc": ("time",),
}


def _get(history, category: str, *quantity):
    """The array or None (the history lacks it)."""
    try:
        v = history.read(category, *quantity)
    except Exception:  # noqa: BLE001 - lasso's Binout raises various errors for what it lacks
        return None
    if v is None or isinstance(v, dict):
        return None
    try:
        v = np.asarray(v, float)
    except (TypeError, ValueError):
        return None
    return v if v.size else None


def _ids(history, category: str, *group) -> np.ndarray | None:
    v = _get(history, category, *group, "ids")
    return None if v is None else np.atleast_1d(v).astype(np.int64).ravel()


def _interp(t_src: np.ndarray, y: np.ndarray, t: np.ndarray) -> np.ndarray:
    """``y`` (time first) on the time axis ``t``."""
    if len(t_src) == len(t) and np.allclose(t_src, t, rtol=1e-9, atol=0.0):
        return y
    if len(t_src) == 0:
        return np.zeros((len(t),) + y.shape[1:])
    flat = y.reshape(len(t_src), -1)
    out = np.empty((len(t), flat.shape[1]))
    for j in range(flat.shape[1]):
        out[:, j] = np.interp(t, t_src, flat[:, j])
    return out.reshape((len(t),) + y.shape[1:])


def _rcforc_lines(history) -> tuple[np.ndarray, np.ndarray]:
    """Interface ID and side (0 slave, 1 master) of each rcforc line. A
    binout lists a contact without surfaces under ID 0 but writes no force
    for it: such IDs are dropped where the forces have fewer columns (as
    LS-DYNA's l2a does)."""
    ids = _ids(history, "rcforc")
    if ids is None:
        return np.zeros(0, np.int64), np.zeros(0)
    side = _get(history, "rcforc", "side")
    side = np.zeros(len(ids)) if side is None else np.atleast_1d(side).ravel()
    x = _get(history, "rcforc", "x_force")
    width = len(ids) if x is None else (x.shape[1] if x.ndim == 2 else 1)
    if width < len(ids):
        keep = ids != 0
        ids, side = ids[keep], side[keep]
    return ids, side


def results_from_history(history: History, model: Model | None = None) -> Results:
    """A ``solver.results.Results`` from a ``results.History``. ``model``
    (the run's deck) gives the history nodes' initial coordinates where
    nodout lacks its coordinate columns."""
    from ..solver.results import Results

    have = set(history.categories())
    times = {c: _get(history, c, *q) for c, q in _TIME.items() if c in have}
    times = {c: np.atleast_1d(v).ravel() for c, v in times.items() if v is not None}
    if not times:
        raise ValueError(
            f"{history.source}: no time history (glstat, nodout, matsum, rwforc, deforc, secforc, spcforc, rcforc) "
            "to read"
        )
    ref = max(times, key=lambda c: (len(times[c]), c == "glstat"))
    t = times[ref]
    n = len(t)

    def on(category, y, *trailing):
        if y is None:
            return np.zeros((n,) + trailing)
        y = np.asarray(y, float)
        if y.ndim == 1 and trailing:
            y = y[:, None]
        return _interp(times[category], y, t)

    def series(category, *quantity):
        """(n,) or empty when the history lacks it."""
        v = _get(history, category, *quantity) if category in times else None
        return np.zeros(0) if v is None else on(category, np.atleast_1d(v).ravel())

    def columns(category, m: int, *quantity):
        """(n, m) or None."""
        v = _get(history, category, *quantity) if category in times else None
        if v is None:
            return None
        return on(category, np.asarray(v, float).reshape(len(times[category]), m))

    def vectors(category, m: int, fmt: str, *group):
        """(n, m, 3) of x/y/z quantities, or None when any is missing."""
        parts = [columns(category, m, *group, fmt.format(a)) for a in "xyz"]
        return None if any(p is None for p in parts) else np.stack(parts, axis=2)

    def ids(category, *group) -> np.ndarray:
        """The entity IDs of a category, empty when the history lacks it."""
        v = _ids(history, category, *group) if category in times else None
        return np.zeros(0, np.int64) if v is None else v

    kinetic = series("glstat", "kinetic_energy")
    internal = series("glstat", "internal_energy")
    wall = series("glstat", "stonewall_energy")
    if not len(wall):
        wall = series("glstat", "rigidwall_energy")
    if not len(wall) and len(kinetic):
        wall = np.zeros(n)  # no rigid wall: LS-DYNA leaves the line out
    external = series("glstat", "external_work")
    if not len(external) and len(kinetic):
        external = np.zeros(n)

    hist = ids("nodout")
    k = len(hist)
    disp = vectors("nodout", k, "{}_displacement")
    vel = vectors("nodout", k, "{}_velocity")
    acc = vectors("nodout", k, "{}_acceleration")
    coor = vectors("nodout", k, "{}_coordinate")

    pids = ids("matsum")
    part_internal = columns("matsum", len(pids), "internal_energy")
    part_kinetic = columns("matsum", len(pids), "kinetic_energy")
    part_hourglass = columns("matsum", len(pids), "hourglass_energy")
    if part_internal is None:
        pids, part_kinetic, part_hourglass = np.zeros(0, np.int64), None, None

    walls = ids("rwforc", "forces")
    wall_force = vectors("rwforc", len(walls), "{}_force", "forces")
    wall_normal = columns("rwforc", len(walls), "forces", "normal_force")

    dids = ids("deforc")
    dforce = columns("deforc", len(dids), "resultant_force")
    delong = columns("deforc", len(dids), "displacement")
    dvec = vectors("deforc", len(dids), "{}_force")
    if dforce is None:
        dids, delong, dvec = np.zeros(0, np.int64), None, None

    sids = ids("secforc")
    sforce = vectors("secforc", len(sids), "{}_force")
    smoment = vectors("secforc", len(sids), "{}_moment")
    if sforce is None:
        sids, smoment = np.zeros(0, np.int64), None

    spc = ids("spcforc")
    spc_force = vectors("spcforc", len(spc), "{}_force")

    lines, side = _rcforc_lines(history) if "rcforc" in times else (np.zeros(0, np.int64), np.zeros(0))
    slave = np.flatnonzero(side == 0)  # crashlite's contact_force: the force on the slave side
    rc = vectors("rcforc", len(lines), "{}_force")
    cids = lines[slave] if rc is not None else np.zeros(0, np.int64)

    final_x = np.zeros((0, 3))
    final_v = np.zeros((0, 3))
    node_ids = np.zeros(0, np.int64)
    if k and disp is not None and n:
        if coor is not None:
            final_x = coor[-1]
        elif model is not None:
            final_x = model.nodes.xyz[model.node_index(hist)] + disp[-1]
        if len(final_x):
            node_ids = hist
            final_v = vel[-1] if vel is not None else np.zeros((k, 3))

    step = series("glstat", "time_step")
    cycle = _get(history, "glstat", "cycle") if ref == "glstat" else None
    empty3 = np.zeros((0, 0, 3))
    res = Results(
        time=t,
        kinetic=kinetic,
        internal=internal,
        wall=wall,
        external=external,
        discrete_force=dforce if dforce is not None else np.zeros((n, 0)),
        discrete_elong=delong if delong is not None else np.zeros((n, len(dids))),
        wall_force=wall_force if wall_force is not None else np.zeros((n, len(walls), 3)),
        wall_velocity=np.zeros((n, len(walls))),
        node_displacement=disp if disp is not None else np.zeros((n, k, 3)),
        node_velocity=vel if vel is not None else np.zeros((n, k, 3)),
        spc_force=spc_force if spc_force is not None else np.zeros((n, len(spc), 3)),
        spc_nodes=spc,
        history_nodes=hist,
        discrete_ids=dids,
        wall_ids=walls,
        section_ids=sids,
        section_force=sforce if sforce is not None else np.zeros((n, len(sids), 3)),
        part_ids=pids,
        part_internal=part_internal if part_internal is not None else np.zeros((n, 0)),
        states_time=np.zeros(0),
        states_x=empty3,
        final_x=final_x,
        final_v=final_v,
        part_kinetic=part_kinetic if part_kinetic is not None else np.zeros((0, 0)),
        part_hourglass=part_hourglass if part_hourglass is not None else np.zeros((0, 0)),
        section_moment=smoment if smoment is not None else np.zeros((0, 0, 3)),
        node_acceleration=acc if acc is not None else np.zeros((0, 0, 3)),
        node_coordinates=coor if coor is not None else np.zeros((0, 0, 3)),
        hourglass=series("glstat", "hourglass_energy"),
        sliding=series("glstat", "sliding_interface_energy"),
        time_step=step,
        discrete_force_vector=dvec if dvec is not None else np.zeros((0, 0, 3)),
        wall_normal_force=wall_normal if wall_normal is not None else np.zeros((0, 0)),
        node_ids=node_ids,
        contact_force=rc[:, slave] if rc is not None else np.zeros((0, 0, 3)),
        contact_ids=cids,
        info={"source": history.source, "time_axis": ref},
    )
    if cycle is not None and len(np.atleast_1d(cycle)) == n:
        res.cycle_number = np.asarray(cycle).astype(np.int64).ravel()
        res.cycles = int(res.cycle_number[-1]) if n else 0
    if len(step):
        res.dt = float(step[-1])
    return res
