"""*INCLUDE_TRANSFORM: ID offsets and the coordinate transformation of an
included file (*DEFINE_TRANSFORMATION: TRANSL, SCALE, ROTATE)."""

from __future__ import annotations

import math

import numpy as np

from .cards import INT_MAX, INT_MIN
from .errors import Collector

# *INCLUDE_TRANSFORM's cards are read by the lexer, which walks the includes
# (kept there so that the lexer does not import this module back)
from .lexer import _KINDS, _OFFSET_FIELDS, Block, IncludeContext, include_context  # noqa: F401
from .schema import INT, Record

# row fields whose ID kind another field of the row decides (so the layout gives them none):
# keyword -> (ID field, switch field, {switch value: kind})
_SWITCHED = {"PART_MOVE": ("pid", "ifset", {0: "part", 1: "set_part"})}


def _switched_offsets(rec: Record, ctx: IncludeContext) -> None:
    """The include's offsets on a row ID whose kind is chosen by another field (a *PART_MOVE row
    names a part, or with IFSET 1 a part set)."""
    field, switch, kinds = _SWITCHED[rec.name]
    if not rec.rows or field not in rec.rows:
        return
    ids = np.asarray(rec.rows[field], dtype=np.int64)
    which = np.asarray(rec.rows.get(switch, np.zeros(len(ids))), dtype=np.int64)
    off = np.array([ctx.offsets.get(kinds.get(int(w), ""), 0) for w in which], dtype=np.int64)
    rec.rows[field] = np.where(ids > 0, ids + off, ids)


def apply_offsets(rec: Record, ctx: IncludeContext, problems: Collector | None = None) -> None:
    """Add the include's ID offsets to every ID field of a record; an ID
    the offset takes past 64 bits is reported (and left unchanged)."""
    lay = rec.spec.layout(rec.options)

    def too_large(name, v, off):
        if problems is not None:
            problems.error(
                *rec.where(name),
                rec.name,
                name.upper(),
                f"ID {int(v)} plus the *INCLUDE_TRANSFORM offset {off} (at {ctx.file}:{ctx.line}) "
                "is past the 64-bit range",
            )

    for c in lay.head:
        for f in c.fields:
            off = ctx.offsets.get(f.ref, 0) if f.ref else 0
            v = rec.values.get(f.name)
            if off and f.kind == INT and isinstance(v, int) and v > 0:
                if not INT_MIN <= v + off <= INT_MAX:
                    too_large(f.name, v, off)
                    continue
                rec.values[f.name] = v + off
    if rec.name in _SWITCHED:
        _switched_offsets(rec, ctx)
    if rec.rows:
        for f in lay.row_fields:
            off = ctx.offsets.get(f.ref, 0) if f.ref else 0
            if off and f.kind == INT and f.name in rec.rows:
                col = np.asarray(rec.rows[f.name], dtype=np.int64)
                pos = col > 0
                over = pos & ((col > INT_MAX - off) if off > 0 else (col < INT_MIN - off))
                if over.any():
                    too_large(f.name, col[np.argmax(over)], off)
                    pos &= ~over
                rec.rows[f.name] = np.where(pos, col + off, col)


def matrix(tr: Record, problems: Collector) -> np.ndarray:
    """4x4 homogeneous matrix of a *DEFINE_TRANSFORMATION (steps applied in order)."""
    m = np.eye(4)
    rows = tr.rows or {}
    n = len(rows.get("option", []))
    for i in range(n):
        opt = str(rows["option"][i]).strip().upper()
        a = [float(rows[f"a{k}"][i]) for k in range(1, 8)]
        step = np.eye(4)
        if opt == "TRANSL":
            step[:3, 3] = a[:3]
        elif opt == "SCALE":
            step[:3, :3] = np.diag([s if s != 0 else 1.0 for s in a[:3]])
        elif opt == "ROTATE":
            axis = np.array(a[:3])
            if np.linalg.norm(axis) == 0:
                problems.error(tr.source[0], tr.source[1], tr.name, "A1", "ROTATE needs a direction A1-A3")
                continue
            k = axis / np.linalg.norm(axis)
            th = math.radians(a[6])
            kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
            r = np.eye(3) + math.sin(th) * kx + (1 - math.cos(th)) * kx @ kx
            p = np.array(a[3:6])
            step[:3, :3] = r
            step[:3, 3] = p - r @ p
        else:
            problems.error(
                tr.source[0],
                tr.source[1],
                tr.name,
                "OPTION",
                f"transformation {opt!r} not supported (TRANSL, SCALE, ROTATE are)",
            )
            continue
        m = step @ m
    return m


def transform_nodes(rec: Record, m: np.ndarray) -> None:
    xyz = np.stack([rec.rows["x"], rec.rows["y"], rec.rows["z"]], axis=1)
    xyz = xyz @ m[:3, :3].T + m[:3, 3]
    rec.rows["x"], rec.rows["y"], rec.rows["z"] = xyz[:, 0].copy(), xyz[:, 1].copy(), xyz[:, 2].copy()
