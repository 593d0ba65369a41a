"""Linear superelements (*ELEMENT_DIRECT_MATRIX_INPUT with a DMIG file)
against closed-form spring–mass answers, with energy balance."""

import math

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.keyword.dmig import write_dmig
from crashlite.solver import SetupError, run

M, K = 0.1, 50.0  # t, N/mm: ω = sqrt(K/M)
SMALL_STEP = "*CONTROL_TIMESTEP\n,0.02"


def _deck(tmp_path, matrix, nodes, masses, velocities, end=0.6, dmig="se.dmig", stif="KSE", extra="", mass=None):
    write_dmig(tmp_path / "se.dmig", {"KSE": matrix} | ({"MSE": mass} if mass is not None else {}))
    text = "\n".join(
        [
            "*KEYWORD",
            "*NODE",
            *nodes,
            *(["*ELEMENT_MASS", *masses] if masses else []),
            "*ELEMENT_DIRECT_MATRIX_INPUT",
            "77,1",
            dmig,
            f"{'MSE' if mass is not None else ''},,{stif}",
            "*INITIAL_VELOCITY_NODE",
            *velocities,
            "*CONTROL_TERMINATION",
            f"{end}",
            "*DATABASE_HISTORY_NODE",
            "1,2",
            extra,
            "*END",
        ]
    )
    p = tmp_path / "se.k"
    p.write_text(text)
    return read_deck(p)


def _spring(k, n):
    """3 DOFs of two nodes each: k along the unit vector n."""
    kn = k * np.outer(n, n)
    return np.block([[kn, -kn], [-kn, kn]])


def test_superelement_spring_against_the_closed_form(tmp_path):
    """K on the x DOFs of a held node and a mass: x = v0/ω sin ωt, period
    and amplitude within 0.5 %, kinetic + internal constant; the step is
    the superelement's own (its node's mass halved) times TSSFAC (small
    here: the test checks accuracy, not stability)."""
    dofs = np.array([[1, 1], [2, 1]])
    m = _deck(
        tmp_path,
        (dofs, K * np.array([[1.0, -1.0], [-1.0, 1.0]])),
        ["1,0,0,0,7,7", "2,100,0,0"],
        [f"10,2,{M}"],
        ["2,1000,0,0"],
        extra=SMALL_STEP,
    )
    r = run(m, output_dt=1e-4)
    w = math.sqrt(K / M)
    ux = r.node_displacement[:, 1, 0]
    assert r.time_step[1] == pytest.approx(0.02 * 2.0 / math.sqrt(2.0 * K / M), rel=1e-9)
    assert np.max(ux) == pytest.approx(1000.0 / w, rel=5e-3)
    ups = r.time[1:][(ux[:-1] < 0) & (ux[1:] >= 0)]
    assert np.diff(ups).mean() == pytest.approx(2 * math.pi / w, rel=5e-3)
    e0 = 0.5 * M * 1000.0**2
    assert np.max(np.abs(r.kinetic + r.internal - e0)) < 5e-3 * e0
    # at the default TSSFAC (ω·dt = 1.27 < 2) the motion stays bounded over 20 periods
    m = _deck(
        tmp_path,
        (dofs, K * np.array([[1.0, -1.0], [-1.0, 1.0]])),
        ["1,0,0,0,7,7", "2,100,0,0"],
        [f"10,2,{M}"],
        ["2,1000,0,0"],
        end=20 * 2 * math.pi / w,
    )
    r = run(m, output_dt=1e-3)
    assert np.abs(r.node_displacement[:, 1, 0]).max() < 1.5 * 1000.0 / w


def test_superelement_in_3d_moves_rigidly_for_free(tmp_path):
    """Two equal masses joined along a skew direction n by a 3×3-block
    superelement: pushed apart along n they oscillate at sqrt(2k/m); a
    common velocity across n (a rigid translation of any size) adds no
    strain energy."""
    n = np.array([1.0, 2.0, 2.0]) / 3.0
    dofs = np.array([[i, c] for i in (1, 2) for c in (1, 2, 3)])
    v_rel, v_common = 500.0, np.array([2.0, -2.0, 1.0]) / 3.0 * 4000.0  # v_common ⟂ n
    va, vb = v_common - 0.5 * v_rel * n, v_common + 0.5 * v_rel * n
    m = _deck(
        tmp_path,
        (dofs, _spring(K, n)),
        ["1,0,0,0", f"2,{100 * n[0]},{100 * n[1]},{100 * n[2]}"],
        [f"10,1,{M}", f"11,2,{M}"],
        [f"1,{va[0]},{va[1]},{va[2]}", f"2,{vb[0]},{vb[1]},{vb[2]}"],
        end=0.3,
        extra=SMALL_STEP,
    )
    r = run(m, output_dt=1e-4)
    w = math.sqrt(2.0 * K / M)
    d = (r.node_displacement[:, 1] - r.node_displacement[:, 0]) @ n
    assert np.max(d) == pytest.approx(v_rel / w, rel=5e-3)
    e_strain_max = 0.5 * (0.5 * M) * v_rel**2  # the relative motion's kinetic energy
    assert r.internal.max() == pytest.approx(e_strain_max, rel=5e-3)
    across = (r.node_displacement[:, 1] - r.node_displacement[:, 0]) - np.outer(d, n)
    assert np.abs(across).max() < 1e-6 * np.abs(r.node_displacement).max()
    e0 = 0.5 * M * (va @ va + vb @ vb)
    assert np.max(np.abs(r.kinetic + r.internal - e0)) < 5e-3 * e0


