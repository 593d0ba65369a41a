"""Pieces shared by the LS-DYNA ASCII history files: the two header lines,
number scanning that survives touching columns, and the assembly of
per-state rows into time-first arrays.

Every reader returns a dict of lasso-python Binout names: ``time``
(n_states,) float64, ``ids`` (n_ids,) int64 and each quantity
(n_states, n_ids) float64. Unknown values are written as ``NAN`` (what
C's and Python's ``%E`` print) and a quantity that is NaN in every state
is left out on reading, so a crashlite run and its files offer the same
quantities.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

# Fortran/C E-format, D exponents, the E-less 3-digit exponent Fortran
# prints for |exponent| > 99 ("1.2345-100"), integers, NAN/INF.
NUMBER = re.compile(
    r"[-+]?(?:(?:\d+\.\d*|\.\d+)(?:[EeDd][-+]?\d+|[-+]\d{3}(?!\d))?|\d+(?:[EeDd][-+]?\d+)?|nan|inf)", re.IGNORECASE
)
_BARE_EXP = re.compile(r"(\d)([-+]\d{3})$")
# "label.......  value" lines of glstat and deforc (labels may hold dots: "cycle.(nanosec)")
LABEL_LINE = re.compile(r"^\s*([A-Za-z+][\w /().#+-]*?)\s*\.{2,}\s*(\S+)(.*)$")


def to_float(token: str) -> float:
    t = token.replace("D", "E").replace("d", "e")
    if "E" not in t and "e" not in t and "." in t:
        t = _BARE_EXP.sub(r"\1E\2", t)
    return float(t)


def numbers(text: str) -> list[float]:
    """Every number of a line, also where fixed-width columns touch
    ("1.0000E+00-2.0000E+00")."""
    return [to_float(t) for t in NUMBER.findall(text)]


def header(title: str = "") -> str:
    """LS-DYNA's two header lines: title, then program and version."""
    from ... import __version__

    return f" {(title or 'crashlite run')[:72]}\n{'':25s}crashlite {__version__}\n"


def fmt(value: float, width: int, digits: int = 4) -> str:
    return f"{value:{width}.{digits}E}"


@dataclass
class State:
    """One output state while reading: ``ids`` (m,) int and ``values``
    (m, k) float64 in the order of the file's columns."""

    time: float
    ids: list
    values: list


def assemble(states: list[State], names: list[str], drop_partial_last: bool = True) -> dict:
    """Time-first arrays from the states of a file.

    An entity missing from a state reads NaN there; a last state with
    fewer entities than the one before (a file cut while being written)
    is dropped; quantities NaN everywhere are left out."""
    if drop_partial_last and len(states) > 1 and len(states[-1].ids) < len(states[-2].ids):
        states = states[:-1]
    k = len(names)
    if not states:
        return {}
    first = states[0].ids
    data = None
    if all(s.ids == first for s in states):  # the usual case: same entities in every state
        ids = list(first)
        if not ids:
            return {"time": np.array([s.time for s in states], float), "ids": np.zeros(0, np.int64)}
        try:
            data = np.array([np.asarray(s.values, float)[:, :k] for s in states])
        except ValueError:  # ragged rows: the general path below
            data = None
        if data is not None and data.ndim == 3 and data.shape[-1] < k:
            data = np.concatenate([data, np.full(data.shape[:2] + (k - data.shape[-1],), np.nan)], axis=2)
    if data is None or data.ndim != 3:
        ids = list(dict.fromkeys(i for s in states for i in s.ids))
        col = {i: j for j, i in enumerate(ids)}
        data = np.full((len(states), len(ids), k), np.nan)
        for n, s in enumerate(states):
            for i, row in zip(s.ids, s.values):
                row = list(row)[:k]
                data[n, col[i], : len(row)] = row
    out = {"time": np.array([s.time for s in states], float), "ids": np.array(ids, np.int64)}
    for q, name in enumerate(names):
        if name and not np.all(np.isnan(data[:, :, q])):
            out[name] = np.ascontiguousarray(data[:, :, q])
    return out


def have(a, n_states: int, n_ids: int | None = None) -> bool:
    """True when ``a`` holds data for every state (and every entity)."""
    a = np.asarray(a) if a is not None else np.zeros(0)
    if a.ndim == 0 or a.shape[0] != n_states or a.size == 0:
        return False
    return n_ids is None or (a.ndim >= 2 and a.shape[1] == n_ids)


def column(data: dict, key, n_states: int, n_ids: int) -> np.ndarray:
    """(n_states, n_ids) quantity of a category, NaN (unknown) when absent."""
    a = data.get(key)
    if a is None or not have(a, n_states, n_ids):
        return np.full((n_states, n_ids), np.nan)
    return np.asarray(a, float) + 0.0  # + 0.0: no "-0.0000E+00" in the files


def known_cycles(cycles: list[int]) -> np.ndarray | None:
    """Cycle numbers of the states, or None where the file carries none
    (several states all at cycle 0: the writer did not know them)."""
    c = np.array(cycles, np.int64)
    return None if len(c) == 0 or (len(c) > 1 and not c.any()) else c
