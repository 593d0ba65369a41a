"""Reading and writing single cards in Python (the complete, slower path).

Formats: ``std`` (fixed columns as in the manual), ``long`` (every field 20
characters: ``*KEYWORD LONG=Y`` or a keyword ending in ``+``), ``i10`` (8-wide
fields become 10: ``I10=Y`` or ``%``), and free format (a line with commas).
"""

from __future__ import annotations

import math
import re

from .schema import INT, STR, Field

STD, LONG, I10 = "std", "long", "i10"

_FORTRAN_EXP = re.compile(r"^([+-]?(?:\d+\.?\d*|\.\d+))([+-]\d+)$")


def width(f: Field, mode: str) -> int:
    if mode == LONG:
        return 20 if (f.kind != STR or f.width <= 20) else f.width
    if mode == I10 and f.width == 8:
        return 10
    return f.width


def split(line: str, fields: tuple[Field, ...], mode: str) -> list[str]:
    """Raw text of each field of one card line."""
    if "," in line:
        toks = line.split(",")
        toks += [""] * (len(fields) - len(toks))
        return [t.strip(BLANKS) for t in toks[: len(fields)]]
    out = []
    pos = 0
    for f in fields:
        w = width(f, mode)
        out.append(line[pos : pos + w])
        pos += w
    return out


class FieldError(ValueError):
    pass


INT_MIN, INT_MAX = -(2**63) + 1, 2**63 - 1  # what an int64 column holds (sign-symmetric)


def check_int(v: int, text) -> int:
    """``v`` when a 64-bit integer holds it; a FieldError otherwise (an ID
    past 64 bits must not wrap round to another entity's)."""
    if not INT_MIN <= v <= INT_MAX:
        shown = text.strip() if isinstance(text, str) else str(text)
        if len(shown) > 40:
            shown = f"{shown[:20]}...{shown[-8:]} ({len(shown)} characters)"
        raise FieldError(f"integer {shown} is outside the 64-bit range (|value| < 2**63)")
    return v


#: What counts as blank around a number: ASCII only. Python's own strip()
#: and float() also take a no-break space (byte 0xA0 read as latin-1) or
#: underscores, which would make "\xa0.85e-09" or "1_000" read silently.
BLANKS = " \t\f\v"
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?\Z", re.ASCII)


def _not_a_number(text: str, kind: str) -> FieldError:
    shown = text.strip(BLANKS)
    what = "an integer" if kind == INT else "a real number"
    if shown.lower().lstrip("+-") in ("inf", "infinity", "nan"):
        what = "a finite real number" if kind != INT else what
    odd = next((c for c in shown if not (" " <= c <= "~") and c != "\t"), None)
    if odd is not None:
        name = {"\xa0": "a no-break space", "\x00": "a NUL byte"}.get(odd, "a non-ASCII character")
        return FieldError(f"expected {what}, got {shown!r}: it holds {name} (byte 0x{ord(odd):02X})")
    return FieldError(f"expected {what}, got {shown!r}")


def to_number(text: str, kind: str):
    """Convert a Fortran-style number; raise FieldError when it is not one."""
    t = text.strip(BLANKS).replace("d", "e").replace("D", "E")
    m = _FORTRAN_EXP.match(t)
    if m:  # Fortran allows "1.5-3" for 1.5e-3
        t = f"{m.group(1)}e{m.group(2)}"
    if not _NUMBER.match(t):
        raise _not_a_number(text, kind)
    if kind == INT:
        if "." not in t and "e" not in t:
            return check_int(int(t), text)
        v = float(t)  # "12." or "1.2e1": accepted when integral
        if not math.isfinite(v) or v != int(v):
            raise FieldError(f"expected an integer, got {text.strip(BLANKS)!r}")
        return check_int(int(v), text)
    v = float(t)
    if not math.isfinite(v):
        raise FieldError(f"expected a finite real number, got {text.strip(BLANKS)!r}")
    return v


