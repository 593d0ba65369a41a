"""The replaced structure as a Craig–Bampton superelement
(``vehicle.connection.craig_bampton``) against the closed forms of a free
uniform tube."""

import numpy as np
import pytest
from _structures import RHO, E, shell_model, tube_mesh
from scipy.linalg import eigh

from crashlite.vehicle.connection.condense import rigid_modes
from crashlite.vehicle.connection.craig_bampton import craig_bampton
from crashlite.vehicle.steps.cut import cut_behind
from crashlite.vehicle.steps.relief import replaced_node_masses

B, T = 50.0, 1.5
LENGTH, X_CUT = 1500.0, 1200.0


@pytest.fixture(scope="module")
def tube():
    xyz, q = tube_mesh(B, LENGTH, 4, 120)
    cut = cut_behind(shell_model(xyz, q, thickness=T, poisson=0.0), x=X_CUT)
    far = np.flatnonzero(np.isclose(xyz[:, 0], 0.0))[:1]  # a node kept for output at the far end
    return cut, craig_bampton(cut, modes=12, kept=far)


def test_held_modes_are_the_cantilevers(tube):
    """The interior modes with the boundary held (the cut and one far node):
    a cantilever L = 1200 pinned near its tip at one corner; its first
    bending pair lies between the clamped–free 1.8751² and clamped–pinned
    3.9266² closed forms f = λ²/(2πL²)·sqrt(EI/μ), the whole list rising."""
    _, cb = tube
    ei = E * (2.0 / 3.0) * T * B**3
    mu = RHO * 4 * B * T
    f = lambda lam: lam**2 / (2 * np.pi * X_CUT**2) * np.sqrt(ei / mu)  # noqa: E731
    assert f(1.8751) < cb.frequencies[0] < f(3.9266)
    assert np.all(np.diff(cb.frequencies) >= -1e-9)


def test_reduced_mass_is_the_structures_and_rigid_motions_are_free(tube):
    """T spans the six rigid motions: against them the reduced mass is the
    static model's lumped masses' mass (ρ·4BT·L of the replaced 1200 mm, to
    1 %: the cut ring's half) and inertia tensor about the CoG (to 1e-9),
    and they store no strain energy (K·r under 1e-9 of K's scale)."""
    cut, cb = tube
    xyz = cut.model.nodes.xyz
    rm = cb.rigid_mass(xyz[cb.nodes])
    assert cb.structure_mass == pytest.approx(RHO * 4 * B * T * X_CUT, rel=0.01)
    m, _ = replaced_node_masses(cut)
    d = xyz - cb.cog
    inertia = np.einsum("n,nk,nk->", m, d, d) * np.eye(3) - np.einsum("n,ni,nj->ij", m, d, d)
    np.testing.assert_allclose(rm[:3, :3], cb.structure_mass * np.eye(3), rtol=1e-9, atol=1e-9 * cb.structure_mass)
    np.testing.assert_allclose(rm[3:, 3:], inertia, rtol=1e-9, atol=1e-9 * np.abs(inertia).max())
    assert np.abs(rm[:3, 3:]).max() < 1e-9 * np.abs(rm).max()  # about the CoG: no first moment
    r = np.zeros((len(cb.mass), 6))
    r[: 3 * len(cb.nodes)] = rigid_modes(xyz[cb.nodes], cb.cog).reshape(-1, 6)
    assert np.abs(cb.stiffness @ r).max() < 1e-9 * np.abs(cb.stiffness).max() * np.abs(r).max()


def test_free_modes_of_the_reduced_tube(tube):
    """The reduced model free (the boundary too): six rigid modes at zero,
    then the free–free bending pair at 4.730²/(2πL²)·sqrt(EI/μ) within 3 %
    (a Rayleigh–Ritz projection: at or above the full model's, which the
    tube's shear puts about 1 % under the Euler–Bernoulli value)."""
    _, cb = tube
    lam = eigh(cb.stiffness, cb.mass, eigvals_only=True)
    scale = lam.max()
    assert (np.abs(lam[:6]) < 1e-8 * scale).all() and lam[6] > 1e-6 * scale
    ei = E * (2.0 / 3.0) * T * B**3
    mu = RHO * 4 * B * T
    f1 = 4.730**2 / (2 * np.pi * X_CUT**2) * np.sqrt(ei / mu)
    f = np.sqrt(lam[6:8]) / (2 * np.pi)
    assert f == pytest.approx([f1, f1], rel=0.03)
