"""Tied contacts (*CONTACT_TIED_NODES_TO_SURFACE, _SHELL_EDGE_TO_SURFACE,
_OFFSET) against statics, kinematics and the conservation laws."""

import math

import numpy as np
import pytest
from _plates import RHO, E, Plates, ramp_curve

from crashlite import read_deck
from crashlite.solver import setup
from crashlite.solver.loop import integrate
from crashlite.solver.setup import SetupError
from crashlite.solver.tied import TiedContact


def _run(path, output_dt):
    s = setup.build(read_deck(path))
    return s, integrate(s, output_dt)


def _ties(s):
    return [c for c in s.constraints if isinstance(c, TiedContact)]


@pytest.mark.parametrize("mstyp", [3, 2, 1, 0])
def test_strip_tied_end_to_end_is_as_stiff_as_one_strip(tmp_path, mstyp):
    """Two 50 x 10 x 1 mm membrane strips (ν = 0) meet end to end; the end
    nodes of the second are tied (nodes to surface) to the first (master:
    its part, a part set, a shell set or a segment set). Clamped at x = 0
    and pulled quasi-statically by u = 0.05 mm at x = 100: the clamp
    reaction is E·t·w·u/L within 2 % and the strain energy ½·F·u within
    1 %."""
    t, w, L, u = 1.0, 10.0, 100.0, 0.05
    T, T_end = 6e-4, 9e-4  # ramp over ~8 axial periods 4L/c, then held
    P = Plates(t=t)
    a = P.plate(1, 0, 50, 10, 0, w, 2)
    b = P.plate(2, 50, 100, 10, 0, w, 2)
    P.node_set(1, b[:, 0])
    last = [e for e in P.elems if e[0] in (1010, 1020)]  # the two elements at the end of the first strip
    P.add(
        {
            3: "",
            2: "*SET_PART_LIST\n5\n1",
            1: "*SET_SHELL_LIST\n5\n" + ",".join(str(e[0]) for e in last),
            0: "*SET_SEGMENT\n5\n" + "\n".join(",".join(str(int(n)) for n in e[2]) for e in last),
        }[mstyp]
    )
    P.add(f"*CONTACT_TIED_NODES_TO_SURFACE\n1,{1 if mstyp == 3 else 5},4,{mstyp}\n0,0\n0,0")
    P.spc(a[:, 0])
    P.spc(np.setdiff1d(np.concatenate([a.ravel(), b.ravel()]), a[:, 0]), "0,0,1,1,1,1")  # in-plane
    P.node_set(2, b[:, -1])
    P.add(ramp_curve(1, u, T, T_end))
    P.add("*BOUNDARY_PRESCRIBED_MOTION_SET\n2,1,2,1,1.0")
    s, r = _run(P.write(tmp_path / "strips.k", T_end), 1e-5)
    (tie,) = _ties(s)
    assert len(tie) == 3 and len(tie.untied) == 0
    np.testing.assert_allclose(tie.gap, 0.0, atol=1e-12)
    k = E * t * w / L
    hold = r.time >= T
    reaction = -r.spc_force[:, :, 0].sum(axis=1)  # x is held at the clamp only
    assert reaction[hold].mean() == pytest.approx(k * u, rel=0.02)
    assert r.internal[-1] == pytest.approx(0.5 * k * u**2, rel=0.01)


def _plate_with_mass(tmp_path, tied: bool):
    P = Plates(t=1.0)
    a = P.plate(1, 0, 40, 8, 0, 40, 8)
    P.nodes.append((9001, 17.5, 17.5, 0.5))  # over the centre of the element 15..20 x 15..20, 0.5 mm up
    P.add("*ELEMENT_MASS\n9001,9001,5e-6")
    if tied:
        P.node_set(1, [9001])
        P.add("*CONTACT_TIED_NODES_TO_SURFACE\n1,1,4,3\n0,0\n0,0")
    rows = []
    for j in range(9):
        for i in range(9):
            x, y = 5.0 * i, 5.0 * j
            rows.append(
                f"{a[j, i]},{500.0 + 2000.0 * math.cos(math.pi * x / 40)!r},"
                f"{1000.0 * math.sin(math.pi * y / 40)!r},300.0"
            )
    P.add("*INITIAL_VELOCITY_NODE\n" + "\n".join(rows))
    P.history([9001, a[3, 3], a[3, 4], a[4, 4], a[4, 3]])
    P.add("*CONTROL_TIMESTEP\n0.0,0.2")  # small steps: the energy measured at the outputs is accurate
    return P.write(tmp_path / f"mass{int(tied)}.k", 1e-3), a


