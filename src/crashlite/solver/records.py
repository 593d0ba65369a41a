"""Reading a deck's records for the solver's setup stages: a problem that
names a record's card, a load curve with its scale factors and offsets, the
node indices of a node set, and the file and line of an element's row.

Shared by ``setup`` and the modules it builds with (``loads``, ``initial``,
``boundary``, ``discretes``, ``nodal_bodies``, ``massless``), so these live
below all of them.
"""

from __future__ import annotations

from pathlib import Path

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


def row_line(model: Model, keyword: str, eid: int) -> tuple[str, int]:
    """(file, line) of the row of element ``eid`` under a ``*keyword`` card
    (any of its options) in the files of the model, for messages; (source, 0)
    when not found. Only called when there is something to report."""
    for f in model.files or [model.source or ""]:
        try:
            lines = Path(f).read_text(errors="replace").splitlines()
        except OSError:
            continue
        inside = False
        for k, ln in enumerate(lines, 1):
            if ln.startswith("*"):
                inside = ln[1:].strip().upper().startswith(keyword)
                continue
            if not inside or ln.startswith("$") or not ln.strip():
                continue
            first = ln.replace(",", " ").split()[0] if "," in ln else ln[:8].strip()
            for cand in (first, ln[:10].strip(), ln[:20].strip()):
                try:
                    if int(cand) == eid:
                        return str(f), k
                except ValueError:
                    pass
    return str(model.source or ""), 0
