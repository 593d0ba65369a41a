"""Time histories of runs, from crashlite or LS-DYNA, behind one interface.

``load(path).read(category, *quantity)`` follows lasso-python's Binout
naming (``read("nodout", "x_displacement")`` -> (n_states, n_ids),
``read("nodout", "ids")``, ``read("glstat", "internal_energy")``,
``read("rwforc", "forces", "x_force")``), so scripts treat crashlite and
LS-DYNA runs alike.
"""

from .history import History, load

__all__ = ["History", "load"]
