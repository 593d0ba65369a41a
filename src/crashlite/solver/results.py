"""Time histories of a run (glstat, matsum, nodout, rwforc, deforc,
secforc, spcforc, rcforc) and the final state; saved as results.npz (full
precision) and as LS-DYNA-style ASCII files."""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..model.model import Model


def _empty(*trailing: int):
    """default_factory of an optional history: no states."""
    return field(default_factory=lambda: np.zeros((0,) + trailing))


@dataclass
class Results:
    time: np.ndarray  # (n_states,) [time]
    kinetic: np.ndarray  # (n_states,) kinetic energy [energy]
    internal: np.ndarray  # (n_states,) internal energy of elements (dampers: dissipated) [energy]
    wall: np.ndarray  # (n_states,) energy taken by rigid walls [energy]
    external: np.ndarray  # (n_states,) work of prescribed motions [energy]
    discrete_force: np.ndarray  # (n_states, n_discrete) axial force, tension positive [force]
    discrete_elong: np.ndarray  # (n_states, n_discrete) elongation δ [length]
    wall_force: np.ndarray  # (n_states, n_walls, 3) force of the nodes on each wall [force]
    wall_velocity: np.ndarray  # (n_states, n_walls) velocity of moving walls along their normal
    node_displacement: np.ndarray  # (n_states, n_hist, 3) of the history nodes [length]
    node_velocity: np.ndarray  # (n_states, n_hist, 3) [length/time]
    spc_force: np.ndarray  # (n_states, n_spc, 3) reaction forces of the supports [force]
    spc_nodes: np.ndarray  # (n_spc,) nodes with a constrained DOF (deck IDs after run())
    history_nodes: np.ndarray  # (n_hist,) deck node IDs
    discrete_ids: np.ndarray  # (n_discrete,) deck element IDs
    wall_ids: np.ndarray  # (n_walls,)
    section_ids: np.ndarray  # (n_sections,) *DATABASE_CROSS_SECTION IDs
    section_force: np.ndarray  # (n_states, n_sections, 3) force through each section (secforc) [force]
    part_ids: np.ndarray  # (n_parts,) parts with elements that store energy
    part_internal: np.ndarray  # (n_states, n_parts) internal energy per part (matsum) [energy]
    states_time: np.ndarray  # (n_fields,) times of the field states (d3plot interval)
    states_x: np.ndarray  # (n_fields, n_nodes, 3) coordinates at those times
    final_x: np.ndarray  # (n_nodes, 3)
    final_v: np.ndarray  # (n_nodes, 3)
    # optional histories (empty: not recorded; writers then omit or derive them)
    part_kinetic: np.ndarray = _empty(0)  # (n_states, n_parts) kinetic energy per part [energy]
    part_momentum: np.ndarray = _empty(0, 3)  # (n_states, n_parts, 3) momentum per part [mass*length/time]
    part_rigid_velocity: np.ndarray = _empty(
        0, 3
    )  # (n_states, n_parts, 3) CoG velocity of each part (momentum / mass) [length/time]
    part_hourglass: np.ndarray = _empty(0)  # (n_states, n_parts) hourglass energy per part [energy]
    # (n_states, n_parts) int64 shells and solids of each part deleted so far (eroded, failed, collapsed)
    part_deleted: np.ndarray = field(default_factory=lambda: np.zeros((0, 0), np.int64))
    section_moment: np.ndarray = _empty(0, 3)  # (n_states, n_sections, 3) moment through each section [force*length]
    node_acceleration: np.ndarray = _empty(0, 3)  # (n_states, n_hist, 3) of the history nodes [length/time^2]
    node_coordinates: np.ndarray = _empty(
        0, 3
    )  # (n_states, n_hist, 3) current coordinates of the history nodes [length]
    hourglass: np.ndarray = _empty()  # (n_states,) global hourglass energy [energy]
    sliding: np.ndarray = _empty()  # (n_states,) global sliding interface (contact) energy [energy]
    time_step: np.ndarray = _empty()  # (n_states,) time step at each state [time]
    cycle_number: np.ndarray = field(
        default_factory=lambda: np.zeros(0, np.int64)
    )  # (n_states,) int64 cycle of each state
    discrete_force_vector: np.ndarray = _empty(
        0, 3
    )  # (n_states, n_discrete, 3) force of each discrete element in global axes [force]
    wall_normal_force: np.ndarray = _empty(0)  # (n_states, n_walls) force along each wall's normal [force]
    contact_force: np.ndarray = _empty(
        0, 3
    )  # (n_states, n_contacts, 3) force on the slave side of each contact interface (rcforc) [force]
    contact_ids: np.ndarray = field(
        default_factory=lambda: np.zeros(0, np.int64)
    )  # (n_contacts,) contact interface IDs
    # effective plastic strain of each deformable shell and solid at the end (the largest over its
    # integration points; it never decreases, so it is the peak of the run), rows by deck element ID
    shell_ids: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    shell_plastic_strain: np.ndarray = _empty()  # (n_shells,)
    solid_ids: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    solid_plastic_strain: np.ndarray = _empty()  # (n_solids,)
    # internal energy of each deformable shell and solid at the end (hourglass energy apart), same rows:
    # where a run's energy went, element by element (the interface proposal sums it behind a plane)
    shell_internal_energy: np.ndarray = _empty()  # (n_shells,) [energy]
    solid_internal_energy: np.ndarray = _empty()  # (n_solids,) [energy]
    cycles: int = 0
    dt: float = 0.0
    wall_time: float = 0.0  # whole run: set-up (with Numba compilation) and time loop [s]
    loop_time: float = 0.0  # wall time of the time loop, Numba compilation met in it excluded [s]
    cpu_time: float = 0.0  # CPU time of the time loop (all threads), compilation excluded [s]
    setup_time: float = 0.0  # wall_time - loop_time: building the arrays, first forces, compilation [s]
    compile_time: float = 0.0  # Numba compilation and cache loads, in and out of the loop [s]
    info: dict = field(default_factory=dict)  # added_mass, stopped, elements (count by type), bodies, title
    # (n_nodes,) int64 deck node IDs of the rows of final_x and states_x (empty: unknown)
    node_ids: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))

    TIMES = ("wall_time", "loop_time", "cpu_time", "setup_time", "compile_time")

    def recorded(self, name: str) -> bool:
        """True when the optional history ``name`` holds every state."""
        a = getattr(self, name)
        return a.ndim >= 1 and a.shape[0] == len(self.time) and a.size > 0

    def deleted(self, parts: np.ndarray | None = None) -> int:
        """Shells and solids deleted by the end (of the parts ``parts``
        when given): 0 when the run did not count them."""
        if not self.recorded("part_deleted"):
            return 0
        last = self.part_deleted[-1]
        return int(last.sum() if parts is None else last[np.isin(self.part_ids, parts)].sum())

    def _or_zero(self, name: str) -> np.ndarray:
        return getattr(self, name) if self.recorded(name) else np.zeros(len(self.time))

    @property
    def total(self) -> np.ndarray:
        """(n_states,) total energy as LS-DYNA's glstat counts it: kinetic
        + internal + rigid-wall + hourglass + sliding [energy]."""
        return self.kinetic + self.internal + self.wall + self._or_zero("hourglass") + self._or_zero("sliding")

    @property
    def energy_ratio(self) -> np.ndarray:
        """(n_states,) total / (initial total + external work): 1 when
        energy is conserved; 1 while a model that starts at rest has neither
        (LS-DYNA's glstat does the same)."""
        if len(self.time) == 0:
            return np.zeros(0)
        supplied = self.total[0] + self.external
        ratio = self.total / np.where(supplied != 0, supplied, 1.0)
        return np.where((supplied == 0) & (self.total == 0), 1.0, ratio)

    def save(self, directory: Path | str, title: str | None = None) -> Path:
        """results.npz (every array, full precision) and the LS-DYNA ASCII
        files that have data (glstat always; matsum, nodout, rwforc,
        deforc, secforc, spcforc, rcforc when the run has their entities)."""
        directory = Path(directory)
        directory.mkdir(parents=True, exist_ok=True)
        path = directory / "results.npz"
        arrays = {k: v for k, v in self.__dict__.items() if isinstance(v, np.ndarray)}
        added = self.info.get("added_mass") or {}
        elements = {f"info_elements_{k}": np.int64(v) for k, v in (self.info.get("elements") or {}).items()}
        np.savez_compressed(
            path,
            cycles=self.cycles,
            dt=self.dt,
            **{k: getattr(self, k) for k in self.TIMES},
            info_added_mass_parts=np.array(list(added), np.int64),
            info_added_mass=np.array(list(added.values()), float),
            info_title=np.array(str(self.info.get("title", ""))),
            info_stopped=np.array(str(self.info.get("stopped") or "")),
            **elements,
            **arrays,
        )
        from ..results.lsdyna_ascii import write_all

        write_all(directory, categories(self), title if title is not None else self.info.get("title", ""))
        return path

    def timing(self) -> dict:
        """Run facts for time accounting: elements by type, last time step,
        cycles and the times [s]."""
        return {
            "elements": dict(self.info.get("elements") or {}),
            "time_step": float(self.dt),
            "cycles": int(self.cycles),
            **{k: float(getattr(self, k)) for k in self.TIMES},
        }

    @classmethod
    def load(cls, path: Path | str) -> Results:
        """A results.npz (or the folder holding it); histories the file
        lacks (written by an older crashlite) come back empty."""
        with np.load(Path(path) / "results.npz" if Path(path).is_dir() else path) as z:
            data = {k: z[k] for k in z.files}
        info = {}
        if "info_added_mass_parts" in data:
            info["added_mass"] = dict(zip(data["info_added_mass_parts"].tolist(), data["info_added_mass"].tolist()))
        if "info_title" in data and str(data["info_title"]):
            info["title"] = str(data["info_title"])
        if "info_stopped" in data and str(data["info_stopped"]):
            info["stopped"] = str(data["info_stopped"])
        elements = {k[len("info_elements_") :]: int(data[k]) for k in data if k.startswith("info_elements_")}
        if elements:
            info["elements"] = elements
        scalars = {
            "cycles": int(data.pop("cycles")),
            "dt": float(data.pop("dt")),
            **{k: float(data.pop(k)) for k in cls.TIMES if k in data},
        }
        known = {f.name for f in fields(cls)}
        return cls(**{k: v for k, v in data.items() if k in known}, **scalars, info=info)


