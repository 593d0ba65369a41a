"""The simplified ODB under the rigid impactor: crush force, energy, overlap."""

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.barrier import ODBSpec, Placement, simplified_barrier
from crashlite.barrier.loadcases import Impactor, write_impactor_case
from crashlite.solver import run


def _run(tmp_path, impactor, end, **kw):
    pl = Placement()
    b = simplified_barrier(placement=pl, **kw)
    main = write_impactor_case(tmp_path, b, pl, impactor, end_time=end)
    return b, read_deck(main), run(main, output_dt=end / 400)


def test_main_block_crushes_at_its_crush_strength(tmp_path):
    """Main block alone, 5 t at 5 m/s: the plateau force is the crush
    strength × face area (0.342 MPa × 1000 × 650 mm = 222 kN) within 5 %,
    and the energy absorbed is the impactor's lost kinetic energy within 2 %."""
    m_imp, v0 = 5.0, 5000.0
    _, _, r = _run(tmp_path, Impactor(mass=m_imp, speed=v0), 0.1, bumper=False, cladding=False)
    f = -r.wall_force[:, 0, 0]
    crushing = f > 0.5 * f.max()
    plateau = np.median(f[crushing])
    spec = ODBSpec()
    assert plateau == pytest.approx(spec.main.strength * spec.main.area, rel=0.05)
    ke_lost = 0.5 * m_imp * (v0**2 - r.wall_velocity[-1, 0] ** 2)
    assert r.internal[-1] + r.kinetic[-1] - 0.5 * m_imp * r.wall_velocity[-1, 0] ** 2 == pytest.approx(
        ke_lost, rel=0.02
    )
    # largest crush: the kinetic energy spent on the plateau, m v0² / (2 F) (+ the gap)
    v = r.wall_velocity[:, 0]
    travel = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(r.time))])
    assert travel.max() - 1.0 == pytest.approx(0.5 * m_imp * v0**2 / plateau, rel=0.03)


def test_full_impact_energy_balance_and_axial_motion(tmp_path):
    """5 t at 64 km/h, 100 %: the barrier bottoms out; energy is conserved
    (ratio within 1 %) and no barrier node moves sideways."""
    b, m, r = _run(tmp_path, Impactor(), 0.06, cladding=False)
    assert np.all(np.abs(r.energy_ratio - 1.0) < 0.01)
    moved = r.final_x - m.nodes.xyz
    assert np.abs(moved[:, 1:]).max() == 0.0  # axial intrusion only
    back = np.isin(m.nodes.ids, b.node_ids["back"])
    assert np.abs(moved[back]).max() == 0.0  # tied to the fixed wall
    assert moved[~back, 0].max() > 0.5 * ODBSpec().bumper.depth


def test_forty_percent_overlap_intrudes_only_under_the_impactor(tmp_path):
    b, m, r = _run(tmp_path, Impactor(overlap=0.4), 0.03, cladding=False)
    front = np.isin(m.nodes.ids, b.node_ids["bumper_front"])
    y = m.nodes.xyz[:, 1]
    covered = y <= -500.0 + 400.0 + 1e-9  # the impactor spans y_min .. y_min + 40 % of the width
    dx = r.final_x[:, 0] - m.nodes.xyz[:, 0]
    assert dx[front & covered].min() > 100.0  # crushed through the bumper
    assert np.abs(dx[front & ~covered]).max() < 1e-9
    assert np.all(np.abs(r.energy_ratio - 1.0) < 0.01)


def test_cladding_adds_no_strength_at_forty_percent_overlap(tmp_path):
    """With the cladding sheets, 40 % overlap: the main-block plateau (after
    the bumper has pushed in, before compaction) is 40 % of the whole-face
    plateau within 5 %: the sheet between pushed and held face nodes yields
    instead of stretching over the stroke; the uncovered face is not pushed
    in (it may lift off its compression-only beams by a few mm). Energy is
    conserved within 1 %."""
    spec = ODBSpec()
    b, m, r = _run(tmp_path, Impactor(overlap=0.4), 0.02)
    v = r.wall_velocity[:, 0]
    travel = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(r.time))])
    f = -r.wall_force[:, 0, 0]
    phase = (travel > spec.bumper.depth + 30.0) & (travel < 0.7 * spec.main.depth)
    assert np.mean(f[phase]) == pytest.approx(0.4 * spec.main.curve.plateau, rel=0.05)
    front = np.isin(m.nodes.ids, np.concatenate([b.node_ids["bumper_front"], b.node_ids["block_front"]]))
    uncovered = m.nodes.xyz[:, 1] > -500.0 + 400.0 + 50.0  # one beam column clear of the impactor's edge
    dx = r.final_x[:, 0] - m.nodes.xyz[:, 0]
    assert dx[front & uncovered].max() < 1.0
    assert np.abs(dx[front & uncovered]).max() < 10.0
    assert np.all(np.abs(r.energy_ratio - 1.0) < 0.01)


