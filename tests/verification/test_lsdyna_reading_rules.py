"""Decks as LS-DYNA runs them: zero fields that mean "default", cards missing
before the next keyword, keywords that cannot change the solution, and
matsum's rigid-body velocity of deformable parts.

A 100 × 20 mm elastic plate flies at 10 m/s (1e4 mm/s) along +x towards a
planar rigid wall at x = 150 and a cylinder (the pole) further on. Written
the way LS-DYNA decks are written: BIRTH and DEATH 0.0 on the walls, the
cylinder's _DISPLAY card left out.
"""

from __future__ import annotations

import numpy as np
import pytest
from _plates import Plates

from crashlite import read_deck
from crashlite.solver import SetupError, run

V0 = 1.0e4  # mm/s


def _deck(tmp_path, walls: str, extra: str = "", end: float = 0.007):
    p = Plates(t=1.0, nu=0.3)
    ids = p.plate(1, 0.0, 100.0, 10, 0.0, 20.0, 2)
    p.add(f"*INITIAL_VELOCITY\n0\n{V0},0,0")
    p.node_set(1, ids)
    p.history([ids[1, -1]])
    p.add(walls)
    if extra:
        p.add(extra)
    path = tmp_path / "deck.k"
    path.write_text(p.text(end))
    return path, ids


# fixed format, every field written: BIRTH = DEATH = 0.0 (LS-DYNA: from 0 to 1e20)
PLANAR = """*RIGIDWALL_PLANAR_ID
         1ground
         1         0         0       0.0       0.0       0.0       0.0
     150.0       0.0       0.0     149.0       0.0       0.0       0.0       0.0"""
# the _DISPLAY card (PID RO E PR) left out, as LS-DYNA allows
CYLINDER = """*RIGIDWALL_GEOMETRIC_CYLINDER_DISPLAY_ID
         2pole
         1         0         0       0.0       0.0
     150.0      10.0    -100.0     150.0      10.0     100.0       0.0
       5.0     200.0"""


def test_walls_with_zero_birth_and_death_act_for_the_whole_run(tmp_path):
    path, ids = _deck(tmp_path, PLANAR)
    model = read_deck(path)
    (wall,) = model.find("RIGIDWALL_PLANAR")
    assert wall["birth"] == 0.0 and wall["death"] == 1e20
    r = run(model)
    x = r.node_coordinates[:, 0, 0]  # the plate's front corner, 50 mm from the wall at the start
    assert x.max() < 150.0 + 0.5  # stopped at the wall
    assert r.part_momentum[-1, 0, 0] < 0  # and sent back (the impact lasts 2L/c = 39 µs, between outputs)


def test_a_cylinder_without_its_display_card_reads_and_acts(tmp_path):
    path, ids = _deck(tmp_path, CYLINDER)
    model = read_deck(path)
    (wall,) = model.find("RIGIDWALL_GEOMETRIC_CYLINDER")
    assert (wall["death"], wall["pid"], wall["ro"], wall["e"], wall["pr"]) == (1e20, 0, 1e-9, 1e-4, 0.3)
    r = run(model)
    assert r.node_coordinates[:, 0, 0].max() < 150.0 - 5.0 + 0.5  # the pole at y = 10 stops the plate
    assert r.part_momentum[-1, 0, 0] < 0.5 * r.part_momentum[0, 0, 0]


def test_an_unused_sensor_runs_with_one_warning_and_a_sensor_control_is_refused(tmp_path):
    sensor = """*SENSOR_DEFINE_FORCE
         1        rw         1
*SENSOR_DEFINE_FORCE
         2        rw         1"""
    path, _ = _deck(tmp_path, PLANAR, sensor + "\n*DATABASE_EXTENT_BINARY\n0,0,3", end=0.002)
    r = run(path)
    warned = [w for w in r.info["warnings"] if "SENSOR_DEFINE_FORCE" in w]
    assert len(warned) == 1 and "cannot change the solution" in warned[0]  # said once, not also by the reader
    assert any("DATABASE_EXTENT_BINARY" in w for w in r.info["warnings"])
    control = "*SENSOR_CONTROL\n1,LOADCURVE,0,1,1"
    path, _ = _deck(tmp_path, PLANAR, sensor + "\n" + control, end=0.002)
    with pytest.raises(SetupError, match="SENSOR_CONTROL"):
        run(path)


def test_matsum_rigid_body_velocity_of_a_deformable_part_is_its_momentum_over_its_mass(tmp_path):
    path, _ = _deck(tmp_path, PLANAR)
    r = run(path, output_dt=1e-3)
    mass = 100.0 * 20.0 * 1.0 * 7.85e-9
    v = r.part_rigid_velocity[:, 0, :]
    np.testing.assert_allclose(v * mass, r.part_momentum[:, 0, :], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(v[0], [V0, 0, 0], rtol=1e-12)  # before the wall: the flight speed
    assert v[-1, 0] < 0  # rebounding after the elastic impact
