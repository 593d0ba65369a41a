"""secforc: resultant force and moment through cross sections
(*DATABASE_CROSS_SECTION).

Layout (l2a.c ``translate_secforc``)::

     line#1  section#     time        x-force     y-force     z-force    magnitude
     line#2  resultant  moments       x-moment    y-moment    z-moment   magnitude
     line#3  centroids                x           y           z            area
               7    1.00000E-03    -2.3000E+03  0.0000E+00  0.0000E+00  2.3000E+03
    global system                   0.0000E+00  0.0000E+00  0.0000E+00  0.0000E+00
                                    0.0000E+00  0.0000E+00  0.0000E+00  0.0000E+00
    (blank)

three lines per section and state: ``%12d%15.5E`` then ``%15.4E`` and
3 × ``%12.4E`` (5 significant digits); line 2 starts with the system
(``global system``, ``rb ID =``, ``ac ID =``, ``cs ID =``). Centroid and
area crashlite does not compute are written as NAN.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ._text import NUMBER, State, assemble, column, header, to_float

NAMES = [
    "x_force",
    "y_force",
    "z_force",
    "total_force",
    "x_moment",
    "y_moment",
    "z_moment",
    "total_moment",
    "x_centroid",
    "y_centroid",
    "z_centroid",
    "area",
]
_HEAD = (
    " line#1  section#     time        x-force     y-force     z-force    magnitude\n"
    " line#2  resultant  moments       x-moment    y-moment    z-moment   magnitude\n"
    " line#3  centroids                x           y           z            area  \n"
)
_BLOCK = (
    "%12d%15.5E%15.4E%12.4E%12.4E%12.4E\n"
    "global system              %15.4E%12.4E%12.4E%12.4E\n"
    "                           %15.4E%12.4E%12.4E%12.4E\n\n"
)


def write(path: Path, data: dict, title: str = "") -> Path:
    """``data``: ``time`` (n,), ``ids`` (m,) section IDs, quantities of
    ``NAMES`` (n, m); a missing magnitude is the norm of its components."""
    t = np.asarray(data["time"], float)
    ids = np.asarray(data["ids"], np.int64).tolist()
    n, m = len(t), len(ids)
    q = {name: column(data, name, n, m) for name in NAMES}
    for kind in ("force", "moment"):
        if f"total_{kind}" not in data:
            q[f"total_{kind}"] = np.sqrt(sum(q[f"{a}_{kind}"] ** 2 for a in "xyz"))
    block = np.stack([q[name] for name in NAMES], axis=2)  # (n, m, 12)
    out = [header(title), "\n\n", "\n\n", _HEAD]
    for i in range(n):
        out.append("".join(_BLOCK % (s, t[i], *v) for s, v in zip(ids, block[i].tolist())))
    Path(path).write_text("".join(out))
    return Path(path)


def read(path: Path) -> dict:
    """Quantities of a secforc file (crashlite's or LS-DYNA's): a force
    line (ID, time, 4 numbers), then the moment line (its last 4 numbers),
    then the centroid line (4 numbers)."""
    states: list[State] = []
    row = None
    expect = 0  # lines still owed to the current section: 2 moment, 1 centroid
    for line in Path(path).read_text(errors="replace").splitlines():
        tokens = NUMBER.findall(line)
        if not tokens or line.lstrip().startswith("line#"):
            continue
        if expect and len(tokens) >= 4 and (expect == 2 or len(tokens) == 4):
            row[4 * (3 - expect) : 4 * (4 - expect)] = [to_float(v) for v in tokens[-4:]]
            expect -= 1
            continue
        if len(tokens) == 6 and tokens[0].isdigit():
            sid, t = int(tokens[0]), to_float(tokens[1])
            if not states or sid in states[-1].ids or t != states[-1].time:
                states.append(State(t, [], []))
            row = [to_float(v) for v in tokens[2:]] + [np.nan] * 8
            states[-1].ids.append(sid)
            states[-1].values.append(row)
            expect = 2
        else:
            expect = 0
    return assemble(states, NAMES)
