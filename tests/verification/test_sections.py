"""Section forces and moments (secforc) against statics."""

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.solver import run


def test_section_moment_of_two_offset_springs(tmp_path):
    """Two springs of different stiffness at y = ±50 mm pull a block
    (nodal rigid body) along x; the plane section through them reports
    their summed force (tension positive, as LS-DYNA's secforc) and the
    moment Mz = -Σ (y - ȳ)·Fx about the centroid of the cut ends, balanced
    by the turning of the body."""
    text = "\n".join(
        [
            "*KEYWORD",
            "*NODE",
            "1,0,50,0,7,7",
            "2,0,-50,0,7,7",
            "3,100,50,0",
            "4,100,-50,0",
            "*ELEMENT_MASS",
            "10,3,0.05",
            "11,4,0.05",
            "*SET_NODE_LIST",
            "1",
            "3,4",
            "*CONSTRAINED_NODAL_RIGID_BODY",
            "100,0,1",
            "*ELEMENT_DISCRETE",
            "1,1,1,3",
            "2,2,2,4",
            "*PART",
            "soft",
            "1,1,1",
            "*PART",
            "stiff",
            "2,1,2",
            "*SECTION_DISCRETE",
            "1,0",
            "*MAT_SPRING_ELASTIC",
            "1,50.0",
            "*MAT_SPRING_ELASTIC",
            "2,150.0",
            "*INITIAL_VELOCITY_NODE",
            "3,1000.0,0,0",
            "4,1000.0,0,0",
            "*DATABASE_CROSS_SECTION_PLANE_ID",
            "5,mid",
            "0,50,0,0,51,0,0",
            "*CONTROL_TERMINATION",
            "0.02",
            "*CONTROL_TIMESTEP",
            ",0.1",
            "*END",
        ]
    )
    p = tmp_path / "two.k"
    p.write_text(text)
    r = run(read_deck(p), output_dt=1e-3)
    f1, f2 = r.discrete_force[:, 0], r.discrete_force[:, 1]
    # the section side is x > 50: the springs' internal force at the far ends
    # (nodes 3, 4) is +F along the axis (they pull the nodes back with -F)
    fx = r.section_force[:, 0, 0]
    np.testing.assert_allclose(fx, (f1 + f2) * 1.0, rtol=2e-2, atol=1e-6 * np.abs(f2).max())
    mz = r.section_moment[:, 0, 2]
    fx_each = np.stack([f1, f2], axis=1)  # approximately along x (the body turns little)
    expected = -(50.0 * fx_each[:, 0] - 50.0 * fx_each[:, 1])
    assert np.abs(expected).max() > 100.0
    np.testing.assert_allclose(mz, expected, rtol=3e-2, atol=1e-3 * np.abs(expected).max())


# --- shells and solids ---------------------------------------------------------------------------

from crashlite.solver import setup  # noqa: E402
from crashlite.solver.loop import integrate  # noqa: E402

E, RHO = 210000.0, 7.85e-9  # MPa, t/mm³


def _solid_bar(tmp_path, extra, end, name="bar.k"):
    """A 100 x 10 x 10 mm elastic bar of 5 mm hexahedra along x (node IDs
    from 1, row by row in x); ``extra`` cards appended."""
    from _solid_driver import brick_mesh

    x, conn = brick_mesh(20, 2, 2, 5.0, 5.0, 5.0)
    lines = ["*KEYWORD", "*NODE"] + [
        f"{i + 1},{float(p[0])!r},{float(p[1])!r},{float(p[2])!r}" for i, p in enumerate(x)
    ]
    lines += ["*ELEMENT_SOLID"] + [f"{e + 1},1," + ",".join(str(int(n) + 1) for n in row) for e, row in enumerate(conn)]
    lines += [
        "*PART",
        "bar",
        "1,1,1,0,1",
        "*SECTION_SOLID",
        "1,1",
        "*MAT_ELASTIC",
        f"1,{RHO},{E},0.3",
        "*HOURGLASS",
        "1,4,0.1",
        extra.strip(),
        "*CONTROL_TERMINATION",
        f"{end!r},",
        "*END",
    ]
    p = tmp_path / name
    p.write_text("\n".join(lines) + "\n")
    return p, x, conn


