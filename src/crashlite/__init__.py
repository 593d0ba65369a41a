"""crashlite: simplified structural modelling for vehicle frontal crash
analysis (barrier and vehicle surrogates), with an embedded explicit solver."""

from ._numba_cache import configure as _configure_numba_cache

_configure_numba_cache()  # before any kernel is defined: see _numba_cache

from .keyword.errors import DeckError  # noqa: E402
from .keyword.reader import read_deck  # noqa: E402
from .keyword.writer import write_deck  # noqa: E402
from .model.model import Model  # noqa: E402

__all__ = ["DeckError", "Model", "read_deck", "write_deck"]
__version__ = "0.1.0"
