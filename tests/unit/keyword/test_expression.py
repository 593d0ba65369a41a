"""crashlite.keyword.expression: *PARAMETER_EXPRESSION values, Fortran semantics, errors."""

import math
import re
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from crashlite.keyword import expression
from crashlite.keyword.expression import ExpressionError, evaluate, names_used


def same(got, want):
    """Equal in value and type: int vs float matters for Fortran semantics."""
    return type(got) is type(want) and (got == want or math.isclose(got, want, rel_tol=1e-15))


@pytest.mark.parametrize(
    "expr,want",
    [
        ("1+2*3", 7),
        ("(1+2)*3", 9),
        ("10-4-3", 3),
        ("24/4/3", 2),
        ("2*3+4*5", 26),
        ("1-2+3", 2),
        ("2+3**2*2", 20),
        ("  1 +\t2 ", 3),
    ],
)
def test_precedence_and_left_associativity(expr, want):
    assert same(evaluate(expr, {}), want)


@pytest.mark.parametrize(
    "expr,want",
    [
        ("2**3**2", 512),
        ("2^3^2", 512),
        ("2**3^2", 512),
        ("(2**3)**2", 64),
        ("2**-1", 0.5),
        ("2**-1**2", 0.5),
        ("4**0.5", 2.0),
        ("0**0", 1),
        ("(-2)**3", -8),
        ("(-2.0)**2", 4.0),
    ],
)
def test_power_is_right_associative(expr, want):
    assert same(evaluate(expr, {}), want)


@pytest.mark.parametrize(
    "expr,want",
    [
        ("-2**2", -4),
        ("-2^2", -4),
        ("(-2)**2", 4),
        ("-x**2", -9),
        ("2*-3", -6),
        ("2*-3**2", -18),
        ("-2*3", -6),
        ("+2", 2),
        ("--2", 2),
        ("1 - -1", 2),
        ("-(1+2)", -3),
    ],
)
def test_unary_minus_binds_looser_than_power(expr, want):
    assert same(evaluate(expr, {"x": 3}), want)


@pytest.mark.parametrize(
    "expr,want",
    [
        ("1", 1),
        ("2.5", 2.5),
        (".5", 0.5),
        ("1.", 1.0),
        ("1e-3", 1e-3),
        ("1.0E+3", 1000.0),
        ("1.0d3", 1000.0),
        ("1.5D-2", 0.015),
        ("2d0", 2.0),
        ("7", 7),
    ],
)
def test_number_literals_including_fortran_d_exponent(expr, want):
    assert same(evaluate(expr, {}), want)


@pytest.mark.parametrize(
    "expr,want",
    [
        ("7/2", 3),
        ("-7/2", -3),
        ("7/-2", -3),
        ("-7/-2", 3),
        ("7/2.0", 3.5),
        ("7.0/2", 3.5),
        ("float(7)/2", 3.5),
        ("1+2", 3),
        ("1+2.0", 3.0),
        ("2*3", 6),
        ("2*3.0", 6.0),
        ("2**3", 8),
        ("2.0**3", 8.0),
        ("2**3.0", 8.0),
    ],
)
def test_integer_arithmetic_stays_integer_and_divides_like_fortran(expr, want):
    assert same(evaluate(expr, {}), want)


# function -> (real arguments, integer arguments)
_REAL_FUNCS = {
    "sin": ((0.3,), (2,)),
    "cos": ((0.3,), (2,)),
    "tan": ((0.3,), (2,)),
    "asin": ((0.3,), (1,)),
    "acos": ((0.3,), (-1,)),
    "atan": ((0.3,), (2,)),
    "sinh": ((0.3,), (2,)),
    "cosh": ((0.3,), (2,)),
    "tanh": ((0.3,), (2,)),
    "sqrt": ((2.0,), (4,)),
    "exp": ((0.3,), (2,)),
    "log": ((2.0,), (3,)),
    "log10": ((2.0,), (1000,)),
    "atan2": ((1.0, -2.0), (1, -2)),
}


@pytest.mark.parametrize("fn", sorted(_REAL_FUNCS))
def test_function_matches_math(fn):
    real_args, int_args = _REAL_FUNCS[fn]
    ref = getattr(math, fn)
    assert same(evaluate(f"{fn}({', '.join(map(repr, real_args))})", {}), ref(*real_args))
    # Upper case works, and integer arguments give a real result (sqrt(4) == 2.0).
    assert same(evaluate(f"{fn.upper()}({', '.join(map(str, int_args))})", {}), ref(*map(float, int_args)))


