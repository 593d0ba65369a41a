"""LS-DYNA ASCII time-history files (glstat, matsum, nodout, rwforc,
deforc, secforc, spcforc, rcforc): written by crashlite runs in LS-DYNA's layout,
so engineers' existing scripts read them, and read from crashlite or
LS-DYNA output folders.

Each module has ``write(path, data, title)`` and ``read(path) -> data``
where ``data`` maps lasso-python Binout names to arrays (time first);
rwforc keys are ``("forces", name)`` as in the Binout; rcforc has a column
per line (``ids`` and ``side``: each interface's slave and master line).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from . import deforc, glstat, matsum, nodout, rcforc, rwforc, secforc, spcforc

FILES = {
    "glstat": glstat,
    "matsum": matsum,
    "nodout": nodout,
    "rwforc": rwforc,
    "deforc": deforc,
    "secforc": secforc,
    "spcforc": spcforc,
    "rcforc": rcforc,
}


def _ids(data: dict):
    return data.get(("forces", "ids")) if ("forces", "ids") in data else data.get("ids")


def has_data(name: str, data: dict) -> bool:
    """glstat always (a run has a global state); the others when they hold
    at least one entity."""
    if name == "glstat":
        return "time" in data
    ids = _ids(data)
    return ids is not None and len(np.atleast_1d(ids)) > 0


def write_all(directory, categories: dict, title: str = "") -> list[Path]:
    """Write every file of ``categories`` (name -> Binout-named data) that
    has data; returns the paths written."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    return [
        FILES[name].write(directory / name, data, title)
        for name, data in categories.items()
        if name in FILES and has_data(name, data)
    ]


def present(directory) -> list[str]:
    """The LS-DYNA ASCII history files in a folder."""
    return [name for name in FILES if (Path(directory) / name).is_file()]


def read_folder(directory) -> dict:
    """name -> Binout-named data of every history file in the folder."""
    return {name: FILES[name].read(Path(directory) / name) for name in present(directory)}
