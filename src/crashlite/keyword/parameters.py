"""*PARAMETER, *PARAMETER_EXPRESSION and their _LOCAL forms.

Parameters are evaluated in input order (includes expanded), so a parameter
may use those defined before it. _LOCAL parameters are visible in their file
and the files it includes; the others are global.
"""

from __future__ import annotations

from dataclasses import dataclass

from .cards import BLANKS, INT_MAX, INT_MIN, LONG
from .errors import Collector
from .lexer import Block


@dataclass
class Parameter:
    name: str  # as written (case kept)
    type: str  # "R", "I" or "C"
    value: int | float | str
    expression: str | None = None  # for *PARAMETER_EXPRESSION
    local: bool = False
    source: tuple[str, int] | None = None


PARAMETER_KEYWORDS = (
    "PARAMETER",
    "PARAMETER_LOCAL",
    "PARAMETER_EXPRESSION",
    "PARAMETER_EXPRESSION_LOCAL",
    "PARAMETER_DUPLICATION",
)


class ParameterTable:
    def __init__(self, scopes: list[int]):
        self.scopes = scopes
        self.global_: dict[str, int | float | str] = {}
        self.local: dict[int, dict[str, int | float | str]] = {}
        self.defined: list[Parameter] = []

    def visible(self, scope: int) -> dict:
        """Lower-case name -> value as seen from a file scope."""
        chain = []
        s = scope
        while s >= 0:
            chain.append(s)
            s = self.scopes[s]
        out = dict(self.global_)
        for s in reversed(chain):
            out.update(self.local.get(s, {}))
        return out

    def define(self, p: Parameter, scope: int) -> None:
        target = self.local.setdefault(scope, {}) if p.local else self.global_
        target[p.name.lower()] = p.value
        self.defined.append(p)

    def process(self, blk: Block, problems: Collector) -> None:
        kw = blk.keyword
        if kw == "PARAMETER_DUPLICATION":
            return  # redefinition is allowed; the last definition wins
        local = kw.endswith("_LOCAL")
        expr = kw.startswith("PARAMETER_EXPRESSION")
        w = 20 if blk.mode == LONG else 10
        for j in range(len(blk.data)):
            line = blk.text(j)
            if not line.strip():
                continue
            lineno = blk.line_no(j)
            if expr:
                # free format: a comma after the name; a comma inside a
                # fixed-format expression (max(a, b)) comes after a '('
                if "," in line and "(" not in line.partition(",")[0]:
                    head, _, text = line.partition(",")
                else:
                    head, text = line[:w], line[w:]
                pairs = [(head, text)]
            elif "," in line:
                toks = [t.strip(BLANKS) for t in line.split(",")]
                pairs = list(zip(toks[0::2], toks[1::2]))
            else:
                pairs = [(line[i : i + w], line[i + w : i + 2 * w]) for i in range(0, len(line), 2 * w)]
            for head, text in pairs:
                head = head.strip(BLANKS)
                if not head:
                    continue
                t, name = head[0].upper(), head[1:].strip(BLANKS)
                if t not in "RIC" or not name:
                    problems.error(
                        blk.file,
                        lineno,
                        kw,
                        "PRMR",
                        f"expected a type letter R, I or C followed by a name, got {head!r}",
                    )
                    continue
                value = self._value(t, text.strip(BLANKS), expr, blk.scope, problems, (blk.file, lineno, kw))
                if value is None:
                    continue
                self.define(
                    Parameter(name, t, value, text.strip(BLANKS) if expr else None, local, (blk.file, lineno)),
                    blk.scope,
                )

    def _value(self, t, text, expr, scope, problems, where):
        file, lineno, kw = where
        if t == "C":
            return text
        if not text:
            problems.error(file, lineno, kw, "VAL", "parameter has no value")
            return None
        from .expression import ExpressionError, evaluate

        try:
            if expr or text.lstrip("-").startswith("&"):
                v = evaluate(text, self.visible(scope))
            else:
                from .cards import to_number

                v = to_number(text, "f")
        except (ExpressionError, ValueError) as e:
            problems.error(file, lineno, kw, "EXPRESSION" if expr else "VAL", str(e))
            return None
        if isinstance(v, str):
            problems.error(file, lineno, kw, "VAL", f"numeric parameter got text {v!r}")
            return None
        field = "EXPRESSION" if expr else "VAL"
        if t == "I":
            if v != int(v):
                problems.error(file, lineno, kw, field, f"integer parameter got {v}")
                return None
            if not INT_MIN <= int(v) <= INT_MAX:
                problems.error(
                    file,
                    lineno,
                    kw,
                    field,
                    f"integer parameter is {_magnitude(v)}, outside the 64-bit range (|value| < 2**63)",
                )
                return None
            return int(v)
        try:
            return float(v)
        except OverflowError:  # an integer result past the largest double
            problems.error(
                file, lineno, kw, field, f"real parameter is {_magnitude(v)}, past the largest double (1.8e308)"
            )
            return None


def _magnitude(v) -> str:
    """A short description of a (possibly huge) number for a message."""
    if isinstance(v, int) and abs(v) >= 2**63:
        return f"{'-' if v < 0 else ''}about 2**{abs(v).bit_length() - 1}"
    return repr(v)
