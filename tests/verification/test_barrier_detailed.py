"""The detailed reference ODB (honeycomb solids, MAT_026): crush force."""

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.barrier import ODBSpec, Placement
from crashlite.barrier.detailed import detailed_barrier
from crashlite.barrier.loadcases import Impactor, write_impactor_case
from crashlite.model.mesh import index_map
from crashlite.solver import run


def test_detailed_main_block_crushes_on_its_honeycomb_curve(tmp_path):
    """Coarse main block of MAT_026 solids crushed by a 5 t wall at 5 m/s:
    the force is the honeycomb's crush stress × face area (the paper's
    230 kN; R94: 0.342 MPa × 0.65 m² = 222 kN, within 5 %), the energy
    is conserved, hourglass energy stays small."""
    pl = Placement()
    b = detailed_barrier(placement=pl, element_size=75.0, bumper=False)
    m = read_deck(b.write(tmp_path / "det.k"))
    assert len(m.solids) == b.solids > 0
    assert m.mass_properties().mass == pytest.approx(ODBSpec().main.mass, rel=1e-9)
    main = write_impactor_case(tmp_path, b, pl, Impactor(mass=5.0, speed=5000.0), end_time=0.02)
    r = run(main, output_dt=2e-4)
    f = -r.wall_force[:, 0, 0]
    plateau = np.median(f[r.time > 0.002])
    spec = ODBSpec()
    assert plateau == pytest.approx(spec.main.curve.plateau, rel=0.02)
    assert plateau == pytest.approx(spec.main.strength * spec.main.area, rel=0.05)
    assert np.all(np.abs(r.energy_ratio - 1.0) < 0.01)
    assert r.hourglass.max() < 0.1 * r.internal.max()


@pytest.mark.parametrize("slip, honeycomb", [(0.0, "classic"), ("columns", "classic"), ("cell", "transverse")])
def test_whole_detailed_barrier_with_the_bumper_crushes_at_the_full_face_plateau(tmp_path, slip, honeycomb):
    """Bumper bonded ahead of the block, 1000 t wall at 10 m/s (constant
    speed), 60 mm solids: once the wall reaches the block face beside the
    bumper, the force is the main block's plateau over the whole face
    (230 kN within 10 %) until compaction: the transverse shear of the cell
    walls keeps the columns behind the bumper's edge from tilting (with
    weak shear they carried half of it). The same with split columns,
    whose links carry the walls' shear until a cell of slip, and with
    MAT_126's transversely isotropic honeycomb, whose walls' shear is
    damaged, not deleted, past a cell's slip."""
    pl = Placement()
    b = detailed_barrier(placement=pl, element_size=60.0, shear_slip=slip, honeycomb=honeycomb)
    main = write_impactor_case(tmp_path, b, pl, Impactor(mass=1000.0, speed=10000.0), end_time=0.033)
    r = run(main, output_dt=2e-4)
    f = -r.wall_force[:, 0, 0]
    spec = ODBSpec()
    whole_face = (r.time > (spec.bumper.depth + 30.0) / 1e4) & (r.time < 0.032)  # 120 .. 320 mm of travel
    assert np.median(f[whole_face]) == pytest.approx(spec.main.curve.plateau, rel=0.10)
    assert f[whole_face].min() > 0.7 * spec.main.curve.plateau
    assert np.all(np.abs(r.energy_ratio - 1.0) < 0.01)


def test_detailed_cladding_sheets_share_the_face_nodes(tmp_path):
    """cladding=True: one shell per face cell on the bumper front and the
    block front, on the solids' own nodes, in the barrier's part set; the
    mass adds the sheets."""
    spec = ODBSpec()
    bare = detailed_barrier(element_size=100.0)
    b = detailed_barrier(element_size=100.0, cladding=True)
    m = read_deck(b.write(tmp_path / "det.k"))
    assert len(m.shells) == b.shells > 0 and bare.shells == 0
    assert np.isin(m.shells.nodes, m.solids.nodes).all()
    c = spec.cladding
    sheets = c.density * (c.thickness_middle * spec.main.area + c.thickness_front * spec.bumper.area)
    assert m.mass_properties().mass == pytest.approx(bare.mass + sheets, rel=1e-9)
    assert {"cladding front", "cladding middle"} <= set(b.part_ids)


