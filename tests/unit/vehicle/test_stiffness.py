"""Step 3: the linear static solve against closed-form stiffnesses."""

import numpy as np
import pytest
from _structures import E, grid_quads, plate_mesh, shell_model, tube_mesh

from crashlite.model.mesh import Beams, Discretes, Nodes
from crashlite.model.model import Model
from crashlite.vehicle.car.records import record
from crashlite.vehicle.steps.cut import cut_behind
from crashlite.vehicle.steps.elements import beam_stiffness, hex_stiffness, shell_stiffness
from crashlite.vehicle.steps.stiffness import longitudinal_stiffness, structure_stiffness

B, L, T = 50.0, 500.0, 1.5  # tube side (mid-line), length, wall [mm]


def _ends(xyz, length):
    return np.flatnonzero(xyz[:, 0] == 0.0), np.flatnonzero(xyz[:, 0] == length)


def _rigid_modes(x, rotations=True):
    modes = []
    for d in range(3):
        u = np.zeros((len(x), 6))
        u[:, d] = 1.0
        modes.append(u)
    for d in range(3):
        th = np.eye(3)[d]
        u = np.zeros((len(x), 6))
        u[:, :3] = np.cross(th, x)
        u[:, 3:] = th
        modes.append(u)
    m = np.array(modes)
    return (m if rotations else m[:, :, :3]).reshape(6, -1)


def test_elements_have_exactly_the_rigid_body_modes():
    rng = np.random.default_rng(3)
    rot, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    quad = np.array([[0, 0, 0], [30, 2, 0], [28, 25, 0], [-3, 20, 0]], float) @ rot.T + 100.0
    tri = quad.copy()
    tri[3] = tri[2]
    for x in (quad, tri):
        k = shell_stiffness(x[None], 1.2, E, 0.3)[0]
        assert np.abs(k - k.T).max() < 1e-12 * np.abs(k).max()
        assert np.abs(k @ _rigid_modes(x).T).max() < 1e-12 * np.abs(k).max()
        w = np.linalg.eigvalsh(k)
        assert np.sum(w < 1e-9 * w.max()) == 6  # no spurious mode (drilling included)
    ends = np.array([[0, 0, 0], [100, 20, 30.0]])
    frames = np.stack([ends[1] - ends[0], np.cross([0, 0, 1.0], ends[1] - ends[0]), [0, 0, 0]])
    frames[2] = np.cross(frames[0], frames[1])
    frames = (frames / np.linalg.norm(frames, axis=1)[:, None]).T[None]
    kb = beam_stiffness(ends[:1], ends[1:], frames, 1e5, 2e6, 3e6, 4e6)[0]
    assert np.abs(kb @ _rigid_modes(ends).T).max() < 1e-12 * np.abs(kb).max() and np.linalg.matrix_rank(kb) == 6
    cube = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1.0]]) * 10
    kh = hex_stiffness(cube[None], 1000.0, 0.3)[0]
    assert np.abs(kh @ _rigid_modes(cube, rotations=False).T).max() < 1e-12 * np.abs(kh).max()
    assert np.linalg.matrix_rank(kh) == 18


@pytest.mark.parametrize("nu, tol", [(0.0, 1e-9), (0.3, 0.01)])
def test_square_tube_axial_stiffness_is_ea_over_l(nu, tol):
    """Clamped at x = 0, pushed through a rigid end ring: K = E·4bt/L
    (exact for ν = 0; with ν the clamped and rigid ends hold the Poisson
    contraction and stiffen it a little)."""
    xyz, q = tube_mesh(B, L, 5, 50)
    model = shell_model(xyz, q, thickness=T, poisson=nu)
    fixed, loaded = _ends(xyz, L)
    r = structure_stiffness(model, fixed, loaded, force=1000.0, direction=(-1.0, 0.0, 0.0))
    ea_l = E * 4 * B * T / L
    assert r.stiffness == pytest.approx(ea_l, rel=tol)
    assert r.stiffness >= ea_l * (1 - 1e-9)
    np.testing.assert_allclose(r.support_reaction, [1000.0, 0.0, 0.0], atol=1e-6)
    np.testing.assert_allclose(r.load_point, [L, 0.0, 0.0], atol=1e-9)
    assert r.elements == {"shell": len(q)} and r.displacement == pytest.approx(1000.0 / r.stiffness)


