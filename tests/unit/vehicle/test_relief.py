"""Step 3 under inertia relief (``vehicle.steps.relief``): the replaced structure
pushed at its interface and held by its own mass."""

import numpy as np
import pytest
from _structures import RHO, E, shell_model, tube_mesh

from crashlite.model.mesh import Masses
from crashlite.vehicle.steps.cut import cut_behind
from crashlite.vehicle.steps.relief import relieved_stiffness, replaced_node_masses
from crashlite.vehicle.steps.stiffness import longitudinal_stiffness

B, T, X = 50.0, 1.5, 300.0  # tube side (mid-line), wall, interface x [mm]


def _tube(n_len=100, length=500.0):
    xyz, q = tube_mesh(B, length, 4, n_len)
    return xyz, shell_model(xyz, q, thickness=T, poisson=0.0)


def test_node_masses_add_up_to_the_replaced_structure():
    xyz, model = _tube(25)
    cut = cut_behind(model, x=X)
    m, notes = replaced_node_masses(cut)
    assert m.sum() == pytest.approx(RHO * 4 * B * T * X, rel=1e-12)
    assert np.all(m[xyz[:, 0] > X + 1e-9] == 0.0)
    assert notes == []


def test_uniform_tube_is_three_times_stiffer_than_when_held_at_its_end():
    """A free uniform bar pushed at one end by F and decelerated by its own
    mass shortens to its centre of mass by F·L/(3·EA): K = 3·EA/L, while
    held at its far end K = EA/L (the paper's step 3). The discrete lumped
    masses bring an O(1/n²) error: 60 elements over the replaced length."""
    xyz, model = _tube(100)
    cut = cut_behind(model, x=X)
    ea = E * 4 * B * T
    r = relieved_stiffness(cut)
    assert r.stiffness == pytest.approx(3.0 * ea / X, rel=2e-3)
    held = longitudinal_stiffness(cut, np.flatnonzero(xyz[:, 0] == 0.0))
    assert r.stiffness / held.stiffness == pytest.approx(3.0, rel=2e-3)
    assert np.linalg.norm(r.support_reaction) < 1e-6 * r.force  # the inertia loads balance the push
    np.testing.assert_allclose(r.direction, [-1.0, 0.0, 0.0])


def test_end_mass_on_the_axis_against_the_closed_form():
    """Point masses spread evenly over the far end's ring (together M_e; a
    uniform edge load, the CoG on the axis): N(x) = F·(1 − ρA·x/M) from the
    pushed end, u(x) = ∫N/EA, and the interface moves against the
    mass-weighted mean ū = (∫ρA·u dx + M_e·u(L))/M, so K = F/ū; it tends
    to EA/L as the end mass dominates."""
    xyz, model = _tube(100)
    ring = np.flatnonzero(xyz[:, 0] == 0.0)
    m_end = 0.008
    n = len(ring)
    model.masses = Masses(
        np.arange(1, n + 1, dtype=np.int64), ring.astype(np.int32), np.full(n, m_end / n), np.zeros(n, np.int64)
    )
    cut = cut_behind(model, x=X)
    r = relieved_stiffness(cut)
    ea, rho_a, f = E * 4 * B * T, RHO * 4 * B * T, r.force
    big_m = rho_a * X + m_end
    u_end = f / ea * (X - rho_a * X**2 / (2 * big_m))
    u_bar = (rho_a * f / ea * (X**2 / 2 - rho_a * X**3 / (6 * big_m)) + m_end * u_end) / big_m
    assert r.stiffness == pytest.approx(f / u_bar, rel=2e-3)
    assert ea / X < r.stiffness < 1.2 * ea / X


