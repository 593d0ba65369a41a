"""The *PARAMETER_EXPRESSION evaluator: Fortran semantics, errors with position."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from crashlite.keyword.expr import ExpressionError, evaluate, names_used


@pytest.mark.parametrize("expr,value", [
    ("1+2*3", 7), ("(1+2)*3", 9), ("2**3**2", 512), ("2^3^2", 512), ("-2**2", -4),
    ("2**-1", 0.5), ("7/2", 3), ("-7/2", -3), ("7/2.0", 3.5), ("mod(-7,3)", -1), ("mod(7.5,2)", 1.5),
    ("sign(3,-1)", -3), ("sign(-3,2)", 3), ("int(-2.7)", -2), ("aint(2.7)", 2.0), ("nint(2.5)", 3),
    ("nint(-2.5)", -3), ("1.5d2", 150.0), (".5e1", 5.0), ("min(3,1,2)", 1), ("max(1,4)", 4),
    ("atan2(1,1)", math.pi / 4), ("log10(1000)", 3.0), ("sqrt(16)", 4.0), ("abs(-3)", 3),
    ("float(3)/2", 1.5), ("pi", math.pi),
])
def test_values(expr, value):
    got = evaluate(expr, {})
    assert got == pytest.approx(value, rel=1e-15) and type(got) is type(value)


@pytest.mark.parametrize("fn", ["sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "exp", "log"])
def test_functions_match_math(fn):
    assert evaluate(f"{fn}(0.3)", {}) == getattr(math, fn)(0.3)


def test_names_case_insensitive_with_ampersand():
    assert evaluate("&Thick*2 + T", {"thick": 1.5, "t": 1}) == 4.0
    assert names_used("a*sin(&B)+c") == {"a", "b", "c"}


@pytest.mark.parametrize("expr,msg,pos", [
    ("1+*2", "unexpected '*'", 2), ("foo(1)", "unknown function 'foo'", 0),
    ("x+1", "undefined parameter 'x'", 0), ("1/0", "division by zero", 1),
    ("sqrt(-1)", "undefined for", 0), ("(1+2", "missing ')'", 4), ("1 $ 2", "unexpected character", 2),
    ("atan2(1)", "takes 2 argument", 0), ("s*2", "is text", 0), ("", "empty", 0),
])
def test_errors(expr, msg, pos):
    with pytest.raises(ExpressionError) as e:
        evaluate(expr, {"s": "steel"})
    assert msg in str(e.value) and e.value.position == pos


@st.composite
def arithmetic(draw, depth=3):
    """(expression text, expected value) built together."""
    if depth == 0 or draw(st.booleans()):
        v = draw(st.floats(min_value=-1e3, max_value=1e3, allow_nan=False).filter(lambda x: x != 0))
        return f"({v!r})", v
    a, va = draw(arithmetic(depth=depth - 1))
    b, vb = draw(arithmetic(depth=depth - 1))
    op = draw(st.sampled_from("+-*/"))
    value = {"+": va + vb, "-": va - vb, "*": va * vb, "/": va / vb if vb else None}[op]
    if value is None or not math.isfinite(value) or value == 0:
        return a, va
    return f"({a}{op}{b})", value


@settings(max_examples=200, deadline=None)
@given(arithmetic())
def test_random_arithmetic(case):
    text, value = case
    assert evaluate(text, {}) == value
