"""The building blocks of a keyword schema: fields, cards, layouts, specs
and the registry the catalogue (``keyword.specs``) fills.

Kept apart from ``schema`` (which looks keywords up and holds the records)
so that the catalogue can import its building blocks without importing the
module that loads the catalogue: no import circle.

Cards are declared with a compact text form, one token per field::

    "eid:i8@elem pid:i8@part n1:i8@node ... "   # name:KIND[WIDTH][=DEFAULT][@REF]

KIND is ``i`` (integer), ``f`` (real) or ``s`` (text); WIDTH defaults to 10.
``~DEFAULT`` instead of ``=DEFAULT`` marks a field that LS-DYNA documents as
"EQ.0: default": a 0 reads as the default too (``death:f~1e20``).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass

INT, FLOAT, STR = "i", "f", "s"

# Entity kinds an ID field can reference. Offsets of *INCLUDE_TRANSFORM are
# applied per kind (IDNOFF, IDEOFF, IDPOFF, IDMOFF, IDSOFF, IDFOFF, IDDOFF).
REF_KINDS = (
    "node",
    "elem",
    "part",
    "sec",
    "mat",
    "eos",
    "hg",
    "curve",
    "vector",
    "coord",
    "set_node",
    "set_part",
    "set_shell",
    "set_solid",
    "set_beam",
    "set_discrete",
    "set_segment",
    "set_any",
    "rigidwall",
    "contact",
    "sect",
    "sdo",
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
