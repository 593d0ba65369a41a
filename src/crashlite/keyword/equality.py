"""Value-by-value equality of records and models (NaN equals NaN)."""

from __future__ import annotations

import math

import numpy as np


def _value_equal(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        return a == b or (math.isnan(a) and math.isnan(b))
    if isinstance(a, str) or isinstance(b, str):
        return (a or "") == (b or "") if (a is None or b is None) else a == b
    return a == b


def _column_equal(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape:
        return False
    if a.dtype.kind == "f" or b.dtype.kind == "f":
        return np.array_equal(a.astype(float), b.astype(float), equal_nan=True)
    if a.dtype == object or b.dtype == object:
        return all(_value_equal(x, y) for x, y in zip(a, b))
    return np.array_equal(a, b)


def records_equal(a, b) -> bool:
    if (a.keyword, a.options) != (b.keyword, b.options):
        return False
    if (a.title or "") != (b.title or ""):
        return False
    if a.values.keys() != b.values.keys():
        return False
    if not all(_value_equal(a.values[k], b.values[k]) for k in a.values):
        return False
    if (a.rows is None) != (b.rows is None):
        return False
    if a.rows is not None:
        if a.rows.keys() != b.rows.keys():
            return False
        return all(_column_equal(a.rows[k], b.rows[k]) for k in a.rows)
    return True


def _raw_key(raw):
    """A verbatim keyword's content, independent of how its format was marked."""
    rest = raw.keyword_line.split(None, 1)[1:] or [""]
    return raw.keyword, rest[0].rstrip(), raw.mode, [ln.rstrip() for ln in raw.lines]


def model_differences(a, b) -> list[str]:
    """What differs between two models (empty: equal)."""
    from ..model.model import ENTITY_GROUPS, MESH_TABLES
    from .schema import RawKeyword

    out = []
    for t in MESH_TABLES:
        if not getattr(a, t).equals(getattr(b, t)):
            out.append(f"{t} differ")
    for g in (*ENTITY_GROUPS, "sets"):
        da, db = getattr(a, g), getattr(b, g)
        if da.keys() != db.keys():
            out.append(f"{g}: IDs differ ({sorted(set(da) ^ set(db))[:10]})")
            continue
        for k in da:
            if not records_equal(da[k], db[k]):
                out.append(f"{g}[{k}] differs")
    ka, kb = a.keywords, b.keywords
    if len(ka) != len(kb):
        out.append(f"keywords: {len(ka)} vs {len(kb)}")
    else:
        for x, y in zip(ka, kb):
            if isinstance(x, RawKeyword) and isinstance(y, RawKeyword):
                if _raw_key(x) != _raw_key(y):
                    out.append(f"verbatim *{x.keyword} differs")
            elif type(x) is not type(y) or not records_equal(x, y):
                out.append(f"*{getattr(x, 'name', x.keyword)} differs from *{getattr(y, 'name', y.keyword)}")
    return out


def models_equal(a, b) -> bool:
    return not model_differences(a, b)
