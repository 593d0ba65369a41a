"""The simplified ODB of the paper (section 2.1): non-linear discrete beams.

Layout (barrier axes: depth along the impact direction, width along y,
height along z): three node planes — bumper front, main-block front (the
sheet between bumper and block) and back. Bumper beams join the bumper
front to the block front, main-block beams join the block front to the
back, one beam per grid node; the grid rows of the block include the
bumper's rows, so both share the nodes of the middle sheet. Each beam is an
inelastic spring (*MAT_SPRING_INELASTIC, compression only, elastic
unloading along the compacted honeycomb's stiffness) on its block's whole force–crush curve, scaled by its tributary
share of the block face (ELEMENT_DISCRETE S). Cladding shells on the two
front planes carry contact and allow local intrusion; every cladding node
moves axially only; the back nodes are held (the fixed rigid wall of the
test rig). Honeycomb mass is lumped on the beam ends.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..units import SYSTEMS, UnitSystem
from .spec import COMPACTED_MODULUS, Block, ODBSpec, per_block

GRID = ("n_width", "n_main", "n_bumper")  # simplified_barrier's grid: nodes across, main-block rows, bumper rows
UNPRINTED = 1  # *ELEMENT_DISCRETE PF: left out of DEFORC (a barrier's thousands of links)


@dataclass(frozen=True)
class Placement:
    """Where the barrier stands: its front face at ``x_face``, its depth
    along ``direction`` (+1: +x, the vehicle travelling in +x), its width
    from ``y_min`` to ``y_min + width``, heights above ``z_ground``."""

    x_face: float = 0.0  # [mm]
    direction: int = 1
    y_min: float = -500.0  # [mm]
    z_ground: float = 0.0  # [mm]


def offset_placement(
    vehicle_width: float,
    overlap: float = 0.4,
    side: str = "left",
    y_centre: float = 0.0,
    x_face: float = 0.0,
    direction: int = 1,
    z_ground: float = 0.0,
    barrier_width: float = 1000.0,
) -> Placement:
    """Placement for an offset test: the barrier covers ``overlap`` of the
    vehicle width on ``side`` (the driver side: left for left-hand drive),
    as seen by the vehicle travelling along ``direction``·x with z up."""
    if not 0.0 < overlap <= 1.0:
        raise ValueError(f"overlap is a fraction of the vehicle width in (0, 1], got {overlap}")
    if side not in ("left", "right"):
        raise ValueError(f"side must be 'left' or 'right', got {side!r}")
    left = 1.0 if direction > 0 else -1.0  # +y is on the left of a vehicle moving in +x (z up)
    out = left if side == "left" else -left  # lateral sign pointing out of the vehicle on that side
    edge = y_centre + out * vehicle_width / 2.0  # vehicle's outer edge on that side
    inner = edge - out * overlap * vehicle_width  # barrier's inner edge
    y_min = inner if out > 0 else inner - barrier_width
    return Placement(x_face, direction, y_min, z_ground)


@dataclass
class SimplifiedBarrier:
    """A generated barrier (simplified or detailed): deck text and what
    load cases need of it."""

    deck: str  # free-format keyword text
    node_ids: dict = field(default_factory=dict)  # plane -> (n,) deck node IDs
    part_ids: dict = field(default_factory=dict)  # name -> part ID
    set_ids: dict = field(default_factory=dict)  # name -> set ID
    beams: int = 0
    shells: int = 0
    mass: float = 0.0  # in the deck's units
    solids: int = 0

    def write(self, path: Path | str, fmt: str = "fixed") -> Path:
        """Write as an LS-DYNA include deck (re-read, then written by the
        keyword writer so the format is exact)."""
        from .. import read_deck, write_deck

        path = Path(path)
        tmp = path.with_suffix(path.suffix + ".free")
        tmp.write_text(self.deck)
        try:
            model = read_deck(tmp)
        finally:
            tmp.unlink()
        write_deck(model, path, fmt=fmt)
        return path


def _rows(main: Block, bumper: Block | None, n_main: int, n_bumper: int) -> tuple[np.ndarray, np.ndarray]:
    """z of the block's node rows (ground at 0) and the indices of the
    bumper's rows among them."""
    if bumper is None:
        return np.linspace(main.z_low, main.z_high, n_main), np.zeros(0, np.int64)
    below, above = bumper.z_low - main.z_low, main.z_high - bumper.z_high
    rest = n_main - n_bumper  # cells outside the bumper's height
    if n_bumper < 2 or rest < (below > 0) + (above > 0):
        raise ValueError(f"{n_main} block rows cannot hold the {n_bumper} bumper rows and the rest of the face")
    n_below = int(round(rest * below / (below + above))) if below + above > 0 else 0
    n_below = min(max(n_below, 1 if below > 0 else 0), rest - (1 if above > 0 else 0))
    n_above = rest - n_below
    z = np.concatenate(
        [
            np.linspace(main.z_low, bumper.z_low, n_below + 1)[:-1],
            np.linspace(bumper.z_low, bumper.z_high, n_bumper),
            np.linspace(bumper.z_high, main.z_high, n_above + 1)[1:],
        ]
    )
    return z, np.arange(n_below, n_below + n_bumper)


