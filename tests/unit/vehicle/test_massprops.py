"""Step 2: the interface cut and the mass properties of the replaced structure."""

import numpy as np
import pytest
from _structures import RHO, box_mesh, shell_model, tube_mesh

from crashlite.model import mass as mk
from crashlite.model.mesh import Masses
from crashlite.vehicle.car.records import id_list, record
from crashlite.vehicle.steps.cut import cut_behind
from crashlite.vehicle.steps.massprops import element_moments, replaced_mass


def _box_inertia(a, b, c, t, rho):
    """Mass and inertia about the centre of a closed box of mid-surface
    sheets of thickness t: per face mass ρ·t·Lu·Lv, second moments
    Lu²/12 and Lv²/12 in its plane, (d/2)² + t²/12 along its normal."""
    dims = np.array([a, b, c])
    s = np.zeros((3, 3))
    mass = 0.0
    for k in range(3):
        u, v = [i for i in range(3) if i != k]
        mf = rho * t * dims[u] * dims[v]
        mass += 2 * mf
        s[k, k] += 2 * mf * ((dims[k] / 2) ** 2 + t**2 / 12)
        s[u, u] += 2 * mf * dims[u] ** 2 / 12
        s[v, v] += 2 * mf * dims[v] ** 2 / 12
    return mass, np.trace(s) * np.eye(3) - s


def test_box_of_shells_mass_cog_and_inertia():
    a, b, c, t = 400.0, 250.0, 150.0, 2.0
    xyz, q = box_mesh(a, b, c, 8)
    model = shell_model(xyz, q, thickness=t)
    cut = cut_behind(model, x=a + 1.0)  # the whole box lies behind the interface
    assert cut.replaced["shells"].all() and not len(cut.interface_nodes)
    rm = replaced_mass(cut)
    mass, inertia = _box_inertia(a, b, c, t, RHO)
    assert rm.structure.mass == pytest.approx(mass, rel=1e-12)
    np.testing.assert_allclose(rm.structure.cog, [a / 2, 0.0, 0.0], atol=1e-9)
    np.testing.assert_allclose(rm.structure.inertia, inertia, rtol=1e-10, atol=1e-12 * inertia.max())
    assert rm.lumped.mass == 0.0


def test_half_tube_with_lumped_masses_behind_an_interface():
    b, length, t, m_node = 60.0, 1000.0, 1.5, 1e-4
    xyz, q = tube_mesh(b, length, 3, 20)
    model = shell_model(xyz, q, thickness=t)
    n = len(xyz)
    ms = Masses.zeros(n)
    ms.ids = np.arange(1, n + 1)
    ms.node = np.arange(n, dtype=np.int32)
    ms.mass = np.full(n, m_node)
    model.masses = ms
    model.sets[("NODE", 7)] = id_list("SET_NODE_LIST_TITLE", 7, model.nodes.ids[xyz[:, 0] == 0.0], title="axle")
    # the car drives in +x: the structure behind the interface x = 500 is replaced
    cut = cut_behind(model, x=500.0)
    ring = np.flatnonzero(xyz[:, 0] == 500.0)
    np.testing.assert_array_equal(np.sort(cut.interface_nodes), ring)
    assert np.array_equal(cut.removed_nodes, xyz[:, 0] < 500.0)
    rm = replaced_mass(cut, axle_nodes="axle")
    shell_mass = RHO * t * 4 * b * 500.0
    behind = xyz[:, 0] < 500.0
    lumped = m_node * behind.sum()  # masses on the interface ring stay with the front
    assert rm.elements.mass == pytest.approx(shell_mass, rel=1e-12)
    assert rm.lumped.mass == pytest.approx(lumped, rel=1e-12)
    assert rm.structure.mass == pytest.approx(shell_mass + lumped, rel=1e-12)
    x_lumped = xyz[behind, 0].mean()
    assert rm.structure.cog[0] == pytest.approx((shell_mass * 250.0 + lumped * x_lumped) / (shell_mass + lumped))
    np.testing.assert_allclose(rm.axle_points, [0.0, 0.0, 0.0], atol=1e-12)
    table = rm.table()
    assert table["replaced structure"]["mass"] == pytest.approx(1e3 * (shell_mass + lumped))
    # along −x (a car driving in −x) the other half is replaced
    back = cut_behind(model, x=-500.0, axis=(-1.0, 0.0, 0.0))
    assert np.array_equal(back.replaced["shells"], ~cut.replaced["shells"])


