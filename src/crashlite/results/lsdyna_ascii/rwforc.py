"""rwforc: resultant force of the nodes on each rigid wall.

Layout (l2a.c ``translate_rwforc``)::

        time       wall#   normal-force    x-force        y-force        z-force
     1.00000E-03       1   2.300000E+05  -2.300000E+05   0.000000E+00   0.000000E+00

one row per wall and state, ``%12.5E%8d`` then 4 × ``%15.6E``; LS-DYNA
writes the column header once (again before each state when force
transducers add their own block). Segment rows (``seg#``), ``total force``
rows and transducer blocks are skipped on reading. Quantities live under
the Binout group ``forces``: ``read("rwforc", "forces", "x_force")``.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ._text import NUMBER, State, assemble, column, header, to_float

GROUP = "forces"
NAMES = ["normal_force", "x_force", "y_force", "z_force"]
_COLUMNS = "    time       wall#   normal-force    x-force        y-force        z-force\n"
_ROW = re.compile(
    r"^\s*(" + NUMBER.pattern + r")\s+(\d+)\s+((?:" + NUMBER.pattern + r")(?:\s*(?:" + NUMBER.pattern + r")){3})\s*$",
    re.IGNORECASE,
)


def write(path: Path, data: dict, title: str = "") -> Path:
    """``data``: keys ``("forces", name)``: ``time`` (n,), ``ids`` (m,)
    wall IDs, ``normal_force``, ``x_force`` ... (n, m)."""
    g = {k[1]: v for k, v in data.items() if isinstance(k, tuple) and k[0] == GROUP}
    t = np.asarray(g["time"], float)
    ids = np.asarray(g["ids"], np.int64).tolist()
    n, m = len(t), len(ids)
    q = np.stack([column(g, name, n, m) for name in NAMES], axis=2)  # (n, m, 4)
    out = [header(title), "\n\n", "\n\n", _COLUMNS]
    for i in range(n):
        out.append(
            "".join("%12.5E%8d%15.6E%15.6E%15.6E%15.6E\n" % (t[i], w, *row) for w, row in zip(ids, q[i].tolist()))
        )
    Path(path).write_text("".join(out))
    return Path(path)


def read(path: Path) -> dict:
    """``{("forces", name): array}`` of an rwforc file; a state ends where
    a wall comes again."""
    states: list[State] = []
    for line in Path(path).read_text(errors="replace").splitlines():
        m = _ROW.match(line)
        if not m:
            continue
        t, wall = to_float(m.group(1)), int(m.group(2))
        values = [to_float(v) for v in NUMBER.findall(m.group(3))]
        if not states or wall in states[-1].ids or t != states[-1].time:
            states.append(State(t, [], []))
        states[-1].ids.append(wall)
        states[-1].values.append(values)
    return {(GROUP, k): v for k, v in assemble(states, NAMES).items()}
