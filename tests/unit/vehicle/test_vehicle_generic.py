"""The generic compact car: deck round trip, mass and CoG, named parts,
sets, sections and history nodes, mesh quality and scaling."""

import numpy as np
import pytest
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from crashlite import read_deck
from crashlite.keyword.equality import model_differences
from crashlite.vehicle import generic_vehicle
from crashlite.vehicle.car.body import INTERFACE_ASSEMBLIES

COARSE = 38.0  # mm: about 20 k shells


@pytest.fixture(scope="module")
def car():
    return generic_vehicle(COARSE)


@pytest.fixture(scope="module")
def reread(car, tmp_path_factory):
    path = car.write(tmp_path_factory.mktemp("car") / "car.k")
    return read_deck(path)


def test_deck_reads_back_identically(car, reread):
    assert model_differences(car.model, reread) == []
    assert reread.warnings == []


def test_mass_and_cog_match_the_target(reread):
    p = reread.mass_properties()
    assert p.mass * 1e3 == pytest.approx(1263.0, rel=1e-6)
    assert p.cog == pytest.approx([-1100.0, 0.0, 500.0], abs=0.01)


def test_other_targets_and_rigid_masses():
    v = generic_vehicle(COARSE, mass=1500.0, cog_x=-1200.0, cog_z=520.0, engine_mass=190.0, axle_mass=80.0)
    p = v.model.mass_properties()
    assert p.mass * 1e3 == pytest.approx(1500.0, rel=1e-6)
    assert p.cog == pytest.approx([-1200.0, 0.0, 520.0], abs=0.01)
    assert v.model.mass_properties("engine and gearbox").mass * 1e3 == pytest.approx(190.0, rel=1e-9)
    assert v.model.mass_properties("rear axle").mass * 1e3 == pytest.approx(80.0, rel=1e-9)
    with pytest.raises(ValueError, match="cannot be reached"):
        generic_vehicle(COARSE, cog_z=1300.0)


def test_size_and_layout(car):
    lo, hi = car.model.nodes.xyz.min(axis=0), car.model.nodes.xyz.max(axis=0)
    assert hi[0] - lo[0] == pytest.approx(3830.0, abs=5)  # overall length
    assert hi[1] - lo[1] == pytest.approx(1690.0, abs=5)  # width over the doors
    assert hi[2] == pytest.approx(1400.0)
    assert 15_000 < car.shells < 25_000
    assert 400.0 < car.structure_mass < 600.0  # body in white, closures, engine, axle


def test_parts_and_assemblies_by_name(car):
    names = set(car.part_ids)
    for side in ("left", "right"):
        for n in (
            "crash box",
            "front rail",
            "upper rail",
            "A-pillar",
            "hinge pillar",
            "sill",
            "floor",
            "door inner",
            "door outer",
            "B-pillar",
            "rear rail",
            "roof rail",
        ):
            assert f"{n} {side}" in names
    for n in (
        "bumper beam",
        "radiator support",
        "engine and gearbox",
        "engine mounts",
        "firewall",
        "tunnel",
        "exhaust",
        "windshield",
        "roof",
        "rear floor",
        "rear axle",
    ):
        assert n in names
    for a in INTERFACE_ASSEMBLIES + ("crash box left", "crash box right", "firewall", "engine and gearbox"):
        assert f"assembly {a}" in car.set_ids
    m = car.model
    kinds = {m.materials[m.parts[car.part_ids[n]]["mid"]].keyword for n in ("engine and gearbox", "rear axle")}
    assert kinds == {"MAT_RIGID"}
    rail = m.parts[car.part_ids["front rail left"]]
    assert m.materials[rail["mid"]].keyword == "MAT_PIECEWISE_LINEAR_PLASTICITY"
    assert 1.2 <= m.sections[rail["secid"]]["t1"] <= 2.0
    assert 1.2 <= m.sections[m.parts[car.part_ids["crash box left"]]["secid"]]["t1"] <= 2.0


