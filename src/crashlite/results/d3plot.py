"""Field states as an LS-DYNA d3plot, written through lasso-python (the
``lsdyna`` extra); beside the VTK states, for LS-PrePost and the tools that
read LS-DYNA's binary database.

What is written (single precision, as LS-DYNA's d3plot):
  geometry: the deck's node IDs and coordinates; shells, solids and beams
  (discrete elements too, as LS-DYNA writes them) with their element IDs
  and parts (part IDs and titles);
  per state: the time; the nodes' current coordinates (d3plot's
  "displacement" field holds the coordinates, as LS-DYNA writes it),
  velocities and accelerations; the shells' stresses (global axes) and
  effective plastic strains through the thickness as LS-DYNA's MAXINT = 3
  output (mid-surface, inner and outer surface: the innermost and outermost
  integration points, the mid-surface one the average of the two central
  points of an even NIP) and their thickness; the solids' stress (global
  axes) and effective plastic strain; the discrete elements' axial force
  (tension positive; in the beams' axial-force field); which shells and
  solids are deleted (eroded, collapsed); the kinetic, internal and total
  energy, from the run's history at the states' times.
Shells and solids of rigid parts, and beams, carry zeros (the geometry and
motion only).

Velocities and accelerations at a state are those of the time histories
(nodout): the mean of the half-step velocities either side of it and their
difference over the step. ``state`` takes an element state in the time loop
(with the half-step velocity before it), ``complete`` gives it the velocity
after it; ``write`` writes the file. lasso-python is imported by ``write``
(and ``lasso``) only.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..model.model import Model
    from ..solver.groups import ElementGroup

MISSING = "d3plot needs lasso-python: pip install crashlite[lsdyna]"
LAYERS = 3  # shell layers written: mid-surface, inner, outer (LS-DYNA's MAXINT = 3)


def lasso() -> tuple[type, type] | None:
    """(D3plot, ArrayType) of lasso-python, or None where it is missing."""
    try:
        from lasso.dyna import ArrayType, D3plot
    except ImportError:
        return None
    return D3plot, ArrayType


# --- in the time loop ------------------------------------------------------------------------------------


def state(groups: Iterable[ElementGroup], x: np.ndarray, v: np.ndarray) -> dict:
    """The fields of one state of the time loop at positions ``x``, ``v``
    the half-step velocity before it (``complete`` adds the one after):
    float32 arrays by element group (deformable shells and solids, discrete
    elements), rows as the groups' ``ids``."""
    out = {"v_before": v.copy(), "velocity": v.astype(np.float32), "acceleration": np.zeros(v.shape, np.float32)}
    for g in groups:
        if not len(g):
            continue
        if g.kind == "shell":
            nip = g.s.nip
            out["shell"] = dict(
                ids=g.ids,
                stress=_shell_global(_layers(g.st.sig, nip), x, g.conn).astype(np.float32),
                plastic_strain=_layers(g.st.epsp, nip).astype(np.float32),
                thickness=g.st.thick.astype(np.float32),
                alive=(g.st.alive == 1).astype(np.float32),
            )
        elif g.kind == "solid":
            out["solid"] = dict(
                ids=g.ids,
                stress=g.st.sig.astype(np.float32),
                plastic_strain=g.st.epsp.astype(np.float32),
                alive=(g.st.alive == 1).astype(np.float32),
            )
        elif g.kind == "discrete":
            out["discrete"] = dict(ids=g.ids, axial_force=g.force.astype(np.float32))
    return out


def _layers(a: np.ndarray, nip: np.ndarray) -> np.ndarray:
    """(n, LAYERS, ...) of a through-thickness field (n, nip_max, ...),
    points from the bottom up: the mid-surface (the central point of an odd
    NIP, the mean of the two central ones of an even NIP), the innermost and
    the outermost point."""
    k = np.arange(len(a))
    nip = np.maximum(np.asarray(nip), 1)
    lo, hi = (nip - 1) // 2, nip // 2
    return np.stack([0.5 * (a[k, lo] + a[k, hi]), a[:, 0], a[k, nip - 1]], axis=1)


