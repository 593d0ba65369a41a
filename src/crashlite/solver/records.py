"""Reading a deck's records for the solver's setup stages: a problem that
names a record's card, a load curve with its scale factors and offsets, and
the node indices of a node set.

Shared by ``setup`` and ``loads`` (``setup`` builds the nodal loads with
``loads``, so these live below both).
"""

from __future__ import annotations

import numpy as np

from ..keyword.errors import Problem
from ..model.model import Model


def _problem(rec, field_, msg) -> Problem:
    src = rec.where(field_) if rec is not None and hasattr(rec, "where") else ("", 0)
    return Problem(src[0], src[1], getattr(rec, "name", ""), field_.upper() if field_ else None, msg)


def _curve(model: Model, lcid: int):
    c = model.curves[lcid]
    a = np.asarray(c.rows["a1"], float) * float(c.get("sfa", 1.0) or 1.0) + float(c.get("offa", 0.0))
    o = np.asarray(c.rows["o1"], float) * float(c.get("sfo", 1.0) or 1.0) + float(c.get("offo", 0.0))
    return a, o


def _node_set(model: Model, sid: int) -> np.ndarray:
    return model.node_index(model.set_members("NODE", sid))
