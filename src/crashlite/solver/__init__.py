"""The explicit solver: central difference with lumped masses.

This stage runs masses, discrete springs and dampers, nodal constraints,
initial velocities and stationary planar rigid walls.
"""

from .loop import RunError, integrate, run
from .results import Results
from .setup import SetupError, build

__all__ = ["Results", "RunError", "SetupError", "build", "integrate", "run"]
