"""A detailed reference ODB: honeycomb blocks of solid elements.

Bumper and main block are meshed with 8-node solids of *MAT_HONEYCOMB
(MAT_026), crush direction along the barrier depth (AOPT 2): the uniaxial
crush curve LCA is the block's force–crush characteristic per face area
against volumetric strain, full compaction at the curve's end. Across the
cells (normal b, c and shear bc) the honeycomb is weak; the transverse
shears ab and ca, carried by the cell walls, are stiff and strong, and
fail at an engineering shear strain (SSEF, the walls tear where an
impactor's edge or a car's rail shears the block). With weak transverse shear the columns
of elements tilt as soon as the bumper has pushed in ahead of the block
face, crush in their weak directions and carry half the block's force.
The bumper is
bonded to the block (shared nodes), the back is held. The element size is
a parameter; its default makes the barrier cost far more to run than the
simplified one, as the honeycomb models of the paper's reference do.
"""

from __future__ import annotations

import numpy as np

from ..units import SYSTEMS, UnitSystem
from .columns import Column, split_columns
from .simplified import UNPRINTED, Placement, SimplifiedBarrier, _Deck, shear_link_springs
from .spec import COMPACTED_MODULUS, Block, ODBSpec, per_block

COLUMNS = "columns"  # shear_slip: split columns joined by links torn at one cell
# a split column's element tears at a cell's slip across one cell (engineering shear 1): the slip of a cut is the
# links' between columns, and a crush that differs across an element is not a tear (each cell crushes on its own)
CELL_TEAR_STRAIN = 1.0
SLIP_WORDS = ("cell", COLUMNS)  # the tear slips given by a word rather than in mm
# the transversely isotropic honeycomb (MAT_126, LCA < 0): a wall's shear falls from half a cell's slip across
# the element to nothing at a whole cell's (the tear), and the element keeps its crush
TEAR_ONSET, TEAR_RESIDUAL = 0.5, 0.0


def _segments(bounds: list[float], size: float) -> np.ndarray:
    """Grid coordinates through every bound, cells close to ``size``."""
    out = [bounds[0]]
    for a, b in zip(bounds[:-1], bounds[1:]):
        n = max(int(round((b - a) / size)), 1)
        out += list(np.linspace(a, b, n + 1)[1:])
    return np.array(out)


# aluminium cladding sheet (R94: AlMg2.5 / AlMg3, tensile strength >= 175 MPa): it tears where an
# impactor's edge stretches it
SHEET_E, SHEET_PR, SHEET_YIELD, SHEET_ETAN, SHEET_FAIL = 70000.0, 0.33, 100.0, 300.0, 0.2  # MPa, -, MPa, MPa, -