def _links(m, b):
    """The shear links' elements (those joining two nodes of one front plane)."""
    fronts = [set(b.node_ids[k].tolist()) for k in ("block_front", "bumper_front") if k in b.node_ids]
    d = m.discretes
    n1, n2 = m.nodes.ids[d.nodes[:, 0]], m.nodes.ids[d.nodes[:, 1]]
    return np.flatnonzero([any(a in f and c in f for f in fronts) for a, c in zip(n1.tolist(), n2.tolist())])


def test_shear_links_are_the_cell_walls_between_columns(tmp_path):
    """Each link joins the front nodes of two neighbouring columns along the
    depth axis; its envelope is τ = 0.5 × the block's plateau stress over
    the shared face (the tributary width × the block's depth, the element's
    scale factor), elastic at G/h per unit area (G the crush modulus, h the
    spacing), torn at the 90 mm slip: on the 36 × 20 main block, 35 × 20 +
    36 × 19 links (two elements each, one per sign), whose faces add up to
    the block's height × its depth for each of the 35 column gaps and its
    width × its depth for each of the 19 row gaps."""
    spec = ODBSpec()
    pl = Placement()
    b = simplified_barrier(placement=pl, bumper=False, cladding=False, shear_strength=0.5)
    path = tmp_path / "b.k"
    b.write(path)
    m = read_deck(path)
    links = _links(m, b)
    assert len(links) == 2 * (35 * 20 + 36 * 19)  # a tension and a compression element each
    d = m.discretes
    assert np.all(d.pf[links] == 1) and np.all(np.delete(d.pf, links) == 0)  # DEFORC prints the beams only
    area = d.scale[links]
    along_y = np.isclose(m.nodes.xyz[d.nodes[links, 0], 2], m.nodes.xyz[d.nodes[links, 1], 2])
    main = spec.main
    assert area[along_y].sum() == pytest.approx(2 * 35 * main.height * main.depth, rel=1e-9)  # 35 column gaps
    assert area[~along_y].sum() == pytest.approx(2 * 19 * main.width * main.depth, rel=1e-9)  # 19 row gaps
    tau = 0.5 * main.curve.plateau / main.area
    for pid in np.unique(d.pid[links]):
        mat = m.materials[int(m.parts[int(pid)]["mid"])]
        curve = m.curves[int(mat["lcfd"])]
        x, f = np.asarray(curve.rows["a1"], float), np.asarray(curve.rows["o1"], float)
        sign = -float(mat["ctf"])  # CTF -1: tension only, 1: compression only
        assert sign in (1.0, -1.0)
        assert np.abs(f).max() == pytest.approx(tau, rel=1e-9) and np.all(sign * f >= 0.0)
        assert np.interp(sign * 89.0, x, f) == pytest.approx(sign * tau)
        assert abs(np.interp(sign * 91.0, x, f)) < 1e-5 * tau
        assert np.interp(-sign * 50.0, x, f) == 0.0  # nothing on the other side


def test_shear_links_carry_nothing_under_a_full_face(tmp_path):
    """Under the full-face impactor every column crushes alike: the links'
    energy stays below 1e-6 of the barrier's and the impactor slows down
    as without links (to 1e-3 of its speed, measured 3e-4: the stiff links shorten the
    step, so the force's one-step impact spike is sampled differently)."""
    kw = dict(bumper=False, cladding=False)
    imp = Impactor(mass=5.0, speed=5000.0)
    b, m, r = _run(tmp_path / "links", imp, 0.02, shear_strength=0.5, **kw)
    _, _, r0 = _run(tmp_path / "none", imp, 0.02, **kw)
    v, v0 = r.wall_velocity[:, 0], r0.wall_velocity[:, 0]
    assert np.abs(v - v0).max() < 1e-3 * imp.speed
    link_parts = np.unique(m.discretes.pid[_links(m, b)])
    on = np.isin(np.asarray(r.part_ids), link_parts)
    assert np.abs(r.part_internal[-1, on]).sum() < 1e-6 * r.internal[-1]


