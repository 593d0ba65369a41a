"""Intrusion in the passenger cell's frame: the cell's rigid motion
(translation, pitch, yaw) is not intrusion, a firewall pushed back is."""

import numpy as np
import pytest

from crashlite.solver.rigid import rotation
from crashlite.vehicle.connection.rigidfit import rearward_in_frame as _in_cell
from crashlite.vehicle.connection.rigidfit import rigid_motion as cell_motion
from crashlite.vehicle.connection.rigidfit import warping, warping_history

CELL = np.array(
    [[-2200.0, 350.0, 350.0], [-2200.0, -350.0, 350.0], [-1490.0, 700.0, 300.0], [-1490.0, -700.0, 300.0]]
)  # rear seats and B-pillar sills of the generic car
FIREWALL = np.array([[-250.0, y, z] for y in (-400.0, 0.0, 400.0) for z in (300.0, 500.0, 750.0)])


def _moved(pitch, yaw, shift):
    r = rotation(np.array([0.0, pitch, 0.0])) @ rotation(np.array([0.0, 0.0, yaw]))
    c = CELL.mean(axis=0)
    x0 = np.vstack([CELL, FIREWALL])
    return x0, (x0 - c) @ r.T + c + shift, r


def test_the_rigid_fit_recovers_the_cells_motion():
    x0, x, r = _moved(0.08, -0.03, [400.0, 5.0, 30.0])
    got, c0, c = cell_motion(x0[:4], x[:4])
    np.testing.assert_allclose(got, r, atol=1e-12)
    np.testing.assert_allclose((x0 - c0) @ got.T + c, x, atol=1e-9)


def test_a_pitching_and_yawing_cell_has_no_intrusion_a_pushed_firewall_has():
    x0, x, r = _moved(0.08, -0.03, [400.0, 5.0, 30.0])
    frame, fw = np.arange(4), np.arange(4, len(x0))
    np.testing.assert_allclose(_in_cell(x, x0, fw, frame, 0), 0.0, atol=1e-9)
    # the same motion measured against one node only counts the pitch: z·θ at the top of the firewall
    assert np.ptp(-(x[fw, 0] - x0[fw, 0]) + (x[0, 0] - x0[0, 0])) > 30.0
    pushed = x.copy()
    d = np.array([10.0, 25.0, 40.0] * 3)  # rearward in the cell frame, more at the top
    pushed[fw] -= np.outer(d, r[:, 0])  # along the cell's turned x axis
    assert _in_cell(pushed, x0, fw, frame, 0) == pytest.approx(d, abs=1e-9)


INTERFACE = np.array([[-600.0, y, z] for y in (-700.0, 0.0, 700.0) for z in (200.0, 450.0, 1000.0)])


def test_the_split_separates_the_interface_motion_from_the_kept_structures_own_deformation():
    """Cell pitched, yawed and shifted; the interface plane pushed 12 mm back
    in the cell frame and pitched by 0.02 rad (its top forward); the
    firewall carried with it plus its own dent d (more at the top): the
    split gives own = d (along the interface's turned axis), carried = 12 mm
    + the interface's pitch at the firewall's positions (to the dent's
    d(1 − cos θ)), and the two add up to the intrusion in the cell frame."""
    from crashlite.vehicle.verify.verification import intrusion_split

    x0 = np.vstack([CELL, FIREWALL, INTERFACE])
    frame, fw, itf = np.arange(4), np.arange(4, 13), np.arange(13, 22)
    # in the cell frame: the interface's rigid motion about its centre, applied to interface and firewall
    theta = -0.02  # about y: a point above the centre moves forward (+x) for theta < 0
    ri = rotation(np.array([0.0, theta, 0.0]))
    ci = INTERFACE.mean(axis=0)
    local = x0.copy()
    moved = (x0[4:] - ci) @ ri.T + ci - [12.0, 0.0, 0.0]
    local[4:] = moved
    d = np.array([10.0, 25.0, 40.0] * 3)
    local[fw] -= np.outer(d, ri[:, 0])  # the dent along the interface's turned axis
    carried_expect = -(moved[:9, 0] - x0[fw, 0])
    # the whole car then moves rigidly with the cell
    r = rotation(np.array([0.0, 0.08, 0.0])) @ rotation(np.array([0.0, 0.0, -0.03]))
    c = CELL.mean(axis=0)
    x = (local - c) @ r.T + c + [400.0, 5.0, 30.0]
    carried, own = intrusion_split(x, x0, fw, frame, itf, 0)
    np.testing.assert_allclose(own, d, atol=1e-9)
    np.testing.assert_allclose(carried, carried_expect, atol=0.5 * 0.02**2 * 40.0)  # less the dent's d(1 − cos θ)
    np.testing.assert_allclose(carried + own, _in_cell(x, x0, fw, frame, 0), atol=1e-9)
    assert carried.min() < 12.0 < carried.max()  # the pitch: the top is carried less far back


def test_a_plane_that_moves_rigidly_does_not_bend_one_that_bows_does():
    """A grid of interface nodes in the plane x = −600, turned and shifted
    as one body: no warping. Bowed back by u = −κ(y² + z²) on top of that
    (symmetric in y and z, so the best fit adds no turn): the warping is
    κ(y² + z² − mean) rearwards at every node, and over a history of such
    states the largest value and the largest rms are those of the most
    bowed state."""
    y, z = np.meshgrid(np.linspace(-700.0, 700.0, 8), np.linspace(150.0, 1050.0, 5))
    x0 = np.column_stack([np.full(y.size, -600.0), y.ravel(), z.ravel()])
    nodes = np.arange(len(x0))
    r = rotation(np.array([0.01, 0.05, -0.03]))
    c = x0.mean(axis=0)

    def moved(kappa):
        bow = x0.copy()
        bow[:, 0] -= kappa * ((x0[:, 1]) ** 2 + (x0[:, 2] - c[2]) ** 2)
        return (bow - c) @ r.T + c + [350.0, -8.0, 22.0]

    np.testing.assert_allclose(warping(moved(0.0), x0, nodes, 0), 0.0, atol=1e-9)
    kappa = 1e-5  # 4.9 mm at the corners
    q = x0[:, 1] ** 2 + (x0[:, 2] - c[2]) ** 2
    expect = kappa * (q - q.mean())
    np.testing.assert_allclose(warping(moved(kappa), x0, nodes, 0), expect, atol=1e-6 * np.abs(expect).max())
    h = warping_history(np.stack([moved(0.0), moved(kappa), moved(0.4 * kappa)]), x0, nodes, 0)
    assert h["max"] == pytest.approx(np.abs(expect).max(), rel=1e-6) and h["state_of_max"] == 1
    assert h["rms"] == pytest.approx(np.sqrt((expect**2).mean()), rel=1e-6) and h["state_of_rms"] == 1