def _honeycomb(
    dk: _Deck,
    mid: int,
    lcid: int,
    b: Block,
    u: UnitSystem,
    d: int,
    modulus: float,
    lateral: float,
    shear_modulus: float,
    shear_strength: float,
    shear_failure: float,
    tear: tuple[float, float] | None = None,
) -> None:
    """The honeycomb of a block, crush along the depth (axis a; b, c
    across), curve ids from lcid on; the walls make the transverse shears
    ab and ca stiff (``shear_modulus`` × the crush modulus), while across
    the cells (normal b and c, shear bc) it is weak (``lateral`` × the
    crush values).

    ``tear`` None: MAT_026, the uniaxial curve the block's force–crush per
    face area, the transverse shears strong (``shear_strength`` × the
    plateau), failing at ``shear_failure`` (SSEF; lcid + 1 weak, lcid + 2
    transverse shear).

    ``tear`` (start, end): MAT_126 in its transversely isotropic form (LCA
    < 0). The yield by the angle off the cells (lcid): the crush plateau
    along them, √2 × ``shear_strength`` × the plateau at 45° (so that pure
    transverse shear yields at ``shear_strength`` × the plateau, as
    MAT_026's), ``lateral`` × the plateau across; the strong axis hardens
    by the crush curve over its plateau (lcid + 1), the weak axis not
    (lcid + 2); the walls' shear (LCS lcid + 3, all planes) falls from the
    engineering shear ``start`` to TEAR_RESIDUAL at ``end`` and the element
    is kept (SSEF 0); SHDFLG 1: the damage scales the undamaged stress.
    Damage counts the element's mean shear, so a crush graded across an
    element tears it as a cut through it does; a torn element keeps its
    crush, where MAT_026 deletes it."""
    cx, cf = b.curve.points(b.depth)
    strain, stress = cx / b.depth, cf / b.area
    e_u = b.crush_modulus
    vf = 1.0 - b.curve.full
    s = u.stress
    weak, g_t = lateral * e_u * s, shear_modulus * e_u * s
    first = [mid, b.density * u.density, modulus * s, 0.0, 20.0 * stress.max() * s, vf, 0.05, 0.0]
    moduli = [e_u * s, weak, weak, g_t, weak, g_t, 2.0, 1]
    axis_a = [0.0, 0.0, 0.0, float(d), 0.0, 0.0]
    if tear is None:
        lcw, lct = lcid + 1, lcid + 2
        dk.kw(
            "MAT_HONEYCOMB",
            first,
            [lcid, lcw, lcw, lcw, lct, lcw, lct, 0],
            moduli,
            axis_a,
            [0.0, 1.0, 0.0, 0.0, shear_failure, 0.0, 0.0, 0.0],
        )
        dk.kw("DEFINE_CURVE", [lcid], *[(float(a), float(f) * s) for a, f in zip(strain, stress)])
        low = lateral * stress[1:].min()
        dk.kw("DEFINE_CURVE", [lcw], (0.0, low * s), (1.0, low * s))
        tau = shear_strength * b.plateau_stress
        dk.kw("DEFINE_CURVE", [lct], (0.0, tau * s), (1.0, tau * s))
        return
    plateau = b.plateau_stress
    la, lb, lc, ls = lcid, lcid + 1, lcid + 2, lcid + 3
    dk.kw(
        "MAT_MODIFIED_HONEYCOMB",
        first,
        [-la, lb, lc, ls, 0, 0, 0, 0],
        moduli,
        axis_a,
        [0.0, 1.0, 0.0, 0.0] + [0.0] * 3 + [1.0],
    )
    across = (0.0, plateau), (45.0, np.sqrt(2.0) * shear_strength * plateau), (90.0, lateral * plateau)
    dk.kw("DEFINE_CURVE", [la], *[(a, f * s) for a, f in across])
    dk.kw("DEFINE_CURVE", [lb], *[(float(a), max(float(f) - plateau, 0.0) * s) for a, f in zip(strain, stress)])
    dk.kw("DEFINE_CURVE", [lc], (0.0, 0.0), (1.0, 0.0))
    start, end = tear
    dk.kw("DEFINE_CURVE", [ls], (0.0, 1.0), (0.5 * start, 1.0), (0.5 * end, TEAR_RESIDUAL), (10.0, TEAR_RESIDUAL))


def _column_links(dk, split, blocks, slip, strength, modulus, lateral, d, eid, u, o, title) -> None:
    """The links of split columns (``columns.split_columns``): along the
    depth the cell walls' shear, ``strength`` × the plateau stress torn at
    the block's ``slip`` (its cell); across, the honeycomb's weak in-plane
    stiffness (``lateral`` × the crush modulus over the columns' spacing),
    elastic."""
    vid = {"x": o + 1, "y": o + 2, "z": o + 3}
    for key, vec in (("x", (float(d), 0.0, 0.0)), ("y", (0.0, 1.0, 0.0)), ("z", (0.0, 0.0, 1.0))):
        dk.kw("DEFINE_SD_ORIENTATION", [vid[key], 0, *vec])
    part_ids = iter(range(o + 10, o + 10**8))  # above the blocks' parts and curves (o + 1 .. o + 6)
    L, F = u.length, u.force
    rows = []
    for b in blocks:
        links = split.links.get(b.name)
        if not links:
            continue
        rows += shear_link_springs(dk, b, links, vid["x"], eid, part_ids, strength, modulus, slip[b.name], title, u)
        pid = next(part_ids)
        dk.kw("PART", [f"{title} {b.name} across the cells"], [pid, pid, pid])
        dk.kw("SECTION_DISCRETE", [pid, 0])
        dk.kw("MAT_SPRING_ELASTIC", [pid, lateral * b.crush_modulus * F / L**2])
        rows += [(next(eid), pid, n1, n2, vid[k], a / h * L, UNPRINTED) for n1, n2, h, a in links for k in ("y", "z")]
    dk.kw("ELEMENT_DISCRETE", *rows)