def _ids(mask):
    return ",".join(str(int(i) + 1) for i in np.flatnonzero(mask))


def _set(kind, sid, ids):
    ids = ids.split(",")
    return f"*SET_{kind}_LIST\n{sid}\n" + "\n".join(",".join(ids[k : k + 8]) for k in range(0, len(ids), 8))


def _ramp(lcid, amp, t_ramp, t_end):
    s = np.linspace(0.0, 1.0, 41)
    rows = [f"{float(a * t_ramp)!r},{float(amp * 0.5 * (1 - np.cos(np.pi * a)))!r}" for a in s]
    return f"*DEFINE_CURVE\n{lcid}\n" + "\n".join(rows + [f"{float(t_end)!r},{float(amp)!r}"])


def test_section_through_a_solid_bar_under_a_static_pull(tmp_path):
    """A clamped solid bar pulled quasi-statically at its far end: the
    section force through the middle (a plane, and the same cut as a node
    set and the solid layer before it) equals the clamp reaction within 1 %
    over the hold, along the bar, and the two definitions agree to
    round-off."""
    from _solid_driver import brick_mesh

    x, conn = brick_mesh(20, 2, 2, 5.0, 5.0, 5.0)
    clamp, pull = x[:, 0] == 0.0, x[:, 0] == 100.0
    layer = np.isclose(x[:, 0], 55.0)
    before = np.all(np.isin(conn, np.flatnonzero((x[:, 0] >= 50.0) & (x[:, 0] <= 55.0))), axis=1)
    T, T_end = 2e-4, 3e-4  # the bar's axial period 4L/c is 77 µs
    extra = "\n".join(
        [
            _set("NODE", 1, _ids(clamp)),
            "*BOUNDARY_SPC_SET",
            "1,0,1,1,1",
            _set("NODE", 2, _ids(pull)),
            _ramp(1, 0.05, T, T_end),
            "*BOUNDARY_PRESCRIBED_MOTION_SET",
            "2,1,2,1,1.0",
            "*DATABASE_CROSS_SECTION_PLANE_ID",
            "7,mid",
            "0,52.5,0,0,60.0,0,0",
            _set("NODE", 3, _ids(layer)),
            _set("SOLID", 4, _ids(before)),
            "*DATABASE_CROSS_SECTION_SET_ID",
            "8,set",
            "3,4",
        ]
    )
    p, _, _ = _solid_bar(tmp_path, extra, T_end)
    s = setup.build(read_deck(p))
    assert [len(sec.corners["solid"][0]) for sec in s.sections] == [16, 16]  # 4 elements x 4 corners
    r = integrate(s, 5e-6)
    hold = r.time >= T
    reaction = r.spc_force[:, :, 0].sum(axis=1)  # the clamp pulls back: -F
    f_plane, f_set = r.section_force[:, 0], r.section_force[:, 1]
    assert reaction[hold].mean() < -1000.0
    assert f_plane[hold, 0].mean() == pytest.approx(-reaction[hold].mean(), rel=0.01)  # tension: +F
    np.testing.assert_allclose(f_plane, f_set, rtol=1e-12, atol=1e-9 * np.abs(f_plane).max())
    assert np.abs(f_plane[hold, 1:]).max() < 1e-6 * np.abs(f_plane[hold, 0]).max()


