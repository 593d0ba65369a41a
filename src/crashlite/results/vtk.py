"""Field states as VTK files ParaView opens (legacy format, one file per
state, and a .pvd collection carrying the times)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..model.model import Model

_LINE, _TRI, _QUAD, _HEX = 3, 5, 9, 12


def cells(model: Model) -> tuple[list[np.ndarray], list[int]]:
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


def element_field(model: Model, ids: dict, values: dict) -> np.ndarray:
    """(n_cells,) values in the order of ``cells``: for each element table
    name ("shells", "solids"), ``values[name]`` at the deck IDs
    ``ids[name]``; 0 for the elements without a value."""
    out = []
    for name in ("beams", "discretes", "shells", "solids"):
        t = getattr(model, name)
        col = np.zeros(len(t))
        if name in ids and len(ids[name]) and len(t):
            from ..model.mesh import index_map

            k = index_map(np.asarray(ids[name]))(t.ids)
            col = np.where(k >= 0, np.asarray(values[name])[np.maximum(k, 0)], 0.0)
        if name in ("beams", "discretes"):
            col = col[np.all(t.nodes[:, :2] >= 0, axis=1)] if len(t) else col
        out.append(col)
    return np.concatenate(out)


def write_states(
    directory: Path | str, model: Model, times: np.ndarray, coords: np.ndarray, last_cells: dict | None = None
) -> Path:
    """``coords`` (n_states, n_nodes, 3); ``last_cells``: name -> (n_cells,)
    element values (``element_field``) written with the last state. Returns
    the .pvd collection."""
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
        lines = [
            "# vtk DataFile Version 3.0",
            f"crashlite state {k} t={t:.9g}",
            "ASCII",
            "DATASET UNSTRUCTURED_GRID",
            f"POINTS {n} double",
            "\n".join(" ".join(f"{c:.9g}" for c in p) for p in x),
            f"CELLS {len(rows)} {size}",
            cell_text,
            f"CELL_TYPES {len(rows)}",
            type_text,
            f"POINT_DATA {n}",
            "VECTORS displacement double",
            "\n".join(" ".join(f"{c:.9g}" for c in p) for p in disp),
        ]
        if last_cells and k == len(times) - 1:
            lines.append(f"CELL_DATA {len(rows)}")
            for field_name, vals in last_cells.items():
                lines += [f"SCALARS {field_name} double 1", "LOOKUP_TABLE default", "\n".join(f"{c:.9g}" for c in vals)]
        (directory / name).write_text("\n".join(lines) + "\n")
        entries.append(f'    <DataSet timestep="{t:.9g}" file="{name}"/>')
    pvd = directory / "states.pvd"
    pvd.write_text(
        '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n'
        + "\n".join(entries)
        + "\n  </Collection>\n</VTKFile>\n"
    )
    return pvd


def read_points(path: Path | str) -> tuple[np.ndarray, np.ndarray]:
    """Points and displacement of a state file written by ``write_states``."""
    lines = Path(path).read_text().splitlines()
    i = next(k for k, ln in enumerate(lines) if ln.startswith("POINTS"))
    n = int(lines[i].split()[1])
    pts = np.array([[float(c) for c in ln.split()] for ln in lines[i + 1 : i + 1 + n]])
    j = next(k for k, ln in enumerate(lines) if ln.startswith("VECTORS"))
    disp = np.array([[float(c) for c in ln.split()] for ln in lines[j + 1 : j + 1 + n]])
    return pts, disp
