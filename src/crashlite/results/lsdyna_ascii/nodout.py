"""nodout: displacement, velocity, acceleration and coordinates of the
history nodes (*DATABASE_HISTORY_NODE).

Layout (l2a.c ``translate_nodout2``, the file LS-DYNA itself writes)::

    (3 blank lines)
     n o d a l   p r i n t   o u t   f o r   t i m e  s t e p       1 ... ( at time 0.0000000E+00 )
    (blank)
     nodal point  x-disp     y-disp      z-disp      x-vel  ...  z-coor
            2  1.0000E+00  0.0000E+00 ...

Rows ``%9d%13.4E`` then 11 × ``%12.4E`` (5 significant digits): the
columns scripts cut at [0:9], [9:22], [22:34] ... Models with rotational
DOFs get a second block with the same time whose columns are ``x-rot`` ...
``z-rot acc``. A quantity crashlite does not have is written as NAN.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ._text import NUMBER, State, assemble, column, header, known_cycles, to_float

_AXES = "xyz"
TRANSLATION = (
    [f"{a}_displacement" for a in _AXES]
    + [f"{a}_velocity" for a in _AXES]
    + [f"{a}_acceleration" for a in _AXES]
    + [f"{a}_coordinate" for a in _AXES]
)
ROTATION = (
    [f"r{a}_displacement" for a in _AXES] + [f"r{a}_velocity" for a in _AXES] + [f"r{a}_acceleration" for a in _AXES]
)
_COLUMNS = (
    " nodal point  x-disp     y-disp      z-disp      x-vel       y-vel       z-vel      "
    "x-accl      y-accl      z-accl      x-coor      y-coor      z-coor\n"
)
_ROW = "%9d%13.4E" + "%12.4E" * 11 + "\n"
_HEAD = re.compile(r"t\s*i\s*m\s*e\s+s\s*t\s*e\s*p\s*(\d+)\s*\(\s*at\s+time\s*(" + NUMBER.pattern + r")", re.IGNORECASE)


def write(path: Path, data: dict, title: str = "") -> Path:
    """``data``: ``time`` (n,), ``ids`` (m,) node IDs, Binout quantities
    (n, m) of ``TRANSLATION``; optional ``cycle`` (n,) int."""
    t = np.asarray(data["time"], float)
    ids = np.asarray(data["ids"], np.int64).tolist()
    n, m = len(t), len(ids)
    cycle = np.asarray(data.get("cycle", np.zeros(n)), np.int64)
    block = np.stack([column(data, name, n, m) for name in TRANSLATION], axis=2)  # (n, m, 12)
    out = [header(title), "\n\n"]
    for i in range(n):
        out.append(
            f"\n\n\n n o d a l   p r i n t   o u t   f o r   t i m e  s t e p{int(cycle[i]):8d}"
            f"                              ( at time{t[i]:14.7E} )\n\n"
        )
        out.append(_COLUMNS)
        out.append("".join(_ROW % (nid, *row) for nid, row in zip(ids, block[i].tolist())))
    Path(path).write_text("".join(out))
    return Path(path)


def read(path: Path) -> dict:
    """Quantities of a nodout file (crashlite's or LS-DYNA's); rotational
    blocks give ``rx_displacement`` ... ``rz_acceleration``."""
    trans: list[State] = []
    rot: list[State] = []
    target = None
    cycles = []
    key = None
    for line in Path(path).read_text(errors="replace").splitlines():
        m = _HEAD.search(line)
        if m:
            key = (int(m.group(1)), to_float(m.group(2)))
            target = None
            continue
        if key is None:
            continue
        low = line.lower()
        if "nodal point" in low:
            if "rot" in low:  # the rotational block of the state just read
                rot.append(State(key[1], [], []))
                target = rot[-1]
            else:
                trans.append(State(key[1], [], []))
                cycles.append(key[0])
                target = trans[-1]
            continue
        if target is None:
            continue
        tokens = NUMBER.findall(line)
        if len(tokens) < 2 or not tokens[0].isdigit():  # blank line or the next header
            continue
        target.ids.append(int(tokens[0]))
        target.values.append([to_float(v) for v in tokens[1:]])
    out = assemble(trans, TRANSLATION)
    if out and known_cycles(cycles[: len(out["time"])]) is not None:
        out["cycle"] = known_cycles(cycles[: len(out["time"])])
    if rot:
        r = assemble(rot, ROTATION)
        n = min(len(r.get("time", [])), len(out.get("time", [])))
        if n and np.array_equal(r["ids"], out["ids"]):
            out = {k: (v[:n] if k not in ("ids",) else v) for k, v in out.items()}
            out.update({k: v[:n] for k, v in r.items() if k not in ("time", "ids")})
    return out
