"""A *DEFINE_TABLE of yield curves by strain rate as the LCSS of MAT_024 and
MAT_081 on shells (kernels.plane_stress.table_yield): one shell stretched
at a constant strain rate, its velocities prescribed so that the rate of
deformation at the mid-step shape is exactly ε̇ along x and nothing else.
The effective strain rate of plane_stress (incompressible flow) is then
ε̇·sqrt(4/3) and the yield stress after each plastic step must be the
table's: the two curves around that rate interpolated linearly, the first
or the last curve outside the table's rates."""

from types import SimpleNamespace

import numpy as np
import pytest

from crashlite.keyword.reader import read_deck
from crashlite.solver.kernels import plane_stress as ps
from crashlite.solver.shells import build_shells

E, NU, RHO = 70.0, 0.3, 7.85e-6  # GPa, kg/mm³ (ms, mm)
EP = np.array([0.0, 0.003, 0.01, 0.02, 0.05, 0.1, 0.3])
SY = np.array([0.4, 0.42, 0.5, 0.6, 0.65, 0.7, 0.8])
SCALES = (1.0, 1.1, 1.3)  # SFO of the table's curves
RATES = (0.5, 2.0, 8.0)  # 1/ms


def table_cards(values=RATES, sfa=1.0) -> str:
    rows = "".join(f"{float(v)!r:>20}{101 + i:>20}\n" for i, v in enumerate(values))
    curves = "".join(
        f"*DEFINE_CURVE\n{101 + i},0,1.0,{s!r}\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(EP, SY))
        for i, s in enumerate(SCALES)
    )
    return f"*DEFINE_TABLE\n100,{sfa!r}\n{rows}{curves}"


def deck(tmp_path, material: str, elform=2, nip=3, extra="") -> str:
    p = tmp_path / "one.k"
    p.write_text(
        "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n*ELEMENT_SHELL\n1,1,1,2,3,4\n"
        f"*PART\nsheet\n1,1,1\n*SECTION_SHELL\n1,{elform},0.8333,{nip}\n1.0,1.0,1.0,1.0\n"
        f"{material}\n{extra}*CONTROL_TERMINATION\n1.0\n*END\n"
    )
    return p


def mat024(lcss=100) -> str:
    return f"*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,{RHO},{E},{NU},0.0,0.0\n0.0,0.0,{lcss},0\n"


class Stretch:
    """One shell of a deck driven at ε̇ along x: v = ε̇·x at the mid-step
    shape, no rotation."""

    def __init__(self, path, rate: float, dt: float = 2e-5, curvature_rate: float = 0.0):
        model = read_deck(path)
        problems: list = []
        self.g = build_shells(model, [], problems)
        assert not problems, [str(p) for p in problems]
        self.x = model.nodes.xyz.copy()
        self.rate, self.kappa, self.dt = rate, curvature_rate, dt

    def step(self) -> None:
        dt, r = self.dt, self.rate
        v = np.zeros_like(self.x)
        v[:, 0] = r * self.x[:, 0] / (1.0 - 0.5 * r * dt)  # = ε̇·x(n+½)
        w = np.zeros_like(self.x)
        w[:, 1] = -self.kappa * (self.x[:, 0] + 0.5 * dt * v[:, 0])  # curvature rate κ̇ about y
        self.x += dt * v
        st = SimpleNamespace(x=self.x, v=v, w=w, dt=dt, f=np.zeros_like(self.x), moment=np.zeros_like(self.x))
        self.g.forces(st)


def mises(s: np.ndarray) -> np.ndarray:
    return np.sqrt(s[..., 0] ** 2 - s[..., 0] * s[..., 1] + s[..., 1] ** 2 + 3 * (s[..., 2:] ** 2).sum(-1))


def table_yield(ep: float, rate: float, values=RATES, log=False) -> float:
    """The table's yield stress in closed form (numpy, not the kernel)."""
    ys = [s * np.interp(ep, EP, SY) for s in SCALES]
    xs = np.log(values) if log else np.asarray(values)
    r = np.log(rate) if log else rate
    return float(np.interp(r, xs, ys))  # np.interp holds the end values outside: no extrapolation


EFFECTIVE = np.sqrt(4.0 / 3.0)  # effective rate / ε̇ of the drive (d_y = 0, d_z = −d_x)


