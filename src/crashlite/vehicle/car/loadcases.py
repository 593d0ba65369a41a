"""Frontal load cases for a vehicle deck: US NCAP and Euro NCAP ODB.

A load case is a main deck that *INCLUDEs the vehicle deck unchanged (any
vehicle deck: the generic car or another one driving in +x with z up) and
adds what the test needs, with IDs above every ID of the vehicle:

- US NCAP: 100 % frontal impact on a fixed rigid wall at 56 km/h (wall
  forces in rwforc), the ground as a second wall;
- Euro NCAP ODB: the offset deformable barrier (``crashlite.barrier``:
  the paper's simplified barrier or the detailed honeycomb one) overlapping
  40 % of the vehicle width on the driver side (left), 64 km/h, an
  automatic surface-to-surface contact between vehicle and barrier, the
  ground wall.

Both give the vehicle's nodes the initial velocity (a node set of all the
vehicle deck's nodes), and set the end time, energy and output requests
(glstat, matsum, rwforc, secforc, nodout, rcforc, d3plot). The vehicle's
front is its largest x; the wall or barrier face stands ``gap`` ahead.
Speeds and lengths are converted to the vehicle deck's unit system (from
its material densities).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...keyword.writer import format_record
from ...units import SYSTEMS, UnitSystem, kmh, system
from .records import record


@dataclass
class VehicleInfo:
    """What a load case needs of a vehicle deck (in the deck's units)."""

    node_ids: np.ndarray  # (n,) sorted deck node IDs
    part_ids: np.ndarray  # (k,) sorted part IDs
    lo: np.ndarray  # (3,) bounding box
    hi: np.ndarray  # (3,)
    id_offset: int  # a power of ten above every ID of the deck
    units: UnitSystem

    @property
    def width(self) -> float:
        return float(self.hi[1] - self.lo[1])

    @property
    def y_centre(self) -> float:
        return float(0.5 * (self.hi[1] + self.lo[1]))


def vehicle_info(path: Path | str, units: str | None = None) -> VehicleInfo:
    """Read a vehicle deck for a load case; ``units`` overrides the guess
    from its densities."""
    from ... import read_deck

    m = read_deck(path)
    if not len(m.nodes):
        raise ValueError(f"{path}: the vehicle deck has no nodes")
    biggest = [0]
    for t in ("nodes", "shells", "solids", "beams", "discretes", "masses", "inertias"):
        ids = getattr(m, t).ids
        if len(ids):
            biggest.append(int(ids.max()))
    for g in ("parts", "sections", "materials", "curves", "hourglasses", "vectors"):
        biggest += [int(k) for k in getattr(m, g)]
    biggest += [int(k[1]) for k in m.sets]
    for r in m.keywords:
        for f in ("cid", "rwid", "csid", "wid"):
            v = getattr(r, "values", {}).get(f)
            if isinstance(v, int):
                biggest.append(v)
    offset = 10 ** max(1, math.ceil(math.log10(max(biggest) + 1)))
    u = system(units) if units else _guess(m)
    return VehicleInfo(
        np.unique(m.nodes.ids),
        np.array(sorted(m.parts), np.int64),
        m.nodes.xyz.min(axis=0),
        m.nodes.xyz.max(axis=0),
        offset,
        u,
    )


def _guess(m) -> UnitSystem:
    label = m.unit_system()
    try:
        return system(label)
    except ValueError:
        return SYSTEMS["mm-t-s"]


def _ranges(ids: np.ndarray) -> np.ndarray:
    """(r, 2) first and last ID of each run of consecutive IDs."""
    ids = np.unique(ids)
    cut = np.flatnonzero(np.diff(ids) != 1)
    return np.stack([ids[np.r_[0, cut + 1]], ids[np.r_[cut, len(ids) - 1]]], axis=1)


def _node_generate(sid: int, ids: np.ndarray, title: str):
    r = _ranges(ids)
    n = -(-len(r) // 4)
    pad = np.zeros((n * 4, 2), np.int64)
    pad[: len(r)] = r
    rows = {}
    for i in range(4):
        rows[f"b{i + 1}beg"] = pad[i::4, 0]
        rows[f"b{i + 1}end"] = pad[i::4, 1]
    return record("SET_NODE_GENERATE_TITLE", rows=rows, card_title=title, sid=sid)


def _part_list(sid: int, ids, title: str):
    from .records import id_list

    return id_list("SET_PART_LIST_TITLE", sid, ids, title=title)


def _include_name(car: Path, out: Path) -> str:
    return os.path.relpath(Path(car).resolve(), Path(out).resolve().parent)


def _common(
    v: VehicleInfo, speed_kmh: float, end_time: float, output_dt: float, ground: float, erode_dtmin: float = 0.0
) -> tuple:
    """Vehicle node and part sets, initial velocity, ground wall, controls,
    outputs (records), and the node-set ID. ``erode_dtmin`` > 0: ERODE = 1
    with that DTMIN (solids whose step falls below DTMIN x their first step
    are deleted; the run stops where the whole model's step falls below
    DTMIN x its first step)."""
    o, u = v.id_offset, v.units
    nodes, parts = o + 1, o + 2
    recs = [
        _node_generate(nodes, v.node_ids, "vehicle nodes (load case)"),
        _part_list(parts, v.part_ids, "vehicle parts (load case)"),
        record("INITIAL_VELOCITY", nsid=nodes, vx=kmh(speed_kmh) * u.velocity),
    ]
    z = ground * u.length
    cx, cy = float(0.5 * (v.lo[0] + v.hi[0])), v.y_centre
    recs.append(
        record(
            "RIGIDWALL_PLANAR_ID",
            rwid=o + 2,
            heading="ground",
            nsid=nodes,
            xt=cx,
            yt=cy,
            zt=z,
            xh=cx,
            yh=cy,
            zh=z + 1.0,
            fric=0.3,
        )
    )
    t, dt = end_time * u.time, output_dt * u.time
    recs += [
        record("CONTROL_TERMINATION", endtim=t, dtmin=erode_dtmin),
        record("CONTROL_TIMESTEP", tssfac=0.9, erode=1 if erode_dtmin > 0 else 0),
        record("CONTROL_ENERGY", hgen=2, rwen=2, slnten=2, rylen=2),
    ]
    recs += [record(f"DATABASE_{d}", dt=dt) for d in ("GLSTAT", "MATSUM", "RWFORC", "SECFORC", "NODOUT", "RCFORC")]
    recs.append(record("DATABASE_BINARY_D3PLOT", dt=5e-3 * u.time))
    return recs, nodes, parts


def _deck(title: str, includes: list[str], recs: list) -> str:
    lines = ["*KEYWORD", "*TITLE", title]
    for inc in includes:
        lines += ["*INCLUDE", inc]
    for r in recs:
        lines += format_record(r, "std")
    lines.append("*END")
    return "\n".join(lines) + "\n"


def usncap_deck(
    car: Path | str,
    out: Path | str,
    speed_kmh: float = 56.0,
    end_time: float = 0.1,
    gap: float = 1.0,
    ground: float = 0.0,
    output_dt: float = 1e-4,
    units: str | None = None,
) -> Path:
    """Write the US NCAP load case for vehicle deck ``car`` to ``out``:
    rigid wall ``gap`` mm ahead of the vehicle's front, ``speed_kmh``,
    ``end_time`` and ``output_dt`` in seconds, ground height [mm]."""
    car, out = Path(car), Path(out)
    v = vehicle_info(car, units)
    recs, nodes, _ = _common(v, speed_kmh, end_time, output_dt, ground)
    x = float(v.hi[0]) + gap * v.units.length
    cy, cz = v.y_centre, float(0.5 * (v.lo[2] + v.hi[2]))
    recs.insert(
        3,
        record(
            "RIGIDWALL_PLANAR_ID",
            rwid=v.id_offset + 1,
            heading="US NCAP rigid wall",
            nsid=nodes,
            xt=x,
            yt=cy,
            zt=cz,
            xh=x - 1.0,
            yh=cy,
            zh=cz,
        ),
    )
    text = _deck(f"US NCAP 100 % rigid wall {speed_kmh:g} km/h", [_include_name(car, out)], recs)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(text)
    return out


def _rig_wall(v: VehicleInfo, pl, nodes: int, rwid: int, heading: str):
    """The test rig's rigid block behind the barrier (R94 Annex 9: the
    barrier is fixed to the face of a block of at least 70 t): a finite
    planar wall over the main block's back face, facing the vehicle, for
    ``nodes`` (a node set). Without it a rail that has crushed the
    honeycomb under it runs on through the barrier's back plane, which
    nothing holds (the barrier's back nodes are held, not its area), and
    so does honeycomb whose elements behind it were deleted."""
    from ...barrier.spec import ODBSpec

    spec, u = ODBSpec(), v.units
    L = u.length
    xb = (pl.x_face + pl.direction * spec.depth) * L
    y0, z0 = pl.y_min * L, (pl.z_ground + spec.main.z_low) * L
    # edge l up (+z), m = n x l across (+y) for the normal -x: the rectangle covers the block's face
    return record(
        "RIGIDWALL_PLANAR_FINITE_ID",
        rwid=rwid,
        heading=heading,
        nsid=nodes,
        xt=xb,
        yt=y0,
        zt=z0,
        xh=xb - pl.direction * L,
        yh=y0,
        zh=z0,
        xhev=xb,
        yhev=y0,
        zhev=z0 + L,
        lenl=spec.main.height * L,
        lenm=spec.main.width * L,
    )


def odb_deck(
    car: Path | str,
    out: Path | str,
    barrier: str = "simplified",
    speed_kmh: float = 64.0,
    overlap: float = 0.4,
    side: str = "left",
    end_time: float = 0.12,
    gap: float = 1.0,
    ground: float = 0.0,
    output_dt: float = 1e-4,
    units: str | None = None,
    element_size: float = 20.0,
    erode_dtmin: float = 0.1,
    honeycomb: dict | None = None,
    beams: dict | None = None,
) -> Path:
    """Write the Euro NCAP ODB load case for vehicle deck ``car`` to ``out``
    and the barrier to ``<out stem>_barrier<suffix>`` beside it:
    ``barrier`` "simplified" (discrete beams) or "detailed" (honeycomb
    solids of ``element_size`` mm), ``overlap`` of the vehicle width on
    ``side`` (the driver's), face ``gap`` mm ahead of the vehicle, and the
    test rig's rigid block behind it (``_rig_wall``). With the
    detailed barrier, honeycomb elements crushed to a step below
    ``erode_dtmin`` x the run's first step, or turned inside out, are deleted
    (ERODE = 1, DTMIN), as honeycomb barrier models are run: crushed solid
    under a rail's edge they would otherwise stop the run (0: keep them).
    ``honeycomb``: further options of the detailed barrier
    (``detailed_barrier``: elform, shear_failure, shear_slip …); ``beams``:
    further options of the simplified one (``simplified_barrier``: n_width,
    n_main, n_bumper …)."""
    from ...barrier import offset_placement, simplified_barrier
    from ...barrier.detailed import detailed_barrier

    car, out = Path(car), Path(out)
    v = vehicle_info(car, units)
    u = v.units
    if barrier not in ("simplified", "detailed"):
        raise ValueError(f"barrier must be 'simplified' or 'detailed', got {barrier!r}")
    # barrier geometry is in mm: the vehicle's extents and gap in mm
    x_face = float(v.hi[0]) / u.length + gap
    pl = offset_placement(v.width / u.length, overlap, side, v.y_centre / u.length, x_face, 1, ground)
    boff = 2 * v.id_offset  # barrier IDs above the vehicle's and the load case's own
    if barrier == "simplified":
        b = simplified_barrier(placement=pl, id_offset=boff, units=u, **(beams or {}))
    else:
        b = detailed_barrier(placement=pl, id_offset=boff, units=u, element_size=element_size, **(honeycomb or {}))
    bpath = out.with_name(f"{out.stem}_barrier{out.suffix or '.k'}")
    out.parent.mkdir(parents=True, exist_ok=True)
    b.write(bpath)
    recs, nodes, parts = _common(
        v, speed_kmh, end_time, output_dt, ground, erode_dtmin if barrier == "detailed" else 0.0
    )
    recs.insert(
        3,
        record(
            "CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID",
            cid=v.id_offset + 1,
            heading="vehicle to barrier",
            ssid=parts,
            sstyp=2,
            msid=b.set_ids["parts"],
            mstyp=2,
            fs=0.3,
            fd=0.3,
            soft=1,
        ),
    )  # soft constraint: the barrier's faces are far softer than steel
    recs.insert(4, _rig_wall(v, pl, nodes, v.id_offset + 1, "ODB test rig: rigid block"))
    # the barrier's own nodes too: honeycomb torn free of the deleted block behind it is stopped by the
    # block and crushed against it, as in the test, instead of passing through the rig
    recs.insert(5, _rig_wall(v, pl, b.set_ids["front"], v.id_offset + 3, "ODB test rig: rigid block (barrier)"))
    title = f"Euro NCAP ODB {overlap * 100:g} % {side} {speed_kmh:g} km/h ({barrier} barrier)"
    text = _deck(title, [_include_name(car, out), bpath.name], recs)
    out.write_text(text)
    return out