def test_shear_links_drag_the_columns_beside_an_edge(tmp_path):
    """At 40 % overlap the links drag the columns beside the impactor's edge
    along: the block takes more force over the first 80 mm than without
    links (by less than the edge's whole cell-wall strength, τ × 650 × 450
    mm: the dragged columns crush at their own strength first), the
    uncovered face away from the edge moves less than the covered, and
    energy is conserved within 1 %."""
    spec = ODBSpec()
    kw = dict(bumper=False, cladding=False)
    imp = Impactor(mass=5.0, speed=5000.0, overlap=0.4)
    b, m, r = _run(tmp_path / "links", imp, 0.02, shear_strength=0.5, **kw)
    _, _, r0 = _run(tmp_path / "none", imp, 0.02, **kw)

    def force_over(res, lo, hi):
        v = res.wall_velocity[:, 0]
        travel = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(res.time))])
        on = (travel > lo) & (travel < hi)
        return float(np.mean(-res.wall_force[on, 0, 0]))

    extra = force_over(r, 20.0, 80.0) - force_over(r0, 20.0, 80.0)
    edge = 0.5 * spec.main.curve.plateau / spec.main.area * spec.main.height * spec.main.depth
    assert 0.1 * edge < extra < edge
    dx = r.final_x[:, 0] - m.nodes.xyz[:, 0]
    front = np.isin(m.nodes.ids, b.node_ids["block_front"])
    y = m.nodes.xyz[:, 1]
    assert dx[front & (y > 300.0)].max() < 0.5 * dx[front & (y < -150.0)].min()
    assert np.all(np.abs(r.energy_ratio - 1.0) < 0.01)


def test_links_given_per_block_join_only_that_blocks_columns(tmp_path):
    """shear_strength and shear_slip as (main block, bumper): with (0, 0.5)
    only the bumper's front nodes are linked, their envelope τ = 0.5 × the
    bumper's plateau stress, torn at the bumper's own slip (6.4 mm, its
    cell), 35 × 10 + 36 × 9 links of two elements each."""
    spec = ODBSpec()
    b = simplified_barrier(placement=Placement(), cladding=False, shear_strength=(0.0, 0.5), shear_slip=(90.0, 6.4))
    m = read_deck(b.write(tmp_path / "b.k"))
    links = _links(m, b)
    d = m.discretes
    bumper = set(b.node_ids["bumper_front"].tolist())
    assert len(links) == 2 * (35 * 10 + 36 * 9)
    assert all(int(n) in bumper for n in m.nodes.ids[d.nodes[links]].ravel())
    tau = 0.5 * spec.bumper.curve.plateau / spec.bumper.area
    for pid in np.unique(d.pid[links]):
        mat = m.materials[int(m.parts[int(pid)]["mid"])]
        curve = m.curves[int(mat["lcfd"])]
        x, f = np.asarray(curve.rows["a1"], float), np.asarray(curve.rows["o1"], float)
        sign = -float(mat["ctf"])
        assert np.abs(f).max() == pytest.approx(tau, rel=1e-9)
        assert np.interp(sign * 6.3, x, f) == pytest.approx(sign * tau)
        assert abs(np.interp(sign * 6.5, x, f)) < 1e-5 * tau


def test_strip_impactor_crushes_only_the_columns_under_it(tmp_path):
    """A strip impactor (a face only as high as a car's bumper beam, 40 %
    of the width): without cladding and links it crushes the main block's
    columns under it at the block's plateau stress over their tributary
    area (5 rows × 34.2 mm, 15 columns over 414.3 mm: within 3 % over
    20–80 mm of travel), and the face above and below the strip stays
    where it was (below 1 % of the strip's push)."""
    spec = ODBSpec()
    main = spec.main
    z = np.linspace(main.z_low, main.z_high, 20)  # the main block's rows without the bumper
    lo, hi = 0.5 * (z[4] + z[5]), 0.5 * (z[9] + z[10])  # rows 5..9 under the strip
    imp = Impactor(mass=5.0, speed=5000.0, overlap=0.4143, height=(lo, hi))
    b, m, r = _run(tmp_path, imp, 0.02, bumper=False, cladding=False)
    v = r.wall_velocity[:, 0]
    travel = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(r.time))])
    on = (travel > 20.0) & (travel < 80.0)
    area = 5 * (z[1] - z[0]) * (1000.0 / 35 * 14.5)  # the first column carries half a spacing
    want = main.curve.plateau / main.area * area
    assert np.mean(-r.wall_force[on, 0, 0]) == pytest.approx(want, rel=0.03)
    dx = r.final_x[:, 0] - m.nodes.xyz[:, 0]
    front = np.isin(m.nodes.ids, b.node_ids["block_front"])
    zz = m.nodes.xyz[:, 2]
    outside = front & ((zz < lo - 20.0) | (zz > hi + 20.0))
    assert np.abs(dx[outside]).max() < 0.01 * travel[-1]
    assert dx[front & (zz > lo) & (zz < hi) & (m.nodes.xyz[:, 1] < Placement().y_min + 400.0)].min() > 0.9 * travel[-1]
