"""The reader behind ``crashlite.results.load``, and the mapping of a
crashlite run onto LS-DYNA's history categories with lasso-python Binout
names (what the ASCII writers write, so a run reads the same from its
results.npz and from its ASCII files)."""

from __future__ import annotations

from pathlib import Path

import numpy as np


class History:
    """Named time histories: ``read(category, *quantity)``."""

    def __init__(self, data: dict, source: str):
        self._data = data  # category -> {quantity or (group, quantity): array}
        self.source = source

    def read(self, category: str, *quantity: str):
        """Without a quantity: the quantities of a category; else the array
        (time first: (n_states, n_ids), ``ids`` (n_ids,), ``time`` (n_states,))."""
        cat = self._data.get(category)
        if cat is None:
            raise KeyError(f"{self.source}: no {category!r} history (has: {', '.join(sorted(self._data))})")
        if not quantity:
            return sorted(k if isinstance(k, str) else "/".join(k) for k in cat)
        key = quantity[0] if len(quantity) == 1 else tuple(quantity)
        if key not in cat:
            raise KeyError(f"{self.source}: {category} has no {'/'.join(quantity)!r} "
                           f"(has: {', '.join(self.read(category))})")
        return cat[key]

    def categories(self) -> list[str]:
        return sorted(self._data)

    def __repr__(self) -> str:
        return f"History({self.source!r}: {', '.join(self.categories())})"


def _xyz(out: dict, array: np.ndarray, fmt: str):
    for k, axis in enumerate("xyz"):
        out[fmt.format(axis)] = array[:, :, k]


def categories(res) -> dict:
    """A crashlite Results as LS-DYNA history categories (Binout names).
    Optional histories the run did not record are left out."""
    t = res.time
    n = len(t)
    rec = res.recorded
    cycle = {"cycle": res.cycle_number} if rec("cycle_number") else {}

    added = (res.info or {}).get("added_mass") or {}
    glstat = {"time": t, **cycle, "time_step": res.time_step if rec("time_step") else np.full(n, res.dt),
              "kinetic_energy": res.kinetic, "internal_energy": res.internal,
              "stonewall_energy": res.wall, "spring_and_damper_energy": res.internal,
              "external_work": res.external, "total_energy": res.total, "energy_ratio": res.energy_ratio}
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

    deforc = {"time": t, "ids": np.asarray(res.discrete_ids), "resultant_force": res.discrete_force,
              "displacement": res.discrete_elong}
    if rec("discrete_force_vector"):
        _xyz(deforc, res.discrete_force_vector, "{}_force")

    rw = {("forces", "time"): t, ("forces", "ids"): np.asarray(res.wall_ids)}
    rw[("forces", "normal_force")] = (res.wall_normal_force if rec("wall_normal_force")
                                      else np.linalg.norm(res.wall_force, axis=2))
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
    return {"glstat": glstat, "matsum": matsum, "nodout": nod, "rwforc": rw, "deforc": deforc,
            "secforc": sec, "spcforc": spc}


def _with_aliases(cats: dict) -> dict:
    """Names kept from earlier crashlite versions."""
    g = cats.get("glstat")
    if g is not None and "stonewall_energy" in g:
        g.setdefault("rigidwall_energy", g["stonewall_energy"])
    return cats


def _from_crashlite(res, source: str) -> History:
    cats = _with_aliases(categories(res))
    cats["rwforc"][("forces", "velocity")] = res.wall_velocity  # moving walls (not in LS-DYNA's rwforc)
    return History(cats, source)


def _from_ascii(files: dict, source: str) -> History:
    return History(_with_aliases(files), source)


def _lasso():
    try:
        from lasso.dyna import Binout
    except ImportError:
        return None
    return Binout


def _from_binout(path) -> History:
    Binout = _lasso()
    if Binout is None:  # optional dependency
        raise ImportError("reading an LS-DYNA binout needs lasso-python: pip install lasso-python")
    b = Binout(str(path))

    class _Binout(History):
        def read(self, category, *quantity):
            return b.read(category, *quantity)

        def categories(self):
            return list(b.read())

    return _Binout({}, str(path))


def load(path) -> History:
    """Time histories of a crashlite results folder (its results.npz), an
    LS-DYNA binout (lasso-python), an LS-DYNA ASCII output folder (glstat,
    matsum, nodout, rwforc, deforc, secforc, spcforc: the categories are
    the files present) or one such ASCII file."""
    from ..solver.results import Results
    from .lsdyna_ascii import FILES, present, read_folder

    p = Path(path)
    if p.is_dir() and (p / "results.npz").is_file():
        return _from_crashlite(Results.load(p), str(p))
    if p.is_file() and p.suffix == ".npz":
        return _from_crashlite(Results.load(p), str(p))
    if p.is_file() and p.name.startswith("binout"):
        return _from_binout(p)
    if p.is_file() and p.name in FILES:
        return _from_ascii({p.name: FILES[p.name].read(p)}, str(p))
    if p.is_dir():
        ascii_files = present(p)
        if list(p.glob("binout*")) and (_lasso() is not None or not ascii_files):
            return _from_binout(p / "binout*")
        if ascii_files:
            return _from_ascii(read_folder(p), str(p))
    raise FileNotFoundError(f"{p}: neither a crashlite results folder, an LS-DYNA binout nor LS-DYNA ASCII "
                            f"history files ({', '.join(FILES)})")
