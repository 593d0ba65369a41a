"""8-node solids (ELFORM 1): patch test, objectivity, wave in a bar,
honeycomb crush, thread-count independence."""

from types import SimpleNamespace

import numba
import numpy as np
import pytest

from crashlite import read_deck
from crashlite.solver import run
from crashlite.solver.setup import build
from crashlite.solver.solids import SolidGroup

E, NU, RHO = 210000.0, 0.3, 7.85e-9
LAM, MU = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))


def _one_hex(tmp_path, xyz, mat="*MAT_ELASTIC\n1,7.85e-9,210000.0,0.3", ihq=4, extra=""):
    nodes = "\n".join(f"{i + 1},{x},{y},{z}" for i, (x, y, z) in enumerate(xyz))
    text = f"""*KEYWORD
*NODE
{nodes}
*ELEMENT_SOLID
1,1,1,2,3,4,5,6,7,8
*PART
block
1,1,1,0,1
*SECTION_SOLID
1,1
{mat}
*HOURGLASS
1,{ihq},0.1
{extra}*CONTROL_TERMINATION
1.0
*END
"""
    p = tmp_path / "hex.k"
    p.write_text(text)
    return read_deck(p)


CUBE = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
# a distorted hexahedron: the patch test must hold for any trilinear shape
DISTORTED = CUBE * [10.0, 8.0, 6.0] + np.array(
    [
        [0, 0, 0],
        [1.5, 0.4, 0],
        [0.7, -0.8, 0.3],
        [-0.6, 0.9, -0.2],
        [0.3, 0.2, 0.8],
        [1.1, -0.5, 0.6],
        [-0.4, 0.6, -0.7],
        [0.5, 0.1, 0.4],
    ]
)


def _group(model):
    s = build(model)
    (g,) = [g for g in s.groups if isinstance(g, SolidGroup)]
    return s, g


def _step(g, x, v, dt):
    st = SimpleNamespace(x=x, v=v, dt=dt, f=np.zeros_like(x))
    g.forces(st)
    return st.f


@pytest.mark.parametrize("ihq", [2, 3, 4, 5])
def test_patch_linear_velocity_gives_uniform_stress_and_balanced_forces(tmp_path, ihq):
    """v = L·x with a constant L: the stress is exactly C:sym(L)·Δt, the
    hourglass modes stay silent and the nodal forces balance the stress
    on the element's faces (Σ f = 0, Σ x × f = 0)."""
    s, g = _group(_one_hex(tmp_path, DISTORTED, ihq=ihq))
    grad = np.array([[1.0, 0.3, -0.2], [0.1, -0.5, 0.4], [0.2, 0.0, 0.7]]) * 1e-3
    dt = 1e-7
    x0 = s.x0.copy()
    v = x0 @ grad.T
    x = x0 + dt * v  # positions at t(n+1) from the mid-step velocity
    f = _step(g, x, v, dt)
    d = 0.5 * (grad + grad.T) * dt
    expect = LAM * np.trace(d) * np.eye(3) + 2 * MU * d
    sig = g.st.sig[0]
    got = np.array([[sig[0], sig[3], sig[5]], [sig[3], sig[1], sig[4]], [sig[5], sig[4], sig[2]]])
    np.testing.assert_allclose(got, expect, rtol=1e-6, atol=1e-9 * np.abs(expect).max())
    assert np.abs(g.st.hgq).max() < 1e-12 * np.abs(f).max()
    assert np.abs(f.sum(axis=0)).max() < 1e-9 * np.abs(f).max()
    assert np.abs(np.cross(x, f).sum(axis=0)).max() < 1e-8 * np.abs(f).max() * 10.0


def test_rigid_rotation_turns_the_stress_with_the_body(tmp_path):
    """A prestressed cube spun rigidly by 90° about z in many steps: the
    stress tensor turns with it (σxx → σyy) and no new strain appears."""
    s, g = _group(_one_hex(tmp_path, CUBE * 10.0))
    g.st.sig[0] = [100.0, 0.0, 0.0, 0.0, 0.0, 0.0]
    omega, steps = 1000.0, 2000
    dt = (np.pi / 2) / omega / steps
    c = s.x0.mean(axis=0)
    x = s.x0.copy()
    for k in range(steps):
        # exact rigid motion from angle θk to θk+1: mid-step velocity (x(n+1) − x(n)) / Δt
        th0, th1 = omega * dt * k, omega * dt * (k + 1)
        r0 = np.array([[np.cos(th0), -np.sin(th0), 0], [np.sin(th0), np.cos(th0), 0], [0, 0, 1]])
        r1 = np.array([[np.cos(th1), -np.sin(th1), 0], [np.sin(th1), np.cos(th1), 0], [0, 0, 1]])
        xa, xb = c + (s.x0 - c) @ r0.T, c + (s.x0 - c) @ r1.T
        x = xb
        _step(g, x, (xb - xa) / dt, dt)
    np.testing.assert_allclose(g.st.sig[0], [0.0, 100.0, 0.0, 0.0, 0.0, 0.0], atol=1e-6)
    assert abs(g.energy[0]) < 1e-9


