"""Free modes of the replaced structure (``vehicle.connection.modes``) against the
closed forms of a free uniform tube."""

import numpy as np
import pytest
from _structures import RHO, E, shell_model, tube_mesh

from crashlite.vehicle.connection.modes import free_modes, held_modes
from crashlite.vehicle.steps.cut import cut_behind
from crashlite.vehicle.steps.relief import relieved_stiffness

B, T = 50.0, 1.5


def test_free_tube_modes_and_their_share_of_the_interface_compliance():
    """A free thin square tube, L = 1200 (L/B = 24), its cut end one rigid
    body: six rigid modes; first bending mode (a pair, y and z)
    f = 4.730²/(2πL²)·sqrt(EI/μ) within 3 % (the tube's shear lowers it by
    about 1 %); the pair carries 4·105/4.730⁴ = 84 % of the end's relieved
    lateral compliance (mass-normalised φ(end)² = 4/m, ω² = 4.730⁴·EI/(mL³),
    against L³/(105·EI)), the first torsion mode 6/π² = 61 % of its roll
    compliance; no axial share below the first axial mode at c/(2L)."""
    length, x_cut = 1500.0, 1200.0
    xyz, q = tube_mesh(B, length, 4, 120)
    model = shell_model(xyz, q, thickness=T, poisson=0.0)
    cut = cut_behind(model, x=x_cut)
    fm = free_modes(cut, count=12)
    assert fm.rigid_modes == 6
    ei = E * (2.0 / 3.0) * T * B**3
    mu = RHO * 4 * B * T
    f1 = 4.730**2 / (2 * np.pi * x_cut**2) * np.sqrt(ei / mu)
    assert fm.frequencies[0] == pytest.approx(f1, rel=0.03)
    assert fm.frequencies[1] == pytest.approx(fm.frequencies[0], rel=1e-3)  # y and z alike
    assert fm.frequencies[-1] < np.sqrt(E / RHO) / (2 * x_cut)  # all below the first axial mode
    flex = relieved_stiffness(cut, transverse=(1000.0, 1.0e6)).flexibility
    share = fm.shares(flex, (1.0, 0.0, 0.0))
    assert share["lateral"][:2].sum() == pytest.approx(4.0 * 105.0 / 4.730**4, rel=0.03)
    assert share["vertical"][:2].sum() == pytest.approx(share["lateral"][:2].sum(), rel=1e-3)
    torsion = int(np.argmax(share["roll"]))
    assert share["roll"][torsion] == pytest.approx(6.0 / np.pi**2, rel=0.03)
    assert np.abs(share["axial"]).max() < 1e-6
    for d in share.values():  # modes add up to at most the whole compliance
        assert d.sum() < 1.0 + 1e-9
    assert list(fm.where[0]) == ["part 1"] and fm.where[0]["part 1"] == pytest.approx(1.0)
    s = fm.summary(flex)
    assert len(s["frequencies"]) == 12 and set(s["compliance_share_percent"]) == set(share)


def test_cantilevered_tube_modes_and_effective_masses():
    """The tube's replaced part clamped at its cut (L = 1200): first bending
    f = 1.8751²/(2πL²)·sqrt(EI/μ) within 3 % holding 61.3 % of the mass
    (the uniform cantilever's), the first torsion mode 8/π² = 81 % of the
    inertia about the axis, the first axial mode at c/(4L) 8/π² of the
    mass, and the effective masses of every mode add up
    to at most the mass."""
    length, x_cut = 1500.0, 1200.0
    xyz, q = tube_mesh(B, length, 4, 120)
    model = shell_model(xyz, q, thickness=T, poisson=0.0)
    cut = cut_behind(model, x=x_cut)
    hm = held_modes(cut, count=12)
    ei = E * (2.0 / 3.0) * T * B**3
    mu = RHO * 4 * B * T
    assert hm.frequencies[0] == pytest.approx(1.8751**2 / (2 * np.pi * x_cut**2) * np.sqrt(ei / mu), rel=0.03)
    s = hm.summary()["effective_mass_percent"]
    assert s["lateral"][0] + s["lateral"][1] == pytest.approx(61.3, rel=0.03)  # the y/z pair, however turned
    assert s["vertical"][0] + s["vertical"][1] == pytest.approx(61.3, rel=0.03)
    assert max(s["roll"]) == pytest.approx(100 * 8 / np.pi**2, rel=0.03)
    axial = int(np.argmax(s["axial"]))  # the first axial mode, c/(4L), 8/π² of the mass too
    assert s["axial"][axial] == pytest.approx(100 * 8 / np.pi**2, rel=0.03)
    assert hm.frequencies[axial] == pytest.approx(np.sqrt(E / RHO) / (4 * x_cut), rel=0.03)
    for d in s.values():
        assert sum(d) < 100.0 + 1e-6
