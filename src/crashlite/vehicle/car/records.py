"""Keyword records built in Python, complete as the reader builds them.

Every head field of the keyword's layout gets its schema default unless
given, and every row field a column, so a generated Model equals the
Model read back from its written deck (``keyword.equality``).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ...keyword.schema import FLOAT, INT, STR, Record, lookup


def _row_default(f):
    if f.default is not None:
        return f.default
    return "" if f.kind == STR else 0


def record(name: str, rows: dict | None = None, card_title: str | None = None, **values) -> Record:
    """A ``*NAME_OPTIONS`` record: head fields by name (others default),
    ``rows`` as columns by field name (missing columns default),
    ``card_title`` the title card of _TITLE keywords."""
    spec, options = lookup(name)
    if spec is None:
        raise ValueError(f"*{name} is not a keyword crashlite types")
    lay = spec.layout(options)
    vals = {f.name: f.default for c in lay.head for f in c.fields}
    unknown = set(values) - set(vals)
    if unknown:
        raise ValueError(f"*{name} has no field(s) {sorted(unknown)}")
    vals.update(values)
    cols = None
    if lay.row:
        rows = rows or {}
        fields = lay.row_fields
        unknown = set(rows) - {f.name for f in fields}
        if unknown:
            raise ValueError(f"*{name} has no row field(s) {sorted(unknown)}")
        n = len(next(iter(rows.values()))) if rows else 0
        cols = {}
        for f in fields:
            if f.name in rows:
                col = np.asarray(rows[f.name])
                if len(col) != n:
                    raise ValueError(f"*{name}: column {f.name} has {len(col)} rows, not {n}")
            else:
                col = np.full(n, _row_default(f), dtype=object if f.kind == STR else None)
            if f.kind == INT:
                col = col.astype(np.int64)
            elif f.kind == FLOAT:
                col = col.astype(np.float64)
            cols[f.name] = col
    elif rows:
        raise ValueError(f"*{name} has no row cards")
    if card_title is not None and "TITLE" not in options and not lay.title_card:
        raise ValueError(f"*{name} takes no title card; add _TITLE")
    return Record(spec.name, options, vals, cols, card_title)


def id_list(name: str, sid: int, members: ArrayLike, title: str | None = None, **values) -> Record:
    """A *SET_..._LIST(_TITLE) of ``members`` (IDs), eight per card."""
    m = np.asarray(members, np.int64).ravel()
    n = -(-len(m) // 8)
    pad = np.zeros(n * 8, np.int64)
    pad[: len(m)] = m
    cols = pad.reshape(n, 8)
    return record(name, card_title=title, rows={f"k{i + 1}": cols[:, i] for i in range(8)}, sid=sid, **values)
