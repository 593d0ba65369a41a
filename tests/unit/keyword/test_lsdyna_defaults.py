"""The keyword-default audit: every typed keyword read as LS-DYNA reads it.

LS-DYNA reads a blank fixed-format field as 0, so a field whose manual entry
says "default X" (or "EQ.0: default X") takes X from a blank *and* from a 0,
and a card missing before the next keyword is a blank card. ``ZERO_READS``
is the manual's default column for every field of a typed keyword where that
value is not 0; every other numeric field must read a 0 as 0. Each keyword
is written three ways (zeros in every field, blanks, and only its first
card) and every field is checked against the table.
"""

from __future__ import annotations

import pytest

from crashlite.keyword.errors import Collector
from crashlite.keyword.reader import read_records
from crashlite.keyword.schema import INT, STR, Record, registered

_CONTACT = {
    "dt": 1e20,
    "sfs": 1.0,
    "sfm": 1.0,
    "sfst": 1.0,
    "sfmt": 1.0,
    "fsf": 1.0,
    "vsf": 1.0,
    "sofscl": 0.1,
    "maxpar": 1.025,
    "sbopt": 2,
    "depth": 2,
    "frcfrq": 1,
    "igap": 1,
    "fricsf": 1.0,
    "fstol": 2.0,
}
_MOTION = {"sf": 1.0, "death": 1e28}
_DATABASE = {"ioopt": 1}

# keyword -> {field: what a 0 (or a blank) reads as}, from the LS-DYNA keyword manual
ZERO_READS: dict[str, dict] = {
    "BOUNDARY_PRESCRIBED_MOTION_NODE": _MOTION,
    "BOUNDARY_PRESCRIBED_MOTION_SET": _MOTION,
    "BOUNDARY_PRESCRIBED_MOTION_RIGID": _MOTION,
    "BOUNDARY_SPC_NODE": {"death": 1e20},  # _BIRTH_DEATH
    "BOUNDARY_SPC_SET": {"death": 1e20},
    "LOAD_BODY_X": {"sf": 1.0},
    "LOAD_BODY_Y": {"sf": 1.0},
    "LOAD_BODY_Z": {"sf": 1.0},
    "LOAD_NODE_POINT": {"sf": 1.0},
    "LOAD_NODE_SET": {"sf": 1.0},
    "RIGIDWALL_PLANAR": {"death": 1e20, "rwksf": 1.0},
    "RIGIDWALL_GEOMETRIC_CYLINDER": {"death": 1e20, "ro": 1e-9, "e": 1e-4, "pr": 0.3},
    "CONTACT_AUTOMATIC_SINGLE_SURFACE": _CONTACT,
    "CONTACT_AUTOMATIC_NODES_TO_SURFACE": _CONTACT,
    "CONTACT_AUTOMATIC_SURFACE_TO_SURFACE": _CONTACT,
    "CONTACT_TIED_NODES_TO_SURFACE": _CONTACT,
    "CONTACT_TIED_SHELL_EDGE_TO_SURFACE": _CONTACT,
    "CONSTRAINED_SPOTWELD": {"tf": 1e20, "ep": 1e20},
    "CONSTRAINED_GENERALIZED_WELD_SPOT": {"tfail": 1e20, "epsf": 1e20},
    "CONTROL_TERMINATION": {"endmas": 1e8},
    "CONTROL_TIMESTEP": {"tssfac": 0.9},
    "CONTROL_ENERGY": {"hgen": 1, "rwen": 2, "slnten": 1, "rylen": 1, "irgen": 2, "maten": 1, "drlen": 1, "disen": 1},
    "CONTROL_HOURGLASS": {"ihq": 1, "qh": 0.1},
    "CONTROL_ACCURACY": {"inn": 1},  # 0 and 1: off
    "CONTROL_BULK_VISCOSITY": {"q1": 1.5, "q2": 0.06, "type": 1},
    "DEFINE_TABLE": {"sfa": 1.0},
    "MAT_PLASTICITY_WITH_DAMAGE": {"eppf": 1e12, "eppfr": 1e14},  # 0: no softening, no rupture
    "CONTROL_SOLUTION": {"lcint": 100, "ncdcf": 1},
    "CONTROL_CONTACT": {
        "slsfac": 0.1,
        "islchk": 1,
        "penopt": 1,
        "orien": 1,
        "xpene": 4.0,
        "ptscl": 1.0,
        "rwgaps": 1,
        "rwksf": 1.0,
    },
    "CONTROL_SHELL": {"wrpang": 20.0, "irnxx": -1, "theory": 2, "bwc": 2, "miter": 1, "rotascl": 1.0, "cstyp6": 1},
    **{
        f"DATABASE_{db}": _DATABASE
        for db in ("GLSTAT", "MATSUM", "NODOUT", "RWFORC", "SECFORC", "DEFORC", "RCFORC", "SPCFORC")
    },
    "MAT_PLASTIC_KINEMATIC": {"fs": 1e20},  # 0: no erosion
    "MAT_PIECEWISE_LINEAR_PLASTICITY": {"fail": 1e21},  # 0: failure not considered
    "MAT_HONEYCOMB": {"mu": 0.05, "macf": 1},
    "MAT_MODIFIED_HONEYCOMB": {"mu": 0.05, "macf": 1},
    "MAT_CRUSHABLE_FOAM": {"damp": 0.1},
    "MAT_SPRING_INELASTIC": {"ctf": 1.0},  # EQ.0: default is set to 1.0 (compression only)
    "HOURGLASS": {"qm": 0.1, "q1": 1.5, "q2": 0.06},
    "SECTION_SHELL": {"elform": 2, "shrf": 1.0, "nip": 2, "propt": 1.0, "setyp": 1},
    "SECTION_SOLID": {"elform": 1},
    "SECTION_BEAM": {"elform": 1, "shrf": 1.0, "qr": 2.0},
    "ELEMENT_DISCRETE": {"s": 1.0},
    "ELEMENT_BEAM": {"local": 2},
    "DEFINE_CURVE": {"sfa": 1.0, "sfo": 1.0},
}
# fields whose blank default is not what a 0 reads as: 0 has a meaning of its own
ZERO_IS_NOT_BLANK = {("INITIAL_VELOCITY_GENERATION", "styp")}  # 1, 2, 3 name the set type; no default

