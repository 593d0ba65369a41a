"""Spot welds (*CONSTRAINED_SPOTWELD, *CONSTRAINED_GENERALIZED_WELD_SPOT):
rigid until the force criterion or the failure time, momentum and energy
kept while intact."""

import numpy as np
import pytest
from _plates import Plates, ramp_curve

from crashlite import read_deck
from crashlite.solver import setup
from crashlite.solver.loop import integrate
from crashlite.solver.setup import SetupError
from crashlite.solver.spotwelds import SpotWelds

SS = 500.0  # N, shear force at failure of each weld


def _welds(s) -> SpotWelds:
    (w,) = [c for c in s.constraints if isinstance(c, SpotWelds)]
    return w


def _run(path, output_dt):
    s = setup.build(read_deck(path))
    return s, integrate(s, output_dt)


def _lap_joint(tmp_path, weld_cards: str, T=1e-3, umax=0.1, z=1.0):
    """Plate 1 (x 0..50, z = 0) clamped at x = 0; plate 2 (x 40..90, z)
    driven along x at x = 90 by a (1 − cos) ramp to ``umax`` over T; the
    plates overlap over x 40..50 (1 x 20 mm sheets, 5 mm elements)."""
    P = Plates(t=1.0)
    a = P.plate(1, 0, 50, 10, 0, 20, 4)
    b = P.plate(2, 40, 90, 10, 0, 20, 4, z=z)
    P.add(weld_cards.format(a=a, b=b))
    P.spc(a[:, 0])
    P.spc(b[:, -1], "0,1,1,1,1,1")
    P.node_set(2, b[:, -1])
    P.add(ramp_curve(1, umax, T, T))
    P.add("*BOUNDARY_PRESCRIBED_MOTION_SET\n2,1,2,1,1.0")
    P.history([a[1, 9], b[1, 1]])
    return P.write(tmp_path / "lap.k", T), a, b


@pytest.mark.parametrize("z", [1.0, 0.0])
def test_lap_shear_welds_fail_at_the_predicted_pull(tmp_path, z):
    """Two welds (x = 45, y = 5 and 15) join the overlap (the sheets 1 mm
    apart, or coincident nodes: the weld normal is then the shells');
    SS = 500 N, SN = 5000 N, N = M = 2. Pulled quasi-statically, the welds
    hold the node pairs at their initial distance until the clamp reaction
    reaches 2·SS (within 5 %), then both fail and the plates part; up to
    then the strain, hourglass and kinetic energy are the work of the pull
    (within 2 %)."""
    cards = "*CONSTRAINED_SPOTWELD\n{a[1][9]},{b[1][1]},5000.0,500.0,2.0,2.0\n{a[3][9]},{b[3][1]},5000.0,500.0,2.0,2.0"
    # 0.3 mm: the 1 mm offset sheets, point-loaded at the weld nodes, yield to the pull through their
    # (IHQ 4) hourglass modes as much as through strain, so the reaction reaches 2·SS only past 0.1 mm
    path, a, b = _lap_joint(tmp_path, cards, umax=0.3, z=z)
    s, r = _run(path, 2.5e-6)
    w = _welds(s)
    assert [e[0] for e in w.log] == [1, 2] and {e[2] for e in w.log} == {"force"}
    t_fail = w.log[0][1]
    assert 0.2e-3 < t_fail < 0.9e-3
    reaction = -r.spc_force[:, :, 0].sum(axis=1)
    assert np.interp(t_fail, r.time, reaction) == pytest.approx(2 * SS, rel=0.05)
    assert w.fs[0] == pytest.approx(SS, rel=0.05) and abs(w.fn[0]) < 0.2 * SS
    # the pair keeps its distance (1 mm along z) while welded, then slides apart
    gap = r.node_coordinates[:, 1] - r.node_coordinates[:, 0]
    before = r.time < t_fail
    np.testing.assert_allclose(np.linalg.norm(gap[before], axis=1), z, atol=1e-4)
    if z == 0.0:
        np.testing.assert_allclose(w.normal0, [[0, 0, 1.0], [0, 0, 1.0]], atol=1e-12)
    assert gap[-1, 0] > 0.02
    # energy: the work of the pull (the quasi-static reaction over the end
    # displacement) is the strain and kinetic energy, up to the failure
    u = np.interp(r.time, *_ramp(1e-3, 0.3))
    work = np.concatenate([[0.0], np.cumsum(0.5 * (reaction[1:] + reaction[:-1]) * np.diff(u))])
    k = np.flatnonzero(before)[-1]
    assert r.internal[k] + r.kinetic[k] + r.hourglass[k] == pytest.approx(work[k], rel=0.02)


