"""Members of *SET_* keywords: LIST, GENERATE and ADD resolved to deck IDs."""

from __future__ import annotations

import numpy as np


def set_members(model, kind: str, sid: int, _seen: frozenset = frozenset()) -> np.ndarray:
    """Sorted unique deck IDs of set ``sid`` of ``kind`` (NODE, PART, SHELL, ...).

    Raises KeyError for an undefined set and ValueError for an ADD cycle.
    """
    key = (kind, sid)
    if key not in model.sets:
        raise KeyError(f"*SET_{kind} {sid} is not defined")
    if key in _seen:
        raise ValueError(f"*SET_{kind}_ADD {sid} includes itself")
    rec = model.sets[key]
    rows = rec.rows or {}
    if kind == "SEGMENT":
        return np.stack([rows[f"n{i}"] for i in range(1, 5)], axis=1) if rows else np.zeros((0, 4), int)
    if "GENERATE" in rec.options:
        out = []
        for i in range(1, 5):
            beg, end = rows.get(f"b{i}beg"), rows.get(f"b{i}end")
            if beg is None:
                continue
            for b, e in zip(beg, end):
                if b > 0 and e >= b:
                    out.append(np.arange(b, e + 1))
        ids = np.concatenate(out) if out else np.zeros(0, np.int64)
    else:
        cols = [np.asarray(rows[f"k{i}"]) for i in range(1, 9) if f"k{i}" in rows]
        ids = np.concatenate(cols) if cols else np.zeros(0, np.int64)
        ids = ids[ids > 0]
        if "ADD" in rec.options:
            subs = [set_members(model, kind, int(s), _seen | {key}) for s in ids]
            ids = np.concatenate(subs) if subs else np.zeros(0, np.int64)
    return np.unique(ids.astype(np.int64))


def history_nodes(model) -> np.ndarray:
    """Sorted node indices that *DATABASE_HISTORY_NODE asks nodout for: IDs
    (eight per row, or one per _ID row) and, with _SET, the members of the
    node sets."""
    out = []
    for rec in model.find("DATABASE_HISTORY_NODE"):
        ids = [np.asarray(v, np.int64).ravel() for k, v in (rec.rows or {}).items() if k.startswith("id")]
        ids = np.concatenate(ids) if ids else np.zeros(0, np.int64)
        ids = ids[ids > 0]
        if "SET" in rec.options:
            ids = np.concatenate([set_members(model, "NODE", int(s)) for s in ids] or [np.zeros(0, np.int64)])
        out.append(model.node_index(ids))
    idx = np.concatenate(out) if out else np.zeros(0, np.int64)
    return np.unique(idx[idx >= 0]).astype(np.int64)
