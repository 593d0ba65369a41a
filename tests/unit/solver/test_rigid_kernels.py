"""The rigid-body kernels against their closed forms (exp of the rotation
vector's cross-product matrix, R I⁻¹ Rᵀ L)."""

import numpy as np
import pytest
from scipy.linalg import expm

from crashlite.solver.kernels.rigid import body_drift, body_kick, body_omega, place_body, rodrigues
from crashlite.solver.rigid import rotation


@pytest.mark.parametrize("seed", range(5))
def test_rodrigues_is_the_rotation_of_the_vector(seed):
    phi = np.random.default_rng(seed).normal(size=3) * (seed + 0.1)
    out = np.empty((3, 3))
    rodrigues(phi[0], phi[1], phi[2], out)
    skew = np.array([[0.0, -phi[2], phi[1]], [phi[2], 0.0, -phi[0]], [-phi[1], phi[0], 0.0]])
    np.testing.assert_allclose(out, expm(skew), atol=1e-13)
    np.testing.assert_allclose(out @ out.T, np.eye(3), atol=1e-14)  # orthonormal
    np.testing.assert_allclose(out @ phi, phi, atol=1e-12 * np.linalg.norm(phi))  # the axis stays


def test_rodrigues_of_zero_is_identity():
    out = np.full((3, 3), 7.0)
    rodrigues(0.0, 0.0, 0.0, out)
    np.testing.assert_array_equal(out, np.eye(3))


def test_body_omega_is_r_inv_inertia_rt_momentum():
    rng = np.random.default_rng(3)
    rot = rotation(rng.normal(size=3))
    a = rng.normal(size=(3, 3))
    inv_i = np.linalg.inv(a @ a.T + 3 * np.eye(3))
    mom = rng.normal(size=3)
    out = np.empty(3)
    body_omega(rot, inv_i, mom, out)
    np.testing.assert_allclose(out, rot @ inv_i @ rot.T @ mom, rtol=1e-13)


def test_body_drift_turns_about_a_principal_axis_exactly():
    """Spin about a principal axis: ω is constant, the body turns by ω·dt a
    step and the CoG moves by v·dt."""
    inertia = np.diag([2.0, 3.0, 5.0])
    w = 40.0
    cog, vel = np.zeros(3), np.array([1.0, -2.0, 0.5])
    mom = np.array([0.0, 3.0 * w, 0.0])
    rot = np.eye(3)
    dt, n = 1e-3, 100
    scratch = np.zeros((3, 3, 3))
    for _ in range(n):
        body_drift(cog, vel, mom, rot, np.linalg.inv(inertia), dt, scratch)
    np.testing.assert_allclose(rot, rotation(np.array([0.0, w * n * dt, 0.0])), atol=1e-12)
    np.testing.assert_allclose(cog, vel * n * dt, rtol=1e-13)


def test_spin_bound_bounds_omega_and_is_reached_about_the_softest_axis():
    """|ω| ≤ λmax(I⁻¹)|L| for any orientation and momentum (the walls' reach
    check uses it instead of ω), with equality for L along the principal
    axis of least inertia."""
    from crashlite.solver.rigid import RigidBody

    rng = np.random.default_rng(5)
    a = rng.normal(size=(3, 3))
    inertia = a @ a.T + 2 * np.eye(3)
    body = RigidBody(
        1,
        np.zeros(1, np.int64),
        1.0,
        np.zeros(3),
        inertia,
        np.zeros((1, 3)),
        np.zeros(3),
        np.zeros(3),
        rotation(rng.normal(size=3)),
    )
    for _ in range(20):
        body.momentum = rng.normal(size=3)
        body.rot = rotation(rng.normal(size=3))
        assert np.linalg.norm(body.omega()) <= body.spin_bound() * (1 + 1e-12)
    lam, vec = np.linalg.eigh(inertia)
    body.rot = np.eye(3)
    body.momentum = 3.0 * vec[:, 0]
    assert np.linalg.norm(body.omega()) == pytest.approx(body.spin_bound(), rel=1e-12)
    assert body.spin_bound() == pytest.approx(3.0 / lam[0], rel=1e-12)