def test_shear_slip_fixes_the_tear_in_mm_at_every_element_size(tmp_path):
    """shear_slip [mm] > 0: the transverse shears' failure strain SSEF is
    the slip over the elements' size across the face (the same tear at 100
    and at 50 mm, and with 25 mm rows and columns under 50 mm depth; the
    finer of rows and columns where they differ); without it SSEF is
    shear_failure, the same strain at every size."""
    cases = (
        (100.0, None, None, 50.0, 0.5),
        (50.0, None, None, 50.0, 1.0),
        (50.0, None, None, 0.0, 1.5),
        (50.0, 25.0, 25.0, 90.0, 3.6),
        (50.0, 12.5, 25.0, 90.0, 7.2),
    )
    for k, (size, height, width, slip, want) in enumerate(cases):
        b = detailed_barrier(element_size=size, height_size=height, width_size=width, shear_slip=slip)
        m = read_deck(b.write(tmp_path / f"d{k}.k"))
        assert [float(mat["ssef"]) for mat in m.materials.values()] == pytest.approx([want, want])


def _grid_lines(model) -> list[np.ndarray]:
    """The structured barrier's node coordinates along x, y and z."""
    return [np.unique(np.round(model.nodes.xyz[:, a], 6)) for a in range(3)]


def test_height_size_refines_the_rows_only(tmp_path):
    """height_size: rows of about that height through every block edge
    (the bumper's included), columns and depth at element_size; the
    barrier's mass and its ids of parts unchanged."""
    spec = ODBSpec()
    coarse = detailed_barrier(element_size=50.0)
    fine = detailed_barrier(element_size=50.0, height_size=25.0)
    mc, mf = (read_deck(b.write(tmp_path / f"{n}.k")) for n, b in (("c", coarse), ("f", fine)))
    (xc, yc, zc), (xf, yf, zf) = _grid_lines(mc), _grid_lines(mf)
    assert np.array_equal(yc, yf) and np.array_equal(xc, xf)
    assert np.diff(zf).max() <= 1.1 * 25.0 < np.diff(zc).min()
    edges = [spec.main.z_low, spec.bumper.z_low, spec.bumper.z_high, spec.main.z_high]
    assert all(np.isclose(zf - zf.min() + edges[0], e).any() for e in edges)
    assert fine.solids > 1.8 * coarse.solids
    assert mf.mass_properties().mass == pytest.approx(mc.mass_properties().mass, rel=1e-9)
    assert fine.part_ids == coarse.part_ids


def test_width_size_refines_the_columns_only(tmp_path):
    """width_size: columns of about that width across the barrier's
    1 000 mm, rows and depth at element_size; mass unchanged."""
    coarse = detailed_barrier(element_size=50.0)
    fine = detailed_barrier(element_size=50.0, width_size=25.0)
    mc, mf = (read_deck(b.write(tmp_path / f"{n}.k")) for n, b in (("c", coarse), ("f", fine)))
    (xc, yc, zc), (xf, yf, zf) = _grid_lines(mc), _grid_lines(mf)
    assert np.array_equal(zc, zf) and np.array_equal(xc, xf)
    assert np.diff(yf).max() <= 1.1 * 25.0 < np.diff(yc).min()
    assert yf[0] == yc[0] and yf[-1] == yc[-1]
    assert fine.solids > 1.9 * coarse.solids
    assert mf.mass_properties().mass == pytest.approx(mc.mass_properties().mass, rel=1e-9)


def test_shear_slip_per_block_and_by_cell(tmp_path):
    """shear_slip as (main block, bumper) sets each block's SSEF from its own
    slip; "cell" takes each block's honeycomb cell (19.14 and 6.4 mm,
    Directive 96/79/EC Annex 6): one cell of slip over the 50 mm face."""
    spec = ODBSpec()
    assert (spec.main.cell, spec.bumper.cell) == (19.14, 6.4)
    for k, slip in enumerate(((19.14, 6.4), "cell")):
        b = detailed_barrier(element_size=50.0, shear_slip=slip)
        m = read_deck(b.write(tmp_path / f"d{k}.k"))
        ssef = {
            m.parts[p]["heading"].split(" ", 2)[-1]: float(m.materials[int(m.parts[p]["mid"])]["ssef"]) for p in m.parts
        }
        assert ssef == pytest.approx({"main block": 19.14 / 50.0, "bumper": 6.4 / 50.0})


def test_shear_slip_refuses_what_it_cannot_place():
    """A tear by "cell" needs every block's cell size (a zero would fall back
    to SSEF unnoticed), and a per-block slip is one value or two."""
    from dataclasses import replace

    spec = ODBSpec()
    with pytest.raises(ValueError, match="cell size"):
        detailed_barrier(replace(spec, bumper=replace(spec.bumper, cell=0.0)), element_size=100.0, shear_slip="cell")
    with pytest.raises(ValueError, match="main block, bumper"):
        detailed_barrier(element_size=100.0, shear_slip=(19.14, 6.4, 1.0))


