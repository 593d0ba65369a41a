"""Section forces and moments (secforc) against statics."""

import numpy as np

from crashlite import read_deck
from crashlite.solver import run


def test_section_moment_of_two_offset_springs(tmp_path):
    """Two springs of different stiffness at y = ±50 mm pull a block
    (nodal rigid body) along x; the plane section through them reports
    their summed force and the moment Mz = -Σ (y - ȳ)·Fx about the
    centroid of the cut ends, balanced by the turning of the body."""
    text = "\n".join([
        "*KEYWORD", "*NODE", "1,0,50,0,7,7", "2,0,-50,0,7,7", "3,100,50,0", "4,100,-50,0",
        "*ELEMENT_MASS", "10,3,0.05", "11,4,0.05",
        "*SET_NODE_LIST", "1", "3,4", "*CONSTRAINED_NODAL_RIGID_BODY", "100,0,1",
        "*ELEMENT_DISCRETE", "1,1,1,3", "2,2,2,4",
        "*PART", "soft", "1,1,1", "*PART", "stiff", "2,1,2", "*SECTION_DISCRETE", "1,0",
        "*MAT_SPRING_ELASTIC", "1,50.0", "*MAT_SPRING_ELASTIC", "2,150.0",
        "*INITIAL_VELOCITY_NODE", "3,1000.0,0,0", "4,1000.0,0,0",
        "*DATABASE_CROSS_SECTION_PLANE_ID", "5,mid", "0,50,0,0,51,0,0",
        "*CONTROL_TERMINATION", "0.02", "*CONTROL_TIMESTEP", ",0.1", "*END"])
    p = tmp_path / "two.k"
    p.write_text(text)
    r = run(read_deck(p), output_dt=1e-3)
    f1, f2 = r.discrete_force[:, 0], r.discrete_force[:, 1]
    # the section side is x > 50: the far ends (nodes 3, 4) receive -F along the axis
    fx = r.section_force[:, 0, 0]
    np.testing.assert_allclose(fx, -(f1 + f2) * 1.0, rtol=2e-2, atol=1e-6 * np.abs(f2).max())
    mz = r.section_moment[:, 0, 2]
    fx_each = np.stack([-f1, -f2], axis=1)  # approximately along x (the body turns little)
    expected = -(50.0 * fx_each[:, 0] - 50.0 * fx_each[:, 1])
    assert np.abs(expected).max() > 100.0
    np.testing.assert_allclose(mz, expected, rtol=3e-2, atol=1e-3 * np.abs(expected).max())
