"""Safe evaluator for LS-DYNA *PARAMETER_EXPRESSION text.

Deck text is untrusted, so it is never handed to Python ``eval``/``exec``/
``compile`` or ``ast``: a small tokenizer feeds a Pratt (precedence-climbing)
parser that computes the value as it goes.

Grammar (LS-DYNA follows Fortran):

* numbers ``1``, ``2.5``, ``.5``, ``1.``, ``1e-3``, ``1.0E+3`` and the Fortran
  double-precision exponent ``1.0d3``; digits alone are integers, anything
  with a point or exponent is real;
* names ``[A-Za-z_][A-Za-z0-9_]*``, optionally written ``&name``; looked up
  case-insensitively; ``pi`` is built in unless the deck defines it;
* binary ``+ - * /`` (left-associative), power ``**`` or ``^``
  (right-associative and binding tighter than unary minus, so
  ``-2**2 == -4`` and ``2**3**2 == 512``), unary ``+ -``, parentheses;
* function calls ``f(a, b, ...)``; function names are case-insensitive and a
  name followed by ``(`` is always a call unless written with ``&``.

Types: ``+ - *`` of two integers, and an integer to a non-negative integer
power, stay integers. ``/`` of two integers is Fortran integer division,
truncating toward zero (``7/2 == 3``, ``-7/2 == -3``), because that is what
LS-DYNA computes; write ``7/2.0`` or ``float(7)/2`` for 3.5. An integer to a
negative integer power is real (``2**-1 == 0.5``; strict Fortran would give
0). Everything else is real.

Functions: sin cos tan asin acos atan atan2 sinh cosh tanh sqrt exp log
(natural) log10 abs min max (two or more arguments) and the Fortran
intrinsics ``sign(a, b)`` (``|a|`` with the sign of ``b``), ``mod(a, p)``
(``a - int(a/p)*p``: sign of ``a``), ``int`` (truncate to an integer),
``aint`` (truncate, real result), ``nint`` (nearest integer, halves away from
zero) and ``float``.

Every failure raises :class:`ExpressionError` with the 0-based character
offset of the offending token. The whole text is parsed before anything is
computed, so a syntax error is reported in preference to, e.g., a division
by zero earlier in the text.
"""

from __future__ import annotations

import math
import numbers
import re
from collections.abc import Callable, Mapping
from typing import NamedTuple

Number = int | float

__all__ = ["ExpressionError", "evaluate", "names_used"]

#: Deeper nesting than this is refused rather than risking RecursionError.
MAX_DEPTH = 100
#: Integer results (powers checked before computing) past this many bits are
#: refused, so ``9**9**9`` or a chain of squares fails fast instead of tying
#: up the reader.
MAX_INT_BITS = 4096


class ExpressionError(ValueError):
    """A *PARAMETER_EXPRESSION could not be evaluated.

    ``expression`` is the full text, ``position`` the 0-based offset of the
    offending character or token (``len(expression)`` when the text ended
    too early) and ``message`` the reason without location.
    """

    def __init__(self, message: str, expression: str, position: int):
        self.message = message
        self.expression = expression
        self.position = position
        super().__init__(f"{message} at position {position} in expression {expression!r}")


# ---------------------------------------------------------------- tokenizer


class _Tok(NamedTuple):
    kind: str  # "num", "name", "op" or "end"
    text: str  # for names: lower-cased, "&" stripped
    pos: int
    value: Number | None = None
    amp: bool = False  # name written as &name: never a function call


_SCAN = re.compile(
    r"(?P<num>(?:\d+\.?\d*|\.\d+)(?:[eEdD][+-]?\d+)?)"
    r"|(?P<name>&?[A-Za-z_][A-Za-z0-9_]*)"
    r"|(?P<op>\*\*|[-+*/^(),])"
)
# A number running straight into letters, digits or a point (``1.2.3``,
# ``2x``, ``1e``) is a typo, better reported as such than as two tokens.
_NUM_TAIL = re.compile(r"[A-Za-z0-9_.]")
_D_TO_E = str.maketrans("dD", "eE")