def detailed_barrier(
    spec: ODBSpec | None = None,
    placement: Placement | None = None,
    element_size: float = 20.0,
    id_offset: int = 0,
    units: UnitSystem | None = None,
    bumper: bool = True,
    compacted_modulus: float = COMPACTED_MODULUS,
    lateral: float = 0.05,
    shear_modulus: float = 1.0,
    shear_strength: float = 0.5,
    shear_failure: float = 1.5,
    shear_slip: float | tuple[float, float] | str = 0.0,
    cladding: bool = False,
    title: str = "detailed ODB",
    elform: int = 1,
    height_size: float | None = None,
    width_size: float | None = None,
    honeycomb: str = "classic",
) -> SimplifiedBarrier:
    """Solid honeycomb barrier (mm–t–s spec, written in ``units``):
    elements of about ``element_size`` mm; ``compacted_modulus`` [MPa] of
    the fully compacted honeycomb; ``lateral`` the strength and stiffness
    across the cells, ``shear_modulus`` and ``shear_strength`` those of the
    transverse shears, as fractions of the crush values, ``shear_failure``
    their failure strain (SSEF; 0: none), or ``shear_slip`` [mm] > 0 the
    slip across an element at which its walls tear (SSEF = ``shear_slip``
    / ``element_size``, the same tear at any size; one value, a (main
    block, bumper) pair, or "cell": each block's honeycomb cell, 19.14 and
    6.4 mm, a bound on the slip a cell wall carries, with which the
    barrier converges under the car to about 5 %; docs/validation.md), or
    "columns": every column of elements on nodes of its own, neighbours
    joined by links along the depth at ``shear_strength`` torn at one
    cell, weak and elastic across (``columns.py``): a tear between
    columns keeps both columns' crush, which LS-DYNA's deletion of a
    failed MAT_026 element takes away; an element itself tears (and is
    deleted) at a cell's slip across one cell (SSEF = CELL_TEAR_STRAIN,
    1): a crush that differs across an element is spread over its cells
    and tears none (at a cell's slip over the element, a car deleted the
    bumper block in its overlap within 4 ms and the main block under its
    beam; docs/validation.md). Not with ``cladding``.
    Beside a car's imprint
    the honeycomb is dragged along until its walls tear: with a strain
    fixed per element, over a band an element wide as far as 1.5
    elements, so the barrier's energy under the generic car falls from
    72.7 to 53.1 kJ between 100 and 50 mm (ELFORM 2 with a 90 mm slip:
    82.4 to 69.8 kJ), and further with finer rows and columns
    (``height_size``, ``width_size``; ``bench/odb_car_convergence.py``,
    docs/validation.md).
    Not the default: under the flat impactor the bumper pushes the block
    face in along its top and bottom edges before the impactor reaches
    it, the slip deletes those bands of the block, and their crush
    capacity goes with them (100 % impactor at 60 mm: 492 instead of
    595 kJ). The back is held, as
    the back plate on the rigid wall. ``cladding``: aluminium sheets bonded
    to the bumper front and the block front (shells sharing the solids'
    nodes, MAT_024 failing at SHEET_FAIL). Off by default: at 50 mm the
    coarse sheets do not tear where the impactor's edge cuts them, as the
    real ones do (paper section 2.1), and at 40 % overlap they drag the
    honeycomb beside the impactor along, +40 % over the crush plateau.
    ``height_size`` [mm]: the elements' size across the height (z), if
    not ``element_size``: a car's bumper beam strikes a strip of the
    bumper block only 110 mm high, and the rows above and below it, shared
    nodes and all, crush by half its push; under the generic car 25 mm
    rows at 50 mm take the barrier's energy at 20 / 40 / 80 ms from 20.6 /
    46.4 / 53.1 to 16.8 / 37.5 / 48.9 kJ (ELFORM 1; docs/validation.md).
    ``width_size`` [mm] likewise across the width (y): the columns at the
    car's edge (the overlap's) and at its rails' edges.
    ``shear_slip`` counts over the elements' size across the face (the
    slip of a tear is a shear across the rows or the columns): the
    smaller of ``height_size`` and ``width_size`` where given (where they
    differ the slip holds across the finer, the coarser tears later), else
    ``element_size``.
    ``elform``: the honeycomb's *SECTION_SOLID formulation: 1 (default)
    one point with stiffness hourglass control (IHQ 4, QM 0.1), whose
    hourglass energy reaches 17–19 % of the internal energy under an
    offset impactor or a car; 2 fully integrated, without hourglass modes.
    Since SSEF counts the shear over the undeformed cell its crushed
    elements no longer fail in shear (40 % impactor at 60 mm: 524 mm,
    697 kJ, crush-phase ratings 0.862 / 0.820; before, 742 mm and 0.675),
    but under the car a 90 mm slip still leaves it unconverged (barrier
    82.4 kJ at 100 mm, 80.8 at 75 mm, 69.8 kJ at 50 mm): the elements
    beside the car's imprint crush by half its push, an error of the
    element size over the imprint's height (the bumper beam's, 110 mm),
    which a tear that keeps the column's crush does not remove
    (docs/validation.md).
    ``honeycomb``: "classic" (default) MAT_026, each stress component
    bounded on its own and a torn element deleted; "transverse" MAT_126's
    transversely isotropic form (``_transverse_honeycomb``): a crushing
    cell carries little shear beside its crush, and its walls' shear falls
    from half to all of a cell's slip across the element (the block's
    cell, or ``shear_slip`` in mm), after which the element keeps its
    crush: no element is deleted. Not with ``shear_slip`` "columns"."""
    spec = spec or ODBSpec()
    spec.check()
    pl = placement or Placement()
    u = units or SYSTEMS["mm-t-s"]
    L = u.length
    main, bmp = spec.main, (spec.bumper if bumper else None)
    d = pl.direction
    y = _segments([pl.y_min, pl.y_min + main.width], width_size or element_size)
    zb = [main.z_low, main.z_high] if bmp is None else [main.z_low, bmp.z_low, bmp.z_high, main.z_high]
    z = _segments(sorted(set(zb)), height_size or element_size)
    s_mid = bmp.depth if bmp is not None else 0.0
    s_main = _segments([s_mid, s_mid + main.depth], element_size)
    across = min(height_size or element_size, width_size or element_size)  # what a tear's slip shears

    o = id_offset
    dk = _Deck(o)
    dk.kw("KEYWORD")
    dk.kw("TITLE", [title])
    ny, nz = len(y), len(z)
    nid_main = (o + 1 + np.arange(len(s_main) * nz * ny)).reshape(len(s_main), nz, ny)
    rows = [
        (n, (pl.x_face + d * s) * L, yy * L, (pl.z_ground + zz) * L)
        for s, plane in zip(s_main, nid_main)
        for zz, line in zip(z, plane)
        for yy, n in zip(y, line)
    ]
    planes = {"block_front": nid_main[0].ravel(), "back": nid_main[-1].ravel()}
    if bmp is not None:
        kb = np.flatnonzero((z >= bmp.z_low - 1e-9) & (z <= bmp.z_high + 1e-9))
        s_b = _segments([0.0, bmp.depth], element_size)
        nid_b = np.empty((len(s_b), len(kb), ny), np.int64)
        nid_b[-1] = nid_main[0][kb]  # bonded: the bumper's back is the block's front
        start = o + 1 + nid_main.size
        nid_b[:-1] = (start + np.arange((len(s_b) - 1) * len(kb) * ny)).reshape(len(s_b) - 1, len(kb), ny)
        rows += [
            (n, (pl.x_face + d * s) * L, yy * L, (pl.z_ground + z[k]) * L)
            for s, plane in zip(s_b[:-1], nid_b[:-1])
            for k, line in zip(kb, plane)
            for yy, n in zip(y, line)
        ]
        planes["bumper_front"] = nid_b[0].ravel()
    dk.kw("NODE", *rows)

    pid = {"main block": o + 1, "bumper": o + 2}
    eid = iter(range(o + 1, o + 10**9))
    elems = []

    cols = []  # the same elements as grid records, for split_columns (only when splitting)

    def hexes(nid, part, name, s, k0):
        a = nid  # (s, z, y): depth, height, width; row k of a is row k0 + k of the barrier's grid
        for i in range(a.shape[0] - 1):
            for k in range(a.shape[1] - 1):
                for j in range(a.shape[2] - 1):
                    # x (depth) × y (width) × z (height) right-handed for d = +1
                    bot = [a[i, k, j], a[i + 1, k, j], a[i + 1, k, j + 1], a[i, k, j + 1]]
                    top = [a[i, k + 1, j], a[i + 1, k + 1, j], a[i + 1, k + 1, j + 1], a[i, k + 1, j + 1]]
                    if d < 0:  # mirrored along x: keep a positive volume
                        bot, top = bot[::-1], top[::-1]
                    elems.append((next(eid), part, *bot, *top))
                    if shear_slip != COLUMNS:
                        continue
                    K = k0 + k
                    cols.append(
                        Column(
                            elems[-1],
                            name,
                            i,
                            (K, j),
                            (a[i, k, j + 1], a[i + 1, k, j + 1], a[i, k + 1, j + 1], a[i + 1, k + 1, j + 1]),
                            (a[i, k + 1, j], a[i + 1, k + 1, j], a[i, k + 1, j + 1], a[i + 1, k + 1, j + 1]),
                            y[j + 1] - y[j],
                            z[K + 1] - z[K],
                            s[i + 1] - s[i],
                        )
                    )

    hexes(nid_main, pid[main.name], main.name, s_main, 0)  # "bumper" when the bumper is characterised alone
    blocks = [main]
    if bmp is not None:
        hexes(nid_b, pid["bumper"], bmp.name, s_b, int(kb[0]))
        blocks.append(bmp)
    slip = {b.name: b.cell for b in blocks} if shear_slip in SLIP_WORDS else per_block(shear_slip)
    if honeycomb not in ("classic", "transverse"):
        raise ValueError(f"honeycomb={honeycomb!r}: 'classic' (MAT_026) or 'transverse' (MAT_126, LCA < 0)")
    if honeycomb == "transverse" and shear_slip == COLUMNS:
        raise ValueError("honeycomb='transverse' tears inside the elements; split columns tear between them")
    if shear_slip in SLIP_WORDS and not all(slip.values()):  # a zero slip would silently mean SSEF
        raise ValueError(f"shear_slip={shear_slip!r} needs each block's cell size, got {slip}")
    split = None
    if shear_slip == COLUMNS:
        if cladding:
            raise ValueError(
                "shear_slip='columns' splits the face nodes the cladding would share; use one or the other"
            )
        split = split_columns(cols, o + 1 + len(rows))
        elems = split.elements
        where = {r[0]: r[1:] for r in rows}
        copies = [(n, *where[orig]) for n, orig in split.new_nodes]
        dk.kw("NODE", *copies)
        rows += copies
        planes = {k: np.array([c for n in v for c in split.copies[n]], np.int64) for k, v in planes.items()}
    dk.kw("ELEMENT_SOLID", *elems)
    for k, b in enumerate(blocks):
        p = pid[b.name]
        dk.kw("PART", [f"{title} {b.name}"], [p, p, p, 0, p if elform == 1 else 0])
        dk.kw("SECTION_SOLID", [p, elform])
        if elform == 1:
            dk.kw("HOURGLASS", [p, 4, 0.1])
        # split: a cut between columns is the links'; the elements keep their shear (with weak shear inside,
        # the columns tilt: a full face carried 126 instead of 230 kN) and tear at a cell across a cell
        # split: a cut between columns is the links'; the elements keep their shear (with weak shear inside,
        # the columns tilt: a full face carried 126 instead of 230 kN) and tear at a cell across a cell
        ssef = CELL_TEAR_STRAIN if split else slip[b.name] / across if slip[b.name] > 0.0 else shear_failure
        cell_slip = (slip[b.name] or b.cell) / across  # the transverse form's tear: a cell's slip across the element
        _honeycomb(
            dk,
            p,
            o + 1 + (4 if honeycomb == "transverse" else 3) * k,  # each block's curves
            b,
            u,
            d,
            compacted_modulus,
            lateral,
            shear_modulus,
            shear_strength,
            ssef,
            (TEAR_ONSET * cell_slip, cell_slip) if honeycomb == "transverse" else None,
        )
    if split:
        _column_links(dk, split, blocks, slip, shear_strength, shear_modulus, lateral, d, eid, u, o, title)
    shells = []
    if cladding:
        c = spec.cladding
        sheets = [("cladding middle", nid_main[0], c.thickness_middle)]
        if bmp is not None:
            sheets.insert(0, ("cladding front", nid_b[0], c.thickness_front))
        for k, (name, nid, t) in enumerate(sheets):
            p = o + 3 + k
            pid[name] = p
            dk.kw("PART", [f"{title} {name}"], [p, p, p])
            dk.kw("SECTION_SHELL", [p, 2, 1.0, 2], [t * L] * 4)
            dk.kw(
                "MAT_PIECEWISE_LINEAR_PLASTICITY",
                [
                    p,
                    c.density * u.density,
                    SHEET_E * u.stress,
                    SHEET_PR,
                    SHEET_YIELD * u.stress,
                    SHEET_ETAN * u.stress,
                    SHEET_FAIL,
                    0.0,
                ],
                [0.0, 0.0, 0, 0, 0.0],
            )
            shells += [
                (next(eid), p, nid[i, j], nid[i, j + 1], nid[i + 1, j + 1], nid[i + 1, j])
                for i in range(nid.shape[0] - 1)
                for j in range(nid.shape[1] - 1)
            ]
        dk.kw("ELEMENT_SHELL", *shells)
    sid = {"front": o + 1, "back": o + 2, "parts": o + 4}
    all_nodes = np.array([r[0] for r in rows], np.int64)
    front = np.setdiff1d(all_nodes, planes["back"])
    for key, nodes in (("front", front), ("back", planes["back"])):
        dk.kw("SET_NODE_LIST", [sid[key]], *[nodes[i : i + 8] for i in range(0, len(nodes), 8)])
    used = [b.name for b in blocks] + [k for k in pid if k.startswith("cladding")]
    dk.kw("SET_PART_LIST", [sid["parts"]], [pid[k] for k in used])
    dk.kw("BOUNDARY_SPC_SET", [sid["back"], 0, 1, 1, 1, 1, 1, 1])
    dk.kw("END")
    mass = (sum(b.mass for b in blocks) + (spec.cladding_mass(bmp is not None) if cladding else 0.0)) * u.mass
    return SimplifiedBarrier(
        deck="\n".join(dk.lines) + "\n",
        node_ids=planes,
        part_ids={k: pid[k] for k in used},
        set_ids=sid,
        beams=0,
        shells=len(shells),
        mass=mass,
        solids=len(elems),
    )
