"""Safe evaluation of *PARAMETER_EXPRESSION text (never Python ``eval``).

A tokenizer and a precedence-climbing parser over numbers, names, + - * /,
``**`` and ``^`` (power, right-associative, binding tighter than unary
minus: ``-2**2 == -4``), parentheses and a fixed set of functions. Integer
arithmetic follows Fortran, as LS-DYNA does: ``7/2 == 3`` and ``-7/2 == -3``
when both operands are integers; ``mod`` takes the sign of its first
argument, ``sign(a, b)`` is ``|a|`` with the sign of ``b``.
"""

from __future__ import annotations

import math
import re
from typing import Mapping

Number = int | float


class ExpressionError(ValueError):
    def __init__(self, message: str, expression: str, position: int):
        self.expression = expression
        self.position = position
        super().__init__(f"{message} in expression {expression.strip()!r} at character {position + 1}")


_TOKEN = re.compile(
    r"\s*(?:(?P<num>(?:\d+\.?\d*|\.\d+)(?:[eEdD][+-]?\d+)?)"
    r"|(?P<name>&?[A-Za-z_][A-Za-z0-9_]*)"
    r"|(?P<op>\*\*|[-+*/^(),]))"
)


def _tokens(expr: str):
    pos = 0
    out = []
    while pos < len(expr):
        if expr[pos:].strip() == "":
            break
        m = _TOKEN.match(expr, pos)
        if not m or m.end() == pos:
            p = pos + (len(expr[pos:]) - len(expr[pos:].lstrip()))
            raise ExpressionError(f"unexpected character {expr[p]!r}", expr, p)
        kind = m.lastgroup
        start = m.start(kind)
        out.append((kind, m.group(kind), start))
        pos = m.end()
    out.append(("end", "", len(expr)))
    return out


def _fint(x: Number) -> int:
    return int(math.trunc(x))


def _nint(x: Number) -> int:
    return int(math.floor(abs(x) + 0.5)) * (1 if x >= 0 else -1)


def _idiv(a: int, b: int) -> int:
    """Fortran integer division: truncates toward zero."""
    q = abs(a) // abs(b)
    return q if (a >= 0) == (b >= 0) else -q


def _mod(a: Number, b: Number) -> Number:
    if b == 0:
        raise ZeroDivisionError
    if isinstance(a, int) and isinstance(b, int):
        return a - _idiv(a, b) * b
    return math.fmod(a, b)


def _sign(a: Number, b: Number) -> Number:
    return abs(a) if b >= 0 else -abs(a)


_FUNCS = {
    "sin": (1, math.sin), "cos": (1, math.cos), "tan": (1, math.tan),
    "asin": (1, math.asin), "acos": (1, math.acos), "atan": (1, math.atan),
    "atan2": (2, math.atan2), "sinh": (1, math.sinh), "cosh": (1, math.cosh),
    "tanh": (1, math.tanh), "sqrt": (1, math.sqrt), "exp": (1, math.exp),
    "log": (1, math.log), "log10": (1, math.log10), "abs": (1, abs),
    "min": (-2, min), "max": (-2, max), "sign": (2, _sign), "mod": (2, _mod),
    "int": (1, _fint), "aint": (1, lambda x: float(math.trunc(x))), "nint": (1, _nint),
    "float": (1, float),
}


