"""Characterisation of the barrier blocks (the paper's figures 1–2).

Each block of the detailed barrier (solid honeycomb) is compressed alone,
its back held, by a rigid block impactor: a moving rigid wall over the whole
face, heavy enough that its speed stays almost constant. The impactor force
against its crush gives the block's force–deflection characteristic, which
``reduce_curve`` turns into the simplified barrier's curve (peak, plateau,
compaction onset and stiffening). ``characterised_spec`` puts those curves
into an ODBSpec for ``simplified_barrier``.
"""

from __future__ import annotations

import json
import tempfile
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from .detailed import detailed_barrier
from .loadcases import Impactor, write_impactor_case
from .simplified import Placement
from .spec import Block, BlockCurve, ODBSpec

SMOOTH_CFC = 600.0  # J211 class that takes the element ringing out of the raw impactor force


@dataclass
class Characteristic:
    """One block's compression test: raw and smoothed force against crush,
    and the reduced curve."""

    block: str
    depth: float  # [mm]
    crush: np.ndarray  # (n,) impactor travel into the block [mm]
    force: np.ndarray  # (n,) impactor force, CFC 600 [N]
    force_raw: np.ndarray  # (n,) unfiltered impactor force [N]
    curve: BlockCurve
    element_size: float  # [mm]
    speed: float  # [mm/s]
    solids: int
    cycles: int
    wall_time: float  # [s]

    def summary(self) -> dict:
        return {
            "block": self.block,
            "depth_mm": self.depth,
            "element_size_mm": self.element_size,
            "speed_m_s": self.speed / 1000.0,
            "solids": self.solids,
            "cycles": self.cycles,
            "wall_time_s": self.wall_time,
            "curve": asdict(self.curve),
            "max_crush_mm": float(self.crush.max()),
            "max_force_kN": float(self.force.max() / 1e3),
        }


def reduce_curve(crush: ArrayLike, force: ArrayLike, depth: float, template: BlockCurve | None = None) -> BlockCurve:
    """The simplified curve of a measured force–crush characteristic.

    crush (n,) [mm] increasing from 0, force (n,) [N] smoothed. Plateau: the
    median force between 15 % and 60 % of the depth (after the initial peak
    has dropped, before compaction); peak: the largest force before 15 %
    (the plateau if not 5 % above it), at crush ``rise``; ``drop_end``: where
    the drop from the peak, taken as straight through the point where the
    force first returns within 5 % of the plateau, meets the plateau;
    compaction onset: where the force last leaves 1.2 × plateau on its way up
    before stiffening; full compaction: where it reaches ``full_factor`` ×
    plateau (extrapolated along the measured stiffening if the test stopped
    before). Factors the test cannot show (``solid``) come from ``template``.
    """
    x, f = np.asarray(crush, float), np.asarray(force, float)
    if x.ndim != 1 or x.shape != f.shape or len(x) < 10:
        raise ValueError("crush and force must be 1-D arrays of the same length (at least 10 points)")
    if x.max() < 0.65 * depth:
        raise ValueError(
            f"the test crushed {x.max():.1f} mm of a {depth:.1f} mm block: "
            "at least 65 % is needed to see the plateau and the compaction onset"
        )
    t = template or BlockCurve(plateau=1.0, peak=1.0)
    mid = (x >= 0.15 * depth) & (x <= 0.60 * depth)
    plateau = float(np.median(f[mid]))
    if not plateau > 0:
        raise ValueError("no positive crush force on the plateau: the impactor did not load the block")
    early = x < 0.15 * depth
    k = int(np.argmax(np.where(early, f, -np.inf)))
    peak, rise = float(f[k]), float(x[k])
    drop_end = t.drop_end
    if peak < 1.05 * plateau:
        peak = plateau
    else:
        back = np.flatnonzero((x > rise) & (f <= 1.05 * plateau))
        if len(back):  # where the drop, taken as straight, meets the plateau
            drop_end = rise + (float(x[back[0]]) - rise) * (peak - plateau) / (peak - 1.05 * plateau)
    rise = max(rise, 1e-3 * depth)
    drop_end = max(drop_end, 1.5 * rise + 1e-6 * depth)
    above = np.flatnonzero((x > 0.6 * depth) & (f > 1.2 * plateau))
    if not len(above):
        raise ValueError(f"no compaction seen up to {x.max():.1f} mm of {depth:.1f} mm: crush the block further")
    # the last point on the plateau before the force climbs for good
    below = np.flatnonzero((x > 0.6 * depth) & (x < x[above[0]]) & (f <= 1.2 * plateau))
    onset = float(x[below[-1]]) if len(below) else float(x[above[0]])
    target = t.full_factor * plateau
    reach = np.flatnonzero((x > onset) & (f >= target))
    if len(reach):
        full = float(x[reach[0]])
    else:  # extrapolate the measured stiffening from the onset to the last point
        slope = (f[-1] - plateau) / max(x[-1] - onset, 1e-9)
        if not slope > 0:
            raise ValueError("the force does not rise after the compaction onset: crush the block further")
        full = onset + (target - plateau) / slope
    solid = max(t.solid, full / depth + 0.01)
    return BlockCurve(
        plateau=plateau,
        peak=peak,
        rise=rise,
        drop_end=drop_end,
        compaction=onset / depth,
        full=min(full / depth, solid - 0.005),
        full_factor=t.full_factor,
        solid=solid,
        solid_factor=t.solid_factor,
    )