def complete(fields: dict, v: np.ndarray, dt_v: float, before: float) -> None:
    """The velocity and acceleration of a state from the half-step
    velocities either side of it, ``dt_v`` apart; the state lies
    ``before`` after the first (``dt_v / 2``: their mean; 0: the first,
    the initial velocity at t = 0)."""
    v0 = fields.pop("v_before")
    a = (v - v0) / dt_v if dt_v > 0 else np.zeros_like(v)
    fields["acceleration"] = a.astype(np.float32)
    fields["velocity"] = (v0 + before * a).astype(np.float32)


def _shell_global(sig: np.ndarray, x: np.ndarray, conn: np.ndarray) -> np.ndarray:
    """(n, layers, 6) xx yy zz xy yz xz in global axes of the stresses
    σx σy τxy τyz τzx (n, layers, 5) in each shell's corotational frame at
    ``x`` (kernels.shell: e3 along the diagonals' cross product, the sides'
    for a triangle; e1 along side 1-2 in the plane; e2 = e3 × e1)."""
    q1, q2, q3 = (x[conn[:, i]] - x[conn[:, 0]] for i in (1, 2, 3))
    with np.errstate(invalid="ignore", divide="ignore"):
        e3 = np.cross(q2, q3 - q1)
        e3 /= np.linalg.norm(e3, axis=1, keepdims=True)
        e1 = q1 - np.einsum("ij,ij->i", q1, e3)[:, None] * e3
        e1 /= np.linalg.norm(e1, axis=1, keepdims=True)
    r = np.nan_to_num(np.stack([e1, np.cross(e3, e1), e3], axis=2))  # columns e1 e2 e3 (collapsed: 0)
    s = np.zeros(sig.shape[:2] + (3, 3))
    s[..., 0, 0], s[..., 1, 1] = sig[..., 0], sig[..., 1]
    s[..., 0, 1] = s[..., 1, 0] = sig[..., 2]
    s[..., 1, 2] = s[..., 2, 1] = sig[..., 3]
    s[..., 0, 2] = s[..., 2, 0] = sig[..., 4]
    g = np.einsum("eij,eljk,emk->elim", r, s, r)
    return np.stack([g[..., 0, 0], g[..., 1, 1], g[..., 2, 2], g[..., 0, 1], g[..., 1, 2], g[..., 0, 2]], axis=-1)


# --- the file --------------------------------------------------------------------------------------------


def _rows(table_ids: np.ndarray, ids: np.ndarray) -> np.ndarray:
    """Row of each element of a model table in a group's ``ids`` (-1: none)."""
    from ..model.mesh import index_map

    if not len(ids) or not len(table_ids):
        return np.full(len(table_ids), -1, np.int64)
    return index_map(np.asarray(ids))(np.asarray(table_ids))


def _per_state(fields: list, group: str, name: str, rows: np.ndarray, shape: tuple) -> np.ndarray:
    """(n_states, n_table, *shape) of a group's field by the model table's
    rows (0 where an element has no row)."""
    out = np.zeros((len(fields), len(rows)) + shape, np.float32)
    has = rows >= 0
    for k, f in enumerate(fields):
        if group in f:
            out[k, has] = f[group][name][rows[has]]
    return out


