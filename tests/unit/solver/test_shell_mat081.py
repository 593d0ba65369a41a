"""*MAT_PLASTICITY_WITH_DAMAGE (MAT_081) on shells: past EPPF the stress is
(1 − D)·σy(ε̄p) with D = (ε̄p − EPPF)/(EPPFR − EPPF), or D from the curve
LCDM of D vs ε̄p − EPPF; a point ruptures at EPPFR (or D = 1) and the shell
is deleted when NUMINT of its points have (0: all); the energy of a strip
pulled apart balances (internal + kinetic, the eroded shells' internal
energy kept, = the work of the prescribed motion). The one-shell drive is
test_shell_rate_table's (ε̇ along x at the mid-step shape)."""

import numpy as np
import pytest
from test_shell_rate_table import EP, NU, RHO, SY, E, Stretch, deck, mises

from crashlite.keyword.reader import read_deck
from crashlite.solver import setup
from crashlite.solver.kernels import plane_stress as ps
from crashlite.solver.loop import integrate
from crashlite.solver.shells import ShellGroup

EPPF, EPPFR = 0.02, 0.06
CURVE = "*DEFINE_CURVE\n101\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(EP, SY))
LCDM_X, LCDM_D = [0.0, 0.01, 0.03], [0.0, 0.1, 1.0]  # D vs ε̄p − EPPF: D = 1 at ε̄p = 0.05 < EPPFR


def mat081(lcdm=0, numint=0, eppf=EPPF, eppfr=EPPFR) -> str:
    text = f"*MAT_081\n1,{RHO},{E},{NU},0.0,0.0,{eppf},0.0\n0.0,0.0,101,0,{eppfr},0.0,{lcdm},{numint}\n" + CURVE
    if lcdm:
        text += f"*DEFINE_CURVE\n{lcdm}\n" + "".join(f"{a},{d}\n" for a, d in zip(LCDM_X, LCDM_D))
    return text


def damage(ep: float, lcdm: bool) -> float:
    if lcdm:
        return float(np.clip(np.interp(ep - EPPF, LCDM_X, LCDM_D), 0.0, 1.0))
    return float(np.clip((ep - EPPF) / (EPPFR - EPPF), 0.0, 1.0))


@pytest.mark.parametrize("elform", [2, 16])
@pytest.mark.parametrize("lcdm", [False, True], ids=["linear", "lcdm"])
def test_stress_is_one_minus_d_times_the_yield_and_the_shell_goes_at_rupture(tmp_path, elform, lcdm):
    drive = Stretch(deck(tmp_path, mat081(lcdm=7 if lcdm else 0), elform), 1.0, dt=1e-4)
    g = drive.g
    assert g.s.mtype[0] == ps.DAMAGE and g.s.props[0, ps.P_FAIL] == EPPFR
    rupture = 0.05 if lcdm else EPPFR  # where D reaches 1 first
    softened = 0
    ep_before = 0.0
    for _ in range(800):
        drive.step()
        ep = g.st.epsp[0, 0]
        if g.st.alive[0] != 1:
            break
        ep_before = ep
        if ep > 0:
            y = np.interp(ep, EP, SY)
            want = (1.0 - damage(ep, lcdm)) * y
            np.testing.assert_allclose(mises(g.st.sig[0, :3]), want, rtol=1e-6, atol=1e-9 * y)
            softened += ep > EPPF
    assert g.st.alive[0] == 0 and softened > 150  # deleted, after a long softening
    assert ep_before < rupture <= g.st.epsp[0, 0]  # in the step ε̄p reached it
    assert np.all(g.st.sig[0] == 0.0) and np.all(g.st.ipfail[0, :3] == 1)


def _bend(tmp_path, elform, numint):
    """Stretching and bending: the top point strains most, the bottom least;
    returns (the step each point ruptured, the step the shell was deleted,
    ε̄p of the points then)."""
    drive = Stretch(deck(tmp_path, mat081(numint=numint), elform, nip=3), 1.0, dt=1e-4, curvature_rate=1.2)
    g = drive.g
    failed_at = [None] * 3
    for n in range(2000):
        drive.step()
        for k in range(3):
            if failed_at[k] is None and g.st.ipfail[0, k]:
                failed_at[k] = n
        if elform == 16:  # the four in-plane points' layers: ipfail is set once all four failed
            f4 = g.st.ipfail4[0].reshape(4, -1)[:, :3]
            assert np.all(f4 == f4[0])  # uniform curvature: the four in-plane points alike
        if g.st.alive[0] != 1:
            return failed_at, n, g.st.epsp[0, :3].copy()
    raise AssertionError("the shell was never deleted")


