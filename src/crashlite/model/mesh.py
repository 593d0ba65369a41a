"""Mesh tables: nodes and elements as struct-of-arrays.

Every table keeps the deck IDs in ``ids`` and refers to nodes by 0-based
index (``-1``: no node). Element part references are deck part IDs
(``pid``), since parts are what users name. Lengths are in the model's unit
system; nothing is converted.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np


class Table:
    """Common behaviour of struct-of-arrays tables (all columns share axis 0)."""

    def __len__(self) -> int:
        return len(self.ids)

    def columns(self) -> dict[str, np.ndarray]:
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def take(self, sel) -> Table:
        """Rows selected by a boolean mask or an index array."""
        return type(self)(**{k: v[sel] for k, v in self.columns().items()})

    @classmethod
    def concat(cls, tables: list[Table]) -> Table:
        if not tables:
            return cls.empty()
        if len(tables) == 1:
            return tables[0]
        return cls(**{f.name: np.concatenate([getattr(t, f.name) for t in tables]) for f in fields(cls)})

    @classmethod
    def empty(cls) -> Table:
        return cls.zeros(0)

    def equals(self, other: Table) -> bool:
        """Value-by-value equality (NaN equals NaN)."""
        if type(self) is not type(other):
            return False
        for k, a in self.columns().items():
            b = getattr(other, k)
            if a.shape != b.shape or a.dtype.kind != b.dtype.kind:
                return False
            if a.dtype.kind == "f":
                if not np.array_equal(a, b, equal_nan=True):
                    return False
            elif not np.array_equal(a, b):
                return False
        return True


def _i(n, *shape, fill=0, dtype=np.int64):
    return np.full((n, *shape), fill, dtype=dtype)


def _f(n, *shape, fill=np.nan):
    return np.full((n, *shape), fill, dtype=np.float64)


@dataclass(eq=False)
class Nodes(Table):
    ids: np.ndarray  # (n,) int64 deck node IDs
    xyz: np.ndarray  # (n, 3) float64 coordinates [length]
    tc: np.ndarray  # (n,) int8 translational constraint code (0 free … 7 all fixed)
    rc: np.ndarray  # (n,) int8 rotational constraint code

    @classmethod
    def zeros(cls, n: int) -> Nodes:
        return cls(_i(n), _f(n, 3, fill=0.0), _i(n, dtype=np.int8), _i(n, dtype=np.int8))


@dataclass(eq=False)
class Shells(Table):
    ids: np.ndarray  # (n,) int64 element IDs
    pid: np.ndarray  # (n,) int64 part IDs
    nodes: np.ndarray  # (n, 4) int32 node indices; triangles repeat node 3
    thickness: np.ndarray  # (n, 4) float64 nodal thickness [length]; NaN: from section
    beta: np.ndarray  # (n,) float64 material angle [deg]; NaN: none given
    mcid: np.ndarray  # (n,) int64 material coordinate system (0: none)
    offset: np.ndarray  # (n,) float64 mid-surface offset [length]; NaN: none

    @classmethod
    def zeros(cls, n: int) -> Shells:
        return cls(_i(n), _i(n), _i(n, 4, fill=-1, dtype=np.int32), _f(n, 4), _f(n), _i(n), _f(n))


@dataclass(eq=False)
class Solids(Table):
    ids: np.ndarray  # (n,) int64
    pid: np.ndarray  # (n,) int64
    nodes: np.ndarray  # (n, 8) int32 node indices (wedges/tets repeat nodes)

    @classmethod
    def zeros(cls, n: int) -> Solids:
        return cls(_i(n), _i(n), _i(n, 8, fill=-1, dtype=np.int32))


@dataclass(eq=False)
class Beams(Table):
    ids: np.ndarray  # (n,) int64
    pid: np.ndarray  # (n,) int64
    nodes: np.ndarray  # (n, 3) int32 end nodes and orientation node (-1: none)
    releases: np.ndarray  # (n, 5) int64 RT1 RR1 RT2 RR2 LOCAL
    params: np.ndarray  # (n, 5) float64 _THICKNESS/_SECTION PARM1..5; NaN: none
    pid2: np.ndarray  # (n, 2) int64 _PID PID1 PID2 (0: none)
    offsets: np.ndarray  # (n, 6) float64 _OFFSET WX1..WZ2 [length]; NaN: none
    orientation: np.ndarray  # (n, 3) float64 _ORIENTATION VX VY VZ; NaN: none

    @classmethod
    def zeros(cls, n: int) -> Beams:
        rel = _i(n, 5)
        rel[:, 4] = 2
        return cls(_i(n), _i(n), _i(n, 3, fill=-1, dtype=np.int32), rel, _f(n, 5), _i(n, 2), _f(n, 6), _f(n, 3))


@dataclass(eq=False)
class Discretes(Table):
    ids: np.ndarray  # (n,) int64
    pid: np.ndarray  # (n,) int64
    nodes: np.ndarray  # (n, 2) int32 (second -1: grounded spring)
    vid: np.ndarray  # (n,) int64 orientation vector ID (0: along the nodes)
    scale: np.ndarray  # (n,) float64 S, force/moment scale factor
    pf: np.ndarray  # (n,) int64 print flag
    offset: np.ndarray  # (n,) float64 initial offset [length or rad]

    @classmethod
    def zeros(cls, n: int) -> Discretes:
        return cls(_i(n), _i(n), _i(n, 2, fill=-1, dtype=np.int32), _i(n), _f(n, fill=1.0), _i(n), _f(n, fill=0.0))


@dataclass(eq=False)
class Masses(Table):
    ids: np.ndarray  # (n,) int64
    node: np.ndarray  # (n,) int32 node index
    mass: np.ndarray  # (n,) float64 [mass]
    pid: np.ndarray  # (n,) int64 part ID for output grouping (0: none)

    @classmethod
    def zeros(cls, n: int) -> Masses:
        return cls(_i(n), _i(n, fill=-1, dtype=np.int32), _f(n, fill=0.0), _i(n))


@dataclass(eq=False)
class Inertias(Table):
    ids: np.ndarray  # (n,) int64
    node: np.ndarray  # (n,) int32 node index
    csid: np.ndarray  # (n,) int64 coordinate system of the tensor (0: global)
    tensor: np.ndarray  # (n, 6) float64 IXX IXY IXZ IYY IYZ IZZ [mass·length²]
    mass: np.ndarray  # (n,) float64 [mass]
    offset: np.ndarray  # (n, 3) float64 _OFFSET x y z [length]; NaN: none

    @classmethod
    def zeros(cls, n: int) -> Inertias:
        return cls(_i(n), _i(n, fill=-1, dtype=np.int32), _i(n), _f(n, 6, fill=0.0), _f(n, fill=0.0), _f(n, 3))


def index_map(ids: np.ndarray):
    """A function from deck IDs to 0-based indices (-1 where unknown).

    Dense IDs use a lookup array (one gather); sparse ones a sorted search.
    """
    ids = np.asarray(ids)
    if len(ids) == 0:
        return lambda q: np.full(np.shape(q), -1, dtype=np.int64)
    lo, hi = int(ids.min()), int(ids.max())
    if lo >= 0 and hi < 4 * len(ids) + 1_000_000:
        from ..keyword.fastparse import gather_index

        table = np.full(hi + 1, -1, dtype=np.int32 if len(ids) < 2**31 else np.int64)
        table[ids] = np.arange(len(ids))

        def lookup(q):
            q = np.asarray(q)
            if q.dtype.kind != "i":
                q = q.astype(np.int64)
            out = np.empty(q.shape, dtype=np.int64 if len(ids) >= 2**31 else np.int32)
            # (rows, columns) for the kernel; explicit sizes, since -1 cannot
            # be inferred for an empty query
            q2 = (
                q
                if q.ndim == 2
                else q.reshape(q.size, 1)
                if q.ndim < 2
                else q.reshape(q.shape[0], q.size // max(q.shape[0], 1))
            )
            gather_index(table, q2, out.reshape(q2.shape))
            return out

        return lookup
    ids = ids.astype(np.int64)
    order = np.argsort(ids, kind="stable")
    sorted_ids = ids[order]

    def lookup_sorted(q):
        q = np.asarray(q, dtype=np.int64)
        pos = np.clip(np.searchsorted(sorted_ids, q), 0, len(ids) - 1)
        return np.where(sorted_ids[pos] == q, order[pos], -1)

    return lookup_sorted
