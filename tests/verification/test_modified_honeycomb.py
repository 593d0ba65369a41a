"""*MAT_MODIFIED_HONEYCOMB (MAT_126) against closed forms: with LCA > 0 it
is MAT_026 to the bit; with LCA < 0 (the transversely isotropic form) a
cube crushed along its cell axis follows |LCA|(0°) + LCB, across it
|LCA|(90°) + LCC, in shear it yields at the 45° surface over √2, and its
shear damage curve takes the shear away without deleting the element,
which then crushes on its curve as before."""

import math

import numpy as np
import pytest
from _solid_driver import (
    HC_CURVE,
    HC_E,
    HC_EAAU,
    HC_RHO,
    HC_SIGY,
    HC_VF,
    Driver,
    brick_mesh,
    deck_text,
    group_from_deck,
)

# |LCA|: yield by the angle off the cell axis [MPa]; flat to 10°, so that the small shear a crush of a sheared
# cube meets in each step's trial (before its damage takes it away) does not tilt the crush off the curve
ANGLE = np.array([[0.0, 0.30], [10.0, 0.30], [45.0, 0.10], [90.0, 0.02]])
STRONG = np.array([[0.0, 0.0], [0.5, 0.1], [0.8, 0.4]])  # LCB: strong-axis hardening vs volumetric strain [MPa]
WEAK = np.array([[0.0, 0.0], [1.0, 0.01]])  # LCC: weak-axis hardening [MPa]
DAMAGE = np.array([[0.0, 1.0], [0.1, 1.0], [0.3, 0.0], [5.0, 0.0]])  # shear factor left vs half the engineering shear


def _curve(cid, pts):
    return f"*DEFINE_CURVE\n{cid}\n" + "\n".join(f"{float(a)!r},{float(b)!r}" for a, b in pts)


def _classic(keyword):
    wk = 0.05 * HC_EAAU
    mat = (
        f"*{keyword}\n1,{HC_RHO},{HC_E},0.3,{HC_SIGY},{HC_VF},0.05,0\n2,3,3,3\n"
        f"{HC_EAAU},{wk},{wk},{wk},{wk},{wk},2.0,1\n0,0,0,1.0,0.0,0.0\n0.0,1.0,0.0,0,0"
    )
    return mat, _curve(2, HC_CURVE) + "\n" + _curve(3, [(0.0, 0.0171), (1.0, 0.0171)])


def _transverse(damage=True, shdflg=1):
    """LCA < 0: |LCA| = curve 2 (angle), LCB 3, LCC 4, LCS 5 (damage)."""
    wk = 0.05 * HC_EAAU
    lcs = 5 if damage else 0
    mat = (
        f"*MAT_MODIFIED_HONEYCOMB\n1,{HC_RHO},{HC_E},0.3,{HC_SIGY},{HC_VF},0.0,0\n-2,3,4,{lcs}\n"
        f"{HC_EAAU},{wk},{wk},{wk},{wk},{wk},2.0,1\n0,0,0,1.0,0.0,0.0\n0.0,1.0,0.0,0,0,0,0,{shdflg}"
    )
    curves = "\n".join(_curve(c, p) for c, p in ((2, ANGLE), (3, STRONG), (4, WEAK), (5, DAMAGE)))
    return mat, curves


def _cube(tmp_path, material, curves, velocity, t_end, elform=1):
    """A 10 mm cube, every node driven by velocity(node, dof) -> v(t).
    Returns the group and records (t, stress of element 0, alive, its volumetric strain)."""
    x, conn = brick_mesh(1, 1, 1, 10.0, 10.0, 10.0)
    g, _, _ = group_from_deck(tmp_path, deck_text(x, conn, material, section=f"1,{elform}", extra=curves))
    driven = [(np.array([n]), dof, velocity(x[n], dof)) for n in range(len(x)) for dof in range(3)]
    dr = Driver(g, x, driven=driven, dt_max=2e-6)
    rows = []
    dr.run(
        t_end,
        lambda d, vn: rows.append((d.st.t, g.st.sig[0].copy(), int(g.st.alive[0]), 1.0 - g.st.vol[0] / g.s.vol0[0])),
        every=10,
    )
    return g, rows


def _crush(axis, speed=1000.0):
    """The face at coordinate 10 along ``axis`` pushed in at ``speed``, the rest held: uniaxial strain."""
    return lambda xn, dof: lambda t: -speed if (dof == axis and xn[axis] == 10.0) else 0.0


def test_modified_honeycomb_with_a_positive_lca_is_mat026_to_the_bit(tmp_path):
    """The same cube crushed along its cell axis to 60 %: MAT_126 (LCA > 0)
    and MAT_026 give the same stresses, bit for bit."""
    out = []
    for kw in ("MAT_HONEYCOMB", "MAT_MODIFIED_HONEYCOMB"):
        mat, curves = _classic(kw)
        (tmp_path / kw).mkdir()
        _, rows = _cube(tmp_path / kw, mat, curves, _crush(0), 6e-3)
        out.append(np.array([r[1] for r in rows]))
    assert out[0].shape == out[1].shape and np.abs(out[0]).max() > 0.3
    np.testing.assert_array_equal(out[0], out[1])