def _tokenize(expr: str) -> list[_Tok]:
    toks: list[_Tok] = []
    pos, n = 0, len(expr)
    while True:
        while pos < n and expr[pos] in " \t\f\v":  # ASCII: a no-break space is an error
            pos += 1
        if pos >= n:
            toks.append(_Tok("end", "", n))
            return toks
        m = _SCAN.match(expr, pos)
        if m is None:
            raise ExpressionError(f"unexpected character {expr[pos]!r}", expr, pos)
        kind, text = m.lastgroup, m.group()
        if kind == "num":
            if m.end() < n and _NUM_TAIL.match(expr, m.end()):
                end = m.end()
                while end < n and _NUM_TAIL.match(expr, end):
                    end += 1
                raise ExpressionError(f"malformed number {expr[pos:end]!r}", expr, pos)
            real = any(c in text for c in ".eEdD")
            shown = text if len(text) <= 40 else f"{text[:20]}... ({len(text)} characters)"
            if real:
                value = float(text.translate(_D_TO_E))
                if not math.isfinite(value):
                    raise ExpressionError(f"number {shown!r} is out of range", expr, pos)
            else:  # digits alone: an integer, held to MAX_INT_BITS as any result
                if len(text) > MAX_INT_BITS // 3 or int(text).bit_length() > MAX_INT_BITS:
                    raise ExpressionError(f"integer {shown!r} is too large (more than {MAX_INT_BITS} bits)", expr, pos)
                value = int(text)
            toks.append(_Tok("num", text, pos, value))
        elif kind == "name":
            amp = text.startswith("&")
            toks.append(_Tok("name", text.lstrip("&").lower(), pos, amp=amp))
        else:
            toks.append(_Tok("op", text, pos))
        pos = m.end()


# ---------------------------------------------------------------- functions


def _trunc_div(a: int, b: int) -> int:
    """Fortran integer division (Python's // floors instead)."""
    q = abs(a) // abs(b)
    return q if (a < 0) == (b < 0) else -q


def _mod(a: Number, p: Number) -> Number:
    if p == 0:
        raise ZeroDivisionError
    if isinstance(a, int) and isinstance(p, int):
        return a - _trunc_div(a, p) * p
    return math.fmod(a, p)  # exact, with the sign of a, as Fortran MOD


def _sign(a: Number, b: Number) -> Number:
    if isinstance(a, int) and isinstance(b, int):
        return abs(a) if b >= 0 else -abs(a)
    return math.copysign(abs(float(a)), float(b))


def _int(x: Number) -> int:
    return math.trunc(x)


def _aint(x: Number) -> float:
    return float(math.trunc(x))


def _nint(x: Number) -> int:
    if isinstance(x, int):
        return x
    # x - trunc(x) is exact in binary floating point; floor(|x| + 0.5) is
    # not (0.49999999999999994 + 0.5 rounds up to 1.0).
    whole = math.trunc(x)
    frac = x - whole
    if frac >= 0.5:
        whole += 1
    elif frac <= -0.5:
        whole -= 1
    return whole


def _minmax(pick: Callable[..., Number]) -> Callable[..., Number]:
    def f(*args: Number) -> Number:
        v = pick(args)
        # Mixed integer/real arguments give a real, as any other operation.
        return v if all(isinstance(a, int) for a in args) else float(v)

    return f


def _real(fn: Callable[..., float]) -> Callable[..., float]:
    return lambda *args: fn(*(float(a) for a in args))