@pytest.mark.parametrize(
    "expr,want",
    [
        # mod: a - int(a/p)*p, sign of a (Python % follows the divisor instead)
        ("mod(7,3)", 1),
        ("mod(-7,3)", -1),
        ("mod(7,-3)", 1),
        ("mod(-7,-3)", -1),
        ("mod(7.5,2)", 1.5),
        ("mod(-7.5,2)", -1.5),
        ("mod(5.5,-2.0)", 1.5),
        # sign(a, b) = |a| with the sign of b
        ("sign(3,-1)", -3),
        ("sign(-3,2)", 3),
        ("sign(-3,0)", 3),
        ("sign(2.5,-1)", -2.5),
        ("sign(-2,3.0)", 2.0),
        # int truncates toward zero to an integer; aint does the same but stays real
        ("int(2.7)", 2),
        ("int(-2.7)", -2),
        ("int(5)", 5),
        ("aint(2.7)", 2.0),
        ("aint(-2.7)", -2.0),
        # nint rounds halves away from zero (Python round() goes to even)
        ("nint(2.5)", 3),
        ("nint(-2.5)", -3),
        ("nint(0.5)", 1),
        ("nint(1.5)", 2),
        ("nint(2.4999)", 2),
        ("nint(-0.4)", 0),
        ("nint(0.49999999999999994)", 0),
        ("nint(4)", 4),
        ("float(3)", 3.0),
        ("abs(-3)", 3),
        ("abs(-2.5)", 2.5),
        ("min(3,1,2)", 1),
        ("max(1,4)", 4),
        ("max(1,4.0)", 4.0),
        ("min(1,4.0)", 1.0),
        ("MAX(-1,-2)", -1),
        ("pi", math.pi),
        ("cos(PI)", -1.0),
    ],
)
def test_fortran_intrinsics(expr, want):
    assert same(evaluate(expr, {}), want)


def test_names_are_case_insensitive_and_ampersand_is_stripped():
    names = {"Thick": 1.5, "N": 4, "sInX": 0.5}
    assert evaluate("&thick*2 + &n", names) == 7.0
    assert evaluate("THICK*n", names) == 6.0
    assert evaluate("sinx", names) == 0.5
    assert same(evaluate("&N/3", names), 1)


def test_defined_pi_overrides_builtin_and_ampersand_name_is_never_a_call():
    assert evaluate("pi*2", {"PI": 3}) == 6
    # &max is the parameter called max, not the function
    assert evaluate("&max + max(1, 2)", {"max": 10}) == 12


def test_name_values_accept_other_number_types():
    import fractions

    # numbers.Integral reads as int (so Fortran division applies), other reals as float
    assert same(evaluate("a/2", {"a": True}), 0)
    assert same(evaluate("a*2", {"a": fractions.Fraction(1, 4)}), 0.5)


def test_names_used():
    assert names_used("a*sin(&B)+c") == {"a", "b", "c"}
    assert names_used("&MAX + max(x, Y)") == {"max", "x", "y"}
    assert names_used("2*pi") == {"pi"}
    assert names_used("1+2") == set()
    assert names_used("max (a, b)") == {"a", "b"}  # blank before '(' still a call


@pytest.mark.parametrize(
    "expr,position,message",
    [
        # syntax
        ("", 0, "empty expression"),
        ("   ", 3, "empty expression"),
        ("1+*2", 2, "unexpected '*'"),
        ("1+", 2, "expression ends"),
        ("1 2", 2, "unexpected number '2'"),
        ("a b", 2, "unexpected name 'b'"),
        ("(1+2", 4, "expected ')' to close '(' at position 0"),
        ("1+2)", 3, "unexpected ')'"),
        ("max(1,)", 6, "unexpected ')'"),
        ("max(1,,2)", 6, "unexpected ','"),
        ("max(1 2)", 6, "expected ')'"),
        ("1,2", 1, "unexpected ','"),
        ("1 $ 2", 2, "unexpected character '$'"),
        ("& x", 0, "unexpected character '&'"),
        ("1.2.3", 0, "malformed number '1.2.3'"),
        ("2x", 0, "malformed number '2x'"),
        ("x+1e", 2, "malformed number '1e'"),
        ("1e999", 0, "out of range"),
        ("&a(1)", 2, "unexpected '('"),
        ("(" * 200 + "1" + ")" * 200, 100, "nested too deeply"),
        # names and functions
        ("1 + xyz", 4, "undefined parameter 'xyz'"),
        ("1 + &XYZ", 4, "undefined parameter 'xyz'"),
        ("2*Foo(1)", 2, "unknown function 'foo'"),
        ("__import__(os)", 0, "unknown function '__import__'"),
        ("1+sin()", 2, "sin() takes 1 argument, got 0"),
        ("atan2(1)", 0, "atan2() takes 2 arguments, got 1"),
        ("log(8, 2)", 0, "log() takes 1 argument, got 2"),
        ("max(1)", 0, "max() takes at least 2 arguments, got 1"),
        ("2*s", 2, "parameter 's' holds text 'steel'"),
        ("s", 0, "holds text"),
        # arithmetic
        ("1/0", 1, "division by zero"),
        ("1.0 / (2-2)", 4, "division by zero"),
        ("mod(5, 0)", 0, "division by zero in mod()"),
        ("0**-1", 1, "division by zero"),
        ("sqrt(-1)", 0, "sqrt(-1)"),
        ("1 + log(0)", 4, "log(0)"),
        ("asin(2)", 0, "domain"),
        ("(-8)**(1.0/3)", 4, "negative base"),
        ("exp(1000)", 0, "exp(1000)"),
        ("1e308*10", 5, "not a finite number"),
        ("10.0**400", 4, "overflow"),
        ("10**400*1.0", 7, "overflow"),
        ("2**100000", 1, "too large"),
        ("int(1e308*1e308)", 9, "not a finite number"),
    ],
)
def test_errors_carry_message_and_position(expr, position, message):
    with pytest.raises(ExpressionError) as info:
        evaluate(expr, {"s": "steel"})
    err = info.value
    assert message in err.message
    assert err.position == position
    assert err.expression == expr
    assert isinstance(err, ValueError)
    assert f"position {position}" in str(err) and message in str(err)


