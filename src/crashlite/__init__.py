"""crashlite: simplified structural modelling for vehicle frontal crash
analysis (barrier and vehicle surrogates), with an embedded explicit solver."""

from .keyword.errors import DeckError
from .keyword.reader import read_deck
from .keyword.writer import write_deck
from .model.model import Model

__all__ = ["DeckError", "Model", "read_deck", "write_deck"]
__version__ = "0.1.0"