def test_split_columns_own_their_nodes_and_link_every_shared_wall(tmp_path):
    """shear_slip="columns": every column of elements (one across the face,
    the block's depth) on nodes of its own, the copies where the shared
    mesh had one node; an element tears (SSEF) at a cell's slip across
    one cell (shear strain 1: a cut between columns is the links'); the links along
    the depth cover every wall
    two columns of a block share, once: the scale factors of each block's
    tension (or compression) links sum to its walls' area, (columns − 1)
    × height × depth + (rows − 1) × width × depth, each at τ = 0.5 × the
    block's plateau stress up to a slip of its cell. Mass unchanged."""
    spec = ODBSpec()
    shared = detailed_barrier(element_size=100.0, shear_slip="cell")
    b = detailed_barrier(element_size=100.0, shear_slip="columns")
    ms, m = (read_deck(x.write(tmp_path / f"{n}.k")) for n, x in (("s", shared), ("c", b)))
    assert m.mass_properties().mass == pytest.approx(ms.mass_properties().mass, rel=1e-9)
    assert len(m.solids) == len(ms.solids)
    xyz = {int(n): tuple(np.round(p, 6)) for n, p in zip(m.nodes.ids, m.nodes.xyz)}
    # a node belongs to one column: its elements' (y, z) centres agree
    cen = {}
    for conn in m.solids.nodes:
        c = tuple(np.round(m.nodes.xyz[conn, 1:].mean(axis=0), 3))
        for n in conn:
            cen.setdefault(int(n), set()).add(c)
    assert max(len(v) for v in cen.values()) == 1
    assert sorted(set(xyz.values())) == sorted({tuple(np.round(p, 6)) for p in ms.nodes.xyz})
    ssef = [float(mat["ssef"]) for mat in m.materials.values() if mat.keyword == "MAT_HONEYCOMB"]
    assert ssef == pytest.approx([1.0, 1.0])  # a cell's slip across a cell, at any element size
    heading = {p: m.parts[p]["heading"] for p in m.parts}
    assert set(m.discretes.pf.tolist()) == {1}  # tens of thousands of links: left out of DEFORC
    for pid, h in heading.items():  # each block's links hold τ = 0.5 × its plateau up to one cell of slip
        if h.endswith("tension"):
            blk = spec.bumper if "bumper" in h else spec.main
            curve = m.curves[int(m.materials[int(m.parts[pid]["mid"])]["lcfd"])]
            x, f = np.asarray(curve.rows["a1"], float), np.asarray(curve.rows["o1"], float)
            assert f.max() == pytest.approx(0.5 * blk.plateau_stress, rel=1e-9)
            assert x[f > 0.5 * f.max()].max() == pytest.approx(blk.cell, rel=1e-9)
    scale: dict = {}
    for pid, s in zip(m.discretes.pid, m.discretes.scale):
        h = heading[int(pid)]
        if h.endswith("tension"):
            block = "bumper" if "bumper" in h else "main block"
            scale[block] = scale.get(block, 0.0) + float(s)
    y = np.unique(ms.nodes.xyz[:, 1])
    for blk in (spec.main, spec.bumper):
        z = ms.nodes.xyz[:, 2] - Placement().z_ground
        zb = np.unique(np.round(z[(z >= blk.z_low - 1e-6) & (z <= blk.z_high + 1e-6)], 6))
        want = (len(y) - 2) * blk.height * blk.depth + (len(zb) - 2) * blk.width * blk.depth
        assert scale[blk.name] == pytest.approx(want, rel=1e-9)


def test_split_columns_crush_at_the_plateau_when_pushed_alike(tmp_path):
    """Under a wall over the whole face every column crushes alike: the
    links stay unloaded, and the split main block crushes at the honeycomb's
    plateau (within 2 %) with its energy balanced (1 %), as the shared
    mesh does."""
    pl = Placement()
    b = detailed_barrier(placement=pl, element_size=75.0, bumper=False, shear_slip="columns")
    main = write_impactor_case(tmp_path, b, pl, Impactor(mass=5.0, speed=5000.0), end_time=0.02)
    r = run(main, output_dt=2e-4)
    f = -r.wall_force[:, 0, 0]
    assert np.median(f[r.time > 0.002]) == pytest.approx(ODBSpec().main.curve.plateau, rel=0.02)
    assert np.all(np.abs(r.energy_ratio - 1.0) < 0.01)


