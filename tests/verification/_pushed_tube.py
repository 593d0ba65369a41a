"""A free elastic square tube pushed sideways at its front end by a step
force: the full model of the condensed and Craig–Bampton surrogates' tests."""

import sys
from pathlib import Path

import numpy as np

from crashlite.vehicle.car.records import id_list, record

sys.path.insert(0, str(Path(__file__).parents[1] / "unit" / "vehicle"))
from _structures import shell_model, tube_mesh  # noqa: E402

B, T, L, X = 50.0, 1.5, 1200.0, 1000.0  # tube side, wall, length, cut [mm]: 1000 mm replaced, 200 kept
END, F = 0.01, 50.0  # s, N


def pushed_tube(history_x=(L, X + 100.0)):
    """(model, history node IDs): the tube, its front ring loaded by F along
    y from t = 0, one history node on the ring at each x of ``history_x``."""
    xyz, q = tube_mesh(B, L, 2, 96)
    m = shell_model(xyz, q, thickness=T, poisson=0.3)
    ids = m.nodes.ids
    front = np.flatnonzero(np.isclose(xyz[:, 0], L))
    hist = ids[[int(np.flatnonzero(np.isclose(xyz[:, 0], x))[0]) for x in history_x]]
    m.sets[("NODE", 1)] = id_list("SET_NODE_LIST_TITLE", 1, ids[front], title="front")
    m.curves[1] = record("DEFINE_CURVE", lcid=1, rows={"a1": np.array([0.0, 1.0]), "o1": np.array([1.0, 1.0])})
    m.keywords += [
        record(
            "LOAD_NODE_SET",
            rows={"nsid": np.array([1]), "dof": np.array([2]), "lcid": np.array([1]), "sf": np.array([F / len(front)])},
        ),
        record("CONTROL_TERMINATION", endtim=END),
        record(
            "DATABASE_HISTORY_NODE_ID",
            rows={"id": hist, "heading": np.array([f"x = {x:g}" for x in history_x], object)},
        ),
    ]
    return m, hist
