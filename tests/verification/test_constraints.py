"""Single-point constraints in local systems against statics and kinematics."""

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.solver import run

G, M = 9810.0, 0.2  # mm/s², t


def _slope_deck(tmp_path, system):
    text = "\n".join(
        [
            "*KEYWORD",
            "*NODE",
            "1,0,0,0,7,7",
            "2,0,0,0",
            "3,100,0,0",
            "4,0,100,0",
            "*ELEMENT_MASS",
            f"10,2,{M}",
            *system,
            "*BOUNDARY_SPC_NODE",
            "2,5,0,1,1,0,0,0",
            "*LOAD_BODY_Y",
            "3",
            "*DEFINE_CURVE",
            "3",
            f"0.0,{G}",
            f"1.0,{G}",
            "*CONTROL_TERMINATION",
            "0.05",
            "*CONTROL_TIMESTEP",
            "0.0,0.9,0,0.0,0.0,9",
            "*DEFINE_CURVE",
            "9",
            "0.0,1e-4",
            "1.0,1e-4",
            "*DATABASE_HISTORY_NODE",
            "2",
            "*END",
        ]
    )
    p = tmp_path / "slope.k"
    p.write_text(text)
    return read_deck(p)


@pytest.mark.parametrize(
    "system",
    [
        ["*DEFINE_COORDINATE_VECTOR", "5,0.8660254,-0.5,0,0,1,0"],
        ["*DEFINE_COORDINATE_SYSTEM", "5,0,0,0,86.60254,-50,0", "0,100,0"],
    ],
)
def test_node_on_an_inclined_guide(tmp_path, system):
    """A mass held in the local y and z of a system whose x runs 30° down
    from the global x axis slides along it under gravity (-y): a = g/2;
    the support reaction is m·g·cos30° along the local y axis and, added to
    the weight, gives m·a (reactions balance the applied load)."""
    r = run(_slope_deck(tmp_path, system), output_dt=1e-3)
    e = np.array([np.cos(np.pi / 6), -0.5, 0.0])
    u = r.node_displacement[:, 0]
    np.testing.assert_allclose(u, np.outer(0.25 * G * r.time**2, e), rtol=1e-6, atol=1e-9)  # 7-digit input
    ey = np.array([0.5, np.cos(np.pi / 6), 0.0])
    assert r.spc_nodes.tolist() == [1, 2]  # the fixed node 1 and the guided node 2
    reaction = r.spc_force[1:, 1]
    np.testing.assert_allclose(
        reaction, np.tile(M * G * np.cos(np.pi / 6) * ey, (len(reaction), 1)), rtol=1e-6, atol=1e-9
    )
    np.testing.assert_allclose(
        reaction + [0.0, -M * G, 0.0], np.tile(M * 0.5 * G * e, (len(reaction), 1)), rtol=1e-6, atol=1e-6
    )
    np.testing.assert_allclose(r.kinetic[1:], r.external[1:], rtol=1e-6)  # gravity's work is the KE


def test_unknown_local_system_is_named(tmp_path):
    from crashlite.keyword.errors import DeckError

    with pytest.raises(DeckError, match=r"slope.k:9: \*BOUNDARY_SPC_NODE, field CID: coordinate system 5"):
        _slope_deck(tmp_path, [])
