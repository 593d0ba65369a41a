"""Mass, CoG and inertia of parts and part sets against hand computations."""

import numpy as np
import pytest

from crashlite import read_deck

RO_S, RO_B = 7.85e-9, 2.7e-9


def _deck():
    """Plate 200 x 100 x 2 (part 1, 2x2 shells, section thickness), plate
    100 x 100 with nodal thickness 3 (part 2, *ELEMENT_SHELL_THICKNESS),
    brick 50 x 40 x 30 (part 3, 2 solids), a 0.01 t point mass on part 3."""
    nodes, shells, solids = [], [], []
    nid = 0

    def node(x, y, z):
        nonlocal nid
        nid += 1
        nodes.append(f"{nid:8d}{x:16.6f}{y:16.6f}{z:16.6f}")
        return nid

    g = [[node(100.0 * i, 50.0 * j, 0.0) for j in range(3)] for i in range(3)]
    eid = 0
    for i in range(2):
        for j in range(2):
            eid += 1
            shells.append(f"{eid:8d}{1:8d}{g[i][j]:8d}{g[i + 1][j]:8d}{g[i + 1][j + 1]:8d}{g[i][j + 1]:8d}")
    q = [node(0, 0, 500), node(100, 0, 500), node(100, 100, 500), node(0, 100, 500)]
    eid += 1
    thick = [f"{eid:8d}{2:8d}" + "".join(f"{n:8d}" for n in q), f"{3.0:16}{3.0:16}{3.0:16}{3.0:16}"]
    b = [[[node(1000 + 25.0 * i, 40.0 * j, 30.0 * k) for k in range(2)] for j in range(2)] for i in range(3)]
    for i in range(2):
        eid += 1
        c = [
            b[i][0][0],
            b[i + 1][0][0],
            b[i + 1][1][0],
            b[i][1][0],
            b[i][0][1],
            b[i + 1][0][1],
            b[i + 1][1][1],
            b[i][1][1],
        ]
        solids.append(f"{eid:8d}{3:8d}" + "".join(f"{n:8d}" for n in c))
    pm = node(0.0, 0.0, 1000.0)
    text = "\n".join(
        [
            "*KEYWORD",
            "*NODE",
            *nodes,
            "*ELEMENT_SHELL",
            *shells,
            "*ELEMENT_SHELL_THICKNESS",
            *thick,
            "*ELEMENT_SOLID",
            *solids,
            "*ELEMENT_MASS",
            f"{eid + 1:8d}{pm:8d}{0.01:16}{3:8d}",
            "*PART",
            "plate",
            "1,1,1",
            "*PART",
            "thick plate",
            "2,1,1",
            "*PART",
            "brick",
            "3,2,2",
            "*SECTION_SHELL",
            "1,2",
            "2.0",
            "*SECTION_SOLID",
            "2,1",
            "*MAT_ELASTIC",
            f"1,{RO_S},210000.0,0.3",
            "*MAT_ELASTIC",
            f"2,{RO_B},70000.0,0.33",
            "*SET_PART_LIST",
            "7",
            "1,3",
            "*END",
        ]
    )
    return text


def _box(m, c, a, b, t):
    """Mass, CoG and inertia about the CoG of a homogeneous box a x b x t."""
    return m, np.array(c, float), np.diag([m * (b * b + t * t), m * (a * a + t * t), m * (a * a + b * b)]) / 12


def _combine(*bodies):
    m = sum(b[0] for b in bodies)
    c = sum(b[0] * b[1] for b in bodies) / m
    inertia = np.zeros((3, 3))
    for mi, ci, ii in bodies:
        d = ci - c
        inertia += ii + mi * (d @ d * np.eye(3) - np.outer(d, d))
    return m, c, inertia


@pytest.fixture(scope="module")
def model(tmp_path_factory):
    p = tmp_path_factory.mktemp("mp") / "mp.k"
    p.write_text(_deck())
    return read_deck(p)


