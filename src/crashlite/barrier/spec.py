"""The offset deformable barrier (ODB) as data.

Dimensions and crush strengths of ECE R94 Annex 9 / EEVC (main block and
bumper of aluminium honeycomb, clad with aluminium sheet), and the
force–deflection characteristics of the paper's simplified barrier (bumper:
≈ 1000 kN peak then ≈ 500 kN to compaction; main block: ≈ 230 kN plateau to
compaction). All values in mm–t–s–N–MPa; ``scaled`` converts to a deck's
system. Every value is a parameter.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..units import UnitSystem

# Young's modulus of fully compacted honeycomb [MPa]: the detailed barrier's
# MAT_026 E past full compaction and the simplified barrier's unloading
# stiffness, so that both give back as little of a compacted column's
# force as each other when a rail that bottomed it out draws back.
COMPACTED_MODULUS = 1000.0


def per_block(value: float | tuple[float, float]) -> dict[str, float]:
    """A value given once for both blocks or as (main block, bumper), by
    block name."""
    pair = tuple(value) if isinstance(value, (tuple, list)) else (value, value)
    if len(pair) != 2:
        raise ValueError(f"one value or (main block, bumper), got {value!r}")
    return {"main block": float(pair[0]), "bumper": float(pair[1])}


@dataclass(frozen=True)
class BlockCurve:
    """Force–crush characteristic of a whole honeycomb block (crush positive).

    The force rises to ``peak`` over ``rise`` (elastic honeycomb), falls to
    ``plateau`` by ``drop_end`` (the peak of unconditioned honeycomb; equal
    to the plateau for none), stays there to the compaction onset
    ``compaction`` (fraction of the depth) and stiffens to
    ``full_factor × plateau`` at ``full`` (fraction of the depth): the
    densified honeycomb; then to ``solid_factor × plateau`` at
    ``solid`` of the depth, so the block cannot be crushed through.
    """

    plateau: float  # [N]
    peak: float  # [N]
    rise: float = 3.0  # [mm]
    drop_end: float = 12.0  # [mm]
    compaction: float = 0.80  # [-] of depth
    full: float = 0.92  # [-] of depth
    full_factor: float = 8.0  # [-]
    solid: float = 0.97  # [-] of depth
    solid_factor: float = 40.0  # [-]

    def points(self, depth: float) -> tuple[np.ndarray, np.ndarray]:
        """(crush [mm], force [N]) defining points, crush increasing from 0."""
        c_on, c_full = self.compaction * depth, self.full * depth
        xs = [0.0, self.rise]
        fs = [0.0, self.peak]
        if self.peak != self.plateau:
            xs.append(max(self.drop_end, self.rise * 1.5))
            fs.append(self.plateau)
        xs += [c_on, c_full, self.solid * depth]
        fs += [self.plateau, self.full_factor * self.plateau, self.solid_factor * self.plateau]
        x = np.array(xs)
        if np.any(np.diff(x) <= 0):
            raise ValueError(f"curve points not increasing in crush: {xs} (depth {depth} mm)")
        return x, np.array(fs)


@dataclass(frozen=True)
class Block:
    """A honeycomb block of the barrier, in barrier axes: width along y,
    height along z (above ground), depth along the impact direction."""

    name: str
    width: float  # [mm]
    height: float  # [mm]
    depth: float  # [mm]
    z_low: float  # lower edge above ground [mm]
    strength: float  # crush strength of the honeycomb [MPa]
    density: float  # honeycomb density [t/mm³]
    curve: BlockCurve
    cell: float = 0.0  # honeycomb cell size [mm] (Directive 96/79/EC Annex 6; 0: not given)

    @property
    def z_high(self) -> float:
        return self.z_low + self.height

    @property
    def area(self) -> float:
        return self.width * self.height

    @property
    def mass(self) -> float:
        return self.density * self.area * self.depth

    @property
    def plateau_stress(self) -> float:
        """The crush plateau over the face [MPa]."""
        return self.curve.plateau / self.area

    @property
    def crush_modulus(self) -> float:
        """The uncompacted honeycomb's crush modulus [MPa]: the curve's
        initial slope as stress against strain."""
        return (self.curve.peak / self.area) / (self.curve.rise / self.depth)


@dataclass(frozen=True)
class Cladding:
    """Cladding sheets: a contact surface that allows local intrusion and
    adds no strength: a soft sheet (its time step stays above the beams')
    that yields at ``yield_stress``, so that where an impactor pushes part
    of the face in, the sheet between pushed and held nodes flows instead
    of stretching elastically over the whole stroke (the real sheet tears
    there, the paper's section 2.1)."""

    thickness_front: float = 0.81  # bumper front sheet [mm]
    thickness_middle: float = 0.5  # sheet between bumper and main block [mm]
    density: float = 2.7e-9  # aluminium [t/mm³]
    modulus: float = 70.0  # [MPa]: 1/1000 of aluminium, by design (paper section 2.1)
    poisson: float = 0.3
    yield_stress: float = 0.5  # [MPa]


def _main_block() -> Block:
    return Block(
        "main block", 1000.0, 650.0, 450.0, 200.0, 0.342, 2.86e-11, BlockCurve(plateau=230e3, peak=230e3), cell=19.14
    )


def _bumper() -> Block:
    return Block(
        "bumper",
        1000.0,
        330.0,
        90.0,
        280.0,
        1.711,
        8.26e-11,
        BlockCurve(plateau=500e3, peak=1000e3, rise=3.0, drop_end=12.0),
        cell=6.4,
    )


@dataclass(frozen=True)
class ODBSpec:
    """The whole barrier: main block, bumper in front of it, cladding.

    Honeycomb densities are typical of the 0.342 and 1.711 MPa aluminium
    honeycombs (≈ 29 and 83 kg/m³); the curves default to the paper's.
    """

    main: Block = field(default_factory=_main_block)
    bumper: Block = field(default_factory=_bumper)
    cladding: Cladding = field(default_factory=Cladding)

    def with_strength_curves(self) -> ODBSpec:
        """The spec with plateaus from the crush strengths × face areas
        (R94: 222 kN and 565 kN) instead of the paper's curves."""
        m, b = self.main, self.bumper
        return replace(
            self,
            main=replace(m, curve=replace(m.curve, plateau=m.strength * m.area, peak=m.strength * m.area)),
            bumper=replace(
                b,
                curve=replace(
                    b.curve, plateau=b.strength * b.area, peak=b.curve.peak / b.curve.plateau * b.strength * b.area
                ),
            ),
        )

    @property
    def depth(self) -> float:
        return self.main.depth + self.bumper.depth

    @property
    def mass(self) -> float:
        """Honeycomb and cladding mass [t]."""
        return self.main.mass + self.bumper.mass + self.cladding_mass()

    def cladding_mass(self, bumper: bool = True) -> float:
        """Mass [t] of the cladding sheets: the block front, and the bumper
        front when there is a bumper."""
        c = self.cladding
        return c.density * (
            self.main.area * c.thickness_middle + (self.bumper.area * c.thickness_front if bumper else 0.0)
        )

    def check(self) -> None:
        for b in (self.main, self.bumper):
            for name in ("width", "height", "depth", "strength", "density"):
                if not getattr(b, name) > 0:
                    raise ValueError(f"{b.name}: {name} must be > 0 (got {getattr(b, name)})")
        if not (self.main.z_low <= self.bumper.z_low and self.bumper.z_high <= self.main.z_high):
            raise ValueError("the bumper must lie within the height of the main block")
        if self.bumper.width != self.main.width:
            raise ValueError("bumper and main block must have the same width")


def scaled(value: float, kind: str, units: UnitSystem) -> float:
    """A mm–t–s value of the given kind (length, mass, force, stress,
    density, velocity) in ``units``."""
    return value * getattr(units, kind)