def _tributary(c: np.ndarray) -> np.ndarray:
    """Length each grid coordinate carries: half of each neighbouring cell."""
    d = np.diff(c)
    t = np.zeros(len(c))
    t[:-1] += d / 2
    t[1:] += d / 2
    return t


class _Deck:
    """Free-format keyword text with an ID offset."""

    def __init__(self, offset: int):
        self.o = offset
        self.lines: list[str] = []

    def kw(self, name: str, *rows):
        self.lines.append(f"*{name}")
        self.lines += [",".join(_num(v) for v in r) for r in rows]


def _num(v) -> str:
    if isinstance(v, str):
        return v
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    return repr(float(v))


def _shear_links(dk, b: Block, nid, y, z, vid, eid, part_ids, strength, modulus, slip, title, u) -> list:
    """Shear links between the front nodes of neighbouring columns of block
    ``b`` (``nid`` rows along z, columns along y), each over the shared
    face (the tributary width across the link × the block's depth); see
    ``shear_link_springs``. Returns the ELEMENT_DISCRETE rows."""
    ty, tz = _tributary(y), _tributary(z)
    links = []  # (n1, n2, h, area)
    for i in range(nid.shape[0]):
        for j in range(nid.shape[1] - 1):
            links.append((nid[i, j], nid[i, j + 1], y[j + 1] - y[j], tz[i] * b.depth))
    for i in range(nid.shape[0] - 1):
        for j in range(nid.shape[1]):
            links.append((nid[i, j], nid[i + 1, j], z[i + 1] - z[i], ty[j] * b.depth))
    return shear_link_springs(dk, b, links, vid, eid, part_ids, strength, modulus, slip, title, u)


def shear_link_springs(
    dk: _Deck,
    b: Block,
    links: list,
    vid: int,
    eid: Iterator[int],
    part_ids: Iterator[int],
    strength: float,
    modulus: float,
    slip: float,
    title: str,
    u: UnitSystem,
) -> list:
    """Springs for shear links ``links`` [(n1, n2, h, area)] of block ``b``:
    each resists the two nodes' relative crush δ along the depth axis
    (orientation ``vid``) as shared cell walls do: τ·A with A the shared
    wall's ``area`` and τ = ``strength`` × the plateau stress, reached at
    δ = τh/G (h the columns' spacing, G = ``modulus`` × the crush modulus),
    torn at δ = ``slip`` (*MAT_SPRING_INELASTIC, unloading elastic; a torn
    link keeps a millionth of its force, so it stays on its envelope).
    *MAT_S08 carries one sign: each link is two elements, tension only and
    compression only, one part (material, curve) each per spacing h with
    IDs from the iterator ``part_ids``, element scale factor A. Returns the
    ELEMENT_DISCRETE rows, with PF 1: thousands of links, left out of DEFORC."""
    tau = strength * b.plateau_stress
    g = modulus * b.crush_modulus
    L, F = u.length, u.force
    stress = F / L**2
    parts = {}
    rows = []
    for n1, n2, h, area in links:
        key = round(float(h), 6)
        if key not in parts:  # *MAT_S08 carries one sign (CTF -1 tension, 1 compression): a part for each
            d_y = min(tau * h / g, 0.5 * slip)  # the plateau's start, well before the tear
            tail = 1e-6 * tau
            env = [(0.0, 0.0), (d_y, tau), (slip, tau), (1.001 * slip, tail), (1e3 * slip, tail)]
            parts[key] = []
            for sign in (1.0, -1.0):
                pid = next(part_ids)
                parts[key].append(pid)
                pts = sorted([(-sign * 1e3 * slip * L, 0.0)] + [(sign * d * L, sign * f * stress) for d, f in env])
                side = "tension" if sign > 0 else "compression"
                dk.kw("PART", [f"{title} {b.name} shear {h:.4g} {side}"], [pid, pid, pid])
                dk.kw("SECTION_DISCRETE", [pid, 0])
                dk.kw("MAT_SPRING_INELASTIC", [pid, pid, g / h * F / L**3, -sign])
                dk.kw("DEFINE_CURVE", [pid], *pts)
        for pid in parts[key]:
            rows.append((next(eid), pid, n1, n2, vid, area * L**2, UNPRINTED))
    return rows