def test_rigid_part_across_the_interface_goes_whole():
    xyz, q = tube_mesh(60.0, 1000.0, 2, 10)
    pids = np.where(xyz[q].mean(axis=1)[:, 0] < 700.0, 1, 2)
    model = shell_model(xyz, q, pids=pids)
    model.materials[2] = record("MAT_RIGID", mid=2, ro=RHO, e=210000.0, pr=0.3)
    model.parts[2] = record("PART", heading="rigid", pid=2, secid=2, mid=2)
    cut = cut_behind(model, x=900.0)  # cuts the rigid part (x 700..1000, centre 850) behind its centre
    assert cut.replaced["shells"][pids == 2].all() and any("rigid part 2" in n for n in cut.notes)
    cut = cut_behind(model, x=800.0)
    assert not cut.replaced["shells"][pids == 2].any()


def test_generic_car_replaced_and_kept_make_the_whole_car():
    from crashlite.vehicle import generic_vehicle

    v = generic_vehicle(38.0)
    m = v.model
    cut = cut_behind(m, x=v.interface_x)
    rm = replaced_mass(cut, axle_nodes="rear axle attachment", axle_parts=["rear axle"])
    em = element_moments(m)
    kept = mk.combine(
        em["shells"],
        mk.point_moments(m.nodes.xyz[m.masses.node], m.masses.mass),
        weights_mask=[~cut.replaced["shells"], ~cut.removed_nodes[m.masses.node]],
    )
    whole = m.mass_properties()
    both = rm.structure + kept
    assert both.mass == pytest.approx(whole.mass, rel=1e-12) and whole.mass * 1e3 == pytest.approx(v.mass)
    np.testing.assert_allclose(both.cog, whole.cog, atol=1e-6)
    np.testing.assert_allclose(both.inertia, whole.inertia, rtol=1e-9, atol=1e-9 * whole.inertia.max())
    assert 0.4 * whole.mass < rm.structure.mass < 0.8 * whole.mass  # the paper: 720 of 1263 kg
    assert rm.structure.cog[0] < v.interface_x and abs(rm.axle.mass * 1e3 - 73.0) < 1e-6
    assert rm.axle_points[0] == pytest.approx(-2480.0) and rm.axle_points[1] == pytest.approx(0.0, abs=1e-9)
    assert set(cut.replaced_parts()) >= {v.part_ids["roof"], v.part_ids["rear axle"], v.part_ids["tunnel"]}
    iface = cut.assembly_interface({name: v.assemblies[name] for name in v.sections})
    assert all(len(nodes) for nodes in iface.values())  # every sectioned assembly crosses the cut
    flat = np.concatenate(list(iface.values()))
    assert len(flat) == len(np.unique(flat))


def test_mass_part_set_row_brings_its_parts_together_to_finmass():
    """*ELEMENT_MASS_PART_SET: FINMASS is the set's final mass, reached by
    scaling its parts alike (the solver's and the model's rule), so the
    replaced structure of a box of two parts weighs FINMASS with its CoG
    where it was."""
    a, b, c, t = 400.0, 250.0, 150.0, 2.0
    xyz, q = box_mesh(a, b, c, 8)
    centres = xyz[np.asarray(q)].mean(axis=1)
    model = shell_model(xyz, q, thickness=t, pids=np.where(centres[:, 2] > 0.0, 1, 2))
    model.sets[("PART", 7)] = id_list("SET_PART_LIST", 7, [1, 2])
    mass, _ = _box_inertia(a, b, c, t, RHO)
    fin = 3.0 * mass
    model.keywords.append(
        record(
            "ELEMENT_MASS_PART_SET", rows={"pid": np.array([7]), "addmass": np.array([0.0]), "finmass": np.array([fin])}
        )
    )
    rm = replaced_mass(cut_behind(model, x=a + 1.0))
    assert rm.structure.mass == pytest.approx(fin, rel=1e-12)
    assert model.mass_properties().mass == pytest.approx(fin, rel=1e-12)
    np.testing.assert_allclose(rm.structure.cog, model.mass_properties().cog, atol=1e-9)
