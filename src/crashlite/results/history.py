"""The reader behind ``crashlite.results.load``.

A crashlite run reads through ``solver.results.categories``: its mapping
onto LS-DYNA's history categories with lasso-python Binout names (what the
ASCII writers write, so a run reads the same from its results.npz and from
its ASCII files). That mapping lives with ``Results`` (the lower module,
which writes its ASCII files with it); ``categories`` stays importable from
here.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np


def __getattr__(name: str):
    # lazily, as before: importing this module does not import the solver
    if name == "categories":
        from ..solver.results import categories

        return categories
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


class History:
    """Named time histories: ``read(category, *quantity)``."""

    def __init__(self, data: dict, source: str):
        self._data = data  # category -> {quantity or (group, quantity): array}
        self.source = source

    def read(self, category: str, *quantity: str) -> list[str] | np.ndarray:
        """Without a quantity: the quantities of a category; else the array
        (time first: (n_states, n_ids), ``ids`` (n_ids,), ``time`` (n_states,))."""
        cat = self._data.get(category)
        if cat is None:
            raise KeyError(f"{self.source}: no {category!r} history (has: {', '.join(sorted(self._data))})")
        if not quantity:
            return sorted(k if isinstance(k, str) else "/".join(k) for k in cat)
        key = quantity[0] if len(quantity) == 1 else tuple(quantity)
        if key not in cat:
            raise KeyError(
                f"{self.source}: {category} has no {'/'.join(quantity)!r} (has: {', '.join(self.read(category))})"
            )
        return cat[key]

    def categories(self) -> list[str]:
        return sorted(self._data)

    def __repr__(self) -> str:
        return f"History({self.source!r}: {', '.join(self.categories())})"


def _with_aliases(cats: dict) -> dict:
    """Names kept from earlier crashlite versions."""
    g = cats.get("glstat")
    if g is not None and "stonewall_energy" in g:
        g.setdefault("rigidwall_energy", g["stonewall_energy"])
    return cats


def _from_crashlite(res, source: str) -> History:
    from ..solver.results import categories

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


def _from_openradioss(path: Path) -> History:
    from . import openradioss_th

    return History(openradioss_th.categories(openradioss_th.read(path)), str(path))


def load(path: Path | str) -> History:
    """Time histories of a crashlite results folder (its results.npz), an
    LS-DYNA binout (lasso-python), an LS-DYNA ASCII output folder (glstat,
    matsum, nodout, rwforc, deforc, secforc, spcforc, rcforc: the categories are
    the files present) or one such ASCII file, or an OpenRadioss time history
    (``<run>T01``, or a folder holding one and no LS-DYNA files: the same
    categories, ``results.openradioss_th``)."""
    from ..solver.results import Results
    from . import openradioss_th
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
    if p.is_file() and openradioss_th.is_time_history(p):
        return _from_openradioss(p)
    if p.is_dir():
        ascii_files = present(p)
        if list(p.glob("binout*")) and (_lasso() is not None or not ascii_files):
            return _from_binout(p / "binout*")
        if ascii_files:
            return _from_ascii(read_folder(p), str(p))
        t01 = openradioss_th.find(p)
        if len(t01) == 1:
            return _from_openradioss(t01[0])
        if t01:
            raise FileNotFoundError(
                f"{p}: holds several OpenRadioss time histories ({', '.join(f.name for f in t01)}): "
                "name the file to read"
            )
    raise FileNotFoundError(
        f"{p}: neither a crashlite results folder, an LS-DYNA binout, LS-DYNA ASCII "
        f"history files ({', '.join(FILES)}) nor an OpenRadioss time history (<run>T01)"
    )
