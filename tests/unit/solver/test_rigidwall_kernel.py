"""The planar rigid-wall kernel: which nodes it strikes, and the momentum
it exchanges with them."""

import numpy as np
import pytest

from crashlite.solver.kernels.rigidwall import N_CHUNKS, planar_wall

DT = 1e-6


def _call(x, v, mass, wall_v=10000.0, wall_mass=5.0, finite=True):
    """A wall at x = 0 moving along +x (normal +x), finite: the square
    y, z in [0, 100] from the corner at the origin."""
    force = np.zeros(4)
    nodes = np.arange(len(x))
    hit = np.zeros(len(x), np.bool_)
    ln = 100.0 if finite else 0.0
    v_new = planar_wall(
        x,
        v,
        v.copy(),
        mass,
        nodes,
        np.zeros(3),
        np.array([1.0, 0.0, 0.0]),
        wall_v,
        wall_mass,
        0.0,
        DT,
        force,
        hit,
        np.array([0.0, 1.0, 0.0]),
        np.array([0.0, 0.0, 1.0]),
        ln,
        ln,
        np.zeros((N_CHUNKS, 2)),
    )
    return v_new, force


def test_a_struck_node_takes_the_common_velocity_and_momentum_is_kept():
    m, M, V = 1e-3, 5.0, 10000.0
    x = np.array([[0.001, 50.0, 50.0]])  # just ahead of the wall, over its face
    v = np.zeros((1, 3))
    v_new, force = _call(x, v, np.array([m]), V, M)
    # plastic impact, counting the gap the node closes this step
    assert v_new == pytest.approx((M * V + m * 0.001 / DT) / (M + m), rel=1e-12)
    assert M * v_new + m * v[0, 0] == pytest.approx(M * V, rel=1e-9)
    assert force[0] == pytest.approx(-m * v[0, 0] / DT, rel=1e-12)


def test_a_node_beside_a_finite_wall_and_behind_its_plane_is_not_struck_when_it_slides_over_the_face():
    """The wall has advanced 80 mm past a node beside it (y just outside the
    face); the node drifting onto the face is not in contact: striking it
    would take an 80 mm jump in one step."""
    x = np.array([[-80.0, 99.99, 50.0]])  # behind the plane by 80 mm, now over the face
    v = np.array([[0.0, -100.0, 0.0]])
    v_new, force = _call(x, v.copy(), np.array([1e-3]))
    assert v_new == 10000.0 and np.all(force == 0.0)
    # a node behind by less than one step of relative motion is struck
    x = np.array([[-0.005, 50.0, 50.0]])
    v = np.zeros((1, 3))
    v_new, force = _call(x, v, np.array([1e-3]))
    assert force[0] < 0.0 and v[0, 0] > 10000.0 * 0.99


def test_many_nodes_struck_at_once_keep_momentum_the_same_on_one_and_two_threads(two_threads):
    """A moving wall strikes a few hundred of 5000 nodes spread over its
    face and beyond (the hit test runs in fixed chunks of nodes, in
    parallel): the wall and the struck nodes leave with the common velocity
    of a plastic impact (momentum kept to 1e-12), the nodes it does not
    strike are untouched, and velocities, wall speed and force are the
    same bit for bit on one and two threads."""
    import numba

    rng = np.random.default_rng(5)
    n = 5000
    x = np.column_stack([rng.uniform(-0.002, 0.03, n), rng.uniform(-20.0, 120.0, n), rng.uniform(0.0, 100.0, n)])
    v0 = rng.normal(size=(n, 3)) * 100.0
    mass = rng.uniform(1e-4, 2e-3, n)
    out = []
    threads = numba.get_num_threads()
    try:
        for nt in (1, 2):
            numba.set_num_threads(nt)
            v = v0.copy()
            v_new, force = _call(x, v, mass, 10000.0, 5.0)
            out.append((v, v_new, force))
    finally:
        numba.set_num_threads(threads)
    (v, v_new, force), (v2, v_new2, force2) = out
    assert np.array_equal(v, v2) and v_new == v_new2 and np.array_equal(force, force2)
    struck = np.any(v != v0, axis=1)
    assert 100 < struck.sum() < n // 2
    np.testing.assert_allclose(v[struck, 0] + x[struck, 0] / DT, v_new, rtol=1e-12)  # they land on the wall
    brought = (mass[struck] * (v0[struck, 0] + x[struck, 0] / DT)).sum()
    assert 5.0 * v_new + (mass[struck] * (v[struck, 0] + x[struck, 0] / DT)).sum() == pytest.approx(
        5.0 * 10000.0 + brought, rel=1e-12
    )