def simplified_barrier(
    spec: ODBSpec | None = None,
    placement: Placement | None = None,
    n_width: int = 36,
    n_main: int = 20,
    n_bumper: int = 10,
    id_offset: int = 0,
    units: UnitSystem | None = None,
    bumper: bool = True,
    cladding: bool = True,
    title: str = "simplified ODB",
    shear_strength: float | tuple[float, float] = 0.0,
    shear_modulus: float = 1.0,
    shear_slip: float | tuple[float, float] = 90.0,
) -> SimplifiedBarrier:
    """The paper's simplified barrier: ``n_width × n_main`` main-block beams
    and ``n_width × n_bumper`` bumper beams (36 × 20 + 36 × 10 = 1080 by
    default), as deck text in ``units`` (default mm–t–s) with every ID
    raised by ``id_offset``. ``bumper=False`` gives the main block alone
    (its characterisation); ``cladding=False`` leaves the sheets out.

    ``shear_strength`` > 0 joins neighbouring columns of each block by
    shear links (``_shear_links``): the honeycomb's cell walls, which drag
    the columns beside an impactor's edge or a car's imprint along until
    they tear, as the detailed barrier's transverse shear does (its
    ``shear_strength``, ``shear_modulus`` and ``shear_slip``: 0.5, 1.0 and
    90 mm there). Columns crushed alike do not shear: a full-face impactor
    never loads them."""
    spec = spec or ODBSpec()
    spec.check()
    pl = placement or Placement()
    u = units or SYSTEMS["mm-t-s"]
    L, F = u.length, u.force
    main, bmp = spec.main, (spec.bumper if bumper else None)
    if n_width < 2 or n_main < 2:
        raise ValueError("the grid needs at least 2 nodes across and 2 rows")
    y = np.linspace(pl.y_min, pl.y_min + main.width, n_width)
    z, brow = _rows(main, bmp, n_main, n_bumper)
    ty, tz = _tributary(y), _tributary(z)
    tzb = _tributary(z[brow]) if bmp is not None else np.zeros(0)
    s_mid = bmp.depth if bmp is not None else 0.0
    d = pl.direction

    o = id_offset
    dk = _Deck(o)
    dk.kw("KEYWORD")
    dk.kw("TITLE", [title])
    ids = iter(range(o + 1, o + 10**8))
    planes = {}
    node_rows = []

    def plane(name, s, zz):
        yy, zg = np.meshgrid(y, zz, indexing="xy")  # rows along z, columns along y
        nid = np.array([next(ids) for _ in range(yy.size)], np.int64).reshape(yy.shape)
        planes[name] = nid
        for n, yv, zv in zip(nid.ravel(), yy.ravel(), zg.ravel()):
            node_rows.append((n, (pl.x_face + d * s) * L, yv * L, (pl.z_ground + zv) * L))

    if bmp is not None:
        plane("bumper_front", 0.0, z[brow])
    plane("block_front", s_mid, z)
    plane("back", s_mid + main.depth, z)
    dk.kw("NODE", *node_rows)

    # parts, sections, materials, curves
    pid = {"main block": o + 1, "bumper": o + 2, "cladding front": o + 3, "cladding middle": o + 4}
    cid = {"main block": o + 1, "bumper": o + 2}
    blocks = [main] + ([bmp] if bmp is not None else [])
    for b in blocks:
        key = b.name
        dk.kw("PART", [f"{title} {key}"], [pid[key], pid[key], pid[key]])
        dk.kw("SECTION_DISCRETE", [pid[key], 0])
        cx, cf = b.curve.points(b.depth)
        # unloading along the compacted honeycomb's stiffness (E_c·A over the depth left at full compaction),
        # or the steepest loading if steeper: a column a rail has bottomed out gives back F²/2KU, a few J
        # (with the loading slope it was ~100 J per beam, which threw its light nodes back at the car)
        k_compacted = COMPACTED_MODULUS * b.area / ((1.0 - b.curve.full) * b.depth)
        ku = max(float(np.max(np.diff(cf) / np.diff(cx))), k_compacted) * F / L
        dk.kw("MAT_SPRING_INELASTIC", [pid[key], cid[key], ku, 1])
        pts = [(-x * L, -f * F) for x, f in zip(cx[::-1], cf[::-1])] + [(b.depth * L, 0.0)]
        dk.kw("DEFINE_CURVE", [cid[key]], *pts)

    vid = o + 1  # beams act along the barrier's depth axis: they stay aligned through full crush
    dk.kw("DEFINE_SD_ORIENTATION", [vid, 0, float(d), 0.0, 0.0])
    elems, masses = [], {}
    eid = iter(range(o + 1, o + 10**8))

    def beams(b, front, back, share):
        for n1, n2, sh in zip(front.ravel(), back.ravel(), share.ravel()):
            elems.append((next(eid), pid[b.name], n1, n2, vid, sh))
            m = 0.5 * b.mass * sh * u.mass
            masses[n1] = masses.get(n1, 0.0) + m
            masses[n2] = masses.get(n2, 0.0) + m

    share_main = np.outer(tz, ty) / main.area
    beams(main, planes["block_front"], planes["back"], share_main)
    if bmp is not None:
        beams(bmp, planes["bumper_front"], planes["block_front"][brow], np.outer(tzb, ty) / bmp.area)
    strength, slip = per_block(shear_strength), per_block(shear_slip)
    fronts = [(main, planes["block_front"], y, z)] + (
        [(bmp, planes["bumper_front"], y, z[brow])] if bmp is not None else []
    )
    link_parts = iter(range(o + 10, o + 10**8))  # above the blocks' and sheets' parts (o + 1 .. o + 4)
    for b, nid, yy, zz in fronts:
        if strength[b.name] > 0:
            elems += _shear_links(
                dk, b, nid, yy, zz, vid, eid, link_parts, strength[b.name], shear_modulus, slip[b.name], title, u
            )
    dk.kw("ELEMENT_DISCRETE", *elems)
    n_beams = len(elems)

    shells = []
    if cladding:
        c = spec.cladding
        sheets = [("cladding middle", planes["block_front"], c.thickness_middle)]
        if bmp is not None:
            sheets.insert(0, ("cladding front", planes["bumper_front"], c.thickness_front))
        for name, nid, t in sheets:
            dk.kw("PART", [f"{title} {name}"], [pid[name], pid[name], pid[name]])
            dk.kw("SECTION_SHELL", [pid[name], 2, 1.0, 2], [t * L] * 4)
            dk.kw(
                "MAT_PLASTIC_KINEMATIC",
                [
                    pid[name],
                    c.density * u.density,
                    c.modulus * u.stress,
                    c.poisson,
                    c.yield_stress * u.stress,
                    0.0,
                    0.0,
                ],
            )
            for i in range(nid.shape[0] - 1):
                for j in range(nid.shape[1] - 1):
                    shells.append((next(eid), pid[name], nid[i, j], nid[i, j + 1], nid[i + 1, j + 1], nid[i + 1, j]))
        dk.kw("ELEMENT_SHELL", *shells)
        shell_mass = spec.cladding_mass(bmp is not None)
    else:
        shell_mass = 0.0
    dk.kw("ELEMENT_MASS", *[(next(eid), n, m) for n, m in sorted(masses.items())])

    # node sets and constraints: cladding planes move axially only, the back is held
    sid = {"front": o + 1, "axial": o + 2, "back": o + 3, "parts": o + 4}
    axial = np.concatenate([planes[k].ravel() for k in planes if k != "back"])
    # an impactor meets the bumper face first, the block face above and below the bumper later
    for key, nodes in (("front", axial), ("axial", axial), ("back", planes["back"].ravel())):
        dk.kw("SET_NODE_LIST", [sid[key]], *[nodes[i : i + 8] for i in range(0, len(nodes), 8)])
    used_parts = (
        [pid[b.name] for b in blocks]
        + ([pid["cladding middle"]] if cladding else [])
        + ([pid["cladding front"]] if cladding and bmp is not None else [])
    )
    dk.kw("SET_PART_LIST", [sid["parts"]], sorted(used_parts))
    dk.kw("BOUNDARY_SPC_SET", [sid["axial"], 0, 0, 1, 1, 0, 0, 0])
    dk.kw("BOUNDARY_SPC_SET", [sid["back"], 0, 1, 1, 1, 1, 1, 1])
    dk.kw("END")
    total = (main.mass + (bmp.mass if bmp is not None else 0.0) + shell_mass) * u.mass
    return SimplifiedBarrier(
        deck="\n".join(dk.lines) + "\n",
        node_ids={k: v.ravel() for k, v in planes.items()},
        part_ids={k: v for k, v in pid.items() if v in used_parts},
        set_ids=sid,
        beams=n_beams,
        shells=len(shells),
        mass=total,
    )