def test_distorted_mesh_passes_the_membrane_patch_test():
    """A strip with shifted interior nodes and triangles under tension:
    uniform stress, K = E·w·t/L to round-off (ν = 0)."""
    length, width = 200.0, 40.0
    xyz, q = plate_mesh(length, width, 10, 4)
    rng = np.random.default_rng(7)
    inner = (xyz[:, 0] > 0) & (xyz[:, 0] < length) & (np.abs(xyz[:, 1]) < width / 2)
    xyz[inner, :2] += rng.uniform(-3.0, 3.0, (inner.sum(), 2))
    q = np.asarray(q).copy()
    split = q[::3].copy()  # every third quad as two triangles (node 4 = node 3)
    q[::3] = split[:, [0, 1, 2, 2]]
    extra = split[:, [0, 2, 3, 3]]
    model = shell_model(xyz, np.vstack([q, extra]), thickness=2.0, poisson=0.0)
    fixed, loaded = _ends(xyz, length)
    r = structure_stiffness(model, fixed, loaded, force=500.0, direction=(1.0, 0.0, 0.0))
    assert r.stiffness == pytest.approx(E * width * 2.0 / length, rel=1e-9)


def test_cantilever_plate_bending_is_pl3_over_3ei():
    length, width, t = 400.0, 40.0, 2.0
    xyz, q = plate_mesh(length, width, 40, 4)
    model = shell_model(xyz, q, thickness=t, poisson=0.0)
    fixed, loaded = _ends(xyz, length)
    r = structure_stiffness(model, fixed, loaded, force=10.0, direction=(0.0, 0.0, -1.0))
    i = width * t**3 / 12
    assert r.stiffness == pytest.approx(3 * E * i / length**3, rel=0.01)


def test_in_plane_bending_of_a_strip_is_timoshenko():
    """The membrane (incompatible modes) bends in its plane like a
    Timoshenko beam: δ = PL³/3EI + PL/(κGA), κ = 5/6."""
    length, depth, t = 800.0, 40.0, 2.0
    xyz, q = plate_mesh(length, depth, 40, 4, plane="xz")
    model = shell_model(xyz, q, thickness=t, poisson=0.0)
    fixed, loaded = _ends(xyz, length)
    r = structure_stiffness(model, fixed, loaded, force=10.0, direction=(0.0, 0.0, 1.0))
    i, a, g = t * depth**3 / 12, t * depth, E / 2.0
    flex = length**3 / (3 * E * i) + length / (5 / 6 * g * a)
    assert r.stiffness == pytest.approx(1.0 / flex, rel=0.01)


def test_square_tube_as_a_cantilever_frame_member():
    """Tip load across a thin-walled square tube: δ = PL³/3EI + PL/(G·A_web),
    I = 2b³t/3, shear carried by the two webs (A_web = 2bt)."""
    xyz, q = tube_mesh(B, L, 5, 50)
    model = shell_model(xyz, q, thickness=T, poisson=0.3)
    fixed, loaded = _ends(xyz, L)
    r = structure_stiffness(model, fixed, loaded, force=100.0, direction=(0.0, 0.0, -1.0))
    i, g = 2 * B**3 * T / 3, E / 2.6
    flex = L**3 / (3 * E * i) + L / (g * 2 * B * T)
    assert r.stiffness == pytest.approx(1.0 / flex, rel=0.015)


def _frame_model(h, a, area, inertia):
    """An L frame of resultant beams: column (0,0,0)-(0,0,h), beam to (a,0,h)."""
    m = Model()
    pts = np.array([[0, 0, z] for z in np.linspace(0, h, 11)] + [[x, 0, h] for x in np.linspace(0, a, 11)[1:]])
    m.nodes = Nodes(
        np.arange(1, len(pts) + 1), pts.astype(float), np.zeros(len(pts), np.int8), np.zeros(len(pts), np.int8)
    )
    bm = Beams.zeros(len(pts) - 1)
    bm.ids = np.arange(1, len(pts))
    bm.pid = np.ones(len(pts) - 1, np.int64)
    bm.nodes[:, 0] = np.arange(len(pts) - 1)
    bm.nodes[:, 1] = np.arange(1, len(pts))
    m.beams = bm
    m.materials[1] = record("MAT_ELASTIC", mid=1, ro=7.85e-9, e=E, pr=0.3)
    m.sections[1] = record("SECTION_BEAM", secid=1, elform=2, a=area, iss=inertia, itt=inertia, irr=2 * inertia)
    m.parts[1] = record("PART", heading="frame", pid=1, secid=1, mid=1)
    return m


def test_l_frame_of_beams():
    """Column h clamped at its foot, beam a; a load P down at the tip:
    δ = Pa³/3EI + Pa²h/EI (the column bent by Pa) + Ph/EA."""
    h, a, area, inertia = 600.0, 400.0, 200.0, 2.0e4
    m = _frame_model(h, a, area, inertia)
    tip = np.flatnonzero(np.all(m.nodes.xyz == [a, 0, h], axis=1))
    r = structure_stiffness(m, [0], tip, force=50.0, direction=(0.0, 0.0, -1.0))
    flex = a**3 / (3 * E * inertia) + a**2 * h / (E * inertia) + h / (E * area)
    assert r.stiffness == pytest.approx(1.0 / flex, rel=1e-9)