def test_superelement_problems_name_the_field(tmp_path):
    dofs = np.array([[1, 1], [2, 1]])
    mat = (dofs, K * np.array([[1.0, -1.0], [-1.0, 1.0]]))
    args = (["1,0,0,0,7,7", "2,100,0,0"], [f"10,2,{M}"], ["2,1000,0,0"])
    with pytest.raises(SetupError, match="FILENAME.*cannot read"):
        run(_deck(tmp_path, mat, *args, dmig="missing.dmig"))
    with pytest.raises(SetupError, match="STIF.*no matrix 'KXX'"):
        run(_deck(tmp_path, mat, *args, stif="KXX"))
    with pytest.raises(SetupError, match="grid point"):
        run(_deck(tmp_path, (np.array([[1, 1], [9, 1]]), mat[1]), *args))


def _bar(tmp_path, velocities, extra=SMALL_STEP, end=0.3, point=0.0):
    """A free bar of mass M and stiffness K along x as one superelement with
    its consistent mass M/6·[[2, 1], [1, 2]] (y and z held); ``point``: a
    point mass on node 2 beside it."""
    dofs = np.array([[1, 1], [2, 1]])
    return _deck(
        tmp_path,
        (dofs, K * np.array([[1.0, -1.0], [-1.0, 1.0]])),
        ["1,0,0,0,5", "2,100,0,0,5"],
        [f"10,2,{point}"] if point else [],
        velocities,
        end=end,
        extra=extra,
        mass=(dofs, M / 6.0 * np.array([[2.0, 1.0], [1.0, 2.0]])),
    )


def test_superelement_consistent_mass_against_the_closed_form(tmp_path):
    """The free bar with its consistent mass rings at ω² = 12K/M (lumped by
    row sums it would ring at 4K/M, √3 slower): period and amplitude of the
    ends' relative motion within 0.5 %; kinetic energy ½vᵀMv + strain energy
    constant to 0.5 %; the centre of mass keeps its velocity (a common
    velocity adds nothing); the step is 2/ω_max of K against M times TSSFAC."""
    v_rel, v_c = 1000.0, 300.0
    r = run(_bar(tmp_path, [f"1,{v_c - v_rel / 2}", f"2,{v_c + v_rel / 2}"]), output_dt=1e-4)
    w = math.sqrt(12.0 * K / M)
    d = r.node_displacement[:, 1, 0] - r.node_displacement[:, 0, 0]
    assert r.time_step[1] == pytest.approx(0.02 * 2.0 / w, rel=1e-9)
    assert d.max() == pytest.approx(v_rel / w, rel=5e-3)
    ups = r.time[1:][(d[:-1] < 0) & (d[1:] >= 0)]
    assert np.diff(ups).mean() == pytest.approx(2 * math.pi / w, rel=5e-3)
    centre = 0.5 * (r.node_displacement[:, 0, 0] + r.node_displacement[:, 1, 0])
    assert np.abs(centre - v_c * r.time).max() < 1e-6 * v_c * r.time[-1]
    v = np.array([v_c - v_rel / 2, v_c + v_rel / 2])
    e0 = 0.5 * v @ (M / 6.0 * np.array([[2.0, 1.0], [1.0, 2.0]])) @ v
    assert np.max(np.abs(r.kinetic + r.internal - e0)) < 5e-3 * e0


def test_superelement_consistent_mass_beside_a_point_mass(tmp_path):
    """A point mass M on one end of the bar (the rest of the node's mass,
    solved with the matrix): ω² = K·(1/m₁ + 1/m₂)-like closed form of the
    2×2 pencil K against M/6·[[2, 1], [1, 8]], within 0.5 %, energy
    constant to 0.5 %."""
    mm = M / 6.0 * np.array([[2.0, 1.0], [1.0, 2.0]]) + np.diag([0.0, M])
    kk = K * np.array([[1.0, -1.0], [-1.0, 1.0]])
    w = math.sqrt(max(np.linalg.eigvals(np.linalg.solve(mm, kk)).real))
    v = np.array([-800.0, 200.0])  # no net momentum: v·M·1 = 0
    v[1] = -v[0] * (mm @ np.ones(2))[0] / (mm @ np.ones(2))[1]
    r = run(_bar(tmp_path, [f"1,{v[0]}", f"2,{v[1]}"], point=M), output_dt=1e-4)
    d = r.node_displacement[:, 1, 0] - r.node_displacement[:, 0, 0]
    ups = r.time[1:][(d[:-1] < 0) & (d[1:] >= 0)]
    assert np.diff(ups).mean() == pytest.approx(2 * math.pi / w, rel=5e-3)
    e0 = 0.5 * v @ mm @ v
    assert np.max(np.abs(r.kinetic + r.internal - e0)) < 5e-3 * e0


def test_superelement_consistent_mass_under_a_body_load(tmp_path):
    """The free bar under a base acceleration along x moves as one body:
    both ends at −½at², no strain (internal energy under 1e-9 of the
    kinetic)."""
    a = 1000.0  # mm/s²: *LOAD_BODY_X loads −M·a
    extra = SMALL_STEP + f"\n*LOAD_BODY_X\n1\n*DEFINE_CURVE\n1\n0,{a}\n10,{a}"
    r = run(_bar(tmp_path, ["1,0", "2,0"], extra=extra), output_dt=1e-3)
    want = -0.5 * a * r.time**2
    assert np.abs(r.node_displacement[:, :, 0] - want[:, None]).max() < 1e-3 * np.abs(want).max()
    assert r.internal.max() < 1e-9 * r.kinetic.max()
