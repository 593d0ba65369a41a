"""Work of prescribed motions against closed forms.

A linear spring (k = 100 N/mm) from a fixed node to node 2, node 2 pulled
along x by *BOUNDARY_PRESCRIBED_MOTION_NODE. The work the prescription
does is the energy it puts in: ½·k·u² in the spring plus ½·m·v² of node 2.
Booking the kinetic-energy jump of the kicked velocity instead gave
−3.8e7 N·mm for a 1e-9 t node (a spurious ½(f·dt)²/m per step) and 0 for
a massless one.
"""

import numpy as np
import pytest

from crashlite.solver import run

K = 100.0  # N/mm
X = 10.0  # mm, end of the ramp
T = 0.01  # s, duration of the ramp


def _deck(tmp_path, m2: float, vad: int, curve: list[str], end: float = 2 * T, dof: int = 1, body: bool = False) -> str:
    mass = [f"2,2,{m2!r}"] if m2 > 0 else []
    if body:  # node 2 is the centre of a rigid part (its own body of mass m2): drive the part
        motion = ["*BOUNDARY_PRESCRIBED_MOTION_RIGID", f"2,{dof},{vad},5,1.0"]
        # a 2 x 2 mm plate, 1 mm thick, centred on node 2 (an extra node of the part)
        rigid = [
            "*PART",
            "plate",
            "2,2,2",
            "*SECTION_SHELL",
            "2",
            "1.0,1.0,1.0,1.0",
            "*MAT_RIGID",
            f"2,{m2 / 4.0!r},210000.0,0.3",
            "*ELEMENT_SHELL",
            "1,2,3,4,5,6",
            "*NODE",
            "3,99,-1,0",
            "4,101,-1,0",
            "5,101,1,0",
            "6,99,1,0",
            "*CONSTRAINED_EXTRA_NODES_NODE",
            "2,2",
        ]
        mass = []
    else:
        motion = ["*BOUNDARY_PRESCRIBED_MOTION_NODE", f"2,{dof},{vad},5,1.0"]
        rigid = []
    lines = [
        "*KEYWORD",
        "*NODE",
        "1,0,0,0",
        "2,100,0,0",
        "*ELEMENT_MASS",
        "1,1,1.0",
        *mass,
        "*ELEMENT_DISCRETE",
        "7,1,1,2",
        "*PART",
        "spring",
        "1,1,1",
        "*SECTION_DISCRETE",
        "1,0",
        "*MAT_SPRING_ELASTIC",
        f"1,{K!r}",
        "*BOUNDARY_SPC_NODE",
        "1,0,1,1,1,1,1,1",
        "*DEFINE_CURVE",
        "5",
        *curve,
        *motion,
        *rigid,
        "*CONTROL_TERMINATION",
        repr(end),
        "*END",
    ]
    p = tmp_path / f"d{vad}_{m2:g}_{int(body)}.k"
    p.write_text("\n".join(lines) + "\n")
    return str(p)


RAMP = ["0,0", f"{T!r},{X!r}", "1.0," + repr(X)]


@pytest.mark.parametrize("m2", [0.0, 1e-9, 1e-7])
def test_displacement_ramp_work_is_half_k_x_squared(tmp_path, m2):
    """VAD = 2, u = X·t/T then held: at the end the work is ½kX² = 5000 N·mm
    (node 2 at rest again); during the ramp ½ku² + ½m(X/T)²."""
    r = run(_deck(tmp_path, m2, 2, RAMP), output_dt=T / 20)
    u = r.discrete_elong[:, 0]
    assert u[-1] == pytest.approx(X, rel=1e-9)
    assert r.external[-1] == pytest.approx(0.5 * K * X**2, rel=1e-6)  # 5000 N·mm
    ramp = (r.time > 0) & (r.time < T * 0.95)
    expected = 0.5 * K * u[ramp] ** 2 + 0.5 * m2 * (X / T) ** 2
    np.testing.assert_allclose(r.external[ramp], expected, rtol=2e-3, atol=1e-6 * 0.5 * K * X**2)
    assert np.all(np.abs(r.energy_ratio[1:] - 1.0) < 2e-3)
    assert r.energy_ratio[0] == 1.0  # at rest, nothing supplied yet: 1, as LS-DYNA's glstat


def test_velocity_and_acceleration_prescriptions_book_the_same_work(tmp_path):
    """VAD = 0 (v = X/T) and VAD = 1 (a = 2X/T², from rest) pull node 2 by
    about 10 mm in T: the work is ½ku² + ½mv² at every state."""
    m2 = 1e-7
    v = X / T
    r0 = run(_deck(tmp_path, m2, 0, ["0," + repr(v), "1.0," + repr(v)], end=T), output_dt=T / 20)
    u0 = r0.discrete_elong[1:, 0]
    np.testing.assert_allclose(u0, v * r0.time[1:], rtol=1e-9)
    np.testing.assert_allclose(r0.external[1:], 0.5 * K * u0**2 + 0.5 * m2 * v**2, rtol=2e-3)
    a = 2 * X / T**2
    r1 = run(_deck(tmp_path, m2, 1, ["0," + repr(a), "1.0," + repr(a)], end=T), output_dt=T / 20)
    u1, v1 = r1.discrete_elong[-1, 0], r1.final_v[1, 0]
    assert u1 == pytest.approx(X, rel=2e-2) and v1 == pytest.approx(a * T, rel=2e-2)
    assert r1.external[-1] == pytest.approx(0.5 * K * u1**2 + 0.5 * m2 * v1**2, rel=2e-3)


def test_rigid_part_pulled_by_displacement(tmp_path):
    """A rigid part (1e-6 t) on the spring's end, VAD = 2 ramp: the work is
    ½kX² once it is at rest again."""
    r = run(_deck(tmp_path, 1e-6, 2, RAMP, body=True), output_dt=T / 20)
    assert r.discrete_elong[-1, 0] == pytest.approx(X, rel=1e-6)
    assert r.external[-1] == pytest.approx(0.5 * K * X**2, rel=1e-3)
