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