def test_single_parts(model):
    m1, c1, i1 = _box(RO_S * 200 * 100 * 2, [100, 50, 0], 200, 100, 2)
    mp = model.mass_properties([1])
    assert mp.mass == pytest.approx(m1, rel=1e-12)
    np.testing.assert_allclose(mp.cog, c1, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(mp.inertia, i1, rtol=1e-9, atol=1e-9 * np.abs(i1).max())
    mp2 = model.mass_properties(["thick plate"])  # by title; nodal thickness overrides the section
    assert mp2.mass == pytest.approx(RO_S * 100 * 100 * 3, rel=1e-12)


def test_part_set_with_point_mass_matches_hand_computation(model):
    plate = _box(RO_S * 200 * 100 * 2, [100, 50, 0], 200, 100, 2)
    brick = _box(RO_B * 50 * 40 * 30, [1025, 20, 15], 50, 40, 30)
    point = (0.01, np.array([0.0, 0.0, 1000.0]), np.zeros((3, 3)))
    m, c, inertia = _combine(plate, brick, point)
    parts = model.set_members("PART", 7)
    assert parts.tolist() == [1, 3]
    mp = model.mass_properties(parts)
    assert mp.mass == pytest.approx(m, rel=1e-9)
    np.testing.assert_allclose(mp.cog, c, rtol=1e-9)
    np.testing.assert_allclose(mp.inertia, inertia, rtol=1e-9, atol=1e-9 * np.abs(inertia).max())


def test_whole_model_is_sum_of_parts(model):
    whole = model.mass_properties()
    parts = model.mass_properties([1, 2, 3])
    assert whole.mass == pytest.approx(parts.mass, rel=1e-12)
    np.testing.assert_allclose(whole.inertia, parts.inertia, rtol=1e-12)


def test_unknown_part_is_an_error(model):
    with pytest.raises(KeyError, match="no part titled"):
        model.mass_properties(["no such part"])


def test_beams_and_part_inertia(tmp_path):
    """A tube beam (CST=1) as a line mass; a part with *PART_INERTIA counts
    with its given mass, CoG and tensor instead of its elements."""
    import math

    text = "\n".join(
        [
            "*KEYWORD",
            "*NODE",
            "1,0,0,0",
            "2,1000,0,0",
            "3,0,0,0",
            "4,10,0,0",
            "5,10,10,0",
            "*ELEMENT_BEAM",
            "1,1,1,2",
            "*ELEMENT_SHELL",
            "2,2,3,4,5",
            "*PART",
            "tube beam",
            "1,1,1",
            "*SECTION_BEAM",
            "1,1,,,1",
            "40.0,40.0,36.0,36.0",
            "*PART_INERTIA",
            "rigid",
            "2,2,2",
            "5.0,6.0,7.0,0.25",
            "1.0,0.0,0.0,2.0,0.0,3.0",
            "0,0,0,0,0,0",
            "*SECTION_SHELL",
            "2,2",
            "1.0",
            "*MAT_ELASTIC",
            "1,7.85e-9,210000.0,0.3",
            "*MAT_RIGID",
            "2,7.85e-9,210000.0,0.3",
            "*END",
        ]
    )
    p = tmp_path / "b.k"
    p.write_text(text)
    model = read_deck(p)
    beam = model.mass_properties([1])
    m = 7.85e-9 * math.pi / 4 * (40.0**2 - 36.0**2) * 1000.0
    assert beam.mass == pytest.approx(m, rel=1e-12)
    np.testing.assert_allclose(
        beam.inertia, np.diag([0.0, m * 1000.0**2 / 12, m * 1000.0**2 / 12]), atol=1e-9 * m * 1000.0**2
    )
    rigid = model.mass_properties(["rigid"])
    assert rigid.mass == 0.25 and rigid.cog.tolist() == [5.0, 6.0, 7.0]
    np.testing.assert_allclose(rigid.inertia, np.diag([1.0, 2.0, 3.0]), atol=1e-12)