KEYWORDS = sorted({s.name for s in registered().values()})
_SAMPLE_OPTIONS = {  # options that bring every optional card of a keyword into play
    "RIGIDWALL_PLANAR": frozenset({"ID", "FINITE", "MOVING", "FORCES"}),
    "RIGIDWALL_GEOMETRIC_CYLINDER": frozenset({"ID", "MOTION", "DISPLAY"}),
    "CONSTRAINED_NODAL_RIGID_BODY": frozenset({"INERTIA", "SPC"}),
    "PART": frozenset({"INERTIA"}),
    "ELEMENT_SHELL": frozenset({"THICKNESS"}),
    "BOUNDARY_SPC_NODE": frozenset({"ID", "BIRTH", "DEATH"}),
    "BOUNDARY_SPC_SET": frozenset({"ID", "BIRTH", "DEATH"}),
    "BOUNDARY_PRESCRIBED_MOTION_NODE": frozenset({"ID"}),
    "BOUNDARY_PRESCRIBED_MOTION_SET": frozenset({"ID"}),
    "BOUNDARY_PRESCRIBED_MOTION_RIGID": frozenset({"ID"}),
    "ELEMENT_BEAM": frozenset({"THICKNESS", "PID", "OFFSET", "ORIENTATION"}),
}


def _name(kw: str, options: frozenset) -> str:
    return "_".join([kw, *sorted(options)])


def _lines(kw: str, options: frozenset, fill: str, first_only: bool = False) -> list[str]:
    """The keyword with every numeric field ``fill`` ("0" or "") but the
    fields without a default (IDs), which get 1; strings stay blank."""
    spec = registered()[kw]
    lay = spec.layout(options)
    lines = [f"*{_name(kw, options)}"]
    if lay.title_card:
        lines.append("title")
    values: dict = {}

    def card_text(c) -> str:
        out = ""
        for f in c.fields:
            text = "" if f.kind == STR else ("1" if f.default is None and f.kind == INT else fill)
            if f.default is None and f.kind != INT and f.kind != STR:
                text = "1.0"
            values[f.name] = text
            out += text.rjust(f.width) if text else " " * f.width
        return out

    for c in lay.head:
        if c.when is not None and not c.when({}, options):
            continue
        lines.append(card_text(c))
        if first_only:
            return lines
    for c in lay.row:
        lines.append(card_text(c))
    return lines