class _Parser:
    def __init__(self, expr: str, names: Mapping[str, Number | str]):
        self.expr = expr
        self.toks = _tokens(expr)
        self.i = 0
        self.names = {str(k).lower(): v for k, v in names.items()}

    def peek(self):
        return self.toks[self.i]

    def take(self):
        t = self.toks[self.i]
        self.i += 1
        return t

    def fail(self, msg, pos=None):
        raise ExpressionError(msg, self.expr, self.peek()[2] if pos is None else pos)

    def parse(self) -> Number:
        if self.peek()[0] == "end":
            self.fail("empty expression")
        v = self.additive()
        if self.peek()[0] != "end":
            self.fail(f"unexpected {self.peek()[1]!r}")
        return v

    def additive(self) -> Number:
        v = self.term()
        while self.peek()[1] in ("+", "-") and self.peek()[0] == "op":
            op = self.take()[1]
            w = self.term()
            v = v + w if op == "+" else v - w
        return v

    def term(self) -> Number:
        v = self.unary()
        while self.peek()[1] in ("*", "/") and self.peek()[0] == "op":
            _, op, pos = self.take()
            w = self.unary()
            if op == "*":
                v = v * w
            else:
                if w == 0:
                    raise ExpressionError("division by zero", self.expr, pos)
                v = _idiv(v, w) if isinstance(v, int) and isinstance(w, int) else v / w
        return v

    def unary(self) -> Number:
        if self.peek()[0] == "op" and self.peek()[1] in ("+", "-"):
            op = self.take()[1]
            v = self.unary()
            return -v if op == "-" else v
        return self.power()

    def power(self) -> Number:
        base = self.atom()
        if self.peek()[0] == "op" and self.peek()[1] in ("**", "^"):
            pos = self.take()[2]
            exp = self.unary()  # right-associative; allows 2**-1
            try:
                if isinstance(base, int) and isinstance(exp, int) and exp >= 0:
                    return base**exp
                r = float(base) ** float(exp)
            except (OverflowError, ZeroDivisionError):
                raise ExpressionError("power out of range", self.expr, pos) from None
            if isinstance(r, complex):
                raise ExpressionError("negative base with a fractional power", self.expr, pos)
            return r
        return base

    def atom(self) -> Number:
        kind, text, pos = self.take()
        if kind == "num":
            t = text.replace("d", "e").replace("D", "E")
            return float(t) if any(c in t for c in ".eE") else int(t)
        if kind == "name":
            name = text.lstrip("&").lower()
            if self.peek()[1] == "(" and not text.startswith("&"):
                return self.call(name, pos)
            if name in self.names:
                v = self.names[name]
                if isinstance(v, str):
                    raise ExpressionError(f"parameter '{name}' is text ({v!r}), a number is needed",
                                          self.expr, pos)
                return v
            if name == "pi":
                return math.pi
            raise ExpressionError(f"undefined parameter '{name}'", self.expr, pos)
        if text == "(":
            v = self.additive()
            if self.peek()[1] != ")":
                self.fail("missing ')'")
            self.take()
            return v
        raise ExpressionError(f"unexpected {text!r}" if text else "expression ends early", self.expr, pos)

    def call(self, name: str, pos: int) -> Number:
        if name not in _FUNCS:
            raise ExpressionError(f"unknown function '{name}'", self.expr, pos)
        self.take()  # (
        args = []
        if self.peek()[1] != ")":
            args.append(self.additive())
            while self.peek()[1] == ",":
                self.take()
                args.append(self.additive())
        if self.peek()[1] != ")":
            self.fail("missing ')' after function arguments")
        self.take()
        n, fn = _FUNCS[name]
        if (n > 0 and len(args) != n) or (n < 0 and len(args) < -n):
            want = f"{n}" if n > 0 else f"at least {-n}"
            raise ExpressionError(f"{name}() takes {want} argument(s), got {len(args)}", self.expr, pos)
        try:
            return fn(*args)
        except (ValueError, OverflowError, ZeroDivisionError):
            raise ExpressionError(f"{name}() is undefined for {', '.join(map(repr, args))}",
                                  self.expr, pos) from None


def evaluate(expr: str, names: Mapping[str, Number | str]) -> Number:
    """Value of ``expr``; ``names`` maps parameter names (any case) to values."""
    return _Parser(expr, names).parse()


def names_used(expr: str) -> set[str]:
    """Lower-case parameter names referenced by ``expr`` (not function names)."""
    toks = _tokens(expr)
    out = set()
    for k, (kind, text, _) in enumerate(toks):
        if kind == "name":
            nxt = toks[k + 1][1] if k + 1 < len(toks) else ""
            if text.startswith("&") or nxt != "(":
                out.add(text.lstrip("&").lower())
    return out
