"""rcforc: resultant contact force of each contact interface, its slave
side and its master side.

Layout (l2a.c ``translate_rcforc``, the file LS-DYNA itself writes)::

      slave           1 time 1.00000E-03  x -2.30000E+03  y  0.00000E+00  z  0.00000E+00 mass  1.00000E-03
      master          1 time 1.00000E-03  x  2.30000E+03  y  0.00000E+00  z  0.00000E+00 mass  2.00000E-03

one line per side, interface and state: ``  slave %11d time%12.5E``
(``  master%11d``), then label and ``%12.5E`` value pairs ``x``, ``y``,
``z``, ``mass`` (the mass of the nodes in contact), optionally ``mx``
``my`` ``mz`` (moments) and ``tied`` ``tied area``. The interface number is
the contact's ID (``_ID``) or its place among the deck's contacts
(``model.contacts``). Single surface contacts get no line ("... is single
surface-resultants are undefined": their forces cancel) and are skipped on
reading.

As in lasso-python's Binout, every line is a column: ``ids`` (n_lines,)
holds each interface twice, ``side`` (n_lines,) 0 for its slave and 1 for
its master line, and ``x_force`` ... (n_states, n_lines).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ._text import NUMBER, State, assemble, column, header, to_float

NAMES = ["x_force", "y_force", "z_force", "mass"]
MOMENTS = ["x_moment", "y_moment", "z_moment"]
_LABELS = dict(zip(["x", "y", "z", "mass", "mx", "my", "mz"], NAMES + MOMENTS))  # tied, tied area: not read
_SIDES = ("slave", "master")
_LINE = re.compile(r"^\s*(slave|master)\s*(\d+)\s+time\s*(" + NUMBER.pattern + r")(.*)$", re.IGNORECASE)
_PAIR = re.compile(r"([a-z]+(?: area)?)\s*(" + NUMBER.pattern + r")", re.IGNORECASE)


def write(path: Path, data: dict, title: str = "") -> Path:
    """``data``: ``time`` (n,), ``ids`` (m,) interface of each line,
    ``side`` (m,) 0 slave / 1 master, quantities of ``NAMES`` (n, m)
    (an unknown mass is written as NAN); moments when ``x_moment`` is given."""
    t = np.asarray(data["time"], float)
    ids = np.asarray(data["ids"], np.int64).tolist()
    side = np.asarray(data.get("side", np.zeros(len(ids))), np.int64).tolist()
    n, m = len(t), len(ids)
    names = NAMES + (MOMENTS if "x_moment" in data else [])
    q = np.stack([column(data, name, n, m) for name in names], axis=2) if m else np.zeros((n, 0, len(names)))
    row = "  %-6s%11d time%12.5E  x %12.5E  y %12.5E  z %12.5E mass %12.5E"
    row += "  mx %12.5E  my %12.5E  mz %12.5E\n" if len(names) > len(NAMES) else "\n"
    out = [header(title), "\n\n"]
    for i in range(n):
        out.append("".join(row % (_SIDES[s], c, t[i], *v) for c, s, v in zip(ids, side, q[i].tolist())))
    Path(path).write_text("".join(out))
    return Path(path)


def read(path: Path) -> dict:
    """Quantities of an rcforc file (crashlite's or LS-DYNA's); a state
    ends where a line of the same side and interface comes again or the
    time changes."""
    states: list[State] = []
    for line in Path(path).read_text(errors="replace").splitlines():
        m = _LINE.match(line)
        if not m:
            continue
        key = 2 * int(m.group(2)) + _SIDES.index(m.group(1).lower())  # one column per side and interface
        t = to_float(m.group(3))
        if not states or key in states[-1].ids or t != states[-1].time:
            states.append(State(t, [], []))
        row = [np.nan] * (len(NAMES) + len(MOMENTS))
        for label, value in _PAIR.findall(m.group(4)):
            name = _LABELS.get(label.lower())
            if name is not None:
                row[(NAMES + MOMENTS).index(name)] = to_float(value)
        states[-1].ids.append(key)
        states[-1].values.append(row)
    out = assemble(states, NAMES + MOMENTS)
    if out:
        keys = out.pop("ids")
        out["ids"], out["side"] = keys // 2, keys % 2
    return out