@pytest.mark.parametrize("elform", [2, 16])
def test_numint_failed_points_delete_the_shell(tmp_path, elform):
    (first, *_), gone, ep = _bend(tmp_path, elform, numint=1)
    assert first is not None and gone - first <= 1  # deleted at once (the next step at most)
    assert sorted(ep)[0] < EPPFR  # while a point was still whole
    failed_at, gone_all, ep_all = _bend(tmp_path, elform, numint=0)
    assert gone_all > min(failed_at) + 20  # NUMINT 0: all of them, long after the first
    assert gone_all == max(failed_at) and np.all(ep_all >= EPPFR)


def _strip(tmp_path):
    """A 4 x 1 strip of MAT_081 shells (4 mm x 1 mm x 1 mm) held at x = 0
    and pulled at 2 m/s at x = 4 until a shell ruptures: the deck's path."""
    nx = 4
    nodes = [(i + 1, float(x), float(y)) for i, (y, x) in enumerate((y, x) for y in (0.0, 1.0) for x in range(nx + 1))]
    elems = [f"{i + 1},1,{i + 1},{i + 2},{i + nx + 3},{i + nx + 2}" for i in range(nx)]
    left, right = [1, nx + 2], [nx + 1, 2 * nx + 2]
    p = tmp_path / "strip.k"
    p.write_text(
        "*KEYWORD\n*NODE\n"
        + "".join(f"{n},{x!r},{y!r},0.0\n" for n, x, y in nodes)
        + "*ELEMENT_SHELL\n"
        + "\n".join(elems)
        + "\n*PART\nstrip\n1,1,1,0,1\n*SECTION_SHELL\n1,2,0.8333,3\n1.0,1.0,1.0,1.0\n"
        + mat081(eppf=0.05, eppfr=0.15)
        + "*HOURGLASS\n1,4,0.1\n"
        + "*BOUNDARY_SPC_NODE\n"
        + "".join(f"{n},0,1,{int(n == 1)},1,0,0,0\n" for n in left)
        + "".join(f"{n},0,0,0,1,0,0,0\n" for n, *_ in nodes if n not in left)
        + "*BOUNDARY_PRESCRIBED_MOTION_NODE\n"
        + "".join(f"{n},1,0,9\n" for n in right)
        + "*DEFINE_CURVE\n9\n0.0,0.0\n0.02,2.0\n1.0,2.0\n"
        + "*CONTROL_TERMINATION\n0.5\n*END\n"
    )
    return p


def test_a_strip_pulled_apart_balances_its_energy(tmp_path):
    """The strip pulled until a shell ruptures and it parts: kinetic +
    internal + hourglass energy equals the work of the prescribed motion
    within 1 % at every output, and the work stays internal energy once it
    parted (the elastic energy of the stress the damage removed is
    dissipated, not given back). The deleted shells are counted state by
    state."""
    s = setup.build(read_deck(_strip(tmp_path)))
    (g,) = [g for g in s.groups if isinstance(g, ShellGroup)]
    res = integrate(s, 0.005)
    assert g.eroded >= 1  # parted
    gone = res.part_deleted[:, 0]  # the part's deleted shells, state by state
    assert gone[0] == 0 and gone[-1] == g.eroded and np.all(np.diff(gone) >= 0)
    assert res.deleted() == res.deleted([1]) == g.eroded and res.deleted([2]) == 0
    from crashlite.solver.results import Results

    assert np.array_equal(Results.load(res.save(tmp_path / "out")).part_deleted, res.part_deleted)
    ie, ke, hg, w = res.internal, res.kinetic, res.hourglass, res.external
    assert np.abs(ie + ke + hg - w).max() < 0.01 * w.max()
    assert ie[-1] > 0.9 * w[-1]  # the work went into the material (and stays there once it parted)


def test_the_run_summary_names_the_deleted_elements(tmp_path, capsys):
    """`crashlite run` ends with how many elements the run deleted, by
    part, as the strip that parts loses its ruptured shells."""
    from crashlite.cli import main
    from crashlite.solver.results import Results

    assert main(["run", str(_strip(tmp_path)), "-o", str(tmp_path / "cli"), "--quiet"]) == 0
    n = int(Results.load(tmp_path / "cli").part_deleted[-1, 0])
    assert n >= 1 and f"; {n} elements deleted (part 1: {n})" in capsys.readouterr().out