# name -> (minimum args, maximum args or None for unlimited, implementation)
_FUNCS: dict[str, tuple[int, int | None, Callable[..., Number]]] = {
    **{
        name: (1, 1, _real(getattr(math, name)))
        for name in ("sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "sqrt", "exp", "log10")
    },
    "log": (1, 1, _real(math.log)),  # wrapped so that log(x, base) is refused
    "atan2": (2, 2, _real(math.atan2)),
    "abs": (1, 1, abs),
    "min": (2, None, _minmax(min)),
    "max": (2, None, _minmax(max)),
    "sign": (2, 2, _sign),
    "mod": (2, 2, _mod),
    "int": (1, 1, _int),
    "aint": (1, 1, _aint),
    "nint": (1, 1, _nint),
    "float": (1, 1, float),
}


# ---------------------------------------------------------------- semantics
# The parser is written once and driven by one of two action sets: one that
# only collects names (names_used, and the syntax check before evaluating)
# and one that computes.


class _Names:
    def __init__(self) -> None:
        self.found: set[str] = set()

    def num(self, tok: _Tok) -> None:
        return None

    def name(self, tok: _Tok) -> None:
        self.found.add(tok.text)

    def unary(self, tok: _Tok, v: None) -> None:
        return None

    def binary(self, tok: _Tok, a: None, b: None) -> None:
        return None

    def call(self, tok: _Tok, args: list) -> None:
        return None


class _Compute:
    def __init__(self, expr: str, names: Mapping[str, Number | str]):
        self.expr = expr
        self.names = {str(k).lower(): v for k, v in names.items()}

    def fail(self, message: str, pos: int) -> ExpressionError:
        return ExpressionError(message, self.expr, pos)

    def finite(self, v: Number, pos: int) -> Number:
        # inf/nan would otherwise flow silently into the deck's numbers.
        if isinstance(v, float) and not math.isfinite(v):
            raise self.fail("result is not a finite number (overflow)", pos)
        return v

    def num(self, tok: _Tok) -> Number:
        return tok.value

    def name(self, tok: _Tok) -> Number:
        if tok.text not in self.names:
            if tok.text == "pi":
                return math.pi
            raise self.fail(f"undefined parameter '{tok.text}'", tok.pos)
        v = self.names[tok.text]
        if isinstance(v, str):
            raise self.fail(f"parameter '{tok.text}' holds text {v!r}, not a number", tok.pos)
        if isinstance(v, numbers.Integral):
            return int(v)
        if isinstance(v, numbers.Real):
            return float(v)
        raise self.fail(f"parameter '{tok.text}' is not a number ({type(v).__name__})", tok.pos)

    def unary(self, tok: _Tok, v: Number) -> Number:
        return -v if tok.text == "-" else v

    def binary(self, tok: _Tok, a: Number, b: Number) -> Number:
        op, pos = tok.text, tok.pos
        try:
            if op == "+":
                r = a + b
            elif op == "-":
                r = a - b
            elif op == "*":
                r = a * b
            elif op == "/":
                if b == 0:
                    raise self.fail("division by zero", pos)
                both_int = isinstance(a, int) and isinstance(b, int)
                r = _trunc_div(a, b) if both_int else a / b
            else:
                r = self.power(a, b, pos)
        except OverflowError:  # an integer too large to become a float
            raise self.fail("numeric overflow", pos) from None
        if isinstance(r, int) and r.bit_length() > MAX_INT_BITS:
            # a chain a = 2**4000, b = a*a, c = b*b, ... would double its
            # size (and time) at every step
            raise self.fail(f"integer result is too large (more than {MAX_INT_BITS} bits)", pos)
        return self.finite(r, pos)

    def power(self, a: Number, b: Number, pos: int) -> Number:
        if isinstance(a, int) and isinstance(b, int) and b >= 0:
            # b*(bit_length-1) is a lower bound on the result's bit count.
            if b * (abs(a).bit_length() - 1) > MAX_INT_BITS:
                raise self.fail("integer power is too large", pos)
            return a**b
        if a == 0 and b < 0:
            raise self.fail("division by zero (zero to a negative power)", pos)
        try:
            # math.pow, not **: a negative base to a fractional power must
            # fail, not turn complex.
            return math.pow(a, b)
        except ValueError:
            raise self.fail(f"negative base {a!r} to the non-integer power {b!r}", pos) from None

    def call(self, tok: _Tok, args: list[Number]) -> Number:
        fn = _FUNCS[tok.text][2]
        try:
            r = fn(*args)
        except ZeroDivisionError:
            raise self.fail(f"division by zero in {tok.text}()", tok.pos) from None
        except (ValueError, OverflowError):
            shown = ", ".join(repr(a) for a in args)
            raise self.fail(f"{tok.text}({shown}) is outside the function's domain or range", tok.pos) from None
        return self.finite(r, tok.pos)


# ---------------------------------------------------------------- parser

# Left binding powers. Unary minus sits between * and **, so -2**2 == -(2**2)
# but -2*3 == (-2)*3.
_BP = {"+": 10, "-": 10, "*": 20, "/": 20, "**": 40, "^": 40}
_UNARY_BP = 30
_RIGHT_ASSOC = {"**", "^"}


def _describe(tok: _Tok) -> str:
    if tok.kind == "end":
        return "end of expression"
    if tok.kind == "num":
        return f"number {tok.text!r}"
    if tok.kind == "name":
        return f"name '{tok.text}'"
    return repr(tok.text)


class _Parser:
    def __init__(self, expr: str, toks: list[_Tok], act):
        self.expr, self.toks, self.act = expr, toks, act
        self.i = 0
        self.depth = 0

    def peek(self) -> _Tok:
        return self.toks[self.i]

    def next(self) -> _Tok:
        tok = self.toks[self.i]
        if tok.kind != "end":
            self.i += 1
        return tok

    def fail(self, message: str, pos: int) -> ExpressionError:
        return ExpressionError(message, self.expr, pos)

    def parse(self):
        if self.peek().kind == "end":
            raise self.fail("empty expression", len(self.expr))
        v = self.expression(0)
        tok = self.peek()
        if tok.kind != "end":
            raise self.fail(f"unexpected {_describe(tok)}", tok.pos)
        return v

    def expression(self, rbp: int):
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise self.fail("expression is nested too deeply", self.peek().pos)
        left = self.prefix(self.next())
        while True:
            tok = self.peek()
            lbp = _BP.get(tok.text, 0) if tok.kind == "op" else 0
            if lbp <= rbp:
                break
            self.next()
            right = self.expression(lbp - 1 if tok.text in _RIGHT_ASSOC else lbp)
            left = self.act.binary(tok, left, right)
        self.depth -= 1
        return left

    def prefix(self, tok: _Tok):
        if tok.kind == "num":
            return self.act.num(tok)
        if tok.kind == "name":
            if not tok.amp and self.peek().text == "(" and self.peek().kind == "op":
                return self.call(tok)
            return self.act.name(tok)
        if tok.text in ("-", "+"):
            return self.act.unary(tok, self.expression(_UNARY_BP))
        if tok.text == "(":
            v = self.expression(0)
            self.close(tok)
            return v
        if tok.kind == "end":
            raise self.fail("expression ends where a value was expected", tok.pos)
        raise self.fail(f"unexpected {_describe(tok)}", tok.pos)

    def close(self, opening: _Tok) -> None:
        tok = self.next()
        if tok.text != ")" or tok.kind != "op":
            raise self.fail(f"expected ')' to close '(' at position {opening.pos}, found {_describe(tok)}", tok.pos)

    def call(self, name: _Tok):
        # Checked before the arguments are parsed so the error points at the
        # function name even when the arguments are also wrong.
        if name.text not in _FUNCS:
            raise self.fail(f"unknown function '{name.text}'", name.pos)
        opening = self.next()
        args = []
        if self.peek().text != ")":
            args.append(self.expression(0))
            while self.peek().text == "," and self.peek().kind == "op":
                self.next()
                args.append(self.expression(0))
        self.close(opening)
        lo, hi, _ = _FUNCS[name.text]
        if len(args) < lo or (hi is not None and len(args) > hi):
            want = f"at least {lo}" if hi is None else str(lo)
            plural = "" if want == "1" else "s"
            raise self.fail(f"{name.text}() takes {want} argument{plural}, got {len(args)}", name.pos)
        return self.act.call(name, args)


# ---------------------------------------------------------------- public API


def names_used(expr: str) -> set[str]:
    """Lower-cased parameter names referenced by ``expr`` (function names excluded).

    Used to order parameter evaluation. ``pi`` is included when referenced,
    since a deck may define it; callers ignore names they do not define.
    Raises :class:`ExpressionError` for anything wrong that is visible
    without values: syntax, unknown functions, argument counts.
    """
    act = _Names()
    _Parser(expr, _tokenize(expr), act).parse()
    return act.found


def evaluate(expr: str, names: Mapping[str, Number | str]) -> Number:
    """Value of ``expr``, with ``names`` mapping parameter names (any case) to values.

    Integer operands give integer results for ``+ - *``, ``/`` (Fortran
    division, truncating toward zero) and non-negative integer powers; see
    the module docstring for the full rules. Raises :class:`ExpressionError`.
    """
    toks = _tokenize(expr)
    _Parser(expr, toks, _Names()).parse()  # every syntax error before any arithmetic error
    return _Parser(expr, toks, _Compute(expr, names)).parse()
