"""Rigid parts (*MAT_RIGID): mass from their elements, constraints, extra
nodes, merged bodies."""

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.solver import run

RO = 7.85e-9


def _plate_deck(tmp_path, extra=(), mat="1,7.85e-9,210000.0,0.3"):
    """A rigid 100 x 100 x 2 shell plate (part 1, 0.157 kg), moving +x at
    1000 mm/s, pushing a 50 N/mm spring grounded at node 100."""
    text = "\n".join(
        [
            "*KEYWORD",
            "*NODE",
            "1,0,0,0",
            "2,0,100,0",
            "3,0,100,100",
            "4,0,0,100",
            "100,-200,50,50,7,7",
            "*ELEMENT_SHELL",
            "1,1,1,2,3,4",
            "*PART",
            "plate",
            "1,1,1",
            "*SECTION_SHELL",
            "1,2",
            "2.0",
            "*MAT_RIGID",
            mat,
            "*NODE",
            "5,0,50,50",
            "*ELEMENT_DISCRETE",
            "10,2,100,5",
            "*PART",
            "spring",
            "2,2,2",
            "*SECTION_DISCRETE",
            "2,0",
            "*MAT_SPRING_ELASTIC",
            "2,50.0",
            "*CONSTRAINED_EXTRA_NODES_NODE",
            "1,5",
            "*INITIAL_VELOCITY",
            "0",
            "-1000.0,0.0,0.0",
            "*CONTROL_TERMINATION",
            "0.02",
            "*CONTROL_TIMESTEP",
            ",0.02",
            "*DATABASE_HISTORY_NODE",
            "1,3",
            *extra,
            "*END",
        ]
    )
    p = tmp_path / "plate.k"
    p.write_text(text)
    return read_deck(p)


def test_rigid_plate_on_a_spring_moves_as_one_body(tmp_path):
    m = _plate_deck(tmp_path)
    plate_mass = RO * 100 * 100 * 2
    assert m.mass_properties([1]).mass == pytest.approx(plate_mass, rel=1e-12)
    r = run(m, output_dt=1e-4)
    omega = np.sqrt(50.0 / plate_mass)
    ux = r.node_displacement[:, 0, 0]
    np.testing.assert_allclose(ux, -1000.0 / omega * np.sin(omega * r.time), atol=0.01 * 1000.0 / omega)
    # the spring acts through the plate's centre (extra node 5): no rotation
    np.testing.assert_allclose(r.node_displacement[:, 1], r.node_displacement[:, 0], atol=1e-9)
    assert np.max(np.abs(r.energy_ratio - 1.0)) < 2e-3


def test_con1_holds_translations(tmp_path):
    """CMO = 1, CON1 = 1: x held; the plate cannot move although pushed."""
    m = _plate_deck(tmp_path, mat="1,7.85e-9,210000.0,0.3\n1.0,1.0,0.0")
    r = run(m, output_dt=1e-3)
    np.testing.assert_allclose(r.node_displacement[:, :, 0], 0.0, atol=1e-12)


def test_merged_rigid_parts_move_together(tmp_path):
    """*CONSTRAINED_RIGID_BODIES: a second rigid plate (part 3) merged into
    part 1: one body of twice the mass, CoG between the plates."""
    extra = [
        "*NODE",
        "11,0,0,200",
        "12,0,100,200",
        "13,0,100,300",
        "14,0,0,300",
        "*ELEMENT_SHELL",
        "2,3,11,12,13,14",
        "*PART",
        "plate 2",
        "3,1,1",
        "*CONSTRAINED_RIGID_BODIES",
        "1,3",
        "*DATABASE_HISTORY_NODE",
        "11",
    ]
    m = _plate_deck(tmp_path, extra)
    r = run(m, output_dt=1e-4)
    plate_mass = RO * 100 * 100 * 2
    assert r.info["bodies"][1]["velocity"].shape == (3,)
    # one body: the distance between the plates' corners stays (the spring pulls off-centre: it turns)
    x1 = r.node_displacement[:, 0] + [0, 0, 0]
    x11 = r.node_displacement[:, 2] + [0, 0, 200]
    np.testing.assert_allclose(np.linalg.norm(x11 - x1, axis=1), 200.0, rtol=1e-12)
    assert np.ptp(r.node_displacement[:, 2, 0] - r.node_displacement[:, 0, 0]) > 0.1  # it did turn
    from crashlite.solver import build

    body = build(m).bodies[0]
    assert body.mass == pytest.approx(2 * plate_mass, rel=1e-12)
    assert body.cog[2] == pytest.approx(150.0, rel=1e-12)


def test_prescribed_motion_of_a_rigid_part(tmp_path):
    """*BOUNDARY_PRESCRIBED_MOTION_RIGID drives the plate at 500 mm/s against
    the spring: it follows the prescription and the spring force is k·u."""
    extra = ["*BOUNDARY_PRESCRIBED_MOTION_RIGID", "1,1,0,7", "*DEFINE_CURVE", "7", "0.0,-500.0", "1.0,-500.0"]
    m = _plate_deck(tmp_path, extra)
    r = run(m, output_dt=1e-3)
    ux = r.node_displacement[:, 0, 0]
    np.testing.assert_allclose(ux, -500.0 * r.time, rtol=1e-6, atol=1e-6)
    np.testing.assert_allclose(r.discrete_force[:, 0], -50.0 * 500.0 * r.time, rtol=1e-6, atol=1e-3)


@pytest.mark.parametrize(
    "card2,extra,turns",
    [
        ("0.0,0.0,0.0", [], True),  # free: the off-centre spring turns the plate about z
        ("1.0,0.0,3.0", [], False),  # CON2 = 3: z rotation held
        ("-1.0,5.0,1.0", ["*DEFINE_COORDINATE_VECTOR", "5,1,1,0,-1,1,0"], False),  # local z (= global z) held
    ],
)
def test_rotation_constraints(tmp_path, card2, extra, turns):
    """A second spring pushes the plate 40 mm off its centre: without constraint
    the plate turns about z; with the z rotation held (global CON2 or a
    local SPC code with CMO = -1) it only translates, and the energy stays
    balanced (the reaction torque does no work)."""
    push = ["*NODE", "6,0,90,50", "*ELEMENT_DISCRETE", "11,2,100,6", "*CONSTRAINED_EXTRA_NODES_NODE", "1,6"]
    m = _plate_deck(tmp_path, [*push, *extra], mat="1,7.85e-9,210000.0,0.3\n" + card2)
    r = run(m, output_dt=1e-4)
    spread = np.abs(r.node_displacement[:, 1, 0] - r.node_displacement[:, 0, 0]).max()
    if turns:
        assert spread > 1.0
    else:
        assert spread < 1e-9
        w = r.info["bodies"][1]
        assert abs(w["momentum"][2]) < 1e-9 * max(1.0, np.abs(w["momentum"]).max())
    assert np.max(np.abs(r.energy_ratio - 1.0)) < 2e-3
