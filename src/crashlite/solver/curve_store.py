"""The CSR curve store the element kernels read (curve_start, curve_stop,
curve_x, curve_y): each *DEFINE_CURVE once, scaled and offset by its SFA,
SFO, OFFA and OFFO; points a material gives itself (EPS1-8 / ES1-8); and
*DEFINE_TABLE tables.

A table is one more curve of the store: x its values (VALUE·SFA + OFFA, the
strain rates of a MAT_024 or MAT_081 LCSS), y the slots of its curves. The
kernels keep their signatures and find a table through a material's own
slot for it (kernels.plane_stress.C_TABLE, kernels.solid_materials.C_TABLE).
"""

from __future__ import annotations

import numpy as np

from ..keyword.schema import Record
from ..model.model import Model


class CurveStore:
    """Curves and tables of one element set, each stored once."""

    def __init__(self, model: Model):
        self.model = model
        self.slot: dict = {}
        self.xs: list[np.ndarray] = []
        self.ys: list[np.ndarray] = []
        self.tables = {
            int(r.id): r for r in model.keywords if isinstance(r, Record) and r.keyword == "DEFINE_TABLE" and r.id
        }

    def get(self, lcid: int) -> int:
        """Slot of *DEFINE_CURVE ``lcid`` (which must exist)."""
        if lcid not in self.slot:
            c = self.model.curves[lcid]
            a = np.asarray(c.rows["a1"], float) * float(c.get("sfa", 1.0) or 1.0) + float(c.get("offa", 0.0))
            o = np.asarray(c.rows["o1"], float) * float(c.get("sfo", 1.0) or 1.0) + float(c.get("offo", 0.0))
            self.add(a, o, lcid)
        return self.slot[lcid]

    def add(self, a, o, key) -> int:
        self.slot[key] = len(self.xs)
        self.xs.append(np.asarray(a, float))
        self.ys.append(np.asarray(o, float))
        return self.slot[key]

    def table(self, tbid: int) -> tuple[int | None, str | None]:
        """(slot, None) of *DEFINE_TABLE ``tbid``, or (None, why it cannot be used)."""
        key = ("table", tbid)
        if key in self.slot:
            return self.slot[key], None
        rec = self.tables[tbid]
        rows = rec.rows or {}
        values = np.asarray(rows.get("value", ()), float) * float(rec.get("sfa", 1.0) or 1.0)
        values = values + float(rec.get("offa", 0.0) or 0.0)
        lcids = [int(i) for i in rows.get("lcid", ())]
        if not len(values):
            return None, f"*DEFINE_TABLE {tbid} has no curves"
        if np.any(np.diff(values) <= 0):
            return None, f"the values of *DEFINE_TABLE {tbid} must rise"
        bad = [i for i in lcids if i not in self.model.curves]
        if bad:
            return None, f"*DEFINE_TABLE {tbid} names curve {bad[0]}, which is not a *DEFINE_CURVE"
        slots = [self.get(i) for i in lcids]
        return self.add(values, np.array(slots, float), key), None

    def yield_slots(self, mat: Record, fld: str) -> tuple[int, int, str | None]:
        """(curve slot, table slot, problem) of a curve-or-table field
        (LCSS): -1 where the field names none; the problem, if any, says
        why the ID cannot be used."""
        lc = int(mat.get(fld, 0) or 0)
        if lc == 0:
            return -1, -1, None
        if lc in self.model.curves:
            if lc in self.tables:
                return -1, -1, f"ID {lc} is both a *DEFINE_CURVE and a *DEFINE_TABLE"
            return self.get(lc), -1, None
        if lc in self.tables:
            t, why = self.table(lc)
            return -1, (-1 if t is None else t), why
        return -1, -1, f"curve {lc} is not defined (a *DEFINE_CURVE or *DEFINE_TABLE is needed)"

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(curve_start, curve_stop, curve_x, curve_y) of the kernels."""
        sizes = np.array([len(a) for a in self.xs], np.int64)
        stop = np.cumsum(sizes)
        cat = lambda xs: np.concatenate(xs) if xs else np.zeros(0)  # noqa: E731
        return stop - sizes, stop, cat(self.xs), cat(self.ys)