def _xyz(out: dict, array: np.ndarray, fmt: str):
    for k, axis in enumerate("xyz"):
        out[fmt.format(axis)] = array[:, :, k]


def categories(res: Results) -> dict:
    """A crashlite Results as LS-DYNA history categories (Binout names).
    Optional histories the run did not record are left out."""
    t = res.time
    n = len(t)
    rec = res.recorded
    cycle = {"cycle": res.cycle_number} if rec("cycle_number") else {}

    added = (res.info or {}).get("added_mass") or {}
    glstat = {
        "time": t,
        **cycle,
        "time_step": res.time_step if rec("time_step") else np.full(n, res.dt),
        "kinetic_energy": res.kinetic,
        "internal_energy": res.internal,
        "stonewall_energy": res.wall,
        "spring_and_damper_energy": res.internal,
        "external_work": res.external,
        "total_energy": res.total,
        "energy_ratio": res.energy_ratio,
    }
    if rec("hourglass"):
        glstat["hourglass_energy"] = res.hourglass
    if rec("sliding"):
        glstat["sliding_interface_energy"] = res.sliding
    if added:
        glstat["added_mass"] = np.full(n, float(sum(added.values())))

    nod = {"time": t, **cycle, "ids": np.asarray(res.history_nodes)}
    _xyz(nod, res.node_displacement, "{}_displacement")
    _xyz(nod, res.node_velocity, "{}_velocity")
    if rec("node_acceleration"):
        _xyz(nod, res.node_acceleration, "{}_acceleration")
    if rec("node_coordinates"):
        _xyz(nod, res.node_coordinates, "{}_coordinate")

    pids = np.asarray(res.part_ids)
    matsum = {"time": t, "ids": pids, "internal_energy": res.part_internal}
    if rec("part_kinetic"):
        matsum["kinetic_energy"] = res.part_kinetic
    if rec("part_hourglass"):
        matsum["hourglass_energy"] = res.part_hourglass
    if rec("part_momentum"):
        _xyz(matsum, res.part_momentum, "{}_momentum")
    if rec("part_rigid_velocity"):  # momentum / mass of every part, as LS-DYNA writes
        _xyz(matsum, np.nan_to_num(res.part_rigid_velocity, nan=0.0), "{}_rbvelocity")
    if added:
        matsum["mass"] = np.tile([float(added.get(int(p), 0.0)) for p in pids], (n, 1)).reshape(n, len(pids))

    deforc = {
        "time": t,
        "ids": np.asarray(res.discrete_ids),
        "resultant_force": res.discrete_force,
        "displacement": res.discrete_elong,
    }
    if rec("discrete_force_vector"):
        _xyz(deforc, res.discrete_force_vector, "{}_force")

    rw = {("forces", "time"): t, ("forces", "ids"): np.asarray(res.wall_ids)}
    rw[("forces", "normal_force")] = (
        res.wall_normal_force if rec("wall_normal_force") else np.linalg.norm(res.wall_force, axis=2)
    )
    for k, axis in enumerate("xyz"):
        rw[("forces", f"{axis}_force")] = res.wall_force[:, :, k]

    spc = {"time": t, "ids": np.asarray(res.spc_nodes), "force_ids": np.asarray(res.spc_nodes)}
    _xyz(spc, res.spc_force, "{}_force")
    for k, axis in enumerate("xyz"):
        spc[f"{axis}_resultant"] = res.spc_force[:, :, k].sum(axis=1)

    sec = {"time": t, "ids": np.asarray(res.section_ids)}
    _xyz(sec, res.section_force, "{}_force")
    sec["total_force"] = np.linalg.norm(res.section_force, axis=2)
    if rec("section_moment"):
        _xyz(sec, res.section_moment, "{}_moment")
        sec["total_moment"] = np.linalg.norm(res.section_moment, axis=2)
    return {
        "glstat": glstat,
        "matsum": matsum,
        "nodout": nod,
        "rwforc": rw,
        "deforc": deforc,
        "secforc": sec,
        "spcforc": spc,
        "rcforc": _rcforc(res),
    }


def _rcforc(res) -> dict:
    """rcforc as LS-DYNA writes it: a slave and a master line per interface;
    the master side takes the reaction (penalty forces come in equal and
    opposite pairs) and the mass in contact is not known (left out)."""
    cids = np.asarray(res.contact_ids, np.int64)
    f = res.contact_force if res.recorded("contact_force") else np.zeros((len(res.time), len(cids), 3))
    both = np.stack([f, -f], axis=2).reshape(len(res.time), 2 * len(cids), 3)  # slave 1, master 1, slave 2 ...
    out = {"time": res.time, "ids": np.repeat(cids, 2), "side": np.tile([0, 1], len(cids))}
    _xyz(out, both, "{}_force")
    return out


def element_counts(model: Model) -> dict[str, int]:
    """Elements of a Model by LS-DYNA element type, as a d3hsp counts them
    (rigid ones included; point masses as "mass")."""
    counts = {
        "solid": len(model.solids),
        "shell": len(model.shells),
        "beam": len(model.beams),
        "discrete": len(model.discretes),
        "mass": len(model.masses),
    }
    return {k: int(v) for k, v in counts.items() if v}
