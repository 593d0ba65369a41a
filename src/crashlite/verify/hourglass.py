"""Hourglass energy against internal energy: the share a crash engineer
checks before trusting a run of one-point elements (the usual limit is
10 % of the internal energy, 5 % preferred).

The share over the run is taken only once the internal energy has reached
``FLOOR`` of its largest value: before that both are small and their
ratio says nothing about the run.
"""

from __future__ import annotations

import numpy as np

FLOOR = 0.1  # internal energy, as a fraction of its largest, from which the share counts


def hourglass_share(
    time: np.ndarray,
    internal: np.ndarray,
    hourglass: np.ndarray,
    part_ids: np.ndarray | None = None,
    part_internal: np.ndarray | None = None,
    part_hourglass: np.ndarray | None = None,
) -> dict:
    """The run's hourglass energy as a percentage of its internal energy:
    at the end (``end_percent``), its largest once the internal energy
    counts (``max_percent`` at ``max_time``) and, with the per-part
    energies (matsum), the part holding most hourglass energy at the end
    (``part``: its ID, hourglass energy and share of its own internal
    energy). Arrays are time-first as in Results; an empty hourglass
    history gives {}."""
    hg = np.asarray(hourglass, float)
    ie = np.asarray(internal, float)
    if hg.size == 0 or ie.size != hg.size or not np.any(ie > 0.0):
        return {}
    counts = ie >= FLOOR * ie.max()
    share = np.where(counts, 100.0 * hg / np.where(ie > 0.0, ie, 1.0), -np.inf)
    k = int(np.argmax(share))
    out = {
        "end_percent": float(100.0 * hg[-1] / ie[-1]) if ie[-1] > 0.0 else None,
        "max_percent": float(share[k]),
        "max_time": float(np.asarray(time)[k]),
    }
    if part_hourglass is not None and np.size(part_hourglass) and part_ids is not None:
        ph, pi = np.asarray(part_hourglass)[-1], np.asarray(part_internal)[-1]
        j = int(np.argmax(ph))
        out["part"] = {
            "id": int(np.asarray(part_ids)[j]),
            "hourglass": float(ph[j]),
            "percent_of_its_internal": float(100.0 * ph[j] / pi[j]) if pi[j] > 0.0 else None,
        }
    return out


def results_share(r) -> dict:
    """``hourglass_share`` of a Results (crashlite's run or one read back);
    {} when it has no hourglass history."""
    if not r.recorded("hourglass"):
        return {}
    parts = r.recorded("part_hourglass") and r.recorded("part_internal")
    return hourglass_share(
        r.time,
        r.internal,
        r.hourglass,
        r.part_ids if parts else None,
        r.part_internal if parts else None,
        r.part_hourglass if parts else None,
    )