def test_sets_sections_and_history_nodes(car, reread):
    m = reread
    titles = {r.title: key for key, r in m.sets.items()}
    for t in ("vehicle", "crash box left nodes", "crash box right nodes", "firewall nodes", "rear axle attachment"):
        assert t in titles
    assert set(m.set_members(*titles["vehicle"])) == set(m.parts)
    box = m.node_index(m.set_members(*titles["crash box left nodes"]))
    assert np.all(m.nodes.xyz[box, 0] >= 610.0) and np.all(m.nodes.xyz[box, 1] > 0)
    att = m.node_index(m.set_members(*titles["rear axle attachment"]))
    assert len(att) > 0 and np.allclose(np.abs(m.nodes.xyz[att, 1]), 410.0)
    sections = {r["title"]: r for r in m.find("DATABASE_CROSS_SECTION_PLANE")}
    assert set(sections) == set(INTERFACE_ASSEMBLIES)  # the paper's eleven at x = -600
    for name, r in sections.items():
        assert r["xct"] == -600.0 and r["xch"] > r["xct"]
        assert m.sets[("PART", r["psid"])].title == f"assembly {name}"
    heads = dict(zip(m.find("DATABASE_HISTORY_NODE")[0].rows["heading"], m.find("DATABASE_HISTORY_NODE")[0].rows["id"]))
    assert set(heads) >= {"engine top", "vehicle CoG", "rear seat left", "rear seat right"}
    x = m.nodes.xyz[m.node_index([heads["engine top"]])[0]]
    assert x[2] == pytest.approx(700.0)
    cog = m.nodes.xyz[m.node_index([heads["vehicle CoG"]])[0]]
    assert abs(cog[0] + 1100.0) < COARSE and abs(cog[1]) < COARSE


def test_interface_on_a_row_of_nodes_moves_into_the_element_row_behind():
    """x = −800 is where the toe pan meets the floor (a lattice line): a
    section there would cut no element that ends on it, so the sections go
    to the middle of the element row behind, and every assembly is cut."""
    v = generic_vehicle(COARSE, interface_x=-800.0)
    x = np.unique(v.model.nodes.xyz[:, 0])
    k = np.searchsorted(x, -800.0)
    assert x[k] == -800.0 and v.interface_x == pytest.approx(0.5 * (x[k] + x[k - 1]))
    assert {r["xct"] for r in v.model.find("DATABASE_CROSS_SECTION_PLANE")} == {v.interface_x}
    assert set(v.sections) == set(INTERFACE_ASSEMBLIES)
    assert generic_vehicle(COARSE, interface_x=-600.0).interface_x == -600.0  # between rows: kept


def test_interface_position_moves_the_sections():
    v = generic_vehicle(COARSE, interface_x=-1000.0)
    planes = v.model.find("DATABASE_CROSS_SECTION_PLANE")
    assert {r["xct"] for r in planes} == {-1000.0}
    assert "A-pillar left" in v.sections and "roof" not in v.sections


@pytest.mark.parametrize("mesh", [COARSE, 20.0])
def test_door_joints_are_weld_patches_across_the_gap(mesh):
    """Each hinge and latch welds every door node within HINGE_REACH of it
    to the body node straight across the DOOR_GAP: a patch of the same
    height whatever the mesh (one welded pair would put the door's load
    into two elements)."""
    from crashlite.vehicle.car import body

    m = generic_vehicle(mesh).model
    w = m.find("CONSTRAINED_SPOTWELD")[0].rows
    a, b = m.nodes.xyz[m.node_index(w["n1"])], m.nodes.xyz[m.node_index(w["n2"])]
    d = a - b
    assert np.allclose(np.abs(d[:, 1]), body.DOOR_GAP) and np.allclose(d[:, [0, 2]], 0.0)
    joints = body.door_joints()
    nearest = np.argmin([np.linalg.norm(b - np.asarray(j.body, float), axis=1) for j in joints], axis=0)
    for k, j in enumerate(joints):
        patch = b[nearest == k]
        assert len(patch) >= 2, j.name
        span = patch[:, 2].max() - patch[:, 2].min()
        assert 1.0 * body.HINGE_REACH <= span <= 2.0 * body.HINGE_REACH + 1e-9, j.name
    assert len(w["n1"]) == len(np.unique(w["n1"]))