def _read(tmp_path, lines: list[str]) -> list[Record]:
    deck = tmp_path / "deck.k"
    deck.write_text("*KEYWORD\n" + "\n".join(lines) + "\n*END\n")
    problems = Collector()
    records, _, _ = read_records(deck, problems)
    assert not problems.problems, [str(p) for p in problems.problems]
    return [r for r in records if isinstance(r, Record)]


def _value(rec: Record, name: str):
    if name in rec.values:
        return rec.values[name]
    col = rec.rows[name]
    assert len(col) == 1
    v = col[0]
    return v.item() if hasattr(v, "item") else v


def _expected(kw: str, f, fill: str):
    if f.kind == STR:
        return f.default
    if f.default is None:
        return 1 if f.kind == INT else 1.0
    table = ZERO_READS.get(kw, {})
    if fill == "" and (kw, f.name) in ZERO_IS_NOT_BLANK:
        return f.default
    return table.get(f.name, 0)


def _fields(kw: str, options: frozenset, first_only: bool = False):
    lay = registered()[kw].layout(options)
    cards_ = [c for c in lay.head if c.when is None or c.when({}, options)]
    if first_only:
        return cards_[0].fields if cards_ else ()
    return tuple(f for c in cards_ for f in c.fields) + lay.row_fields


def _blank_cases():
    """Keywords whose row of blanks is still a row: a row line with nothing
    on it is an empty line, and EID PID alone is the two-card *ELEMENT_SOLID."""
    for kw in KEYWORDS:
        lay = registered()[kw].layout(_SAMPLE_OPTIONS.get(kw, frozenset()))
        if lay.row and all(f.default is not None or f.kind == STR for f in lay.row_fields):
            continue
        if kw != "ELEMENT_SOLID":
            yield kw


@pytest.mark.parametrize("kw,fill", [(k, "0") for k in KEYWORDS] + [(k, "") for k in _blank_cases()])
def test_every_field_reads_as_lsdyna(tmp_path, kw, fill):
    options = _SAMPLE_OPTIONS.get(kw, frozenset())
    (rec,) = _read(tmp_path, _lines(kw, options, fill))[-1:]
    for f in _fields(kw, options):
        got = _value(rec, f.name)
        want = _expected(kw, f, fill)
        if f.kind == STR and want is None:
            assert got in (None, ""), (kw, f.name, got)
            continue
        assert got == pytest.approx(want), f"*{kw} {f.name.upper()}: {fill or 'blank'} reads {got}, LS-DYNA {want}"


@pytest.mark.parametrize(
    "kw",
    [
        k
        for k in KEYWORDS
        if registered()[k].layout(_SAMPLE_OPTIONS.get(k, frozenset())).head
        and not registered()[k].layout(_SAMPLE_OPTIONS.get(k, frozenset())).row
    ],
)
def test_cards_missing_before_the_next_keyword_take_their_defaults(tmp_path, kw):
    """Only the first card written: every later card whose fields all have
    defaults reads as blank (LS-DYNA reads as far as the deck goes)."""
    options = _SAMPLE_OPTIONS.get(kw, frozenset())
    lay = registered()[kw].layout(options)
    cards_ = [c for c in lay.head if c.when is None or c.when({}, options)]
    later = [f for c in cards_[1:] for f in c.fields]
    if any(f.default is None and f.kind != STR for f in later):
        problems = Collector()
        deck = tmp_path / "deck.k"
        deck.write_text("*KEYWORD\n" + "\n".join(_lines(kw, options, "0", first_only=True)) + "\n*END\n")
        read_records(deck, problems)
        assert problems.problems and "has no default" in str(problems.problems[0])
        return
    (rec,) = _read(tmp_path, _lines(kw, options, "0", first_only=True))[-1:]
    for f in later:
        want = _expected(kw, f, "")
        got = rec.values[f.name]
        assert got == want or (want is None and got in (None, "")), (kw, f.name, got, want)


def test_the_table_names_only_real_fields():
    """A typo in the table would make its check vacuous."""
    for kw, table in ZERO_READS.items():
        options = _SAMPLE_OPTIONS.get(kw, frozenset())
        names = {f.name for f in _fields(kw, options)}
        assert set(table) <= names, (kw, set(table) - names)
