"""Time histories of a run (glstat, deforc, rwforc, nodout) and the final state."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np


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
    cycles: int = 0
    dt: float = 0.0
    wall_time: float = 0.0
    info: dict = field(default_factory=dict)

    @property
    def total(self) -> np.ndarray:
        return self.kinetic + self.internal

    @property
    def energy_ratio(self) -> np.ndarray:
        """(kinetic + internal + wall) / (initial total + external work): 1
        when energy is conserved."""
        supplied = self.total[0] + self.external
        return (self.kinetic + self.internal + self.wall) / np.where(supplied != 0, supplied, 1.0)

    def save(self, directory) -> Path:
        directory = Path(directory)
        directory.mkdir(parents=True, exist_ok=True)
        path = directory / "results.npz"
        arrays = {k: v for k, v in self.__dict__.items() if isinstance(v, np.ndarray)}
        np.savez_compressed(path, cycles=self.cycles, dt=self.dt, wall_time=self.wall_time, **arrays)
        from ..results.ascii import write_glstat

        added = sum(self.info.get("added_mass", {}).values()) if self.info else 0.0
        write_glstat(directory / "glstat", {
            "time": self.time, "time_step": np.full(len(self.time), self.dt),
            "kinetic_energy": self.kinetic, "internal_energy": self.internal,
            "spring_and_damper_energy": self.internal, "external_work": self.external,
            "total_energy": self.kinetic + self.internal, "energy_ratio": self.energy_ratio,
            "added_mass": np.full(len(self.time), added)})
        return path

    @classmethod
    def load(cls, path) -> "Results":
        with np.load(Path(path) / "results.npz" if Path(path).is_dir() else path) as z:
            data = {k: z[k] for k in z.files}
        scalars = {"cycles": int(data.pop("cycles")), "dt": float(data.pop("dt")),
                   "wall_time": float(data.pop("wall_time"))}
        return cls(**data, **scalars)