def test_split_columns_crushed_unevenly_keep_their_elements(tmp_path):
    """Split columns pushed unevenly across the height (the face's nodes
    driven along the depth at speeds rising linearly with their height,
    15 to 100 % of 5 m/s for 60 ms): the crush differs across every
    element by 0.39 of its height, a slip spread over the cells that tears
    none of them, so no element is deleted (at a cell's slip over the
    100 mm elements, 0.19, 40 elements were, and the honeycomb took 0.79
    of its crush) and the honeycomb takes its plateau stress over the
    volume the face sweeps (within 6 %; 0.96), energy balanced."""
    spec = ODBSpec()
    pl = Placement()
    b = detailed_barrier(placement=pl, element_size=100.0, bumper=False, shear_slip="columns", elform=2)
    b.write(tmp_path / "barrier.k")
    m = read_deck(tmp_path / "barrier.k")
    front = np.asarray(b.node_ids["block_front"])
    z = m.nodes.xyz[index_map(m.nodes.ids)(front), 2]
    z0, h = z.min(), np.ptp(z)
    v, end = 5000.0, 0.06  # mm/s, s
    share = 0.15 + 0.85 * (z - z0) / h
    rows = "\n".join(f"{n},1,0,900,{v * s:.6g}" for n, s in zip(front, share))
    (tmp_path / "main.k").write_text(
        "*KEYWORD\n*INCLUDE\nbarrier.k\n*DEFINE_CURVE\n900\n0.0,1.0\n1.0,1.0\n"
        f"*BOUNDARY_PRESCRIBED_MOTION_NODE\n{rows}\n*CONTROL_TERMINATION\n{end}\n*END\n"
    )
    r = run(tmp_path / "main.k", output_dt=1e-3)
    assert r.deleted() == 0
    solids = np.isin(r.part_ids, list(b.part_ids.values()))
    crush = r.part_internal[-1, solids].sum()
    swept = spec.main.area * v * end * 0.575  # the mean share over the height: 0.15 + 0.85 / 2
    assert crush == pytest.approx(spec.main.strength * swept, rel=0.06)
    assert np.all(np.abs(r.energy_ratio - 1.0) < 0.02)


def test_transverse_honeycomb_writes_mat126_with_its_angle_hardening_and_damage_curves(tmp_path):
    """honeycomb="transverse": each block is a MAT_126 with LCA < 0 whose
    |LCA| holds the plateau along the cells, √2 × the shear strength × the
    plateau at 45° and the lateral fraction across; LCB the crush curve
    over its plateau; the damage curve LCS (of half the engineering shear)
    falls from 1 at half a cell's slip across the element to the residual
    at a whole cell's; no SSEF (nothing deleted), SHDFLG 1. A
    main block alone crushed by a 5 t wall at 5 m/s crushes at its plateau
    (2 %), energy balanced, nothing deleted."""
    from crashlite.barrier.detailed import TEAR_ONSET, TEAR_RESIDUAL

    spec, pl = ODBSpec(), Placement()
    b = detailed_barrier(placement=pl, element_size=75.0, bumper=False, honeycomb="transverse", shear_strength=0.5)
    m = read_deck(b.write(tmp_path / "det.k"))
    (mat,) = [r for r in m.materials.values() if r.keyword == "MAT_MODIFIED_HONEYCOMB"]
    assert int(mat["lca"]) < 0 and float(mat["ssef"]) == 0.0 and float(mat["shdflg"]) == 1.0
    plateau = spec.main.plateau_stress
    angle = m.curves[-int(mat["lca"])].rows
    np.testing.assert_allclose(angle["o1"], [plateau, np.sqrt(2.0) * 0.5 * plateau, 0.05 * plateau])
    np.testing.assert_allclose(angle["a1"], [0.0, 45.0, 90.0])
    damage = m.curves[int(mat["lcs"])].rows
    tear = spec.main.cell / 75.0  # a cell's slip across the element
    np.testing.assert_allclose(damage["a1"][:3], [0.0, 0.5 * TEAR_ONSET * tear, 0.5 * tear])
    np.testing.assert_allclose(damage["o1"][:3], [1.0, 1.0, TEAR_RESIDUAL])
    main = write_impactor_case(tmp_path, b, pl, Impactor(mass=5.0, speed=5000.0), end_time=0.02)
    r = run(main, output_dt=2e-4)
    f = -r.wall_force[:, 0, 0]
    assert np.median(f[r.time > 0.002]) == pytest.approx(spec.main.curve.plateau, rel=0.02)
    assert r.deleted() == 0
    assert np.all(np.abs(r.energy_ratio - 1.0) < 0.01)
