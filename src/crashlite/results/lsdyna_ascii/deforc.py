"""deforc: force and elongation of discrete elements (springs, dampers).

Layout (l2a.c ``translate_deforc``)::

     time.........................   1.00000E-03
     spring/damper number.........         1
     x-force......................  -2.30000E+03
     y-force......................   0.00000E+00
     z-force......................   0.00000E+00
     resultant force..............  -2.30000E+03
     change in length.............  -1.20000E+01

labels padded with dots to 29 characters, ``%14.5E`` values (6
significant digits), ``%10d`` IDs. Rotational elements print ``x-moment``
... ``relative rotation``; as in the Binout they are read into the same
names (``x_force`` ... ``displacement``) and flagged by ``irot`` (n_ids,).
The resultant is the signed axial force (tension positive).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ._text import LABEL_LINE, State, assemble, column, header, to_float

NAMES = ["x_force", "y_force", "z_force", "resultant_force", "displacement"]
_LABELS = ["x-force", "y-force", "z-force", "resultant force", "change in length"]
_ROT_LABELS = ["x-moment", "y-moment", "z-moment", "resultant moment", "relative rotation"]
_INDEX = {label: k for k, label in enumerate(_LABELS)} | {label: k for k, label in enumerate(_ROT_LABELS)}


def write(path: Path, data: dict, title: str = "") -> Path:
    """``data``: ``time`` (n,), ``ids`` (m,) element IDs, quantities of
    ``NAMES`` (n, m); missing components are written as NAN."""
    t = np.asarray(data["time"], float)
    ids = np.asarray(data["ids"], np.int64).tolist()
    n, m = len(t), len(ids)
    q = np.stack([column(data, name, n, m) for name in NAMES], axis=2)  # (n, m, 5)
    rows = "".join(f" {label}{'.' * (29 - len(label))}%14.5E\n" for label in _LABELS)
    row = " spring/damper number.........%10d\n" + rows
    out = [header(title)]
    for i in range(n):
        out.append(f"\n time.........................{t[i]:14.5E}\n")
        out.append("".join(row % (e, *v) for e, v in zip(ids, q[i].tolist())))
    Path(path).write_text("".join(out))
    return Path(path)


def read(path: Path) -> dict:
    """Quantities of a deforc file (crashlite's or LS-DYNA's)."""
    states: list[State] = []
    rot: dict[int, int] = {}
    row = None
    for line in Path(path).read_text(errors="replace").splitlines():
        m = LABEL_LINE.match(line)
        if not m:
            continue
        label = " ".join(m.group(1).split())
        try:
            value = to_float(m.group(2))
        except ValueError:
            continue
        if label == "time":
            states.append(State(value, [], []))
            row = None
        elif label == "spring/damper number" and states:
            row = [np.nan] * len(NAMES)
            states[-1].ids.append(int(value))
            states[-1].values.append(row)
        elif row is not None and label in _INDEX:
            row[_INDEX[label]] = value
            if label in _ROT_LABELS:
                rot[states[-1].ids[-1]] = 1
    out = assemble(states, NAMES)
    if out:
        out["irot"] = np.array([rot.get(int(e), 0) for e in out["ids"]], np.int64)
    return out
