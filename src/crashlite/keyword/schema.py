"""Keyword schemas: the card layout of every keyword crashlite types.

One schema serves both reading and writing, so what the writer emits is by
construction what the reader expects. A schema is data: cards of fields with
a name, a kind (int, float, string), a width in characters, a default and,
for ID fields, the kind of entity referenced (used for *INCLUDE_TRANSFORM
offsets and for dangling-reference checks).

Cards are declared (see ``layout``) with a compact text form, one token per field::

    "eid:i8@elem pid:i8@part n1:i8@node ... "   # name:KIND[WIDTH][=DEFAULT][@REF]

KIND is ``i`` (integer), ``f`` (real) or ``s`` (text); WIDTH defaults to 10.
``~DEFAULT`` instead of ``=DEFAULT`` marks a field that LS-DYNA documents as
"EQ.0: default": a 0 reads as the default too (``death:f~1e20``).

Reading rule (LS-DYNA's): a blank field takes its default; a card missing
before the next keyword is a blank card, so its fields take their defaults
(a missing card with a field that has none is an error naming the field).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

# The building blocks live in ``layout`` (the catalogue imports them from
# there); they stay importable from here.
from .layout import (  # noqa: F401
    _REGISTRY,
    FLOAT,
    INT,
    REF_KINDS,
    STR,
    Card,
    Field,
    Layout,
    Spec,
    card,
    fixed,
    parse_fields,
    register,
)


def lookup(keyword: str) -> tuple[Spec | None, frozenset]:
    """Spec and options for a keyword name such as ``SECTION_SHELL_TITLE``.

    The longest registered name that is a ``_``-prefix of the keyword wins;
    the remaining ``_``-separated words are its options. Options the spec does
    not know make the keyword unknown (kept verbatim) rather than misread.
    """
    _ensure_loaded()
    kw = keyword.upper()
    parts = kw.split("_")
    for n in range(len(parts), 0, -1):
        base = "_".join(parts[:n])
        spec = _REGISTRY.get(base)
        if spec is None:
            continue
        opts = parts[n:]
        known = set(spec.options) | ({"TITLE"} if spec.title_option else set())
        if all(o in known for o in opts):
            return spec, frozenset(opts)
        return None, frozenset()
    return None, frozenset()


def registered() -> dict[str, Spec]:
    _ensure_loaded()
    return dict(_REGISTRY)


_loaded = False


def _ensure_loaded() -> None:
    global _loaded
    if not _loaded:
        _loaded = True
        from . import specs  # noqa: F401  (registers the catalogue)


@dataclass
class Record:
    """One typed keyword instance.

    ``values`` holds the head-card fields by name (None where the deck left a
    field blank and the schema gives no default); ``rows`` holds repeated
    row fields as columns (NumPy arrays, one entry per row).
    """

    keyword: str
    options: frozenset = frozenset()
    values: dict = field(default_factory=dict)
    rows: dict | None = None
    title: str | None = None
    source: tuple[str, int] | None = field(default=None, compare=False)
    card_lines: dict = field(default_factory=dict, compare=False, repr=False)  # field -> line

    def where(self, field_name: str | None = None) -> tuple[str, int]:
        """(file, line) of a field's card, or of the keyword."""
        src = self.source or ("", 0)
        return src[0], self.card_lines.get(field_name, src[1])

    @property
    def spec(self) -> Spec:
        _ensure_loaded()
        return _REGISTRY[self.keyword]

    @property
    def id(self):
        f = self.spec.id_field
        return self.values.get(f) if f else None

    @property
    def name(self) -> str:
        """Full keyword name with options, as written in a deck: options in
        the order the spec lists them (the manual's), ID and TITLE last."""
        order = {o: i for i, o in enumerate(self.spec.options)}
        last = {"ID": 1000, "TITLE": 1001}
        opts = sorted(self.options, key=lambda o: (last.get(o, order.get(o, 999)), o))
        return "_".join([self.keyword, *opts])

    def __getitem__(self, key):
        return self.values[key]

    def __setitem__(self, key, value):
        self.values[key] = value

    def get(self, key, default=None):
        v = self.values.get(key)
        return default if v is None else v

    def __eq__(self, other):
        if not isinstance(other, Record):
            return NotImplemented
        return records_equal(self, other)


@dataclass
class RawKeyword:
    """A keyword crashlite does not type: kept verbatim, written back unchanged."""

    keyword_line: str
    lines: list[str]
    source: tuple[str, int] | None = field(default=None, compare=False)
    mode: str = "std"  # card format it was written in (cards.STD, LONG, I10)

    @property
    def keyword(self) -> str:
        """Upper-case name without '*' and without a format suffix."""
        words = self.keyword_line.split()
        return words[0].lstrip("*").rstrip("+-%").upper() if words else ""


# --- value-by-value equality of records (NaN equals NaN) -------------------
def _value_equal(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        return a == b or (math.isnan(a) and math.isnan(b))
    if isinstance(a, str) or isinstance(b, str):
        return (a or "") == (b or "") if (a is None or b is None) else a == b
    return a == b


def _column_equal(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape:
        return False
    if a.dtype.kind == "f" or b.dtype.kind == "f":
        return np.array_equal(a.astype(float), b.astype(float), equal_nan=True)
    if a.dtype == object or b.dtype == object:
        return all(_value_equal(x, y) for x, y in zip(a, b))
    return np.array_equal(a, b)


def records_equal(a, b) -> bool:
    if (a.keyword, a.options) != (b.keyword, b.options):
        return False
    if (a.title or "") != (b.title or ""):
        return False
    if a.values.keys() != b.values.keys():
        return False
    if not all(_value_equal(a.values[k], b.values[k]) for k in a.values):
        return False
    if (a.rows is None) != (b.rows is None):
        return False
    if a.rows is not None:
        if a.rows.keys() != b.rows.keys():
            return False
        return all(_column_equal(a.rows[k], b.rows[k]) for k in a.rows)
    return True
