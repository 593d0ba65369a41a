"""The reader behind ``crashlite.results.load``."""

from __future__ import annotations

from pathlib import Path

import numpy as np


class History:
    """Named time histories: ``read(category, *quantity)``."""

    def __init__(self, data: dict, source: str):
        self._data = data  # category -> {quantity or (group, quantity): array}
        self.source = source

    def read(self, category: str, *quantity: str):
        """Without a quantity: the quantities of a category; else the array."""
        cat = self._data.get(category)
        if cat is None:
            raise KeyError(f"{self.source}: no {category!r} history (has: {', '.join(sorted(self._data))})")
        if not quantity:
            return sorted(k if isinstance(k, str) else "/".join(k) for k in cat)
        key = quantity[0] if len(quantity) == 1 else tuple(quantity)
        if key not in cat:
            raise KeyError(f"{self.source}: {category} has no {'/'.join(quantity)!r}")
        return cat[key]

    def categories(self) -> list[str]:
        return sorted(self._data)


def _from_crashlite(res, source: str) -> History:
    t = res.time
    nod = {"time": t, "ids": np.asarray(res.history_nodes)}
    for k, axis in enumerate("xyz"):
        nod[f"{axis}_displacement"] = res.node_displacement[:, :, k]
        nod[f"{axis}_velocity"] = res.node_velocity[:, :, k]
    glstat = {"time": t, "kinetic_energy": res.kinetic, "internal_energy": res.internal,
              "total_energy": res.kinetic + res.internal, "external_work": res.external,
              "rigidwall_energy": res.wall, "energy_ratio": res.energy_ratio,
              "time_step": np.full(len(t), res.dt)}
    deforc = {"time": t, "ids": np.asarray(res.discrete_ids), "resultant_force": res.discrete_force,
              "displacement": res.discrete_elong}
    rw = {("forces", "time"): t, ("forces", "ids"): np.asarray(res.wall_ids)}
    for k, axis in enumerate("xyz"):
        rw[("forces", f"{axis}_force")] = res.wall_force[:, :, k]
    rw[("forces", "normal_force")] = np.linalg.norm(res.wall_force, axis=2)
    rw[("forces", "velocity")] = res.wall_velocity
    spc = {"time": t, "ids": np.asarray(res.spc_nodes)}
    for k, axis in enumerate("xyz"):
        spc[f"{axis}_force"] = res.spc_force[:, :, k]
    sec = {"time": t, "ids": np.asarray(res.section_ids),
           "total_force": np.linalg.norm(res.section_force, axis=2)}
    for k, axis in enumerate("xyz"):
        sec[f"{axis}_force"] = res.section_force[:, :, k]
    matsum = {"time": t, "ids": np.asarray(res.part_ids), "internal_energy": res.part_internal}
    return History({"nodout": nod, "glstat": glstat, "deforc": deforc, "rwforc": rw, "spcforc": spc,
                    "matsum": matsum, "secforc": sec}, source)


def _from_binout(path: Path) -> History:
    try:
        from lasso.dyna import Binout
    except ImportError as e:  # optional dependency
        raise ImportError("reading an LS-DYNA binout needs lasso-python: pip install lasso-python") from e
    b = Binout(str(path))

    class _Binout(History):
        def read(self, category, *quantity):
            return b.read(category, *quantity)

        def categories(self):
            return list(b.read())

    return _Binout({}, str(path))


def load(path) -> History:
    """A crashlite results folder (or its results.npz) or an LS-DYNA binout."""
    from ..solver.results import Results

    p = Path(path)
    if p.is_dir() and (p / "results.npz").is_file():
        return _from_crashlite(Results.load(p), str(p))
    if p.is_file() and p.suffix == ".npz":
        return _from_crashlite(Results.load(p), str(p))
    if p.name.startswith("binout") or (p.is_dir() and list(p.glob("binout*"))):
        return _from_binout(p if p.is_file() else p / "binout*")
    if p.is_dir() and (p / "glstat").is_file():  # LS-DYNA ASCII output folder
        from .ascii import read_glstat

        return History({"glstat": read_glstat(p / "glstat")}, str(p))
    raise FileNotFoundError(f"{p}: neither a crashlite results folder nor an LS-DYNA binout")
