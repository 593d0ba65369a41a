"""The explicit solver: central difference with lumped masses.

``build`` (setup.py) turns a Model into a Setup: element groups (shells,
solids, beams, discrete elements, superelements: one module each), contacts
(contact_build.py, run by contact.py), rigid bodies, constraints, walls and
motions (boundary.py); ``integrate``/``run`` (loop.py) advance it in time
and write the results. The Numba kernels those groups call live in
``kernels/``; the keywords run and refused: docs/solver.md.
"""

from .loop import RunError, integrate, run
from .results import Results
from .setup import SetupError, build

__all__ = ["Results", "RunError", "SetupError", "build", "integrate", "run"]
