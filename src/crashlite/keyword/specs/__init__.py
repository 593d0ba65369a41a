"""The keyword catalogue: importing this package registers every schema.

One module per family. Field names follow the LS-DYNA keyword manual in
lower case (``secid``, ``ro``, ``sigy``), so users find them where the
manual puts them.
"""

from . import mesh  # noqa: F401
import importlib as _importlib

for _mod in ("parts", "materials", "define", "sets", "loads", "contact", "constrained", "control"):
    try:
        _importlib.import_module(f"{__name__}.{_mod}")
    except ModuleNotFoundError as _e:  # catalogue modules land one by one
        if _e.name != f"{__name__}.{_mod}":
            raise