def write(
    path: Path | str,
    model: Model,
    times: np.ndarray,
    coords: np.ndarray,
    fields: list,
    energies: dict | None = None,
    title: str = "",
) -> Path:
    """The d3plot ``path`` (its states in ``path``01, as lasso-python
    writes them; earlier ``path``NN files are removed) of a model's field
    states: ``times`` (n_states,), ``coords`` (n_states, n_nodes, 3) and
    ``fields`` (one ``state`` dict per state, completed); ``energies``:
    {"time", "kinetic", "internal", "total"} histories, interpolated at the
    states' times. Raises ImportError without lasso-python."""
    found = lasso()
    if found is None:
        raise ImportError(MISSING)
    D3plot, A = found
    n = min(len(times), len(coords), len(fields))
    times, coords, fields = np.asarray(times[:n], float), coords[:n], fields[:n]
    d = D3plot()
    d.header.title = (title or model.title or "crashlite").encode("ascii", "replace").decode()[:40]
    arr = d.arrays
    nodes = model.nodes
    arr[A.node_ids] = nodes.ids.astype(np.int64)
    arr[A.node_coordinates] = nodes.xyz.astype(np.float64)
    arr[A.global_timesteps] = times
    arr[A.node_displacement] = np.asarray(coords, np.float32)  # d3plot keeps the current coordinates
    arr[A.node_velocity] = np.stack([f["velocity"] for f in fields]) if n else np.zeros((0, len(nodes), 3))
    arr[A.node_acceleration] = np.stack([f["acceleration"] for f in fields]) if n else np.zeros((0, len(nodes), 3))
    if energies is not None and len(energies["time"]):
        for key, name in (
            (A.global_kinetic_energy, "kinetic"),
            (A.global_internal_energy, "internal"),
            (A.global_total_energy, "total"),
        ):
            arr[key] = np.interp(times, energies["time"], energies[name])

    shells, solids = model.shells, model.solids
    beam_ok = np.all(model.beams.nodes[:, :2] >= 0, axis=1) if len(model.beams) else np.zeros(0, bool)
    disc_ok = np.all(model.discretes.nodes >= 0, axis=1) if len(model.discretes) else np.zeros(0, bool)
    pids = [shells.pid, solids.pid, model.beams.pid[beam_ok], model.discretes.pid[disc_ok]]
    part_ids = np.unique(np.concatenate([np.asarray(p, np.int64) for p in pids]))
    arr[A.part_ids] = part_ids
    arr[A.part_titles_ids] = part_ids
    arr[A.part_titles] = np.array(
        [
            str(model.parts[int(p)].get("heading", "") if int(p) in model.parts else "")
            .strip()
            .encode("ascii", "replace")[:72]
            for p in part_ids
        ],
        dtype="S72",
    )

    def part_index(pid):
        return np.searchsorted(part_ids, np.asarray(pid, np.int64))

    if len(shells):
        arr[A.element_shell_node_indexes] = shells.nodes.astype(np.int64)
        arr[A.element_shell_part_indexes] = part_index(shells.pid)
        arr[A.element_shell_ids] = shells.ids.astype(np.int64)
        rows = _rows(shells.ids, fields[0]["shell"]["ids"] if n and "shell" in fields[0] else [])
        arr[A.element_shell_stress] = _per_state(fields, "shell", "stress", rows, (LAYERS, 6))
        arr[A.element_shell_effective_plastic_strain] = _per_state(fields, "shell", "plastic_strain", rows, (LAYERS,))
        thick = _per_state(fields, "shell", "thickness", rows, ())
        given = ~np.isnan(shells.thickness)  # rigid shells: the mean of the deck's nodal thicknesses, or 0
        mean = np.where(given, shells.thickness, 0.0).sum(axis=1) / np.maximum(given.sum(axis=1), 1)
        thick[:, rows < 0] = mean[rows < 0]
        arr[A.element_shell_thickness] = thick
        alive = _per_state(fields, "shell", "alive", rows, ())
        alive[:, rows < 0] = 1.0
        arr[A.element_shell_is_alive] = alive
    if len(solids):
        arr[A.element_solid_node_indexes] = solids.nodes.astype(np.int64)
        arr[A.element_solid_part_indexes] = part_index(solids.pid)
        arr[A.element_solid_ids] = solids.ids.astype(np.int64)
        rows = _rows(solids.ids, fields[0]["solid"]["ids"] if n and "solid" in fields[0] else [])
        arr[A.element_solid_stress] = _per_state(fields, "solid", "stress", rows, (6,))[:, :, None, :]
        arr[A.element_solid_effective_plastic_strain] = _per_state(fields, "solid", "plastic_strain", rows, ())[
            :, :, None
        ]
        alive = _per_state(fields, "solid", "alive", rows, ())
        alive[:, rows < 0] = 1.0
        arr[A.element_solid_is_alive] = alive
    beams = model.beams.nodes[beam_ok].astype(np.int64)
    third = np.where(beams[:, 2] >= 0, beams[:, 2], beams[:, 0]) if len(beams) else np.zeros(0, np.int64)
    springs = model.discretes.nodes[disc_ok].astype(np.int64)
    conn = np.concatenate(
        [
            np.stack([beams[:, 0], beams[:, 1], third], axis=1).reshape(-1, 3),
            np.stack([springs[:, 0], springs[:, 1], springs[:, 0]], axis=1).reshape(-1, 3),
        ]
    )
    if len(conn):
        arr[A.element_beam_node_indexes] = np.concatenate([conn, np.zeros((len(conn), 2), np.int64)], axis=1)
        arr[A.element_beam_part_indexes] = part_index(np.concatenate([pids[2], pids[3]]))
        arr[A.element_beam_ids] = np.concatenate([model.beams.ids[beam_ok], model.discretes.ids[disc_ok]]).astype(
            np.int64
        )
        rows = _rows(
            model.discretes.ids[disc_ok], fields[0]["discrete"]["ids"] if n and "discrete" in fields[0] else []
        )
        force = np.zeros((n, len(conn)), np.float32)
        force[:, len(beams) :] = _per_state(fields, "discrete", "axial_force", rows, ())
        arr[A.element_beam_axial_force] = force
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    d.write_d3plot(str(path))
    return path