def test_mesh_is_one_conforming_body(car):
    """Every part is tied into the body through shared nodes, the doors
    through their hinge and latch welds; no two nodes coincide; no sliver
    elements (the smallest A/longest-side stays near the size)."""
    m = car.model
    q = m.shells.nodes.astype(np.int64)
    n = len(m.nodes)
    rows = np.concatenate([q[:, 0], q[:, 1], q[:, 2], q[:, 3]])
    cols = np.concatenate([q[:, 1], q[:, 2], q[:, 3], q[:, 0]])
    weld = m.find("CONSTRAINED_SPOTWELD")[0].rows
    rows = np.concatenate([rows, m.node_index(weld["n1"])])
    cols = np.concatenate([cols, m.node_index(weld["n2"])])
    k, _ = connected_components(coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n)), directed=False)
    assert k == 1
    assert len(np.unique(np.round(m.nodes.xyz, 3), axis=0)) == n
    x = m.nodes.xyz[q]
    area = 0.5 * np.linalg.norm(np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 1]), axis=1)
    side = np.linalg.norm(x - np.roll(x, -1, axis=1), axis=2).max(axis=1)
    assert (area / side).min() > 0.4 * COARSE
    assert side.max() < 1.6 * COARSE


def test_element_count_scales_with_the_mesh_size_geometry_stays(car):
    fine = generic_vehicle(COARSE / 2)
    ratio = fine.shells / car.shells
    assert 3.3 < ratio < 4.7
    for v in (car, fine):
        assert v.model.nodes.xyz.min(axis=0) == pytest.approx(car.model.nodes.xyz.min(axis=0))
        assert v.model.nodes.xyz.max(axis=0) == pytest.approx(car.model.nodes.xyz.max(axis=0))
    assert fine.structure_mass == pytest.approx(car.structure_mass, rel=1e-4)
    assert fine.cog == pytest.approx(car.cog, abs=1e-3)


def test_crash_boxes_are_closed_tubes_with_a_trigger(car):
    m = car.model
    pid = car.part_ids["crash box left"]
    q = m.shells.nodes[m.shells.pid == pid].astype(np.int64)
    edges = np.sort(np.stack([q, np.roll(q, -1, axis=1)], axis=2).reshape(-1, 2), axis=1)
    e, count = np.unique(edges, axis=0, return_counts=True)
    free = np.unique(e[count == 1])
    x = m.nodes.xyz[free, 0]
    assert set(np.round(x, 6)) == {610.0, 760.0}  # open only at its two ends: a closed section
    y = m.nodes.xyz[np.unique(q), 1]
    assert y.min() > 410.0 - 1.01 and y.max() < 490.0 + 1.01
    assert ((y > 410.0) & (y < 411.0)).any()  # the side walls are dented inwards


def test_stiff_front_is_a_thicker_shallower_bumper_on_longer_crash_boxes():
    """The second front (``front="stiff"``, what a barrier is checked
    under besides the generic car): the bumper beam 2.5 mm instead of
    1.6 mm and 45 mm deep instead of 70 mm, its face where it was; the crash
    boxes reach its back and share their end nodes with it; the car keeps
    its mass and CoG targets."""
    v = generic_vehicle(COARSE, front="stiff")
    m = v.model
    pid = v.part_ids["bumper beam"]
    assert m.sections[m.parts[pid]["secid"]]["t1"] == 2.5
    bumper = np.unique(m.shells.nodes[m.shells.pid == pid].astype(np.int64))
    xb = m.nodes.xyz[bumper, 0]
    assert xb.min() == pytest.approx(785.0) and xb.max() == pytest.approx(830.0)
    box = np.unique(m.shells.nodes[m.shells.pid == v.part_ids["crash box left"]].astype(np.int64))
    xc = m.nodes.xyz[box, 0]
    assert xc.min() == pytest.approx(610.0) and xc.max() == pytest.approx(785.0)
    shared = np.intersect1d(box, bumper)
    assert len(shared) >= 4 and np.allclose(m.nodes.xyz[shared, 0], 785.0)
    p = m.mass_properties()
    assert p.mass * 1e3 == pytest.approx(1263.0, rel=1e-6)
    assert p.cog == pytest.approx([-1100.0, 0.0, 500.0], abs=0.01)
    with pytest.raises(ValueError, match="front must be one of"):
        generic_vehicle(COARSE, front="flat")