def convert(text: str, f: Field, params: dict):
    """Value of one field: blank (and 0 where the field's default is
    LS-DYNA's "EQ.0" default) gives the default, ``&name``/``-&name`` a
    parameter (``params`` maps lower-case names to values)."""
    t = text.strip() if f.kind == STR else text.strip(BLANKS)
    if f.kind == STR:
        if t.startswith("&") and t[1:].lower() in params:
            return str(params[t[1:].lower()])
        return t if t else f.default
    if not t:
        return f.default
    v = _number(t, f, params)
    return f.default if f.zero_default and v == 0 else v


def _number(t: str, f: Field, params: dict):
    neg = False
    if t.startswith("-&"):
        neg, t = True, t[1:]
    if t.startswith("&"):
        name = t[1:].strip().lower()
        if name not in params:
            raise FieldError(f"undefined parameter '&{t[1:].strip()}'")
        v = params[name]
        if isinstance(v, str):
            raise FieldError(f"parameter '&{name}' is text ({v!r}), a number is needed")
        if f.kind == INT:
            if v != int(v):
                raise FieldError(f"parameter '&{name}' = {v} is not an integer")
            v = check_int(int(v), f"'&{name}'")
        else:
            v = float(v)
        return -v if neg else v
    return to_number(t, f.kind)


def format_float(v: float, w: int) -> str | None:
    """Shortest text of ``v`` that reads back to the same double and fits
    in ``w`` characters, or None."""
    if v is None:
        return ""
    if not math.isfinite(v):
        raise ValueError(f"cannot write non-finite value {v}")
    s = repr(float(v))
    if len(s) <= w:
        return s
    # compact forms that still round-trip: drop exponent zeros and '+', leading 0
    if "e" in s:
        m, e = s.split("e")
        e = str(int(e))
        s = f"{m}e{e}"
        if m.endswith(".0"):
            s = f"{m[:-2]}e{e}"
    if s.startswith("0."):
        s = s[1:]
    elif s.startswith("-0."):
        s = "-" + s[2:]
    if len(s) <= w:
        return s
    # a fixed-point form can be shorter than repr's exponent form (1e-05 → .00001)
    for p in range(1, 18):
        t = f"{v:.{p}g}"
        if float(t) == v:
            t2 = t.replace("e-0", "e-").replace("e+0", "e").replace("e+", "e")
            if len(t2) <= w:
                return t2
            break
    return None


def format_value(v, f: Field, w: int) -> str | None:
    """Text of one field, right-justified in ``w`` (strings left), or None
    if it does not fit without loss."""
    if v is None:
        return " " * w
    if f.kind == STR:
        s = str(v)
        return s.ljust(w) if len(s) <= w else None
    if f.kind == INT:
        s = str(int(v))
    else:
        s = format_float(float(v), w)
        if s is None:
            return None
    return s.rjust(w) if len(s) <= w else None


def format_card(values: list, fields: tuple[Field, ...], mode: str) -> str | None:
    """One fixed-format line, or None when a value does not fit ``mode``."""
    parts = []
    for v, f in zip(values, fields):
        s = format_value(v, f, width(f, mode))
        if s is None:
            return None
        parts.append(s)
    return "".join(parts).rstrip()


def format_free(values: list, fields: tuple[Field, ...]) -> str:
    """One free-format line: always lossless (no widths)."""
    out = []
    for v, f in zip(values, fields):
        if v is None:
            out.append("")
        elif f.kind == STR:
            if "," in str(v):
                raise ValueError(f"text {v!r} of field {f.name} holds a comma")
            out.append(str(v))
        elif f.kind == INT:
            out.append(str(int(v)))
        else:
            out.append(repr(float(v)))
    while out and out[-1] == "":
        out.pop()
    return ",".join(out) if len(out) > 1 else (out[0] + "," if out else ",")