@pytest.mark.parametrize("elform", [2, 16])
@pytest.mark.parametrize("rate", [0.2, 1.25, 5.0, 20.0], ids=["below", "first-second", "second-third", "above"])
def test_mat024_yield_is_the_tables_at_the_strain_rate(tmp_path, elform, rate):
    drive = Stretch(
        deck(tmp_path, mat024() + table_cards(), elform), rate / EFFECTIVE, dt=0.12 / (rate / EFFECTIVE) / 400
    )
    g = drive.g
    assert g.s.mcurve[0, ps.C_TABLE] >= 0 and g.s.mcurve[0, ps.C_LCSS] == -1
    checked = 0
    for _ in range(400):
        drive.step()
        ep = g.st.epsp[0, 0]
        if ep > 0:
            q = mises(g.st.sig[0, :3])
            want = table_yield(ep, rate)
            np.testing.assert_allclose(q, want, rtol=1e-6)
            np.testing.assert_allclose(g.st.epsp[0, :3], ep, rtol=1e-9)  # no bending: the points agree
            checked += 1
    assert checked > 300 and g.st.epsp[0, 0] > 0.08  # across several segments of the curves


def test_table_scale_offset_and_log_rates(tmp_path):
    """SFA scales the values (0.25, 1, 4 × 2 = the rates above); a first
    value < 0 makes them ln(ε̇), interpolated in ln(ε̇)."""
    for cards, log in ((table_cards((0.25, 1.0, 4.0), sfa=2.0), False), (table_cards(tuple(np.log(RATES))), True)):
        drive = Stretch(deck(tmp_path, mat024() + cards), 1.25 / EFFECTIVE, dt=1e-4)
        for _ in range(200):
            drive.step()
        ep = drive.g.st.epsp[0, 0]
        assert ep > 0.01
        np.testing.assert_allclose(mises(drive.g.st.sig[0, 0]), table_yield(ep, 1.25, log=log), rtol=1e-6)


def test_the_hat_table_is_the_mean_of_its_curves_at_half_its_top_rate(tmp_path):
    """The hat deck's table (0 /ms: curve 111, 5 /ms: curve 112 with SFO 1.2)
    under MAT_081 before softening (EPPF 0.5): at 2.5 /ms, 1.1 × the curve."""
    mat = f"*MAT_PLASTICITY_WITH_DAMAGE\n1,{RHO},{E},{NU},0.0,0.0,0.5\n0.0,0.0,110,0,1.5\n"
    curves = "".join(
        f"*DEFINE_CURVE\n{i},0,1.0,{s}\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(EP, SY))
        for i, s in ((111, 1.0), (112, 1.2))
    )
    table = f"*DEFINE_TABLE\n110\n{0.0!r:>20}{111:>20}\n{5.0!r:>20}{112:>20}\n"
    drive = Stretch(deck(tmp_path, mat + table + curves, elform=16, nip=5), 2.5 / EFFECTIVE, dt=1e-4)
    for _ in range(300):
        drive.step()
        ep = drive.g.st.epsp[0, 0]
        if ep > 0:
            np.testing.assert_allclose(mises(drive.g.st.sig[0, 0]), 1.1 * np.interp(ep, EP, SY), rtol=1e-6)
    assert drive.g.st.epsp[0, 0] > 0.05


def test_c_p_and_lcsr_do_not_apply_with_a_table_and_a_table_of_tables_is_refused(tmp_path):
    mat = f"*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,{RHO},{E},{NU},0.0,0.0\n40.0,5.0,100,0\n"
    warns: list = []
    problems: list = []
    model = read_deck(deck(tmp_path, mat + table_cards()))
    build_shells(model, [], problems, warns)
    assert not problems and any(w.field == "LCSS" and "C, P do not apply" in w.message for w in warns)
    bad = table_cards().replace(f"{'8.0':>20}{103:>20}", f"{'8.0':>20}{100:>20}")
    problems = []
    build_shells(read_deck(deck(tmp_path, mat024() + bad)), [], problems)
    (p,) = problems
    assert (p.keyword, p.field) == ("MAT_PIECEWISE_LINEAR_PLASTICITY", "LCSS") and "not a *DEFINE_CURVE" in p.message
