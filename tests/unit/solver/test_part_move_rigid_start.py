"""*PART_MOVE and *INITIAL_VELOCITY_RIGID_BODY run by the solver: a rigid
brick moved 20 mm above a rigid wall lands on it at the time the move and
its speed give; a brick spun about a non-principal axis starts with its
nodes at v_c + ω × r and keeps ½mv² + ½ωᵀIω; LCID turns the velocities
from the local system; a part set moves whole, a node shared with a part not
moved moves (with a warning); cards that cannot be run are refused."""

from __future__ import annotations

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.solver import run
from crashlite.solver.part_moves import moved_model
from crashlite.solver.setup import SetupError, build

RO = 7.85e-9  # t/mm³
A, B, C = 10.0, 20.0, 40.0  # brick edges along x, y, z [mm]
MASS = RO * A * B * C


def _brick(x0=(0.0, 0.0, 0.0), first=1, eid=1, pid=1):
    """Node and element lines of one A x B x C hexahedron at x0."""
    x, y, z = x0
    corners = [(0, 0, 0), (A, 0, 0), (A, B, 0), (0, B, 0), (0, 0, C), (A, 0, C), (A, B, C), (0, B, C)]
    nodes = [f"{first + i},{x + cx},{y + cy},{z + cz}" for i, (cx, cy, cz) in enumerate(corners)]
    return nodes, f"{eid},{pid}," + ",".join(str(first + i) for i in range(8))


def _deck(tmp_path, extra=(), end=0.03, rigid=True, second=False):
    """A brick (part 1, rigid unless told) standing on z = 0; ``second``: a
    deformable brick (part 2) on top of it, sharing its top face."""
    nodes, el = _brick()
    lines = ["*KEYWORD", "*NODE", *nodes]
    els = [el]
    if second:
        n2, e2 = _brick((0.0, 0.0, C), first=5, eid=2, pid=2)
        lines += n2[4:]  # its bottom nodes are the first brick's top nodes 5-8
        els.append(e2)
    lines += ["*ELEMENT_SOLID", *els]
    lines += ["*PART", "brick", f"1,1,{1 if rigid else 2}", "*SECTION_SOLID", "1,1"]
    lines += ["*MAT_RIGID", f"1,{RO},210000.0,0.3", "*MAT_ELASTIC", f"2,{RO},210000.0,0.3"]
    if second:
        lines += ["*PART", "top", "2,1,2"]
    lines += ["*CONTROL_TERMINATION", f"{end}", "*DATABASE_HISTORY_NODE", "1,7", *extra, "*END"]
    p = tmp_path / "brick.k"
    p.write_text("\n".join(lines) + "\n")
    return read_deck(p)


def test_a_moved_brick_lands_on_the_wall_when_the_move_says(tmp_path):
    """Moved 20 mm up and sent down at 1000 mm/s onto the wall z = 0 (which
    stops what reaches it): it falls freely to t = 0.02 s and rests on the
    wall from then on; without the move it would start on the wall."""
    extra = [
        "*PART_MOVE",
        "       1             0.0             0.0            20.0       0       0",
        "*INITIAL_VELOCITY_RIGID_BODY",
        "1,0.0,0.0,-1000.0",
        "*RIGIDWALL_PLANAR",
        "0",
        "0,0,0,0,0,1",
    ]
    m = _deck(tmp_path, extra)
    s = build(m)
    np.testing.assert_allclose(s.x0[:8] - m.nodes.xyz[:8], np.tile([0.0, 0.0, 20.0], (8, 1)), atol=0)
    r = run(m, output_dt=1e-3)
    z = 20.0 + r.node_displacement[:, 0, 2]  # node 1 at the bottom, moved
    t = r.time
    falling = t < 0.02 - 1e-9
    np.testing.assert_allclose(z[falling], 20.0 - 1000.0 * t[falling], atol=1e-9)
    np.testing.assert_allclose(z[t > 0.0205], 0.0, atol=0.05)  # within the last step's travel (v·dt = 0.03 mm)
    vz = r.node_velocity[:, 0, 2]
    landed = t[np.flatnonzero(np.abs(vz) < 1.0)[0]]
    assert landed == pytest.approx(0.02, abs=1.1e-3)  # the first output at or after 20 mm / (1000 mm/s)


