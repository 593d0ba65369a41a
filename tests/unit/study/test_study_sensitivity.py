"""Sensitivity indices and metamodels on functions with known answers.

Ishigami function f = sin x1 + a sin² x2 + b x3⁴ sin x1 on [-π, π]³
(a = 7, b = 0.1): V = a²/8 + bπ⁴/5 + b²π⁸/18 + 1/2,
S1 = (1/2)(1 + bπ⁴/5)²/V, S2 = a²/8/V, S3 = 0,
ST1 = S1 + (b²π⁸/18 − b²π⁸/50)/V... in closed form below,
ST2 = S2, ST3 = (8b²π⁸/225)/V (Ishigami & Homma 1990; Sobol' 1999).
Acceptance: every index within 10 % (the zero index S3 within 0.03,
10 % of the largest index)."""

import math

import numpy as np
import pytest

from crashlite.study.config import Variable
from crashlite.study.metamodel import fit
from crashlite.study.sampling import doe, to_bounds, unit_points
from crashlite.study.sensitivity import morris_indices, morris_points, sobol_indices

A, B = 7.0, 0.1
PI = math.pi
V = A**2 / 8 + B * PI**4 / 5 + B**2 * PI**8 / 18 + 0.5
V1 = 0.5 * (1 + B * PI**4 / 5) ** 2
V2 = A**2 / 8
V13 = B**2 * PI**8 * (1 / 18 - 1 / 50)  # = 8 b² π⁸ / 225
EXPECTED = {
    "x1": {"S1": V1 / V, "ST": (V1 + V13) / V},
    "x2": {"S1": V2 / V, "ST": V2 / V},
    "x3": {"S1": 0.0, "ST": V13 / V},
}


def ishigami(x):
    return np.sin(x[:, 0]) + A * np.sin(x[:, 1]) ** 2 + B * x[:, 2] ** 4 * np.sin(x[:, 0])


def _vars(n, lo, hi):
    return [Variable(f"x{i + 1}", lo, hi, parameter=f"x{i + 1}") for i in range(n)]


def test_expected_values_are_the_published_ones():
    # Sobol' & Levitan / Saltelli et al. (2008): S1 = 0.3139, 0.4424, 0; ST = 0.5576, 0.4424, 0.2437
    assert [round(EXPECTED[k]["S1"], 4) for k in ("x1", "x2", "x3")] == [0.3139, 0.4424, 0.0]
    assert [round(EXPECTED[k]["ST"], 4) for k in ("x1", "x2", "x3")] == [0.5576, 0.4424, 0.2437]


def test_sobol_indices_of_ishigami_within_10_percent():
    got = sobol_indices(_vars(3, -PI, PI), ishigami, n=8192, seed=1)
    for k, exp in EXPECTED.items():
        for idx in ("S1", "ST"):
            if exp[idx] == 0.0:
                assert abs(got[k][idx]) < 0.03, (k, idx, got[k][idx])
            else:
                assert got[k][idx] == pytest.approx(exp[idx], rel=0.10), (k, idx, got[k][idx])


def test_morris_of_a_linear_function_is_exact():
    """f = Σ c_i x_i: every elementary effect is c_i·(hi − lo), so
    μ* = |c_i|·(hi − lo) and σ = 0; a failed run drops its trajectory."""
    c = np.array([3.0, -1.0, 0.0, 0.5])
    vs = [Variable(f"x{i}", 1.0, 3.0, parameter=f"x{i}") for i in range(4)]
    x = morris_points(vs, 12, 4, seed=3)
    y = x @ c
    res = morris_indices(vs, x, y, 4)
    for i, v in enumerate(vs):
        assert res[v.name]["mu_star"] == pytest.approx(abs(c[i]) * 2.0, abs=1e-9)
        assert res[v.name]["mu"] == pytest.approx(c[i] * 2.0, abs=1e-9)
        assert res[v.name]["sigma"] == pytest.approx(0.0, abs=1e-9)
    y[7] = np.nan  # trajectory 2 of 12 (rows 5..9) failed
    res = morris_indices(vs, x, y, 4)
    assert res["trajectories_used"] == 11
    assert res["x0"]["mu_star"] == pytest.approx(6.0, abs=1e-9)


def test_quadratic_metamodel_recovers_a_quadratic_and_its_indices():
    """f = x1 + x2² on [0, 1]²: Var(x1) = 1/12, Var(x2²) = 1/5 − 1/9 = 4/45;
    the quadratic fit on 12 LHS designs is exact (LOO R² = 1), and the
    Sobol indices on it are the function's within 10 %."""
    vs = _vars(2, 0.0, 1.0)
    x = to_bounds(unit_points("lhs", 12, 2, seed=4), vs)
    y = x[:, 0] + x[:, 1] ** 2
    m = fit(x, y, [0, 0], [1, 1], "quadratic")
    assert m.loo_r2 == pytest.approx(1.0, abs=1e-9)
    xt = np.random.default_rng(0).random((50, 2))
    assert np.allclose(m.predict(xt), xt[:, 0] + xt[:, 1] ** 2, atol=1e-9)
    assert fit(x, y, [0, 0], [1, 1], "auto").kind == "quadratic"
    v1, v2 = 1 / 12, 4 / 45
    got = sobol_indices(vs, m.predict, n=4096, seed=2)
    assert got["x1"]["S1"] == pytest.approx(v1 / (v1 + v2), rel=0.10)
    assert got["x2"]["ST"] == pytest.approx(v2 / (v1 + v2), rel=0.10)


def test_rbf_interpolates_and_its_loo_error_is_honest():
    vs = _vars(2, -1.0, 1.0)
    x = to_bounds(unit_points("sobol", 32, 2, seed=5), vs)
    y = np.sin(2 * x[:, 0]) * np.cos(x[:, 1])
    m = fit(x, y, [-1, -1], [1, 1], "rbf")
    assert np.allclose(m.predict(x), y, atol=1e-8)  # exact at the designs
    assert 0.9 < m.loo_r2 < 1.0  # but not claimed perfect elsewhere
    with pytest.raises(ValueError, match="at least"):
        fit(x[:3], y[:3], [-1, -1], [1, 1], "quadratic")


@pytest.mark.parametrize("method", ["lhs", "sobol", "halton", "random"])
def test_doe_points_fill_the_bounds_reproducibly(method):
    from crashlite.study.config import DoeSettings

    vs = [Variable("a", 1.0, 2.0, parameter="a"), Variable("n", 1, 5, parameter="n", integer=True)]
    s = DoeSettings(method, 16, seed=7)
    x = doe(s, vs)
    assert x.shape == (16, 2)
    assert np.array_equal(x, doe(s, vs))
    assert np.all((x[:, 0] >= 1.0) & (x[:, 0] <= 2.0))
    assert set(np.unique(x[:, 1])) <= {1.0, 2.0, 3.0, 4.0, 5.0}
    if method == "lhs":  # one point in each of the 16 strata of each variable
        assert sorted(np.floor((x[:, 0] - 1.0) * 16).astype(int)) == list(range(16))
