"""*ELEMENT_MASS_PART(_SET) run by the solver: a free rigid brick pushed by
a known force accelerates at F / m_final (FINMASS, or its mass plus
ADDMASS), its inertia scaled alike and its CoG kept; a deformable part's
nodes carry the added mass in proportion to the mass its own elements give
them (a node shared with another part takes only its share); total mass,
momentum and kinetic energy count it; a _SET row brings its parts together
to FINMASS; a mass varying in time, FINMASS below the part's mass and a
negative ADDMASS are refused."""

from __future__ import annotations

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.solver import run
from crashlite.solver.setup import SetupError, build

RO = 7.85e-9  # t/mm³
L = 10.0  # brick edge [mm]
M = RO * L**3  # one brick's mass [t]
F = 0.5  # total push [N]


def _deck(tmp_path, extra=(), parts=(1,), rigid=True, shared=False, end=2e-3):
    """Cubes of edge L along x, one per entry of ``parts`` (its part ID);
    ``shared``: neighbours share a face, else they stand 5 mm apart."""
    nodes, els = [], []
    for k, pid in enumerate(parts):
        x0 = k * L if shared else k * (L + 5.0)
        first = 4 * k + 1 if shared else 8 * k + 1
        left = [first, first + 1, first + 2, first + 3]
        right = [first + 4, first + 5, first + 6, first + 7]
        for n, (y, z) in zip(left, [(0, 0), (L, 0), (L, L), (0, L)]):
            if not shared or k == 0:
                nodes.append(f"{n},{x0},{y},{z}")
        for n, (y, z) in zip(right, [(0, 0), (L, 0), (L, L), (0, L)]):
            nodes.append(f"{n},{x0 + L},{y},{z}")
        conn = [left[0], right[0], right[1], left[1], left[3], right[3], right[2], left[2]]
        els.append(f"{k + 1},{pid}," + ",".join(map(str, conn)))
    lines = ["*KEYWORD", "*NODE", *nodes, "*ELEMENT_SOLID", *els, "*SECTION_SOLID", "1,1"]
    for pid in sorted(set(parts)):
        lines += ["*PART", f"part {pid}", f"{pid},1,{1 if rigid else 2}"]
    lines += ["*MAT_RIGID", f"1,{RO},210000.0,0.3", "*MAT_ELASTIC", f"2,{RO},210000.0,0.3"]
    lines += ["*CONTROL_TERMINATION", f"{end}", "*DATABASE_HISTORY_NODE", "1", *extra, "*END"]
    p = tmp_path / "bricks.k"
    p.write_text("\n".join(lines) + "\n")
    return read_deck(p)


_PUSH = ["*SET_NODE_LIST", "1", "1,2,3,4,5,6,7,8", "*LOAD_NODE_SET", f"1,1,1,{F / 8}", "*DEFINE_CURVE", "1"]
_PUSH += ["0.0,1.0", "1.0,1.0"]


@pytest.mark.parametrize("card, m_final", [("1,0.0,3.0e-5", 3.0e-5), (f"1,{2 * M}", 3 * M)])
def test_a_pushed_rigid_brick_accelerates_at_f_over_its_final_mass(tmp_path, card, m_final):
    """FINMASS 3e-5 t, or ADDMASS 2 M (final 3 M): x(t) = ½ F/m t²."""
    m = _deck(tmp_path, ["*ELEMENT_MASS_PART", card, *_PUSH])
    s = build(m)
    body = s.bodies[0]
    assert body.mass == pytest.approx(m_final, rel=1e-12)
    np.testing.assert_allclose(body.cog, [L / 2] * 3, rtol=1e-12)  # in proportion: the CoG stays
    np.testing.assert_allclose(body.inertia_body, m_final * L**2 / 6 * np.eye(3), atol=1e-9 * m_final * L**2)
    assert m.mass_properties([1]).mass == pytest.approx(m_final, rel=1e-12)  # what `crashlite info` says
    r = run(m, output_dt=2e-4)
    x = r.node_displacement[:, 0, 0]
    np.testing.assert_allclose(x, 0.5 * F / m_final * r.time**2, rtol=1e-6, atol=1e-12)


