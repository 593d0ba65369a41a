"""Field states as VTK files ParaView opens (legacy format, one file per
state, and a .pvd collection carrying the times)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

_LINE, _TRI, _QUAD, _HEX = 3, 5, 9, 12


def cells(model) -> tuple[list[np.ndarray], list[int]]:
    """Connectivity rows and VTK cell types of the model's elements."""
    rows, types = [], []
    for t, kind in ((model.beams, _LINE), (model.discretes, _LINE)):
        if len(t):
            conn = t.nodes[:, :2]
            ok = np.all(conn >= 0, axis=1)
            rows += list(conn[ok])
            types += [kind] * int(ok.sum())
    s = model.shells
    for row in s.nodes:
        tri = row[3] == row[2]
        rows.append(row[:3] if tri else row)
        types.append(_TRI if tri else _QUAD)
    for row in model.solids.nodes:
        rows.append(row)
        types.append(_HEX)
    return rows, types


def write_states(directory, model, times: np.ndarray, coords: np.ndarray) -> Path:
    """``coords`` (n_states, n_nodes, 3). Returns the .pvd collection."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    rows, types = cells(model)
    x0 = model.nodes.xyz
    n = len(x0)
    size = sum(len(r) + 1 for r in rows)
    cell_text = "\n".join(f"{len(r)} " + " ".join(map(str, r)) for r in rows)
    type_text = "\n".join(map(str, types))
    entries = []
    for k, (t, x) in enumerate(zip(times, coords)):
        name = f"state_{k:04d}.vtk"
        disp = x - x0
        lines = ["# vtk DataFile Version 3.0", f"crashlite state {k} t={t:.9g}", "ASCII",
                 "DATASET UNSTRUCTURED_GRID", f"POINTS {n} double",
                 "\n".join(" ".join(f"{c:.9g}" for c in p) for p in x),
                 f"CELLS {len(rows)} {size}", cell_text, f"CELL_TYPES {len(rows)}", type_text,
                 f"POINT_DATA {n}", "VECTORS displacement double",
                 "\n".join(" ".join(f"{c:.9g}" for c in p) for p in disp)]
        (directory / name).write_text("\n".join(lines) + "\n")
        entries.append(f'    <DataSet timestep="{t:.9g}" file="{name}"/>')
    pvd = directory / "states.pvd"
    pvd.write_text('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n'
                   + "\n".join(entries) + "\n  </Collection>\n</VTKFile>\n")
    return pvd


def read_points(path) -> tuple[np.ndarray, np.ndarray]:
    """Points and displacement of a state file written by ``write_states``."""
    lines = Path(path).read_text().splitlines()
    i = next(k for k, ln in enumerate(lines) if ln.startswith("POINTS"))
    n = int(lines[i].split()[1])
    pts = np.array([[float(c) for c in ln.split()] for ln in lines[i + 1:i + 1 + n]])
    j = next(k for k, ln in enumerate(lines) if ln.startswith("VECTORS"))
    disp = np.array([[float(c) for c in ln.split()] for ln in lines[j + 1:j + 1 + n]])
    return pts, disp