def test_mass_tied_to_a_plate_moves_with_it(tmp_path):
    """A point mass (40 % of the plate's) 0.5 mm over the centre of a plate
    element, at rest, tied to a free plate that moves and vibrates: the
    mass moves as the mean of the element's corners at every output (to
    round-off), the momentum of plate and mass is the plate's initial one
    to round-off, and the energy is conserved within 1 %."""
    path, _ = _plate_with_mass(tmp_path, True)
    s, r = _run(path, 2e-5)
    (tie,) = _ties(s)
    assert len(tie) == 1 and tie.gap[0] == pytest.approx(0.5, rel=1e-12)
    np.testing.assert_allclose(tie.w[0], 0.25, rtol=1e-9)
    free = setup.build(read_deck(_plate_with_mass(tmp_path, False)[0]))
    p0 = (free.mass[:, None] * free.v0).sum(axis=0)  # the physical momentum at the start
    assert free.mass.sum() == pytest.approx(s.mass.sum(), rel=1e-14)
    scale = np.abs(p0).max()
    np.testing.assert_allclose((s.mass[:, None] * r.final_v).sum(axis=0), p0, rtol=0, atol=1e-11 * scale)
    col = np.searchsorted(r.history_nodes, s.constraints[0].slave[0])  # history columns: by node index
    v_mass, v_plate = r.node_velocity[:, col], np.delete(r.node_velocity, col, axis=1)
    np.testing.assert_allclose(v_mass, v_plate.mean(axis=1), rtol=0, atol=1e-9 * np.abs(v_plate).max())
    assert np.abs(v_plate[:, :, 0]).max() > 1000.0  # the plate does vibrate
    total = r.kinetic + r.internal + r.hourglass
    assert r.internal.max() > 0.1 * total[0]
    assert np.abs(total - total[0]).max() < 0.01 * total[0]


@pytest.mark.parametrize(
    "kind, carries",
    [("SHELL_EDGE_TO_SURFACE_OFFSET", True), ("SHELL_EDGE_TO_SURFACE", True), ("NODES_TO_SURFACE_OFFSET", False)],
)
def test_cantilever_of_two_tied_plates(tmp_path, kind, carries):
    """A 100 x 10 x 4 mm cantilever (ν = 0) made of two plates: the first
    (x 0..60) clamped, the second (x 50..100) lying on it 4 mm up, its edge
    at x = 50 tied to the first with the gap as a rigid offset. The tip
    pushed quasi-statically by 1 mm: the clamp reaction (mean over the
    hold) is the continuous beam's 3EI·δ/L³ within 5 % and the strain
    energy its ½·F·δ within 5 %, when the tie carries the edge rotations
    (shell edge); tied by the translations only, the edge is a hinge and
    carries almost nothing."""
    L, b, t, d = 100.0, 10.0, 4.0, 1.0
    ei = E * b * t**3 / 12
    per = 2 * math.pi * L**2 / 1.8751**2 * math.sqrt(RHO * b * t / ei)
    T, T_end = 3 * per, 4 * per
    P = Plates(t=t)
    a = P.plate(1, 0, 60, 6, 0, b, 1)
    c = P.plate(2, 50, 100, 5, 0, b, 1, z=t)
    P.node_set(1, c[:, 0])
    P.add(f"*CONTACT_TIED_{kind}\n1,1,4,3\n0,0\n0,0")
    P.spc(a[:, 0])
    P.node_set(2, c[:, -1])
    P.add(ramp_curve(1, -d, T, T_end))
    P.add("*BOUNDARY_PRESCRIBED_MOTION_SET\n2,3,2,1,1.0")
    s, r = _run(P.write(tmp_path / "cantilever.k", T_end), per / 50)
    (tie,) = _ties(s)
    assert len(tie) == 2 and np.allclose(tie.gap, t)
    k = 3 * ei / L**3
    hold = r.time >= T
    reaction = r.spc_force[:, :, 2].sum(axis=1)
    if carries:
        assert tie.rotations and tie.mrot.all()
        assert reaction[hold].mean() == pytest.approx(k * d, rel=0.05)
        assert r.internal[-1] == pytest.approx(0.5 * k * d**2, rel=0.05)
    else:
        assert abs(reaction[hold].mean()) < 0.02 * k * d