def test_a_deformable_parts_nodes_carry_their_share(tmp_path):
    """Parts 1 and 2 share a face; ADDMASS M on part 1 doubles the mass its
    own element gives each of its nodes: M/4 on its four own nodes, M/8 + M/8
    + M/8 on the shared ones, M/8 on part 2's own."""
    m = _deck(tmp_path, ["*ELEMENT_MASS_PART", f"1,{M}"], parts=(1, 2), rigid=False, shared=True)
    s = build(m)
    np.testing.assert_allclose(s.mass[:4], M / 4, rtol=1e-12)
    np.testing.assert_allclose(s.mass[4:8], 3 * M / 8, rtol=1e-12)
    np.testing.assert_allclose(s.mass[8:], M / 8, rtol=1e-12)
    assert s.mass.sum() == pytest.approx(3 * M, rel=1e-12)


def test_mass_momentum_and_energy_of_a_moving_deformable_part(tmp_path):
    """Part 1 (two cubes) gets FINMASS 5 M, part 2 stays M; all move at
    v: total mass 6 M, momentum 6 M v (part 1: 5 M v) and ½ 6 M v² kept."""
    v = np.array([1000.0, 300.0, 0.0])
    extra = ["*ELEMENT_MASS_PART", f"1,0.0,{5 * M}", "*INITIAL_VELOCITY", "0", ",".join(map(str, v))]
    m = _deck(tmp_path, extra, parts=(1, 1, 2), rigid=False, end=1e-4)
    s = build(m)
    assert s.mass.sum() == pytest.approx(6 * M, rel=1e-12)
    r = run(m, output_dt=2e-5)
    ke = 0.5 * 6 * M * v @ v
    np.testing.assert_allclose(r.kinetic, ke, rtol=1e-9)
    k = list(r.part_ids).index(1)
    np.testing.assert_allclose(r.part_momentum[:, k], np.tile(5 * M * v, (len(r.time), 1)), rtol=1e-9, atol=1e-15)


def test_a_set_row_brings_its_parts_together_to_finmass(tmp_path):
    """Parts 1 (M) and 2 (2 M) of set 7 to FINMASS 6 M: both doubled, the
    set's mass 6 M (not 6 M each); the rigid part's body and the deformable
    part's nodes alike."""
    extra = ["*SET_PART_LIST", "7", "1,2", "*ELEMENT_MASS_PART_SET", f"7,0.0,{6 * M}"]
    m = _deck(tmp_path, extra, parts=(1, 2, 2), rigid=False)
    s = build(m)
    assert s.mass.sum() == pytest.approx(6 * M, rel=1e-12)
    assert m.mass_properties([1, 2]).mass == pytest.approx(6 * M, rel=1e-12)
    m.parts[1]["mid"] = 1  # part 1 now rigid
    s = build(m)
    body = s.bodies[0]
    assert body.mass == pytest.approx(2 * M, rel=1e-12)
    assert s.mass.sum() == pytest.approx(4 * M, rel=1e-12)


@pytest.mark.parametrize(
    "card, field, words",
    [
        (f"1,0.0,{0.5 * M}", "FINMASS", "below its mass"),
        ("1,-1e-7", "ADDMASS", "ADDMASS"),
        ("1,1e-7,0.0,5", "LCID", "varying in time"),
    ],
)
def test_rows_that_cannot_be_run_are_refused(tmp_path, card, field, words):
    extra = ["*ELEMENT_MASS_PART", card, "*DEFINE_CURVE", "5", "0.0,1.0", "1.0,1.0"]
    with pytest.raises(SetupError) as e:
        build(_deck(tmp_path, extra, rigid=False))
    found = [p for p in e.value.problems if p.field == field]
    assert found and words in found[0].message, e.value.problems
