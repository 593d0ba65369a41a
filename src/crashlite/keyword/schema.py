"""Keyword schemas: the card layout of every keyword crashlite types.

One schema serves both reading and writing, so what the writer emits is by
construction what the reader expects. A schema is data: cards of fields with
a name, a kind (int, float, string), a width in characters, a default and,
for ID fields, the kind of entity referenced (used for *INCLUDE_TRANSFORM
offsets and for dangling-reference checks).

Cards are declared with a compact text form, one token per field::

    "eid:i8@elem pid:i8@part n1:i8@node ... "   # name:KIND[WIDTH][=DEFAULT][@REF]

KIND is ``i`` (integer), ``f`` (real) or ``s`` (text); WIDTH defaults to 10.
``~DEFAULT`` instead of ``=DEFAULT`` marks a field that LS-DYNA documents as
"EQ.0: default": a 0 reads as the default too (``death:f~1e20``).

Reading rule (LS-DYNA's): a blank field takes its default; a card missing
before the next keyword is a blank card, so its fields take their defaults
(a missing card with a field that has none is an error naming the field).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Iterable

INT, FLOAT, STR = "i", "f", "s"

# Entity kinds an ID field can reference. Offsets of *INCLUDE_TRANSFORM are
# applied per kind (IDNOFF, IDEOFF, IDPOFF, IDMOFF, IDSOFF, IDFOFF, IDDOFF).
REF_KINDS = (
    "node", "elem", "part", "sec", "mat", "eos", "hg", "curve", "vector",
    "coord", "set_node", "set_part", "set_shell", "set_solid", "set_beam",
    "set_discrete", "set_segment", "set_any", "rigidwall", "contact", "sect", "sdo",
)


@dataclass(frozen=True)
class Field:
    name: str
    kind: str  # INT, FLOAT or STR
    width: int = 10
    default: int | float | str | None = None
    ref: str | None = None
    zero_default: bool = False  # 0 reads as the default ("EQ.0: default" in the manual)


@dataclass(frozen=True)
class Card:
    """One line of input.

    ``when(values, options)`` decides whether the card is present at all
    (e.g. the angle cards of a composite shell section); ``optional`` cards
    may simply be missing at the end of a keyword.
    """

    fields: tuple[Field, ...]
    optional: bool = False
    when: Callable[[dict, frozenset], bool] | None = None

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(f.name for f in self.fields)


@dataclass(frozen=True)
class Layout:
    """The cards of one keyword instance, given its options.

    ``head`` cards occur once, in order. ``row`` cards form a group repeated
    until the next keyword (nodes, elements, curve points, set members).
    """

    head: tuple[Card, ...] = ()
    row: tuple[Card, ...] = ()
    title_card: bool = False  # a free 80-character title line before the head

    @property
    def row_fields(self) -> tuple[Field, ...]:
        return tuple(f for c in self.row for f in c.fields)


@dataclass(frozen=True)
class Spec:
    """A keyword family: canonical name, aliases, options it understands and
    a function from the options present to the layout."""

    name: str
    layout: Callable[[frozenset], Layout]
    aliases: tuple[str, ...] = ()
    options: tuple[str, ...] = ()
    group: str = "keywords"  # where the model keeps it (see model.Model)
    id_field: str | None = None  # field that identifies an instance
    bulk: bool = False  # rows are mesh data taken by the fast parser
    title_option: bool = True  # "_TITLE" adds a title card
    doc: str = ""
    # options implied by the first data line (a card format the keyword
    # name does not show, e.g. the two-card *ELEMENT_SOLID)
    sniff: Callable[[str, frozenset], frozenset] | None = None


_REGISTRY: dict[str, Spec] = {}


def parse_fields(text: str) -> tuple[Field, ...]:
    """Fields from the compact text form (see module docstring)."""
    out = []
    for tok in text.split():
        ref = None
        if "@" in tok:
            tok, ref = tok.split("@")
            if ref not in REF_KINDS:
                raise ValueError(f"unknown reference kind {ref!r}")
        default: int | float | str | None = None
        zero = "~" in tok
        if zero or "=" in tok:
            tok, dtext = tok.split("~" if zero else "=", 1)
        else:
            dtext = None
        name, kw = tok.split(":")
        kind = kw[0]
        width = int(kw[1:]) if len(kw) > 1 else 10
        if dtext is not None:
            default = int(dtext) if kind == INT else float(dtext) if kind == FLOAT else dtext
        if zero and (kind == STR or not default):
            raise ValueError(f"field {name}: '~' needs a non-zero numeric default")
        out.append(Field(name, kind, width, default, ref, zero))
    if sum(f.width for f in out) > 80:
        raise ValueError(f"card wider than 80 columns: {text}")
    return tuple(out)


def card(text: str, optional: bool = False, when=None) -> Card:
    return Card(parse_fields(text), optional, when)


def fixed(*cards: Card, row: Iterable[Card] = (), title_card: bool = False):
    """A layout function that ignores options."""
    lay = Layout(tuple(cards), tuple(row), title_card)
    return lambda options: lay


def register(spec: Spec) -> Spec:
    for name in (spec.name, *spec.aliases):
        if name in _REGISTRY:
            raise ValueError(f"keyword {name} registered twice")
        _REGISTRY[name] = spec
    return spec


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
        from .equality import records_equal

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