def test_springs_in_series_and_spot_welded_tube_halves():
    m = Model()
    m.nodes = Nodes(
        np.arange(1, 4), np.array([[0, 0, 0], [100, 0, 0], [250, 0, 0.0]]), np.zeros(3, np.int8), np.zeros(3, np.int8)
    )
    d = Discretes.zeros(2)
    d.ids = np.array([1, 2])
    d.pid = np.array([1, 2])
    d.nodes = np.array([[0, 1], [1, 2]], np.int32)
    m.discretes = d
    for p, k in ((1, 300.0), (2, 600.0)):
        m.materials[p] = record("MAT_SPRING_ELASTIC", mid=p, k=k)
        m.parts[p] = record("PART", heading=f"spring {p}", pid=p, secid=1, mid=p)
    m.sections[1] = record("SECTION_DISCRETE", secid=1)
    r = structure_stiffness(m, [0], [2], force=10.0, direction=(-1.0, 0.0, 0.0))
    assert r.stiffness == pytest.approx(200.0, rel=1e-12)
    # two tubes end to end on separate coincident nodes, joined by spot welds at every ring node
    xyz, q = tube_mesh(B, L / 2, 4, 10)
    second = xyz + [L / 2, 0, 0]
    model = shell_model(np.vstack([xyz, second]), np.vstack([q, q + len(xyz)]), thickness=T, poisson=0.0)
    a = np.flatnonzero(xyz[:, 0] == L / 2)
    b = len(xyz) + np.flatnonzero(second[:, 0] == L / 2)
    ids = model.nodes.ids
    model.keywords.append(
        record("CONSTRAINED_SPOTWELD_ID", rows={"wid": np.arange(1, len(a) + 1), "n1": ids[a], "n2": ids[b]})
    )
    allx = model.nodes.xyz[:, 0]
    r = structure_stiffness(model, np.flatnonzero(allx == 0.0), np.flatnonzero(allx == L), force=1000.0)
    assert r.stiffness == pytest.approx(E * 4 * B * T / L, rel=1e-9)


def test_an_unsupported_structure_is_refused():
    xyz, q = tube_mesh(B, L, 2, 5)
    model = shell_model(xyz, q, thickness=T)
    fixed, loaded = _ends(xyz, L)
    with pytest.raises(KeyError, match="no \\*SET_NODE titled"):
        structure_stiffness(model, "rear axle", loaded)
    two = shell_model(np.vstack([xyz, xyz + [0, 200.0, 0]]), np.vstack([q, q + len(xyz)]), thickness=T)
    with pytest.raises(ValueError, match="mechanism"):  # the second tube floats
        structure_stiffness(two, fixed, loaded)


def test_cut_tube_longitudinal_stiffness_of_the_replaced_half():
    """The car drives in +x; the interface at x = 300 replaces the tube
    behind it, borne at x = 0: K = EA/300."""
    xyz, q = tube_mesh(B, L, 4, 25)
    model = shell_model(xyz, q, thickness=T, poisson=0.0)
    cut = cut_behind(model, x=300.0)
    r = longitudinal_stiffness(cut, np.flatnonzero(xyz[:, 0] == 0.0))
    assert r.stiffness == pytest.approx(E * 4 * B * T / 300.0, rel=1e-9)
    np.testing.assert_allclose(r.direction, [-1, 0, 0])
    assert r.load_point[0] == pytest.approx(300.0)


@pytest.mark.slow
def test_generic_car_longitudinal_stiffness():
    from crashlite.vehicle import generic_vehicle

    v = generic_vehicle(38.0)
    cut = cut_behind(v.model, x=v.interface_x)
    r = longitudinal_stiffness(cut, "rear axle attachment")
    assert 5e3 < r.stiffness < 1e5  # N/mm; the paper's car: 23 585
    np.testing.assert_allclose(r.support_reaction, [1000.0, 0.0, 0.0], atol=1e-6)
    assert (
        r.elements["shell"]
        == cut.replaced["shells"].sum()
        - np.isin(v.model.shells.pid[cut.replaced["shells"]], [v.part_ids["rear axle"]]).sum()
    )
    assert r.load_point[0] == pytest.approx(v.interface_x, abs=40.0)


def test_grid_helper_is_conforming():
    q = grid_quads(3, 4, wrap=True)
    assert q.shape == (8, 4) and q.max() == 11