def test_section_force_of_a_solid_bar_is_the_inertia_beyond_the_cut(tmp_path):
    """A free solid bar whose first half starts at 1 m/s: the force
    through the middle section is, at every output, minus the mass times
    the acceleration of the nodes beyond the cut (the cut elements push
    them with m·a; secforc reports the elements' internal force, -m·a),
    to round-off, and not small."""
    from _solid_driver import brick_mesh

    x, conn = brick_mesh(20, 2, 2, 5.0, 5.0, 5.0)
    beyond = x[:, 0] > 52.5
    ids = _ids(beyond).split(",")
    extra = "\n".join(
        [
            _set("NODE", 1, _ids(x[:, 0] < 50.0)),
            "*INITIAL_VELOCITY",
            "1",
            "1000.0,0,0",
            "*DATABASE_CROSS_SECTION_PLANE",
            "0,52.5,0,0,60.0,0,0",
            "*DATABASE_HISTORY_NODE",
        ]
        + [",".join(ids[k : k + 8]) for k in range(0, len(ids), 8)]
    )
    p, _, _ = _solid_bar(tmp_path, extra, 4e-5, name="free.k")
    s = setup.build(read_deck(p))
    r = integrate(s, 1e-6)
    m = s.mass[r.history_nodes]
    inertia = np.einsum("k,tkj->tj", m, r.node_acceleration)
    f = r.section_force[:, 0]
    assert np.abs(f[:, 0]).max() > 100.0
    np.testing.assert_allclose(f[1:], -inertia[1:], rtol=0, atol=1e-9 * np.abs(f).max())


def test_section_through_a_shell_cantilever_force_and_moment(tmp_path):
    """A 100 x 10 x 4 mm shell cantilever (ν = 0) pushed quasi-statically at
    the tip by 1 mm: the section at x = 55 (plane, normal +x) carries the
    static tip force 3EI·δ/L³ as its shear force, −F along z (the
    elements' internal force at the nodes beyond the plane; mean over the
    hold; the higher modes still ringing in the shear: within 3 %) and the
    bending moment M_y = F·(L − x_c) about its centroid (x_c = 60, the
    nodes beyond the plane) within 2 %; a set section (the node line x = 60 and
    the shell layer 50..60) gives the same to round-off."""
    import math

    from _plates import Plates, ramp_curve

    L, b, t = 100.0, 10.0, 4.0
    ei = E * b * t**3 / 12
    per = 2 * math.pi * L**2 / 1.8751**2 * math.sqrt(RHO * b * t / ei)
    T, T_end = 3 * per, 4 * per
    P = Plates(t=t)
    a = P.plate(1, 0, L, 10, 0, b, 1)
    P.spc(a[:, 0])
    P.node_set(2, a[:, -1])
    P.add(ramp_curve(1, -1.0, T, T_end))
    P.add("*BOUNDARY_PRESCRIBED_MOTION_SET\n2,3,2,1,1.0")
    P.add("*DATABASE_CROSS_SECTION_PLANE\n0,55.0,0,0,56.0,0,0")
    P.node_set(3, a[:, 6])
    P.add(f"*SET_SHELL_LIST\n4\n{1000 + 6},{1000 + 16}")  # the elements x 50..60 (IDs 1000·pid + j·nx + i + 1)
    P.add("*DATABASE_CROSS_SECTION_SET\n3,0,0,4")
    s = setup.build(read_deck(P.write(tmp_path / "cantilever.k", T_end)))
    assert [len(sec.corners["shell"][0]) for sec in s.sections] == [2, 2]
    r = integrate(s, per / 50)
    hold = r.time >= T
    reaction = r.spc_force[:, :, 2].sum(axis=1)
    f = r.section_force[:, 0]
    assert reaction[hold].mean() > 10.0
    force = 3 * ei * 1.0 / L**3
    assert reaction[hold].mean() == pytest.approx(force, rel=0.02)
    assert f[hold, 2].mean() == pytest.approx(-force, rel=0.03)
    assert np.abs(f[hold, :2].mean(axis=0)).max() < 0.01 * force
    my = r.section_moment[:, 0, 1]
    assert my[hold].mean() == pytest.approx(force * (L - 60.0), rel=0.02)
    np.testing.assert_allclose(r.section_force[:, 1], f, rtol=0, atol=1e-9 * np.abs(f).max())
    np.testing.assert_allclose(r.section_moment[:, 1], r.section_moment[:, 0], rtol=0, atol=1e-9 * np.abs(my).max())