def _ramp(T, umax):
    t = np.linspace(0, T, 401)
    return t, umax * 0.5 * (1 - np.cos(np.pi * t / T))


def _free_pair(tmp_path, welds: str, name="free.k", tssfac=0.2, end=2e-4):
    """Two free 20 x 20 x 1 plates overlapping over x 10..20 (the second
    1 mm up); the first moves at (1000, 0, 500) mm/s and turns about z,
    the second is at rest."""
    P = Plates(t=1.0)
    a = P.plate(1, 0, 20, 4, 0, 20, 4)
    b = P.plate(2, 10, 30, 4, 0, 20, 4, z=1.0)
    P.add(welds.format(a=a, b=b))
    rows = [
        f"{a[j, i]},{1000.0 - 50.0 * (5.0 * j - 10.0)!r},{50.0 * (5.0 * i - 10.0)!r},500.0"
        for j in range(5)
        for i in range(5)
    ]
    P.add("*INITIAL_VELOCITY_NODE\n" + "\n".join(rows))
    P.add(f"*CONTROL_TIMESTEP\n0.0,{tssfac}")
    P.history([a[1, 3], b[1, 1], a[3, 3], b[3, 1]])
    return P.write(tmp_path / name, end), a, b


_TWO = "*CONSTRAINED_SPOTWELD\n{a[1][3]},{b[1][1]}\n{a[3][3]},{b[3][1]}"


def test_welded_plates_in_free_flight_keep_momentum_and_energy(tmp_path):
    """The welds make each node pair one rigid body at the start (their
    relative motion is taken out, momentum kept); from then on the
    momentum of the pair of plates is kept to round-off and the energy
    within 1 %, and each pair moves rigidly."""
    path, a, b = _free_pair(tmp_path, _TWO)
    s, r = _run(path, 5e-6)
    free = setup.build(read_deck(_free_pair(tmp_path, "", name="loose.k")[0]))
    p0 = (free.mass[:, None] * free.v0).sum(axis=0)
    np.testing.assert_allclose((s.mass[:, None] * s.v0).sum(axis=0), p0, rtol=1e-13, atol=1e-13 * abs(p0).max())
    np.testing.assert_allclose((s.mass[:, None] * r.final_v).sum(axis=0), p0, rtol=1e-12, atol=1e-12 * abs(p0).max())
    gap = r.node_coordinates[:, 2:] - r.node_coordinates[:, :2]  # history columns by index: a, a, b, b
    np.testing.assert_allclose(np.linalg.norm(gap, axis=2), 1.0, rtol=1e-4)
    total = r.kinetic + r.internal + r.hourglass
    assert r.internal.max() > 0.02 * total[0]
    assert np.abs(total - total[0]).max() < 0.01 * total[0]
    assert _welds(s).log == []


def test_weld_fails_at_its_time(tmp_path):
    """TF = 50 µs: the weld lets go at the first step at or after TF (a
    step is < 1 µs), the other (TF default) holds."""
    path, a, b = _free_pair(
        tmp_path, "*CONSTRAINED_SPOTWELD\n{a[1][3]},{b[1][1]},0,0,0,0,5e-5\n{a[3][3]},{b[3][1]}", tssfac=0.9, end=1e-4
    )
    s, r = _run(path, 5e-6)
    w = _welds(s)
    assert len(w.log) == 1 and w.log[0][0] == 1 and w.log[0][2] == "time"
    assert 5e-5 <= w.log[0][1] < 5e-5 + 1e-6
    assert w.alive.tolist() == [False, True]


