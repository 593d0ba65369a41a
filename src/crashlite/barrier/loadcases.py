"""Barrier load cases: the rigid impactor of the paper's verification
(5000 kg at 64 km/h, 100 % and 40 % overlap, figures 5–8).

The impactor is a moving rigid wall (*RIGIDWALL_PLANAR_MOVING, _FINITE for
a partial overlap) acting on the barrier's front nodes: a rigid block face
with its mass and speed, which is what a rigid impactor is to the barrier.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from ..units import kmh
from .simplified import Placement, SimplifiedBarrier

if TYPE_CHECKING:
    from .spec import ODBSpec

DTMIN = 1e-3  # of the first step: a solid whose step falls below it is eroded (ERODE = 1); honeycomb
# steps fall 50x from the soft uncompacted cells to the compacted ones, so only degenerate cells go


@dataclass(frozen=True)
class Impactor:
    """A rigid impactor: mass [t], speed [mm/s], overlap as a fraction of the
    barrier width counted from ``y_min`` of the barrier, gap to the face [mm],
    friction of its face (the wall's FRIC: 0 frictionless, 1 no sliding).
    ``height``: (low, high) [mm above ground] of a strip impactor, a face
    only as high as a car's bumper beam, whose top and bottom edges shear
    the honeycomb as the beam's do (None: the barrier's whole height)."""

    mass: float = 5.0
    speed: float = kmh(64.0)
    overlap: float = 1.0
    gap: float = 1.0
    friction: float = 0.0
    height: tuple[float, float] | None = None


def impactor_deck(
    barrier_file: str,
    front_set: int,
    placement: Placement,
    impactor: Impactor,
    end_time: float,
    width: float = 1000.0,
    z_range: tuple[float, float] = (0.0, 1000.0),
    output_dt: float | None = None,
    title: str = "rigid impactor on ODB",
) -> str:
    """Main deck text: the barrier include, the impactor wall, controls and
    output requests (mm–t–s); ``z_range`` the wall's height above ground
    unless the impactor gives its own."""
    if not 0.0 < impactor.overlap <= 1.0:
        raise ValueError(f"overlap must be in (0, 1], got {impactor.overlap}")
    d = placement.direction
    x0 = placement.x_face - d * impactor.gap
    finite = impactor.overlap < 1.0 or impactor.height is not None
    z_range = impactor.height or z_range
    if not z_range[0] < z_range[1]:
        raise ValueError(f"the impactor's height needs its low edge below its high one, got {z_range}")
    name = "RIGIDWALL_PLANAR_MOVING_FINITE" if finite else "RIGIDWALL_PLANAR_MOVING"
    dt = output_dt or end_time / 200.0
    fric = float(impactor.friction)
    lines = [
        "*KEYWORD",
        "*TITLE",
        title,
        "*INCLUDE",
        barrier_file,
        f"*{name}",
        f"{front_set},0,0,0.0",
        f"{x0!r},0.0,0.0,{x0 + d!r},0.0,0.0,{fric!r}",
    ]
    if finite:
        z_lo, z_hi = (float(placement.z_ground + z) for z in z_range)  # repr of a NumPy float is no number
        y_lo = float(placement.y_min)
        # wall origin at the lower corner on the y_min side; l along +y, m = n x l
        lenl = impactor.overlap * width
        if d > 0:  # n = +x, l = +y: m = +z
            lines[-1] = f"{x0!r},{y_lo!r},{z_lo!r},{x0 + d!r},{y_lo!r},{z_lo!r},{fric!r}"
            lines.append(f"{x0!r},{y_lo + 1.0!r},{z_lo!r},{lenl!r},{z_hi - z_lo!r}")
        else:  # n = -x, l = +y: m = -z, start from the top
            lines[-1] = f"{x0!r},{y_lo!r},{z_hi!r},{x0 + d!r},{y_lo!r},{z_hi!r},{fric!r}"
            lines.append(f"{x0!r},{y_lo + 1.0!r},{z_hi!r},{lenl!r},{z_hi - z_lo!r}")
    # one value per card, comma-terminated: free format, so a long number cannot spill into the next field
    lines += [
        f"{impactor.mass!r},{impactor.speed!r}",
        "*CONTROL_TERMINATION",
        f"{end_time!r},0,{DTMIN!r},",
        # honeycomb solids sheared through at the impactor's edge are deleted, as in LS-DYNA
        "*CONTROL_TIMESTEP",
        "0.0,0.9,0,0.0,0.0,0,1,0",
        "*DATABASE_GLSTAT",
        f"{dt!r},",
        "*DATABASE_MATSUM",
        f"{dt!r},",
        "*DATABASE_RWFORC",
        f"{dt!r},",
        "*DATABASE_SPCFORC",
        f"{dt!r},",
        "*DATABASE_DEFORC",
        f"{dt!r},",
        "*DATABASE_BINARY_D3PLOT",
        f"{end_time / 20.0!r},",
        "*END",
    ]
    return "\n".join(lines) + "\n"


def write_impactor_case(
    directory: Path | str,
    barrier: SimplifiedBarrier,
    placement: Placement,
    impactor: Impactor,
    end_time: float,
    spec: ODBSpec | None = None,
) -> Path:
    """Write ``barrier.k`` (the generated barrier) and ``main.k`` (the load
    case) into ``directory``; returns the main deck's path."""
    from .spec import ODBSpec

    spec = spec or ODBSpec()
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    barrier.write(directory / "barrier.k")
    text = impactor_deck(
        "barrier.k",
        barrier.set_ids["front"],
        placement,
        impactor,
        end_time,
        width=spec.main.width,
        z_range=(spec.main.z_low - 50.0, spec.main.z_high + 50.0),
    )
    main = directory / "main.k"
    main.write_text(text)
    return main
