"""Consistent unit systems of LS-DYNA decks.

A deck has no unit field: its numbers are consistent in one system. Values
defined in physical terms (barrier dimensions, crush strengths, speeds) are
kept in mm–t–s–N–MPa and converted once, at the boundary, to the system of
the deck they go into.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class UnitSystem:
    """Scale factors from mm, t, s to this system's length, mass and time
    units (value_here = value_mm_t_s · factor)."""

    name: str
    length: float  # per mm
    mass: float  # per tonne
    time: float  # per second

    @property
    def force(self) -> float:
        return self.mass * self.length / self.time**2

    @property
    def stress(self) -> float:
        return self.force / self.length**2

    @property
    def velocity(self) -> float:
        return self.length / self.time

    @property
    def density(self) -> float:
        return self.mass / self.length**3

    @property
    def energy(self) -> float:
        return self.force * self.length


SYSTEMS = {
    "mm-t-s": UnitSystem("mm-t-s", 1.0, 1.0, 1.0),  # N, MPa
    "mm-kg-ms": UnitSystem("mm-kg-ms", 1.0, 1e3, 1e3),  # kN, GPa
    "mm-g-ms": UnitSystem("mm-g-ms", 1.0, 1e6, 1e3),  # N, MPa
    "m-kg-s": UnitSystem("m-kg-s", 1e-3, 1e3, 1.0),  # N, Pa
}


def system(name: str) -> UnitSystem:
    """The unit system named like ``mm-t-s``; also accepts the labels of
    ``Model.unit_system()`` (e.g. ``"mm-kg-ms (kN, GPa)"``)."""
    key = name.split()[0].strip().lower()
    if key not in SYSTEMS:
        raise ValueError(f"unknown unit system {name!r}; known: {', '.join(SYSTEMS)}")
    return SYSTEMS[key]


def kmh(speed_kmh: float) -> float:
    """A speed in km/h as mm/s."""
    return speed_kmh / 3.6 * 1e3