def test_the_model_is_moved_on_a_copy_and_only_once(tmp_path):
    extra = ["*PART_MOVE", "1,5.0,-2.0,30.0"]
    m = _deck(tmp_path, extra)
    before = m.nodes.xyz.copy()
    mm = moved_model(m, [], [])
    np.testing.assert_array_equal(m.nodes.xyz, before)  # the deck's model keeps its coordinates and card
    assert m.find("PART_MOVE") and not mm.find("PART_MOVE")
    np.testing.assert_allclose(mm.nodes.xyz - before, np.tile([5.0, -2.0, 30.0], (8, 1)))
    assert moved_model(mm, [], []) is mm  # applied once: the copy has no card left
    cog = mm.mass_properties([1]).cog
    np.testing.assert_allclose(cog, [A / 2 + 5.0, B / 2 - 2.0, C / 2 + 30.0], rtol=1e-12)


def test_a_move_in_a_local_system_and_by_part_set(tmp_path):
    """CID: the system's x axis is the global y axis, its y the global -x;
    IFSET 1 moves both parts of set 9, each node once."""
    extra = [
        "*DEFINE_COORDINATE_VECTOR",
        "3,0.0,1.0,0.0,-1.0,0.0,0.0",
        "*SET_PART_LIST",
        "9",
        "1,2",
        "*PART_MOVE",
        "9,1.0,2.0,3.0,3,1",
    ]
    m = _deck(tmp_path, extra, second=True)
    mm = moved_model(m, problems := [], warnings := [])
    assert not problems and not warnings
    np.testing.assert_allclose(mm.nodes.xyz - m.nodes.xyz, np.tile([-2.0, 1.0, 3.0], (12, 1)), atol=1e-12)


def test_a_node_shared_with_a_part_not_moved_moves_with_a_warning(tmp_path):
    m = _deck(tmp_path, ["*PART_MOVE", "1,0.0,0.0,-1.0"], second=True)
    mm = moved_model(m, problems := [], warnings := [])
    assert not problems
    d = mm.nodes.xyz - m.nodes.xyz
    np.testing.assert_allclose(d[:8, 2], -1.0)  # every node of part 1, its top face (shared) included
    np.testing.assert_allclose(d[8:], 0.0)  # part 2's own nodes stay
    assert len(warnings) == 1 and "4 node(s)" in warnings[0].message