def compression_test(
    block: Block,
    spec: ODBSpec | None = None,
    element_size: float = 25.0,
    speed: float = 10000.0,
    crush: float = 0.9,
    directory: Path | str | None = None,
    progress: bool = False,
) -> Characteristic:
    """Compress ``block`` (``spec.main`` or ``spec.bumper``) of the detailed
    barrier alone by a rigid impactor of 1000 t at ``speed`` [mm/s] up to
    ``crush`` × its depth, and reduce the result. ``directory`` keeps the
    deck and results (default: a temporary folder)."""
    from ..solver import run

    spec = spec or ODBSpec()
    alone = replace(spec, main=block, bumper=block)
    barrier = detailed_barrier(
        alone, Placement(), element_size=element_size, bumper=False, title=f"characterisation {block.name}"
    )
    gap = 1.0
    end = (crush * block.depth + gap) / speed
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(directory) if directory is not None else Path(tmp)
        main = write_impactor_case(
            folder, barrier, Placement(), Impactor(mass=1000.0, speed=speed, gap=gap), end_time=end, spec=alone
        )
        r = run(main, out=folder / "out" if directory is not None else None, quiet=not progress, output_dt=end / 500.0)
    from ..verify.filters import filter_signal

    t = r.time
    v = r.wall_velocity[:, 0]
    travel = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])
    x = np.maximum(travel - gap, 0.0)
    f_raw = -r.wall_force[:, 0, 0]
    tf, f = filter_signal(t, f_raw, SMOOTH_CFC)
    f = np.interp(t, tf, f)
    curve = reduce_curve(x, f, block.depth, block.curve)
    return Characteristic(
        block.name, block.depth, x, f, f_raw, curve, element_size, speed, barrier.solids, r.cycles, r.wall_time
    )


def characterise(
    spec: ODBSpec | None = None,
    element_size: float = 25.0,
    speed: float = 10000.0,
    directory: Path | str | None = None,
    progress: bool = False,
) -> dict[str, Characteristic]:
    """Compression tests of the bumper and the main block."""
    spec = spec or ODBSpec()
    out = {}
    for b in (spec.bumper, spec.main):
        sub = None if directory is None else Path(directory) / b.name.replace(" ", "_")
        out[b.name] = compression_test(b, spec, element_size, speed, directory=sub, progress=progress)
    return out


def characterised_spec(curves: dict[str, BlockCurve], spec: ODBSpec | None = None) -> ODBSpec:
    """``spec`` with the blocks' curves replaced by ``curves`` (by block name)."""
    spec = spec or ODBSpec()
    blocks = {}
    for key in ("main", "bumper"):
        b = getattr(spec, key)
        blocks[key] = replace(b, curve=curves[b.name]) if b.name in curves else b
    return replace(spec, **blocks)


def write_curves(chars: dict[str, Characteristic], path: Path | str) -> Path:
    """curves.json: the reduced curves and the test facts, for ``read_curves``."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(json.dumps({name: c.summary() for name, c in chars.items()}, indent=2) + "\n")
    return p


def read_curves(path: Path | str) -> dict[str, BlockCurve]:
    """Block curves from a curves.json written by ``write_curves``."""
    p = Path(path)
    try:
        data = json.loads(p.read_text())
        return {name: BlockCurve(**entry["curve"]) for name, entry in data.items()}
    except (OSError, ValueError, KeyError, TypeError) as e:
        raise ValueError(f"{p}: not a curves file of `crashlite barrier characterise` ({e})") from None