def test_out_of_reach_is_the_gap_against_twice_the_fastest_node():
    """A body's nodes cannot reach a plane over a step when the smallest gap
    exceeds 2·(|v| + λmax(I⁻¹)|L|·r_max + |wall speed|)·dt: the test flips
    exactly there, for translation, spin and a moving wall alike."""
    from crashlite.solver.kernels.rigid import out_of_reach

    x = np.array([[0.0, 0.0, 10.0], [0.0, 0.0, 14.0], [0.0, 3.0, 10.0]])  # nearest node 10 above z = 0
    nodes, cog = np.arange(3, dtype=np.int64), np.array([0.0, 0.0, 12.0])
    point, normal = np.zeros(3), np.array([0.0, 0.0, 1.0])
    r_max = np.sqrt(9.0 + 4.0)  # node 3 from the CoG
    zero, dt = np.zeros(3), 0.5

    def reach(v, mom, spin, wall):  # the speed at which the gap is just covered twice over
        return out_of_reach(x, nodes, cog, point, normal, v, mom, spin, wall, dt)

    assert reach(np.array([0.0, 0.0, -9.99]), zero, 0.0, 0.0)  # 2·9.99·0.5 < 10
    assert not reach(np.array([0.0, 0.0, -10.01]), zero, 0.0, 0.0)
    assert not reach(np.array([10.01, 0.0, 0.0]), zero, 0.0, 0.0)  # any direction counts
    spin = 10.01 / r_max  # |ω| bound = spin_per_momentum·|L| with |L| = 1
    assert not reach(zero, np.array([0.0, 1.0, 0.0]), spin, 0.0)
    assert reach(zero, np.array([0.0, 1.0, 0.0]), 9.99 / r_max, 0.0)
    assert not reach(zero, zero, 0.0, -10.01)  # the wall's own speed
    assert reach(zero, zero, 0.0, 9.99)


def test_body_kick_sums_forces_and_moments_about_the_cog_and_keeps_the_momenta_before():
    rng = np.random.default_rng(5)
    x, f, moment = rng.normal(size=(9, 3)), rng.normal(size=(9, 3)), rng.normal(size=(9, 3))
    nodes = np.array([1, 4, 7], np.int64)
    cog, mass, dt = rng.normal(size=3), 2.5, 1e-3
    vel, mom = rng.normal(size=3), rng.normal(size=3)
    vel0, mom0 = vel.copy(), mom.copy()
    prev_v, prev_m, sums = np.zeros(3), np.zeros(3), np.zeros(6)
    body_kick(f, x, moment, nodes, cog, True, mass, dt, vel, mom, prev_v, prev_m, sums)
    force = f[nodes].sum(axis=0)
    torque = np.cross(x[nodes] - cog, f[nodes]).sum(axis=0) + moment[nodes].sum(axis=0)
    np.testing.assert_allclose(vel, vel0 + dt * force / mass, rtol=1e-14)
    np.testing.assert_allclose(mom, mom0 + dt * torque, rtol=1e-14)
    np.testing.assert_array_equal(prev_v, vel0)
    np.testing.assert_array_equal(prev_m, mom0)


def test_place_body_puts_the_nodes_on_the_rigid_motion():
    rng = np.random.default_rng(6)
    n = 6
    x, v, rot_n, w_n = np.zeros((n, 3)), np.zeros((n, 3)), np.zeros((n, 3, 3)), np.zeros((n, 3))
    nodes = np.array([0, 2, 5], np.int64)
    r_body, cog, vel, mom = rng.normal(size=(3, 3)), rng.normal(size=3), rng.normal(size=3), rng.normal(size=3)
    rot = rotation(rng.normal(size=3))
    a = rng.normal(size=(3, 3))
    inv_i = np.linalg.inv(a @ a.T + 3 * np.eye(3))
    omega = np.zeros(3)
    place_body(x, v, rot_n, w_n, nodes, r_body, cog, rot, vel, inv_i, mom, True, omega)
    w = rot @ inv_i @ rot.T @ mom
    arm = r_body @ rot.T
    np.testing.assert_allclose(omega, w, rtol=1e-13)
    np.testing.assert_allclose(x[nodes], cog + arm, rtol=1e-13)
    np.testing.assert_allclose(v[nodes], vel + np.cross(w, arm), rtol=1e-13, atol=1e-14)
    np.testing.assert_allclose(rot_n[nodes], np.broadcast_to(rot, (3, 3, 3)), rtol=1e-15)
    np.testing.assert_allclose(w_n[nodes], np.broadcast_to(w, (3, 3)), rtol=1e-13)
    others = np.setdiff1d(np.arange(n), nodes)
    assert not x[others].any() and not v[others].any() and not w_n[others].any()  # only the members move