def test_a_spun_brick_keeps_its_energy_and_its_nodes_follow_it(tmp_path):
    """ω = (5, 10, 20) rad/s about no principal axis (the brick tumbles)
    plus v = (100, -50, 30) mm/s: the nodes start at v_c + ω × (x - x_c) and
    the kinetic energy ½mv² + ½ωᵀIω, I = m/12 diag(B²+C², A²+C², A²+B²),
    stays within 1e-6 over 0.3 s (about a turn)."""
    v = np.array([100.0, -50.0, 30.0])
    w = np.array([5.0, 10.0, 20.0])
    m = _deck(tmp_path, ["*INITIAL_VELOCITY_RIGID_BODY", "1," + ",".join(f"{c}" for c in (*v, *w))], end=0.3)
    s = build(m)
    body = s.bodies[0]
    inertia = MASS / 12 * np.diag([B**2 + C**2, A**2 + C**2, A**2 + B**2])
    assert body.mass == pytest.approx(MASS, rel=1e-12)
    np.testing.assert_allclose(body.inertia_body, inertia, rtol=1e-12, atol=1e-12 * inertia.max())
    cog = np.array([A, B, C]) / 2
    np.testing.assert_allclose(s.v0[:8], v + np.cross(w, s.x0[:8] - cog), rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(body.omega(), w, rtol=1e-12)
    ke = 0.5 * MASS * v @ v + 0.5 * w @ inertia @ w
    assert body.kinetic_now() == pytest.approx(ke, rel=1e-12)
    r = run(m, output_dt=0.01)
    assert np.max(np.abs(r.kinetic / ke - 1.0)) < 1e-6
    # the brick stays rigid while it turns: the diagonal 1-7 keeps its length
    d = (r.node_displacement[:, 1] + [A, B, C]) - r.node_displacement[:, 0]
    np.testing.assert_allclose(np.linalg.norm(d, axis=1), np.sqrt(A * A + B * B + C * C), rtol=1e-12)
    assert np.ptp(d[:, 0]) > 1.0  # it did turn


def test_velocities_given_in_a_local_system(tmp_path):
    """LCID 3: local x = global y, local y = global -x, local z = z."""
    extra = ["*DEFINE_COORDINATE_VECTOR", "3,0.0,1.0,0.0,-1.0,0.0,0.0", "*INITIAL_VELOCITY_RIGID_BODY"]
    extra += ["1,10.0,0.0,0.0,0.0,2.0,0.0,3"]
    s = build(_deck(tmp_path, extra))
    body = s.bodies[0]
    np.testing.assert_allclose(body.velocity, [0.0, 10.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(body.omega(), [-2.0, 0.0, 0.0], atol=1e-12)


def test_the_card_overrides_initial_velocity_and_keeps_cmo_constraints(tmp_path):
    extra = ["*INITIAL_VELOCITY", "0", "5.0,5.0,5.0", "*INITIAL_VELOCITY_RIGID_BODY", "1,1.0,2.0,3.0"]
    s = build(_deck(tmp_path, extra))
    np.testing.assert_allclose(s.bodies[0].velocity, [1.0, 2.0, 3.0])
    np.testing.assert_allclose(s.v0[:8], np.tile([1.0, 2.0, 3.0], (8, 1)))
    m = _deck(tmp_path, extra)
    m.materials[1]["cmo"], m.materials[1]["con1"] = 1.0, 3  # z held
    np.testing.assert_allclose(build(m).bodies[0].velocity, [1.0, 2.0, 0.0])


@pytest.mark.parametrize(
    "extra, field, words",
    [
        (["*INITIAL_VELOCITY_RIGID_BODY", "1,1.0"], "PID", "not a rigid part"),
        (
            [
                "*DEFINE_COORDINATE_VECTOR",
                "8,1.0,0.0,0.0,2.0,0.0,0.0",
                "*INITIAL_VELOCITY_RIGID_BODY",
                "1,1,0,0,0,0,0,8",
            ],
            "LCID",
            "collinear",
        ),
        (["*PART_MOVE", "4,1.0"], "PID", "part 4 is not defined"),
        (["*PART_MOVE", "4,1.0,0,0,0,1"], "PID", "part set 4"),
        (["*PART_MOVE", "1,1.0,0,0,0,2"], "IFSET", "IFSET = 2"),
    ],
)
def test_cards_that_cannot_be_run_are_refused(tmp_path, extra, field, words):
    m = _deck(tmp_path, extra, rigid="LCID" in field)
    with pytest.raises(SetupError) as e:
        build(m)
    found = [p for p in e.value.problems if p.field == field]
    assert found and words in found[0].message, e.value.problems


def test_a_rigid_part_inertia_in_a_local_system_is_refused_naming_ircs(tmp_path):
    """*PART_INERTIA with IRCS = 1 gives the tensor in a local system that
    rigid parts do not turn yet: refused by name, never taken as global."""
    model = _deck(tmp_path)
    text = (
        open(model.source)
        .read()
        .replace(
            "*PART\nbrick\n1,1,1\n",
            "*PART_INERTIA\nbrick\n1,1,1\n0,0,0,0.5,1,0\n1.0,0.0,0.0,1.0,0.0,1.0\n0,0,0,0,0,0\n1,0,0,0,1,0,0\n",
        )
    )
    p = tmp_path / "ircs.k"
    p.write_text(text)
    with pytest.raises(SetupError) as e:
        build(read_deck(p))
    (pr,) = [pr for pr in e.value.problems if pr.field == "IRCS"]
    assert "local system" in pr.message and pr.keyword.startswith("PART")
