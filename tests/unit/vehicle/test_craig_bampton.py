"""The replaced structure as a Craig–Bampton superelement
(``vehicle.connection.craig_bampton``) against the closed forms of a free
uniform tube."""

import numpy as np
import pytest
from _structures import RHO, E, shell_model, tube_mesh
from scipy.linalg import eigh

from crashlite.model.mesh import Masses, Nodes
from crashlite.vehicle.connection.cb_surrogate import build_cb_surrogate
from crashlite.vehicle.connection.condense import rigid_modes
from crashlite.vehicle.connection.craig_bampton import craig_bampton
from crashlite.vehicle.steps.cut import cut_behind
from crashlite.vehicle.steps.massprops import replaced_mass
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


def test_mass_off_the_static_model_goes_on_the_boundary_rigidly():
    """A point mass on a node no element holds (10 kg, 700 mm behind the
    cut) is not on the static model: the surrogate puts it on the boundary
    so that, moved rigidly, the superelement has the replaced structure's
    mass and inertia about its CoG (to 1e-9), and says so."""
    xyz, q = tube_mesh(B, 1200.0, 2, 48)
    m = shell_model(xyz, q, thickness=T)
    extra = Nodes.zeros(1)
    extra.ids, extra.xyz = np.array([99999]), np.array([[300.0, 0.0, 0.0]])
    m.nodes = Nodes.concat([m.nodes, extra])
    point = Masses.zeros(1)
    point.ids, point.node, point.mass = np.array([1]), np.array([len(m.nodes) - 1], np.int32), np.array([0.01])
    m.masses = Masses.concat([m.masses, point])
    cut = cut_behind(m, x=1000.0)
    mass = replaced_mass(cut)
    sur = build_cb_surrogate(cut, mass, modes=2)
    assert any("10.0 kg" in n and "not on its static model" in n for n in sur.notes)
    dofs, mm = sur.matrix[0], sur.mass_matrix
    on = ~np.isin(dofs[:, 0], sur.node_ids["modes"])
    r = np.zeros((len(dofs), 6))
    r[on] = rigid_modes(sur.model.nodes.xyz[sur.model.node_index(dofs[on, 0][::3])], mass.structure.cog).reshape(-1, 6)
    rm = r.T @ mm @ r
    np.testing.assert_allclose(np.diag(rm)[:3], mass.structure.mass, rtol=1e-9)
    np.testing.assert_allclose(rm[3:, 3:], mass.structure.inertia, rtol=1e-9, atol=1e-9 * np.abs(rm[3:, 3:]).max())
