"""matsum: energies, momentum and rigid-body velocity per part.

Layout (l2a.c ``translate_matsum``; newer LS-DYNA versions append
``eroded_ie=``/``eroded_ke=``/``eroded_he=`` fields to the same lines)::

     time =   1.0000E-03
     mat.#=    1             inten=   8.0000E+02     kinen=   8.0000E+01
     x-mom=   0.0000E+00     y-mom=   0.0000E+00     z-mom=   0.0000E+00
     x-rbv=   0.0000E+00     y-rbv=   0.0000E+00     z-rbv=   0.0000E+00
                             hgeng=   0.0000E+00     +mass=   0.0000E+00

Values ``%13.4E`` (5 significant digits). LS-DYNA prints 0 as the
rigid-body velocity of deformable parts, and so does crashlite. The reader
takes every ``key=value`` pair, so extra fields of newer versions are read
too (``eroded_ie`` ...).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ._text import NUMBER, State, assemble, column, header, to_float

# field in the file -> Binout name, in the file's order
FIELDS = [
    ("inten", "internal_energy"),
    ("kinen", "kinetic_energy"),
    ("x-mom", "x_momentum"),
    ("y-mom", "y_momentum"),
    ("z-mom", "z_momentum"),
    ("x-rbv", "x_rbvelocity"),
    ("y-rbv", "y_rbvelocity"),
    ("z-rbv", "z_rbvelocity"),
    ("hgeng", "hourglass_energy"),
    ("+mass", "mass"),
]
_EXTRA = {
    "eroded_ie": "eroded_internal_energy",
    "eroded_ke": "eroded_kinetic_energy",
    "eroded_he": "eroded_hourglass_energy",
}
_PAIR = re.compile(r"([A-Za-z+][\w.#+-]*)\s*=\s*(" + NUMBER.pattern + ")", re.IGNORECASE)
_TIME = re.compile(r"^\s*time\s*=\s*(\S+)")


def write(path: Path, data: dict, title: str = "") -> Path:
    """``data``: ``time`` (n,), ``ids`` (m,) part IDs and Binout
    quantities (n, m); a missing quantity is written as NAN, a NaN
    rigid-body velocity (deformable part) as 0 as LS-DYNA does."""
    t = np.asarray(data["time"], float)
    ids = np.asarray(data["ids"], np.int64)
    n, m = len(t), len(ids)
    q = {name: column(data, name, n, m) for _, name in FIELDS}
    for a in "xyz":
        q[f"{a}_rbvelocity"] = np.nan_to_num(q[f"{a}_rbvelocity"], nan=0.0)
    has_mass = "mass" in data
    out = [header(title), "\n\n"]
    for i in range(n):
        out.append(f"\n\n time ={t[i]:13.4E}\n")
        for j, pid in enumerate(ids):
            v = {name: q[name][i, j] for _, name in FIELDS}
            out.append(f" mat.#={pid:5d}   " if pid < 100000 else f" mat.#={pid:8d}")
            out.append(f"          inten={v['internal_energy']:13.4E}     kinen={v['kinetic_energy']:13.4E}\n")
            out.append(
                f" x-mom={v['x_momentum']:13.4E}     y-mom={v['y_momentum']:13.4E}     z-mom={v['z_momentum']:13.4E}\n"
            )
            out.append(
                f" x-rbv={v['x_rbvelocity']:13.4E}     y-rbv={v['y_rbvelocity']:13.4E}"
                f"     z-rbv={v['z_rbvelocity']:13.4E}\n"
            )
            out.append(f"                         hgeng={v['hourglass_energy']:13.4E}     ")
            out.append(f"+mass={v['mass']:13.4E}\n" if has_mass else "\n")
    Path(path).write_text("".join(out))
    return Path(path)


def read(path: Path) -> dict:
    """Per-part quantities of a matsum file (crashlite's or LS-DYNA's)."""
    names = [name for _, name in FIELDS] + list(_EXTRA.values())
    index = {key: k for k, (key, _) in enumerate(FIELDS)} | {key: len(FIELDS) + k for k, key in enumerate(_EXTRA)}
    states: list[State] = []
    row = None
    for line in Path(path).read_text(errors="replace").splitlines():
        m = _TIME.match(line)
        if m:
            states.append(State(to_float(m.group(1)), [], []))
            row = None
            continue
        if not states:
            continue
        for key, value in _PAIR.findall(line):
            key = key.lower()
            if key == "mat.#":
                row = [np.nan] * len(names)
                states[-1].ids.append(int(to_float(value)))
                states[-1].values.append(row)
            elif row is not None and key in index:
                row[index[key]] = to_float(value)
    return assemble(states, names)
