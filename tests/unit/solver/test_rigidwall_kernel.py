"""The planar rigid-wall kernel: which nodes it strikes, and the momentum
it exchanges with them."""

import numpy as np
import pytest

from crashlite.solver.kernels.rigidwall import planar_wall

DT = 1e-6


def _call(x, v, mass, wall_v=10000.0, wall_mass=5.0, finite=True):
    """A wall at x = 0 moving along +x (normal +x), finite: the square
    y, z in [0, 100] from the corner at the origin."""
    force = np.zeros(4)
    nodes = np.arange(len(x))
    hit = np.zeros(len(x), np.bool_)
    ln = 100.0 if finite else 0.0
    v_new = planar_wall(x, v, v.copy(), mass, nodes, np.zeros(3), np.array([1.0, 0.0, 0.0]), wall_v, wall_mass, 0.0, DT,
                        force, hit, np.array([0.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0]), ln, ln)
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