def test_generalized_weld_holds_a_node_set_until_tfail(tmp_path):
    """*CONSTRAINED_GENERALIZED_WELD_SPOT on a set of four nodes (two of
    each plate): they move as one rigid body (distances kept) until TFAIL,
    the momentum is kept to round-off throughout."""
    welds = "*SET_NODE_LIST\n5\n{a[1][3]},{b[1][1]},{a[3][3]},{b[3][1]}\n*CONSTRAINED_GENERALIZED_WELD_SPOT\n5\n1e-4"
    path, a, b = _free_pair(tmp_path, welds, end=1.5e-4)
    s, r = _run(path, 5e-6)
    w = _welds(s)
    assert len(w.log) == 1 and w.log[0][2] == "time" and 1e-4 <= w.log[0][1] < 1.01e-4
    x = r.node_coordinates
    d = np.linalg.norm(x[:, :, None] - x[:, None, :], axis=3)
    held = r.time < 1e-4
    np.testing.assert_allclose(d[held], np.broadcast_to(d[0], d[held].shape), atol=1e-4)
    free = setup.build(read_deck(_free_pair(tmp_path, "", name="loose.k")[0]))
    p0 = (free.mass[:, None] * free.v0).sum(axis=0)
    np.testing.assert_allclose((s.mass[:, None] * r.final_v).sum(axis=0), p0, rtol=1e-12, atol=1e-12 * abs(p0).max())


def test_generalized_weld_of_one_node_is_refused(tmp_path):
    path, a, b = _free_pair(
        tmp_path, "*SET_NODE_LIST\n5\n{a[1][3]}\n*CONSTRAINED_GENERALIZED_WELD_SPOT\n5\n1e20", name="bad.k"
    )
    with pytest.raises(
        SetupError,
        match=r"bad.k:\d+: \*CONSTRAINED_GENERALIZED_WELD_SPOT, field NSID: a generalized "
        r"spot weld needs at least 2 defined nodes; \*SET_NODE 5 has 1",
    ):
        setup.build(read_deck(path))


def test_spot_weld_needs_two_distinct_nodes(tmp_path):
    path, a, b = _free_pair(tmp_path, "*CONSTRAINED_SPOTWELD\n{a[1][3]},{a[1][3]}", name="bad.k")
    with pytest.raises(SetupError, match=r"\*CONSTRAINED_SPOTWELD, field N1: a spot weld needs two distinct"):
        setup.build(read_deck(path))


def test_welds_and_ties_bit_identical_on_one_and_two_threads(tmp_path, two_threads):
    """Welded plates with a point mass tied to one of them: the run gives
    the same bits on 1 and 2 threads (the constraints work serially in a
    fixed order)."""
    import numba

    welds = _TWO + (
        "\n*NODE\n9001,22.5,7.5,1.5\n*ELEMENT_MASS\n9001,9001,1e-6\n*SET_NODE_LIST\n9\n9001\n"
        "*CONTACT_TIED_NODES_TO_SURFACE\n9,2,4,3\n0,0\n0,0"
    )
    path, a, b = _free_pair(tmp_path, welds, tssfac=0.9, end=1e-4)
    out = []
    before = numba.get_num_threads()
    try:
        for n in (1, min(2, numba.config.NUMBA_NUM_THREADS)):
            numba.set_num_threads(n)
            s, r = _run(path, 1e-5)
            assert len(s.constraints) == 2 and len(s.constraints[0]) == 1
            out.append((r.final_x.copy(), r.final_v.copy()))
    finally:
        numba.set_num_threads(before)
    assert np.array_equal(out[0][0], out[1][0]) and np.array_equal(out[0][1], out[1][1])