def test_off_axis_mass_is_balanced_by_rotary_inertia():
    """A lumped mass at one corner of the far end puts the CoG off the line
    of the push: the d'Alembert loads must include the angular acceleration,
    or the 3-2-1 support would react."""
    xyz, model = _tube(50)
    far = int(np.argmin(np.linalg.norm(xyz - [0.0, B / 2, B / 2], axis=1)))
    model.masses = Masses(np.array([1], np.int64), np.array([far], np.int32), np.array([0.002]), np.zeros(1, np.int64))
    cut = cut_behind(model, x=X)
    m, _ = replaced_node_masses(cut)
    assert m.sum() == pytest.approx(RHO * 4 * B * T * X + 0.002, rel=1e-12)
    r = relieved_stiffness(cut)
    assert np.linalg.norm(r.support_reaction) < 1e-6 * r.force
    assert not any("reacts" in n for n in r.notes)
    assert r.stiffness > 0.0


def test_slender_tube_across_and_twisted():
    """A free uniform beam pushed across at one end by P and held by its own
    inertia: M(x) = P·(x² − x³/L)/L from the free end, and the loaded end's
    deflection against the best-fit rigid motion is P·L³/(105·EI), so the
    lateral and vertical stiffness are 105·EI/L³ (the tube's shear adds
    0.1 % at L/B = 24); twisted, 3·GJ/L (Bredt's J = B³·t for the thin
    square tube). Against the tube held at its far end: 35 and 3 times. The
    same solve gives the whole 6×6 flexibility (turned: 13·L/(35·EI))."""
    length, x_cut = 1500.0, 1200.0
    xyz, q = tube_mesh(B, length, 4, 120)
    model = shell_model(xyz, q, thickness=T, poisson=0.0)
    cut = cut_behind(model, x=x_cut)
    r = relieved_stiffness(cut, transverse=(1000.0, 1.0e6))
    ei = E * (2.0 / 3.0) * T * B**3
    gj = E / 2.0 * B**3 * T
    tr = r.transverse
    assert tr["lateral"] == pytest.approx(105.0 * ei / x_cut**3, rel=0.03)
    assert tr["vertical"] == pytest.approx(tr["lateral"], rel=1e-6)
    assert tr["shear"] == min(tr["lateral"], tr["vertical"])
    assert tr["roll"] == pytest.approx(3.0 * gj / x_cut, rel=0.03)
    held = longitudinal_stiffness(cut, np.flatnonzero(xyz[:, 0] == 0.0), transverse=(1000.0, 1.0e6)).transverse
    assert tr["lateral"] / held["lateral"] == pytest.approx(35.0, rel=0.03)
    assert tr["roll"] / held["roll"] == pytest.approx(3.0, rel=0.03)
    assert r.stiffness == pytest.approx(3.0 * E * 4 * B * T / x_cut, rel=2e-3)  # the axial case, same solve
    # turned about y or z by an end moment and held by its rotary inertia, the end rotates 13·M·L/(35·EI)
    # against the best-fit rigid motion; pushed across, it turns (and turned, moves) by 11·L²/(210·EI) per
    # unit load (Maxwell–Betti); the whole 6×6 flexibility at the interface from six loads on one solve
    c = r.flexibility
    assert c[4, 4] == pytest.approx(13.0 * x_cut / (35.0 * ei), rel=0.03)
    assert c[5, 5] == pytest.approx(c[4, 4], rel=1e-6)
    assert abs(c[1, 5]) == pytest.approx(11.0 * x_cut**2 / (210.0 * ei), rel=0.03)
    assert abs(c[2, 4]) == pytest.approx(abs(c[1, 5]), rel=1e-6)
    assert c[1, 1] == pytest.approx(1.0 / tr["lateral"], rel=1e-9) and c[3, 3] == pytest.approx(1.0 / tr["roll"])
    assert c[0, 0] == pytest.approx(1.0 / r.stiffness, rel=1e-9)
    assert np.all(np.linalg.eigvalsh(c) > 0)
    off = c.copy()  # no other coupling in a doubly symmetric tube
    for i, j in ((1, 5), (5, 1), (2, 4), (4, 2)):
        off[i, j] = 0.0
    assert np.abs(off - np.diag(np.diag(off))).max() < 1e-3 * np.abs(c[1, 5])