def test_offset_tie_on_a_solid_follows_its_spin(tmp_path):
    """A small point mass 2 mm off the face of a solid block (no rotational
    DOFs: the offset turns with the spin of the face), tied with
    NODES_TO_SURFACE_OFFSET; block and mass spin freely at ω about z: after
    a quarter turn the mass sits at its initial position turned by ω·t
    within 1 % of the offset, still 7 mm from the axis (0.1 %)."""
    from _solid_driver import brick_mesh

    x, conn = brick_mesh(2, 2, 2, 5.0, 5.0, 5.0)
    x -= 5.0
    omega = 2000.0
    t_end = 0.5 * math.pi / omega
    lines = ["*KEYWORD", "*NODE"] + [
        f"{i + 1},{float(p[0])!r},{float(p[1])!r},{float(p[2])!r}" for i, p in enumerate(x)
    ]
    lines += ["900,7.0,0.0,0.0", "*ELEMENT_MASS", "900,900,1e-8", "*ELEMENT_SOLID"]
    lines += [f"{e + 1},1," + ",".join(str(int(n) + 1) for n in row) for e, row in enumerate(conn)]
    lines += [
        "*PART",
        "block",
        "1,1,1",
        "*SECTION_SOLID",
        "1,1",
        "*MAT_ELASTIC",
        f"1,{RHO},{E},0.3",
        "*SET_NODE_LIST",
        "1",
        "900",
        "*CONTACT_TIED_NODES_TO_SURFACE_OFFSET",
        "1,1,4,3",
        "0,0",
        "1,1,4.0",  # SST: a 4 mm slave thickness reaches 0.6·4 = 2.4 mm
        "*SET_NODE_GENERATE",
        "2",
        "1,900",
        "*INITIAL_VELOCITY_GENERATION",
        f"2,3,{omega},0,0,0",
        "0,0,0,0,0,1",
        "*DATABASE_HISTORY_NODE",
        "900",
        "*CONTROL_TERMINATION",
        f"{t_end!r},",
        "*END",
    ]
    p = tmp_path / "spin.k"
    p.write_text("\n".join(lines) + "\n")
    s, r = _run(p, t_end / 50)
    (tie,) = _ties(s)
    assert len(tie) == 1 and not tie.mrot[0] and tie.gap[0] == pytest.approx(2.0)
    assert tie.seg[0].tolist() != [] and np.all(s.x0[tie.seg[0], 0] == 5.0)  # the face at x = 5
    np.testing.assert_allclose(s.v0[-1], [0.0, 7.0 * omega, 0.0], rtol=1e-9)  # consistent from the start
    for k in (len(r.time) // 2, -1):
        end = r.node_coordinates[k, 0]
        turned = 7.0 * np.array([math.cos(omega * r.time[k]), math.sin(omega * r.time[k]), 0.0])
        assert np.linalg.norm(end - turned) < 0.01 * 2.0
        assert np.linalg.norm(end[:2]) == pytest.approx(7.0, rel=1e-3)


def _lap(tmp_path, extra, name="bad.k"):
    P = Plates(t=1.0)
    P.plate(1, 0, 10, 2, 0, 10, 2)
    P.add(extra)
    return P.write(tmp_path / name, 1e-4)


def test_far_slave_node_is_left_free_and_reported(tmp_path):
    """A slave node 5 mm off a 1 mm plate (beyond 0.6·(t_s + t_m) and 5 %
    of the segment) is not tied: listed with a warning naming the card,
    and it keeps its own mass and motion."""
    p = _lap(
        tmp_path,
        "*NODE\n9001,5.0,5.0,5.0\n9002,5.0,5.0,0.4\n*ELEMENT_MASS\n1,9001,1e-6\n2,9002,1e-6\n"
        "*SET_NODE_LIST\n7\n9001,9002\n*CONTACT_TIED_NODES_TO_SURFACE\n7,1,4,3\n0,0\n0,0",
    )
    model = read_deck(p)
    s = setup.build(model)
    (tie,) = _ties(s)
    assert tie.untied.tolist() == [9001]
    assert model.nodes.ids[tie.slave].tolist() == [9002]
    assert "CONTACT_TIED_NODES_TO_SURFACE" in str(tie.warnings[0]) and "9001" in str(tie.warnings[0])
    assert s.mass[model.node_index([9001])[0]] == pytest.approx(1e-6)
    assert s.mass[model.node_index([9002])[0]] == 0.0


def test_undefined_slave_set_is_a_setup_error(tmp_path):
    p = _lap(tmp_path, "*CONTACT_TIED_NODES_TO_SURFACE\n99,1,4,3\n0,0\n0,0")
    with pytest.raises(
        SetupError,
        match=r"bad.k:\d+: \*CONTACT_TIED_NODES_TO_SURFACE, field SSID: "
        r"\*SET_NODE 99 is not defined",
    ):
        setup.build(read_deck(p))


def test_undefined_master_part_is_a_setup_error(tmp_path):
    p = _lap(tmp_path, "*SET_NODE_LIST\n1\n1001\n*CONTACT_TIED_SHELL_EDGE_TO_SURFACE_OFFSET\n1,5,4,3\n0,0\n0,0")
    with pytest.raises(
        SetupError,
        match=r"\*CONTACT_TIED_SHELL_EDGE_TO_SURFACE_OFFSET, field MSID: part 5 is not "
        "defined",
    ):
        setup.build(read_deck(p))


def test_projection_on_triangles_and_quads():
    """Closest points: inside a triangle (barycentric weights), beyond its
    edge (clamped to the edge) and on a warped quad (weights that rebuild
    the point's foot)."""
    from crashlite.solver.tied import project

    x = np.array([[0, 0, 0], [10, 0, 0], [0, 10, 0], [10, 10, 1.0], [20, 0, 0]], float)
    seg = np.array([[0, 1, 2, 2], [1, 4, 3, 3]])
    idx, w, d = project(np.array([[2.0, 3.0, 0.5], [-1.0, 4.0, 0.0]]), x, seg, np.array([1.0, 1.0]))
    assert idx.tolist() == [0, 0]
    np.testing.assert_allclose(w[0], [0.5, 0.2, 0.3, 0.0], atol=1e-12)
    np.testing.assert_allclose(d, [0.5, 1.0], atol=1e-12)
    np.testing.assert_allclose(w[1], [0.6, 0.0, 0.4, 0.0], atol=1e-12)
    quad = np.array([[0, 0, 0], [10, 0, 0], [10, 10, 2.0], [0, 10, 0]], float)
    p = np.array([[6.0, 3.0, 3.0]])
    idx, w, d = project(p, quad, np.array([[0, 1, 2, 3]]), np.array([5.0]))
    foot = w[0] @ quad
    assert idx[0] == 0 and w[0].sum() == pytest.approx(1.0)
    # the foot is where p - foot is normal to both surface tangents
    xi, eta = 2 * (foot[:2] / 10.0) - 1
    t1 = 0.25 * ((1 - eta) * (quad[1] - quad[0]) + (1 + eta) * (quad[2] - quad[3]))
    t2 = 0.25 * ((1 - xi) * (quad[3] - quad[0]) + (1 + xi) * (quad[2] - quad[1]))
    assert abs((p[0] - foot) @ t1) < 1e-9 and abs((p[0] - foot) @ t2) < 1e-9
    assert d[0] == pytest.approx(np.linalg.norm(p[0] - foot))


def test_unsupported_tied_variant_is_refused(tmp_path):
    p = _lap(tmp_path, "*CONTACT_TIED_SURFACE_TO_SURFACE_FAILURE\n1,1,3,3\n0,0\n0,0")
    with pytest.raises(SetupError, match=r"CONTACT_TIED_SURFACE_TO_SURFACE_FAILURE.*not run by the crashlite solver"):
        setup.build(read_deck(p))
