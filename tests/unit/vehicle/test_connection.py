"""The surrogate's 6×6 connection of interface and rear body
(``vehicle.connection.connection``) against closed forms, the static model of the
written surrogate deck, and the structure it replaces."""

import numpy as np
import pytest
from test_surrogate import _surrogate, _tmp, _tube

from crashlite import read_deck
from crashlite.vehicle.connection.connection import (
    beam_end_stiffness,
    compare_connection,
    connection_stiffness,
    moved_to,
    spring_stiffness,
)
from crashlite.vehicle.steps.cut import cut_behind
from crashlite.vehicle.steps.stiffness import structure_stiffness, transverse_stiffness


def test_springs_and_a_cantilever_against_closed_forms():
    """Two springs k at y = ±h along x: 2k axially, 2k·h² in yaw, nothing
    across; moved 100 mm off their line, an axial force there also turns
    them. A cantilever of length L along y: tip compliance L³/(3·EI) across
    with the tip free to turn, L/EI under a moment, L/GJ twisted, L/EA
    pulled."""
    k, h = 2.0e4, 300.0
    p = np.array([-600.0, 0.0, 500.0])
    ks = sum(spring_stiffness(k, p + [0.0, s * h, 0.0], [-1.0, 0.0, 0.0], p) for s in (-1, 1))
    assert ks[0, 0] == pytest.approx(2 * k) and ks[5, 5] == pytest.approx(2 * k * h * h)
    assert np.abs(ks[[1, 2, 3]]).max() == 0.0 and ks[0, 5] == pytest.approx(0.0, abs=1e-9)
    off = moved_to(ks, p, p + [0.0, 100.0, 0.0])  # the same springs seen from 100 mm to the left
    assert off[0, 5] == pytest.approx(-2 * k * (-100.0)) and off[5, 5] == pytest.approx(2 * k * (h * h + 100.0**2))
    length, ea, ei, gj = 1500.0, 3.0e8, 4.0e12, 2.5e12
    c = np.linalg.inv(beam_end_stiffness(np.zeros(3), [0.0, length, 0.0], ea, ei, gj))
    assert c[1, 1] == pytest.approx(length / ea, rel=1e-9)
    assert c[0, 0] == pytest.approx(length**3 / (3 * ei), rel=1e-9) == c[2, 2]
    assert c[5, 5] == pytest.approx(length / ei, rel=1e-9) == c[3, 3]
    assert c[4, 4] == pytest.approx(length / gj, rel=1e-9)
    assert abs(c[0, 5]) == pytest.approx(length**2 / (2 * ei), rel=1e-9)


def test_connection_is_that_of_the_written_surrogate_deck():
    """The 6×6 of the surrogate's springs and beam, at the interface body's
    centre, is what a static solve of the written deck gives with the rear
    body held: axial, lateral, vertical and roll compliance to 1e-6."""
    m, _, _ = _tube()
    tr = transverse_stiffness(cut_behind(m, x=250.0), "axle")
    cut, rm, k, s = _surrogate(m, transverse=tr)
    back = read_deck(s.write(_tmp() / "surrogate.k"))
    rear = back.find("CONSTRAINED_NODAL_RIGID_BODY_INERTIA")[0]
    iface = back.find("CONSTRAINED_NODAL_RIGID_BODY")[0]
    fe = structure_stiffness(
        back,
        ("set", int(rear["nsid"])),
        ("set", int(iface["nsid"])),
        direction=(-1.0, 0.0, 0.0),
        transverse=(1000.0, 1.0e6),
    )
    c = np.linalg.inv(connection_stiffness(s, fe.load_point))
    assert 1.0 / c[0, 0] == pytest.approx(fe.stiffness, rel=1e-6)
    assert 1.0 / c[1, 1] == pytest.approx(fe.transverse["lateral"], rel=1e-6)
    assert 1.0 / c[2, 2] == pytest.approx(fe.transverse["vertical"], rel=1e-6)
    assert 1.0 / c[3, 3] == pytest.approx(fe.transverse["roll"], rel=1e-6)
    # the beam's EI makes its tip as stiff across as the clamped tube (its tip free to turn)
    assert 1.0 / c[1, 1] == pytest.approx(tr["lateral"], rel=1e-6)


def test_comparison_names_the_direction_that_misfits():
    """A surrogate equal to the structure: every ratio 1. Twice as stiff in
    pitch alone (the rest held): pitch compliance halved, named the
    largest misfit; in the vehicle frame of an axis along y the directions
    turn with it."""
    rng = np.random.default_rng(3)
    a = rng.normal(size=(6, 6))
    k = a @ a.T + 6 * np.eye(6)
    same = compare_connection(k, np.linalg.inv(k), (1.0, 0.0, 0.0))
    for d in same["directions"].values():
        assert d["compliance_ratio"] == pytest.approx(1.0) and d["stiffness_ratio_held"] == pytest.approx(1.0)
    diag = np.diag([1e5, 2e4, 3e4, 1e10, 2e10, 5e10])
    stiff = diag.copy()
    stiff[4, 4] *= 2.0
    out = compare_connection(stiff, np.linalg.inv(diag), (1.0, 0.0, 0.0))
    assert out["directions"]["pitch"]["compliance_ratio"] == pytest.approx(0.5)
    assert out["largest_compliance_misfit"]["direction"] == "pitch"
    assert out["directions"]["yaw"]["compliance_ratio"] == pytest.approx(1.0)
    turned = compare_connection(stiff, np.linalg.inv(diag), (0.0, 1.0, 0.0))  # the y axis is the vehicle's axis
    assert turned["directions"]["axial"]["structure_compliance"] == pytest.approx(1 / 2e4)
