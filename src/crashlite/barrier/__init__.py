"""The offset deformable barrier: specification, the paper's simplified
barrier of discrete beams, and its placement for a vehicle."""

from .simplified import Placement, SimplifiedBarrier, offset_placement, simplified_barrier
from .spec import ODBSpec

__all__ = ["ODBSpec", "Placement", "SimplifiedBarrier", "offset_placement", "simplified_barrier"]