def _bar_deck(tmp_path, n=20, h=5.0, v0=1000.0, end=6e-5, bq0=False):
    ids, lines = {}, ["*KEYWORD", "*NODE"]
    nid = 0
    for k in range(n + 1):
        for j, (y, z) in enumerate([(0, 0), (10, 0), (10, 10), (0, 10)]):
            nid += 1
            ids[k, j] = nid
            lines.append(f"{nid},{k * h},{y},{z}")
    lines.append("*ELEMENT_SOLID")
    for k in range(n):
        c = [ids[k, 0], ids[k + 1, 0], ids[k + 1, 1], ids[k, 1], ids[k, 3], ids[k + 1, 3], ids[k + 1, 2], ids[k, 2]]
        lines.append(f"{k + 1},1," + ",".join(map(str, c)))
    lines += [
        "*PART",
        "bar",
        "1,1,1",
        "*SECTION_SOLID",
        "1,1",
        "*MAT_ELASTIC",
        f"1,{RHO},{E},{NU}",
        "*SET_NODE_LIST",
        "1",
    ] + [",".join(map(str, range(i, min(i + 8, nid + 1)))) for i in range(1, nid + 1, 8)]
    lines += (
        [
            "*BOUNDARY_SPC_SET",
            "1,0,0,1,1",
            "*INITIAL_VELOCITY",
            "1",
            f"{-v0},0,0",
            "*RIGIDWALL_PLANAR",
            "0",
            "0,0,0,1,0,0",
            "*CONTROL_TERMINATION",
            f"{end}",
        ]
        + (["*CONTROL_BULK_VISCOSITY", "1e-12,1e-12"] if bq0 else [])  # a 0 reads as the default
        + ["*END"]
    )
    p = tmp_path / "bar.k"
    p.write_text("\n".join(lines))
    return read_deck(p)


@pytest.mark.parametrize("bulk_q", [False, True])
def test_bar_impact_on_a_rigid_wall_gives_rho_c_v_for_two_transits(tmp_path, bulk_q):
    """Laterally held bar (uniaxial strain) at V onto a rigid wall: wall
    stress ρ·c·V with c = √(M/ρ), M the constrained modulus, for 2L/c
    (duration of the force above half the plateau, and impulse / plateau
    force); rebound at V; energy conserved; no hourglass energy in a
    one-dimensional wave. LS-DYNA's default bulk viscosity (Q1 1.5, Q2
    0.06) damps the released wave: a few % shorter contact and slower
    rebound, as in LS-DYNA."""
    n, h, v0 = 40, 2.5, 1000.0
    r = run(_bar_deck(tmp_path, n, h, v0, bq0=not bulk_q), output_dt=2.5e-7)
    c = np.sqrt((LAM + 2 * MU) / RHO)
    f = np.abs(r.wall_force[:, 0, 0])
    plateau = RHO * c * v0 * 100.0
    assert np.median(f[f > 0.5 * f.max()]) == pytest.approx(plateau, rel=0.01)
    on = r.time[f > 0.5 * plateau]
    tol = 0.05 if bulk_q else 0.025
    assert on[-1] - on[0] == pytest.approx(2 * n * h / c, rel=tol)
    assert np.trapezoid(f, r.time) / plateau == pytest.approx(2 * n * h / c, rel=tol)
    assert r.final_v[:, 0].mean() == pytest.approx(v0, rel=2 * tol)
    assert np.all(np.abs(r.energy_ratio - 1.0) < 0.02)
    assert r.hourglass.max() < 1e-6 * r.internal.max()


def test_thread_count_does_not_change_the_result(tmp_path, two_threads):
    model = _bar_deck(tmp_path, end=2e-5)
    default = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        one = run(model)
        numba.set_num_threads(min(2, numba.config.NUMBA_NUM_THREADS))
        two = run(model)
    finally:
        numba.set_num_threads(default)
    assert np.array_equal(one.final_x, two.final_x) and np.array_equal(one.wall_force, two.wall_force)