@pytest.mark.parametrize("elform", [1, 2])
@pytest.mark.parametrize("axis", [0, 1], ids=["along-the-cells", "across-the-cells"])
def test_transverse_honeycomb_crushes_on_the_angle_and_axis_curves(tmp_path, axis, elform):
    """Uniaxial strain along a (x) crushes at |LCA|(0°) + LCB(ε_v), along b
    (y) at |LCA|(90°) + LCC(ε_v), within 1 % from 5 to 60 % of crush
    (ε_v from the element's volume); the other stresses stay below the
    lateral moduli's few per cent."""
    mat, curves = _transverse(damage=False)
    g, rows = _cube(tmp_path, mat, curves, _crush(axis), 6e-3, elform)
    checked = 0
    for _, s, alive, ev in rows:
        if 0.05 < ev < 0.6:
            angle = 0.0 if axis == 0 else 90.0
            hard = np.interp(ev, *STRONG.T) if axis == 0 else np.interp(ev, *WEAK.T)
            expected = np.interp(angle, *ANGLE.T) + hard
            assert -s[axis] == pytest.approx(expected, rel=0.01)
            checked += 1
        assert alive == 1
    assert checked > 20


def test_transverse_honeycomb_yields_in_shear_at_the_45_degree_surface(tmp_path):
    """Simple shear in the ca plane (u_x = γ·z) without damage: the
    principal stresses ±τ lie at 45° off the cell axis, so τ holds at
    (|LCA|(45°) + ½LCB(0) + ½LCC(0)) / √2 = 0.1 / √2 MPa within 0.5 %
    (the element's volume does not change: ε_v = 0)."""
    mat, curves = _transverse(damage=False)
    rate = 100.0  # engineering shear rate [1/s]
    _, rows = _cube(tmp_path, mat, curves, lambda xn, dof: lambda t: rate * xn[2] if dof == 0 else 0.0, 3e-3)
    tau = np.interp(45.0, *ANGLE.T) / math.sqrt(2.0)
    late = [s for t, s, *_ in rows if rate * t > 0.1]
    assert late
    for s in late:
        assert abs(s[5]) == pytest.approx(tau, rel=0.005)
        assert np.abs(s[:3]).max() < 1e-6


def test_transverse_honeycomb_shear_damage_keeps_the_element_and_its_crush(tmp_path):
    """Shear in the ca plane with the damage curve (factor 1 to γ/2 = 0.1,
    0 at 0.3), SHDFLG 1: at γ/2 = 0.2 the shear is half the undamaged
    yield (0.5 · 0.1/√2), past 0.3 it is zero and stays zero when the
    shear turns back; the element is never deleted. Crushed along its cell
    axis afterwards, it carries |LCA|(0°) + LCB(ε_v) as an untorn cube."""
    mat, curves = _transverse(damage=True, shdflg=1)
    rate, t1, t2 = 100.0, 8e-3, 9e-3  # shear to γ = 0.8, back to 0.7, then crush
    speed = 1000.0

    def velocity(xn, dof):
        def v(t):
            if t <= t1:
                return rate * xn[2] if dof == 0 else 0.0
            if t <= t2:
                return -rate * xn[2] if dof == 0 else 0.0
            return -speed if (dof == 0 and xn[0] >= 10.0) else 0.0

        return v

    g, rows = _cube(tmp_path, mat, curves, velocity, t2 + 4e-3)
    tau = np.interp(45.0, *ANGLE.T) / math.sqrt(2.0)
    mid = min(rows, key=lambda r: abs(rate * r[0] / 2.0 - 0.2))
    assert abs(mid[1][5]) == pytest.approx(0.5 * tau, rel=0.03)
    after = [s for t, s, *_ in rows if rate * min(t, t1) / 2.0 > 0.31 and t <= t2]
    assert after and max(abs(s[5]) for s in after) < 1e-9
    assert all(r[2] == 1 for r in rows)
    crushed = [(ev, s) for t, s, _, ev in rows if t > t2 + 5e-4]
    for ev, s in crushed:
        expected = np.interp(0.0, *ANGLE.T) + np.interp(ev, *STRONG.T)
        assert -s[0] == pytest.approx(expected, rel=0.02)
    assert g.st.hist[0, 24 + 2] == 1.0  # the ca plane fully damaged


def test_transverse_honeycomb_needs_both_hardening_curves(tmp_path):
    """LCA < 0 without LCC is refused, naming the field."""
    mat, curves = _transverse(damage=False)
    mat = mat.replace("-2,3,4,0", "-2,3,0,0")
    x, conn = brick_mesh(1, 1, 1, 10.0, 10.0, 10.0)
    with pytest.raises(AssertionError, match="LCC is needed with LCA < 0"):
        group_from_deck(tmp_path, deck_text(x, conn, mat, extra=curves))