# --- reading -----------------------------------------------------------------------------------------------


def read_states(path: Path | str) -> tuple | None:
    """(times (n_f,), coordinates (n_f, n_nodes, 3), node IDs (n_nodes,),
    shell and solid connectivity rows (0-based node indices)) of an
    LS-DYNA d3plot family (``path`` the d3plot or its folder), read
    through lasso-python; None where there is no d3plot. Raises
    ImportError without lasso-python."""
    p = Path(path)
    first = p / "d3plot" if p.is_dir() else p
    if first.name != "d3plot" or not first.is_file():
        return None
    lib = lasso()
    if lib is None:
        raise ImportError(MISSING)
    D3plot, ArrayType = lib
    d = D3plot(str(first))
    arr = d.arrays
    t = np.asarray(arr[ArrayType.global_timesteps], float)
    x = np.asarray(arr[ArrayType.node_displacement], float)  # d3plot's "displacement" is the coordinates
    ids = np.asarray(arr[ArrayType.node_ids], np.int64)
    cells = []
    for key in (ArrayType.element_shell_node_indexes, ArrayType.element_solid_node_indexes):
        if key in arr:
            # a triangle or degenerate solid repeats nodes: keep each once, in order
            cells += [np.array(list(dict.fromkeys(r.tolist())), np.int64) for r in np.asarray(arr[key], np.int64)]
    return t, x, ids, cells


@dataclass
class FinalState:
    """The last state of a d3plot: ``time``, ``node_ids`` (n,) and each
    node's ``displacement`` (n, 3) from the geometry's coordinates."""

    time: float
    node_ids: np.ndarray
    displacement: np.ndarray
    source: str = ""


def read_final_state(path: Path | str) -> FinalState | None:
    """The final state of an LS-DYNA d3plot family (``path`` the d3plot or
    its folder), its last state alone read through lasso-python (a full
    car's states would not fit in memory); None where there is no d3plot
    or it holds no state. Raises ImportError without lasso-python."""
    p = Path(path)
    first = p / "d3plot" if p.is_dir() else p
    if first.name != "d3plot" or not first.is_file():
        return None
    lib = lasso()
    if lib is None:
        raise ImportError(MISSING)
    D3plot, A = lib
    d = D3plot(str(first), state_filter={-1}, state_array_filter=[A.global_timesteps, A.node_displacement])
    t = np.atleast_1d(np.asarray(d.arrays.get(A.global_timesteps, []), float))
    if not len(t) or A.node_displacement not in d.arrays:
        return None
    x = np.asarray(d.arrays[A.node_displacement], float)[-1]  # d3plot's "displacement" is the coordinates
    x0 = np.asarray(d.arrays[A.node_coordinates], float)
    return FinalState(float(t[-1]), np.asarray(d.arrays[A.node_ids], np.int64), x - x0, str(first))
