"""spcforc: reaction forces (and moments) at constrained nodes.

Layout (l2a.c ``translate_spcforc``)::

     single point constraint forces

     output at time =   1.00000E-03
     node=       1 local x,y,z forces =   -2.3000E+03    0.0000E+00    0.0000E+00
     node=       1 local x,y,z moments=    0.0000E+00    0.0000E+00    0.0000E+00
                 force resultants   =   -2.3000E+03    0.0000E+00    0.0000E+00

``%8d`` node IDs, ``%14.4E`` values (5 significant digits), nodes in
increasing order, translations before moments. Newer LS-DYNA versions
append a set ID to node lines; the reader takes the three numbers after
``=``. A node listed twice in a state (two constraint sets) gets the sum.
Binout names: ``ids`` (= ``force_ids``), ``x_force`` ..., ``moment_ids``,
``x_moment`` ..., ``x_resultant`` ... (n_states,).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ._text import NUMBER, State, assemble, column, header, to_float

_N = "(" + NUMBER.pattern + ")"
_NODE = re.compile(
    r"node\s*=\s*(\d+)\s+local\s+x,y,z\s+(forces|moments)\s*=\s*" + _N + r"\s*" + _N + r"\s*" + _N, re.IGNORECASE
)
_TIME = re.compile(r"output\s+at\s+time\s*=\s*" + _N, re.IGNORECASE)
_RESULTANT = re.compile(r"force\s+resultants\s*=\s*" + _N + r"\s*" + _N + r"\s*" + _N, re.IGNORECASE)
FORCES = ["x_force", "y_force", "z_force"]
MOMENTS = ["x_moment", "y_moment", "z_moment"]


def write(path: Path, data: dict, title: str = "") -> Path:
    """``data``: ``time`` (n,), ``ids`` (m,) node IDs, ``x_force`` ...
    (n, m); optional ``moment_ids`` (k,) with ``x_moment`` ... (n, k).
    The resultants are the sums of the forces."""
    t = np.asarray(data["time"], float)
    ids = np.asarray(data["ids"], np.int64)
    n, m = len(t), len(ids)
    f = np.stack([column(data, name, n, m) for name in FORCES], axis=2)  # (n, m, 3)
    mids = np.asarray(data.get("moment_ids", np.zeros(0)), np.int64)
    mom = np.stack([column(data, name, n, len(mids)) for name in MOMENTS], axis=2)
    # nodes in increasing order, translations before moments (as LS-DYNA)
    order = sorted([(int(i), 0, j) for j, i in enumerate(ids)] + [(int(i), 1, j) for j, i in enumerate(mids)])
    total = f.sum(axis=1)
    out = [header(title), " single point constraint forces\n\n"]
    for s in range(n):
        out.append(f" output at time ={t[s]:14.5E}\n")
        for nid, kind, j in order:
            v = (f if kind == 0 else mom)[s, j]
            word = "forces =" if kind == 0 else "moments="
            out.append(f" node={nid:8d} local x,y,z {word}{v[0]:14.4E}{v[1]:14.4E}{v[2]:14.4E}\n")
        out.append(f"             force resultants   ={total[s, 0]:14.4E}{total[s, 1]:14.4E}{total[s, 2]:14.4E}\n")
    Path(path).write_text("".join(out))
    return Path(path)


def read(path: Path) -> dict:
    """Reactions of an spcforc file (crashlite's or LS-DYNA's)."""
    forces: list[State] = []
    moments: list[State] = []
    resultants: list[list[float]] = []

    def add(state: State, nid: int, values: list[float]):
        if nid in state.ids:  # a second constraint set on the node
            k = state.ids.index(nid)
            state.values[k] = [a + b for a, b in zip(state.values[k], values)]
        else:
            state.ids.append(nid)
            state.values.append(values)

    for line in Path(path).read_text(errors="replace").splitlines():
        m = _TIME.search(line)
        if m:
            t = to_float(m.group(1))
            forces.append(State(t, [], []))
            moments.append(State(t, [], []))
            resultants.append([np.nan] * 3)
            continue
        if not forces:
            continue
        m = _NODE.search(line)
        if m:
            add(
                forces[-1] if m.group(2).lower() == "forces" else moments[-1],
                int(m.group(1)),
                [to_float(m.group(k)) for k in (3, 4, 5)],
            )
            continue
        m = _RESULTANT.search(line)
        if m:
            resultants[-1] = [to_float(m.group(k)) for k in (1, 2, 3)]
    out = assemble(forces, FORCES)
    if not out:
        return {}
    n = len(out["time"])
    out["force_ids"] = out["ids"]
    if any(s.ids for s in moments):
        mo = assemble(moments[:n], MOMENTS, drop_partial_last=False)
        out["moment_ids"] = mo["ids"]
        out.update({k: v for k, v in mo.items() if k in MOMENTS})
    r = np.array(resultants[:n], float)
    for k, a in enumerate("xyz"):
        if not np.all(np.isnan(r[:, k])):
            out[f"{a}_resultant"] = r[:, k]
    return out
