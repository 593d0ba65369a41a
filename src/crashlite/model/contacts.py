"""Contact interface numbers: the number each ``*CONTACT_`` card of a deck
has in rcforc (LS-DYNA's and crashlite's, so a study's ``contact_force``
``id`` names the same interface on both) and the ``/INTER`` ID that
OpenRadioss's LS-DYNA reader gives it (the interface in its time history).

rcforc (LS-DYNA, crashlite): a card with an ID card (``_ID`` or ``_TITLE``,
CID > 0) is numbered by its CID; a card without one by its place among the
deck's contact interfaces (1, 2, ...: every ``*CONTACT_`` card but the
keywords of ``NOT_INTERFACES``, which define no interface of their own).
In a deck mixing both, a plain card keeps its place even where that is
another card's CID: the number is then ambiguous (``duplicates``) and a
response naming it is refused; give every contact an ``_ID``.

OpenRadioss (its LS-DYNA reader, ``reader/source/dyna2rad``,
``ConvertContact``): the cards it converts (``converted_by_openradioss``)
are taken in ID order, the cards without an ID after them in deck order;
a card with a CID gets that ``/INTER`` ID, one without gets the next free
ID (one more than the largest given so far). Force transducers
(``*CONTACT_FORCE_TRANSDUCER_PENALTY``, ``/INTER/SUB``) are converted after
all other cards, in the same order, and take their CID where it is still
free. Cards the reader does not convert get no interface.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..keyword.cards import split
from ..keyword.layout import INT, Field
from ..keyword.schema import RawKeyword, Record

if TYPE_CHECKING:
    from .model import Model

# *CONTACT_ keywords that define no contact interface of their own (no rcforc line, no place in the numbering)
NOT_INTERFACES = (
    "CONTACT_1D",
    "CONTACT_2D_",
    "CONTACT_ADD_WALL",
    "CONTACT_AUTO_MOVE",
    "CONTACT_COUPLING",
    "CONTACT_ENTITY",
    "CONTACT_EXCLUDE_INTERACTION",
    "CONTACT_GEBOD",
    "CONTACT_INTERIOR",
    "CONTACT_RIGID_SURFACE",
    "CONTACT_SPG",
)
SINGLE_SURFACE = ("SINGLE_SURFACE", "SINGLE_EDGE", "AUTOMATIC_GENERAL")  # no resultant in LS-DYNA's rcforc
TRANSDUCER = "CONTACT_FORCE_TRANSDUCER_PENALTY"
_CID = (Field("cid", INT),)  # the first field of an ID card
# the parts of a keyword that make OpenRadioss's LS-DYNA reader convert it to an /INTER (dyna2rad ConvertContact)
_OPENRADIOSS = (
    "AUTOMATIC_SURFACE_TO_SURFACE",
    "ERODING_SURFACE_TO_SURFACE",
    "AUTOMATIC_GENERAL",
    "AUTOMATIC_NODES_TO_SURFACE",
    "AUTOMATIC_SINGLE_SURFACE",
    "ERODING_SINGLE_SURFACE",
    "AUTOMATIC_BEAMS_TO_SURFACE",
    "AUTOMATIC_ONE_WAY_SURFACE_TO_SURFACE",
    "CONTACT_AIRBAG_SINGLE_SURFACE",
    "SPOTWELD",
    "TIED_NODES_TO_SURFACE",
    "TIED_SHELL_EDGE_TO_SURFACE",
    "TIEBREAK_NODES",
    "NODES_TO_SURFACE",
    "TIED_SURFACE_TO_SURFACE",
)


@dataclass(frozen=True)
class ContactCard:
    """One contact interface card of a deck."""

    keyword: str  # the keyword as written, options included (no '*')
    cid: int  # the ID card's CID; 0 without an ID card (or a blank CID)
    place: int  # 1, 2, ...: its place among the deck's contact interfaces
    card: Record | RawKeyword
    known: bool = True  # False: a verbatim card with an ID card whose CID could not be read

    @property
    def number(self) -> int:
        """Its interface number in rcforc (LS-DYNA's and crashlite's)."""
        return self.cid if self.cid > 0 else self.place

    @property
    def single_surface(self) -> bool:
        return any(s in self.keyword for s in SINGLE_SURFACE) and TRANSDUCER not in self.keyword

    @property
    def converted_by_openradioss(self) -> bool:
        """Whether OpenRadioss's LS-DYNA reader makes an /INTER of it."""
        return TRANSDUCER in self.keyword or any(s in self.keyword for s in _OPENRADIOSS)


def _name(k: Record | RawKeyword) -> str:
    return k.name if isinstance(k, Record) else k.keyword


def _raw_cid(k: RawKeyword) -> tuple[int, bool]:
    """(CID, read) of a verbatim card: the first field of its first card."""
    words = k.keyword.split("_")
    if "ID" not in words and "TITLE" not in words:
        return 0, True
    for line in k.lines:
        if line.startswith("$") or not line.strip():
            continue
        (field,) = split(line, _CID, k.mode)  # as the reader splits a card (fixed, long, i10 or free)
        try:
            return max(int(field.strip() or 0), 0), True
        except ValueError:
            return 0, False
    return 0, False


def contact_cards(model: Model) -> list[ContactCard]:
    """The deck's contact interface cards, in deck order."""
    out = []
    for k in model.keywords:
        name = _name(k)
        if not name.startswith("CONTACT_") or name.startswith(NOT_INTERFACES):
            continue
        if isinstance(k, Record):
            has_id = bool(k.options & {"ID", "TITLE"})
            cid, known = (int(k.get("cid") or 0) if has_id else 0), True
        else:
            cid, known = _raw_cid(k)
        out.append(ContactCard(name, max(cid, 0), len(out) + 1, k, known))
    return out


def interface_numbers(model: Model) -> dict[int, int]:
    """``id(card)`` -> its rcforc interface number, for the deck's contact
    interface cards (crashlite's solver numbers its interfaces by it)."""
    return {id(c.card): c.number for c in contact_cards(model)}


def duplicates(cards: list[ContactCard]) -> dict[int, list[ContactCard]]:
    """Interface numbers held by more than one card."""
    by: dict[int, list[ContactCard]] = {}
    for c in cards:
        by.setdefault(c.number, []).append(c)
    return {n: cs for n, cs in by.items() if len(cs) > 1}


def openradioss_ids(cards: list[ContactCard]) -> dict[int, int]:
    """rcforc interface number -> the /INTER ID OpenRadioss's LS-DYNA
    reader gives the card (cards it does not convert are left out)."""
    out: dict[int, int] = {}
    used: set[int] = set()
    nxt = 1
    for group in (
        [c for c in cards if c.converted_by_openradioss and TRANSDUCER not in c.keyword],
        [c for c in cards if TRANSDUCER in c.keyword],
    ):
        for c in sorted(group, key=lambda c: (c.cid == 0, c.cid)):  # stable: plain cards in deck order
            inter = c.cid if c.cid > 0 and c.cid not in used else nxt
            used.add(inter)
            nxt = max(nxt, inter + 1)
            out.setdefault(c.number, inter)
    return out
