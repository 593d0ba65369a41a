"""A *DEFINE_TABLE of yield curves by strain rate as the LCSS of MAT_024 on
solids (kernels.solid_materials): one hexahedron in uniaxial strain at a
constant rate ε̇ (velocities v = ε̇·x at the mid-step shape, where the
element takes its rate of deformation), whose effective strain rate is
(2/3)·ε̇; the von Mises stress after each plastic step is the table's
yield stress at that rate (test_shell_rate_table's table and closed form).
MAT_081 on solids is refused by name."""

from types import SimpleNamespace

import numpy as np
import pytest
from test_shell_rate_table import NU, RHO, E, table_cards, table_yield

from crashlite.keyword.reader import read_deck
from crashlite.solver.kernels import solid_materials as sm
from crashlite.solver.solids import SolidGroup, build_solids


def _deck(tmp_path, material: str) -> str:
    xyz = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    p = tmp_path / "cube.k"
    p.write_text(
        "*KEYWORD\n*NODE\n"
        + "".join(f"{i + 1},{x}.0,{y}.0,{z}.0\n" for i, (x, y, z) in enumerate(xyz))
        + "*ELEMENT_SOLID\n1,1,1,2,3,4,5,6,7,8\n*PART\ncube\n1,1,1\n*SECTION_SOLID\n1,1\n"
        + material
        + "*CONTROL_TERMINATION\n1.0\n*END\n"
    )
    return p


def _von_mises(s: np.ndarray) -> float:
    p = s[:3].mean()
    d = s[:3] - p
    return float(np.sqrt(1.5 * (d @ d + 2.0 * (s[3:] @ s[3:]))))


@pytest.mark.parametrize("rate", [0.2, 1.25, 5.0, 20.0], ids=["below", "first-second", "second-third", "above"])
def test_mat024_table_on_a_solid(tmp_path, rate):
    mat = f"*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,{RHO},{E},{NU},0.0,0.0\n0.0,0.0,100,0\n"
    model = read_deck(_deck(tmp_path, mat + table_cards()))
    problems: list = []
    s = build_solids(model, [], problems)
    assert not problems, [str(p) for p in problems]
    assert s.mcurve[0, sm.C_TABLE] >= 0 and s.mcurve[0, sm.C_LCSS] == -1
    g = SolidGroup(s, len(model.nodes.xyz))
    x = model.nodes.xyz.copy()
    eps_rate = 1.5 * rate  # ε̇ with an effective rate (2/3)·ε̇ = rate
    dt = 0.1 / eps_rate / 400
    checked = 0
    for _ in range(400):
        v = np.zeros_like(x)
        v[:, 0] = eps_rate * x[:, 0] / (1.0 - 0.5 * eps_rate * dt)  # = ε̇·x(n+½)
        x += dt * v
        g.forces(SimpleNamespace(x=x, v=v, dt=dt, f=np.zeros_like(x)))
        ep = g.st.epsp[0]
        if ep > 0:
            np.testing.assert_allclose(_von_mises(g.st.sig[0]), table_yield(ep, rate), rtol=1e-6)
            checked += 1
    assert checked > 300 and g.st.epsp[0] > 0.05


def test_mat081_on_a_solid_is_refused_by_name(tmp_path):
    mat = f"*MAT_PLASTICITY_WITH_DAMAGE\n1,{RHO},{E},{NU},0.4,0.0,0.5\n0.0,0.0,0,0,1.5\n"
    model = read_deck(_deck(tmp_path, mat))
    problems: list = []
    build_solids(model, [], problems)
    (p,) = problems
    assert p.keyword == "MAT_PLASTICITY_WITH_DAMAGE" and p.line == 18 and p.file.endswith("cube.k")
    assert "not supported for solids" in p.message
