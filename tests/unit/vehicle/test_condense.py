"""The replaced structure condensed onto the cut nodes under inertia relief
(``vehicle.connection.condense``) and the superelement built from it (``condensed``)."""

import numpy as np
import pytest
from _structures import E, shell_model, tube_mesh

from crashlite.vehicle.connection.condense import relieved_condensation, rigid_modes
from crashlite.vehicle.connection.condensed import superelement_matrix
from crashlite.vehicle.steps.cut import cut_behind
from crashlite.vehicle.steps.relief import relieved_stiffness

B, T, X = 50.0, 1.5, 300.0  # tube side (mid-line), wall, interface x [mm]


@pytest.fixture(scope="module")
def tube():
    xyz, q = tube_mesh(B, 500.0, 4, 100)
    cut = cut_behind(shell_model(xyz, q, thickness=T, poisson=0.0), x=X)
    return cut, relieved_condensation(cut)


def test_cut_held_rigid_is_the_relieved_bar(tube):
    """Held rigid, the condensed cut of a uniform tube pushed along its axis
    is the inertia-relief bar, 3·EA/L (to the lumped masses' O(1/n²)), and
    the same number ``relief`` gets from its own rigid interface. Across,
    the condensed cut's free shell rotations make it a little softer than
    the relief's rigid interface, which also holds them."""
    cut, cond = tube
    assert len(cond.nodes) == 16 and not len(cond.left_out)
    rel = relieved_stiffness(cut, transverse=(1000.0, 1.0e6))
    k6 = cond.rigid_stiffness(rel.load_point)
    assert k6[0, 0] == pytest.approx(3.0 * E * 4 * B * T / X, rel=2e-3)
    assert k6[0, 0] == pytest.approx(rel.stiffness, rel=1e-9)
    kr = np.linalg.inv(rel.flexibility)
    for j in (1, 2, 4, 5):  # lateral, vertical, their bending rotations
        assert 0.93 < k6[j, j] / kr[j, j] <= 1.0 + 1e-9
    assert k6[3, 3] / kr[3, 3] == pytest.approx(1.0, rel=5e-3)  # torsion: the section turns as a whole


def test_flexibility_is_symmetric_and_positive(tube):
    """Maxwell–Betti: the inertia-relief flexibility at the cut DOFs is
    symmetric before it is made so, and positive definite."""
    _, cond = tube
    assert not any("unsymmetric" in n for n in cond.notes)
    np.testing.assert_allclose(cond.stiffness @ cond.flexibility, np.eye(len(cond.flexibility)), atol=1e-8)
    assert np.linalg.eigvalsh(cond.flexibility)[0] > 0.0


def test_superelement_leaves_rigid_motions_free(tube):
    """The superelement on the cut and four anchors of the rear body gives no
    force under any rigid motion of the whole, and the cut's stiffness
    relative to the anchors' motion is K_s."""
    _, cond = tube
    anchors = cond.cog + 300.0 * np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]]) / np.sqrt(3.0)
    k = superelement_matrix(cond, anchors)
    phi = np.vstack(
        [rigid_modes(cond.xyz_nodes, cond.cog).reshape(-1, 6), rigid_modes(anchors, cond.cog).reshape(-1, 6)]
    )
    assert np.abs(k @ phi).max() < 1e-9 * np.abs(k).max() * np.abs(phi).max()
    nb = 3 * len(cond.nodes)
    np.testing.assert_allclose(k[:nb, :nb], cond.stiffness, rtol=1e-12)
    assert np.linalg.eigvalsh(k)[0] > -1e-9 * np.abs(k).max()


def test_axial_impedance_is_the_cut_sections_rho_c_area():
    """ρ·c·A summed over the cut nodes is the tube wall's ring, ρ·√(E/ρ(1−ν²))·4b·t
    (to round-off: the replaced shells' edges on the cut, not the kept
    ones' that share them), shared among the ring's nodes by their half
    edges."""
    from crashlite.vehicle.connection.impedance import axial_impedance

    xyz, q = tube_mesh(B, 500.0, 4, 100)
    model = shell_model(xyz, q, thickness=T, poisson=0.3)
    cut = cut_behind(model, x=X)
    z = axial_impedance(cut, cut.interface_nodes)
    rho, e, nu = 7.85e-9, E, 0.3
    zc = rho * np.sqrt(e / (rho * (1 - nu * nu)))
    assert z.sum() == pytest.approx(zc * 4 * B * T, rel=1e-12)
    assert z == pytest.approx(np.full(16, zc * T * B / 4), rel=1e-12)  # 16 edges of b/4, each node on two