def test_syntax_error_reported_before_arithmetic_error():
    with pytest.raises(ExpressionError, match="expression ends"):
        evaluate("1/0 +", {})


def test_names_used_rejects_what_is_wrong_without_values():
    with pytest.raises(ExpressionError) as info:
        names_used("a + foo(b)")
    assert info.value.position == 4
    assert names_used("1/0 + undefined") == {"undefined"}  # needs values to fail


def test_module_never_uses_python_evaluation():
    """Deck text is untrusted: no eval/exec/compile/ast anywhere in the evaluator."""
    src = Path(expression.__file__).read_text()
    assert not re.search(r"(?<![.\w])(eval|exec|compile)\s*\(", src)
    assert not re.search(r"^\s*(import|from)\s+ast\b", src, re.MULTILINE)


# ---------------------------------------------------------------- property test
# Expressions are built as trees of non-negative float literals and rendered
# with the fewest parentheses precedence allows; the expected value is computed
# alongside with Python floats in the same tree order, so the evaluator must
# agree exactly.

_PREC = {"+": 1, "-": 1, "*": 2, "/": 2, "neg": 3, "**": 4, "atom": 5}


def _literal(x: float, letter: str) -> str:
    return repr(x).replace("e", letter)


leaves = st.builds(
    lambda x, letter: (_literal(x, letter), _PREC["atom"], x),
    st.floats(min_value=0, max_value=1e6, allow_nan=False, allow_infinity=False),
    st.sampled_from("eEdD"),
)


def _wrap(node, need):
    return f"({node[0]})" if need else node[0]


def _binary(args):
    (a, b, op, spaced) = args
    va, vb = a[2], b[2]
    try:
        value = {
            "+": lambda: va + vb,
            "-": lambda: va - vb,
            "*": lambda: va * vb,
            "/": lambda: va / vb,
            "**": lambda: va**vb,
        }[op]()
    except (ZeroDivisionError, OverflowError):
        return None
    if isinstance(value, complex) or not math.isfinite(value):
        return None
    p = _PREC[op]
    if op == "**":  # right-associative: only the left operand needs parens at equal precedence
        left, right = _wrap(a, a[1] <= p), _wrap(b, b[1] < p)
    else:  # left-associative; floats are not associative, so a+(b+c) keeps its parens
        left, right = _wrap(a, a[1] < p), _wrap(b, b[1] <= p)
    sym = "^" if op == "**" and spaced == 2 else op
    sep = " " if spaced else ""
    return f"{left}{sep}{sym}{sep}{right}", p, value


def _negate(a):
    return "-" + _wrap(a, a[1] < _PREC["neg"]), _PREC["neg"], -a[2]


def _parens(a):
    return f"({a[0]})", _PREC["atom"], a[2]


def _extend(children):
    binary = (
        st.tuples(children, children, st.sampled_from(["+", "-", "*", "/", "**"]), st.integers(0, 2))
        .map(_binary)
        .filter(lambda n: n is not None)
    )
    return st.one_of(binary, children.map(_negate), children.map(_parens))


arithmetic = st.recursive(leaves, _extend, max_leaves=12)


@settings(max_examples=300, deadline=None)
@given(arithmetic)
def test_random_float_expressions_match_reference(case):
    text, _, want = case
    got = evaluate(text, {})
    assert type(got) is float
    assert got == want, text
