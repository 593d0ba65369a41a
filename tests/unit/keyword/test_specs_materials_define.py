"""Schemas of materials, hourglass controls, sections, curves, vectors,
coordinate systems, transformations and *TITLE (specs/mat.py, specs/defines.py).

For every keyword and alias: lookup finds it (with _TITLE where the manual
allows it), every layout branch (the ``when`` cards of SECTION_SHELL and
SECTION_BEAM included) fits 80 columns, every card formats and reads back
value by value, and spot checks put fields in the manual's columns.
"""

import math

import pytest

from crashlite.keyword import cards
from crashlite.keyword.reader import read_records
from crashlite.keyword.schema import (
    FLOAT,
    INT,
    REF_KINDS,
    STR,
    Record,
    lookup,
    registered,
)

# keyword -> (aliases, group, id_field, title_option)
MATS = {
    "MAT_ELASTIC": ("MAT_001",),
    "MAT_PLASTIC_KINEMATIC": ("MAT_003",),
    "MAT_RIGID": ("MAT_020",),
    "MAT_PIECEWISE_LINEAR_PLASTICITY": ("MAT_024",),
    "MAT_HONEYCOMB": ("MAT_026",),
    "MAT_MODIFIED_HONEYCOMB": ("MAT_126",),
    "MAT_CRUSHABLE_FOAM": ("MAT_063",),
    "MAT_SPRING_ELASTIC": ("MAT_S01",),
    "MAT_DAMPER_VISCOUS": ("MAT_S02",),
    "MAT_SPRING_NONLINEAR_ELASTIC": ("MAT_S04",),
    "MAT_SPRING_GENERAL_NONLINEAR": ("MAT_S06",),
    "MAT_SPRING_INELASTIC": ("MAT_S08",),
}
EXPECTED = {
    **{name: (aliases, "materials", "mid", True) for name, aliases in MATS.items()},
    "HOURGLASS": ((), "hourglasses", "hgid", True),
    "SECTION_SHELL": ((), "sections", "secid", True),
    "SECTION_SOLID": ((), "sections", "secid", True),
    "SECTION_BEAM": ((), "sections", "secid", True),
    "SECTION_DISCRETE": ((), "sections", "secid", True),
    "DEFINE_CURVE": ((), "curves", "lcid", True),
    "DEFINE_VECTOR": ((), "vectors", "vid", True),
    "DEFINE_COORDINATE_NODES": ((), "coordinate_systems", "cid", True),
    "DEFINE_COORDINATE_SYSTEM": ((), "coordinate_systems", "cid", True),
    "DEFINE_COORDINATE_VECTOR": ((), "coordinate_systems", "cid", True),
    "DEFINE_TRANSFORMATION": ((), "transformations", "tranid", True),
    "TITLE": ((), "keywords", None, False),
}
NAMES = sorted(EXPECTED)
ALL_NAMES = sorted(set(NAMES) | {a for v in EXPECTED.values() for a in v[0]})

# keyword -> value dicts that drive the `when` cards to every branch
BRANCHES = {
    "MAT_MODIFIED_HONEYCOMB": [{"aopt": 2.0, "lcsr": 0}, {"aopt": 4.0, "lcsr": -1}],
    "SECTION_SHELL": [
        {"icomp": 0, "nip": 2},
        {"icomp": 1, "nip": 1},
        {"icomp": 1, "nip": 8},
        {"icomp": 1, "nip": 10},
        {"icomp": 1, "nip": 16},
        {"icomp": 1, "nip": 17},
        {"icomp": 1, "nip": 100},
        {"icomp": 0, "nip": 100},
    ],
    "SECTION_BEAM": [{"elform": e} for e in (1, 2, 3, 4, 5, 6, 9, 11, 12, 13, 14)],
}


def _active(name, values=None, options=frozenset()):
    """Cards of a layout present for the given values (head then row)."""
    lay = registered()[name].layout(options)
    values = values or {}
    return [c for c in lay.head if c.when is None or c.when(values, options)] + list(lay.row)


def _branches(name):
    return BRANCHES.get(name, [{}])


def _layout(name, *opts):
    spec, options = lookup("_".join((name,) + opts))
    assert spec is not None and name in (spec.name, *spec.aliases)
    return spec.layout(options)


def _names(card):
    return " ".join(card.names)


def _col(card, name):
    """1-based first and last column of a field in the fixed format."""
    pos = 0
    for f in card.fields:
        if f.name == name:
            return pos + 1, pos + f.width
        pos += f.width
    raise KeyError(name)


def _field(card, name):
    return next(f for f in card.fields if f.name == name)


def _sample(f, k):
    if f.kind == STR:
        return f"t{k}x"[: max(1, min(f.width, 8))]
    if f.kind == INT:
        return (k * 37 + 3) % (10 ** (min(f.width, 9) - 1))
    return [1.5, -2.25, 1e-9, 210000.0, 0.3, 7.85e-9, 1e20, -0.125][k % 8]


def _read_back(line, fields):
    return [cards.convert(t, f, {}) for t, f in zip(cards.split(line, fields, "std"), fields)]


# --- lookup -------------------------------------------------------------------


@pytest.mark.parametrize("name", NAMES)
def test_lookup_finds_keyword_aliases_and_title(name):
    aliases, group, id_field, title_option = EXPECTED[name]
    spec, options = lookup(name)
    assert spec is not None and spec.name == name and options == frozenset()
    assert tuple(spec.aliases) == aliases
    assert spec.group == group and spec.id_field == id_field
    assert spec.title_option is title_option
    assert spec.options == ()
    for kw in (name, *aliases):
        assert lookup(kw) == (spec, frozenset())
        assert lookup(kw.lower())[0] is spec  # keyword names are case-blind
        if title_option:
            assert lookup(f"{kw}_TITLE") == (spec, frozenset({"TITLE"}))
        else:
            assert lookup(f"{kw}_TITLE") == (None, frozenset())
        assert lookup(f"{kw}_NOSUCHOPTION") == (None, frozenset())


def test_aliases_are_the_numbered_forms():
    reg = registered()
    for name, (aliases, *_) in EXPECTED.items():
        for a in aliases:
            assert reg[a] is reg[name]
    # the numbered forms of the spring/damper materials are S01.., not 001..
    assert lookup("MAT_S01")[0].name == "MAT_SPRING_ELASTIC"
    assert lookup("MAT_001")[0].name == "MAT_ELASTIC"


def test_unsupported_variants_stay_unknown():
    for kw in (
        "MAT_ELASTIC_FLUID",
        "SECTION_SHELL_ALE",
        "SECTION_BEAM_AISC",
        "DEFINE_CURVE_SMOOTH",
        "DEFINE_VECTOR_NODES",
        "DEFINE_CURVE_FUNCTION",
        "HOURGLASS_X",
    ):
        assert lookup(kw) == (None, frozenset())


# --- every layout branch ------------------------------------------------------


@pytest.mark.parametrize("name", NAMES)
def test_every_layout_branch_builds(name):
    spec = registered()[name]
    for options in (frozenset(), frozenset({"TITLE"})) if spec.title_option else (frozenset(),):
        lay = spec.layout(options)
        assert lay.head or lay.row
        assert not lay.title_card  # the title line comes from _TITLE only
        optional = [c.optional for c in lay.head]
        assert optional == sorted(optional)  # cards that may be absent come last
        for values in _branches(name):
            seen = set()
            for c in _active(name, values, options):
                assert c.fields
                assert sum(f.width for f in c.fields) <= 80
                for f in c.fields:
                    assert f.kind in (INT, FLOAT, STR)
                    assert f.ref is None or f.ref in REF_KINDS
                    assert f.name == f.name.lower()
                    assert f.name not in seen, f"{name} {values}: {f.name} twice"
                    seen.add(f.name)
            if spec.id_field:
                assert spec.id_field in seen
                first = lay.head[0].fields[0]
                assert first.name == spec.id_field and first.kind == INT and first.default is None


# --- format, split and convert round trip --------------------------------------


@pytest.mark.parametrize("name", NAMES)
def test_every_card_round_trips(name):
    for values in _branches(name):
        for c in _active(name, values):
            sample = [_sample(f, k) for k, f in enumerate(c.fields)]
            line = cards.format_card(sample, c.fields, "std")
            assert line is not None and len(line) <= 80
            assert _read_back(line, c.fields) == sample, f"{name} {values} {_names(c)}"
            blank = cards.format_card([None] * len(c.fields), c.fields, "std")
            assert _read_back(blank, c.fields) == [f.default for f in c.fields]
            free = cards.format_free(sample, c.fields)
            assert _read_back(free, c.fields) == sample
            for mode in ("long", "i10"):
                wide = cards.format_card(sample, c.fields, mode)
                assert wide is not None
                back = [cards.convert(t, f, {}) for t, f in zip(cards.split(wide, c.fields, mode), c.fields)]
                assert back == sample


# --- materials as in the manual ----------------------------------------------


def _heads(name):
    return [_names(c) for c in _layout(name).head]


def test_mat_elastic_and_plastic_kinematic():
    assert _heads("MAT_ELASTIC") == ["mid ro e pr da db k"]
    c = _layout("MAT_001").head[0]
    assert c.fields[0].ref == "mat" and _col(c, "k") == (61, 70)
    assert _heads("MAT_PLASTIC_KINEMATIC") == ["mid ro e pr sigy etan beta", "src srp fs vp"]
    c1, c2 = _layout("MAT_PLASTIC_KINEMATIC").head
    assert _col(c1, "sigy") == (41, 50) and _col(c1, "beta") == (61, 70)
    assert _field(c1, "etan").default == 0.0 and _field(c1, "beta").default == 0.0
    assert c2.optional and _col(c2, "fs") == (21, 30)
    assert _field(c2, "fs").default >= 1e20


def test_mat_rigid():
    assert _heads("MAT_RIGID") == ["mid ro e pr n couple m alias", "cmo con1 con2", "lco a2 a3 v1 v2 v3"]
    c1, c2, c3 = _layout("MAT_020").head
    assert _field(c1, "alias").kind == STR and _col(c1, "alias") == (71, 80)
    assert _col(c2, "con2") == (21, 30) and c3.optional
    assert _col(c3, "v1") == (31, 40)
    assert [_field(c2, n).default for n in ("cmo", "con1", "con2")] == [0.0] * 3


def test_mat_piecewise_linear_plasticity():
    lay = _layout("MAT_PIECEWISE_LINEAR_PLASTICITY")
    assert [_names(c) for c in lay.head] == [
        "mid ro e pr sigy etan fail tdel",
        "c p lcss lcsr vp lcf",
        " ".join(f"eps{i}" for i in range(1, 9)),
        " ".join(f"es{i}" for i in range(1, 9)),
    ]
    c1, c2, c3, c4 = lay.head
    assert _col(c1, "sigy") == (41, 50)  # manual: card 1, columns 41-50
    assert _col(c1, "fail") == (61, 70) and _field(c1, "fail").default == 1e21
    assert _field(c1, "tdel").default == 0.0
    assert _col(c2, "lcss") == (21, 30) and _col(c2, "vp") == (41, 50) and _col(c2, "lcf") == (51, 60)
    assert [_field(c2, n).ref for n in ("lcss", "lcsr", "lcf")] == ["curve"] * 3
    assert _field(c2, "lcss").kind == INT and _field(c2, "c").kind == FLOAT
    assert _col(c3, "eps8") == (71, 80) and _col(c4, "es1") == (1, 10)
    assert [c.optional for c in lay.head] == [False, False, True, True]


def test_mat_honeycomb():
    lay = _layout("MAT_HONEYCOMB")
    assert [_names(c) for c in lay.head] == [
        "mid ro e pr sigy vf mu bulk",
        "lca lcb lcc lcs lcab lcbc lcca lcsr",
        "eaau ebbu eccu gabu gbcu gcau aopt macf",
        "xp yp zp a1 a2 a3",
        "d1 d2 d3 tsef ssef v1 v2 v3",
    ]
    c1, c2, c3, c4, c5 = lay.head
    assert _col(c4, "a1") == (31, 40)
    assert _field(c1, "mu").default == 0.05 and _col(c1, "vf") == (51, 60)
    assert {f.ref for f in c2.fields} == {"curve"} and all(f.kind == INT for f in c2.fields)
    assert _field(c3, "macf").default == 1 and _col(c3, "aopt") == (61, 70)
    assert [c.optional for c in lay.head] == [False, False, False, True, True]
    assert _col(c5, "tsef") == (31, 40)


def test_mat_modified_honeycomb():
    """MAT_126: MAT_026's first four cards, then VREF, TREF, SHDFLG beside
    TSEF, SSEF; the V card only for AOPT 3 and 4, the six rate curves only
    for LCSR = -1; LCA may be negative (the transversely isotropic form)."""
    spec = registered()["MAT_MODIFIED_HONEYCOMB"]
    lay = spec.layout(frozenset())
    names = [_names(c) for c in lay.head]
    assert names[:5] == [
        "mid ro e pr sigy vf mu bulk",
        "lca lcb lcc lcs lcab lcbc lcca lcsr",
        "eaau ebbu eccu gabu gbcu gcau aopt macf",
        "xp yp zp a1 a2 a3",
        "d1 d2 d3 tsef ssef vref tref shdflg",
    ]
    c1, c2, c3, c4, c5, c6, c7 = lay.head
    assert _field(c2, "lca").ref is None and _field(c2, "lcb").ref == "curve"
    assert _col(c5, "shdflg") == (71, 80) and _field(c1, "mu").default == 0.05
    assert c6.when({"aopt": 3.0}, frozenset()) and not c6.when({"aopt": 2.0}, frozenset())
    assert c7.when({"lcsr": -1}, frozenset()) and not c7.when({"lcsr": 0}, frozenset())


def test_mat_crushable_foam():
    (c,) = _layout("MAT_063").head
    assert _names(c) == "mid ro e pr lcid tsc damp"
    assert _field(c, "lcid").ref == "curve" and _col(c, "lcid") == (41, 50)
    assert _field(c, "damp").default == 0.1


@pytest.mark.parametrize(
    "name,names,curves",
    [
        ("MAT_SPRING_ELASTIC", "mid k", ()),
        ("MAT_DAMPER_VISCOUS", "mid dc", ()),
        ("MAT_SPRING_NONLINEAR_ELASTIC", "mid lcd lcr", ("lcd", "lcr")),
        ("MAT_SPRING_GENERAL_NONLINEAR", "mid lcdl lcdu beta tyi cyi", ("lcdl", "lcdu")),
        ("MAT_SPRING_INELASTIC", "mid lcfd ku ctf", ("lcfd",)),
    ],
)
def test_spring_and_damper_materials(name, names, curves):
    (c,) = _layout(name).head
    assert _names(c) == names
    assert all(f.width == 10 for f in c.fields) and c.fields[0].ref == "mat"
    for n in curves:
        assert _field(c, n).ref == "curve" and _field(c, n).kind == INT


def test_hourglass():
    (c,) = _layout("HOURGLASS").head
    assert _names(c) == "hgid ihq qm ibq q1 q2 qb qw"
    assert c.fields[0].ref == "hg"
    assert [_field(c, n).default for n in ("ihq", "qm", "q1", "q2")] == [0, 0.1, 1.5, 0.06]
    assert _field(c, "qb").default is None and _field(c, "qw").default is None  # blank: QM
    assert _col(c, "qb") == (61, 70)


# --- sections -----------------------------------------------------------------


def test_section_shell_cards_and_columns():
    head = _layout("SECTION_SHELL").head
    c1, c2 = head[:2]
    assert _names(c1) == "secid elform shrf nip propt qr icomp setyp"
    assert _names(c2) == "t1 t2 t3 t4 nloc marea idof edgset"
    assert c1.fields[0].ref == "sec"
    assert [_field(c1, n).default for n in ("elform", "shrf", "nip", "propt", "qr", "icomp", "setyp")] == [
        2,
        1.0,
        2,
        1.0,
        0.0,
        0,
        1,
    ]
    assert _col(c2, "t1") == (1, 10)  # manual: card 2, columns 1-10
    assert _col(c1, "icomp") == (61, 70) and _col(c2, "edgset") == (71, 80)
    angles = head[2:]
    assert all(c.when is not None for c in angles)
    assert _names(angles[0]) == " ".join(f"b{i}" for i in range(1, 9))
    assert _names(angles[1]) == " ".join(f"b{i}" for i in range(9, 17))


@pytest.mark.parametrize(
    "icomp,nip,n_angle_cards",
    [
        (0, 2, 0),
        (0, 10, 0),
        (1, 1, 1),
        (1, 8, 1),
        (1, 9, 2),
        (1, 10, 2),
        (1, 16, 2),
        (1, 17, 3),
        (1, 100, 13),
        (1, None, 1),  # blank NIP is 2
    ],
)
def test_section_shell_angle_cards(icomp, nip, n_angle_cards):
    active = _active("SECTION_SHELL", {"icomp": icomp, "nip": nip})
    assert len(active) == 2 + n_angle_cards
    if nip:
        assert n_angle_cards == (math.ceil(nip / 8) if icomp == 1 else 0)
    if n_angle_cards:
        assert active[-1].names[-1] == f"b{8 * n_angle_cards}"


def test_section_solid_and_discrete():
    (c,) = _layout("SECTION_SOLID").head
    assert _names(c) == "secid elform aet" and _field(c, "elform").default == 1
    d1, d2 = _layout("SECTION_DISCRETE").head
    assert _names(d1) == "secid dro kd v0 cl fd" and _names(d2) == "cdl tdl"
    assert _field(d1, "dro").kind == INT and _field(d1, "dro").default == 0
    assert d2.optional and _col(d1, "fd") == (51, 60)


BEAM_CARD2 = {
    1: "ts1 ts2 tt1 tt2 nsloc ntloc",
    11: "ts1 ts2 tt1 tt2 nsloc ntloc",
    3: "a rampt stress",
    6: "vol iner cid ca offset rrcon srcon trcon",
}


def test_section_beam_card1():
    c1 = _layout("SECTION_BEAM").head[0]
    assert c1.names[:7] == ("secid", "elform", "shrf", "qr", "cst", "scoor", "nsm")
    assert _field(c1, "elform").default == 1 and _field(c1, "shrf").default == 1.0
    assert _field(c1, "qr").default == 2.0 and _col(c1, "cst") == (41, 50)


@pytest.mark.parametrize("elform", [1, 2, 3, 6, 11, 12, 13])
def test_section_beam_card2_follows_elform(elform):
    active = _active("SECTION_BEAM", {"elform": elform})
    assert len(active) == 2
    c2 = active[1]
    if elform in BEAM_CARD2:
        assert _names(c2) == BEAM_CARD2[elform]
    else:  # resultant beams: A ISS ITT (J / IRR) SA (IST)
        assert c2.names[:3] == ("a", "iss", "itt") and c2.names[4] == "sa"
        assert _col(c2, "sa") == (41, 50)
    if elform == 6:
        assert _field(c2, "cid").ref == "coord" and _col(c2, "offset") == (41, 50)
    assert _col(c2, c2.names[0]) == (1, 10)


def test_section_beam_blank_elform_is_hughes_liu():
    lay = _layout("SECTION_BEAM")
    assert [_names(c) for c in _active("SECTION_BEAM", {"elform": None})][1] == BEAM_CARD2[1]
    assert len([c for c in lay.head if c.when is not None]) == 4


# --- curves, vectors, coordinate systems, transformations, title -------------


def test_define_curve():
    lay = _layout("DEFINE_CURVE", "TITLE")
    assert [_names(c) for c in lay.head] == ["lcid sidr sfa sfo offa offo dattyp lcint"]
    assert [_names(c) for c in lay.row] == ["a1 o1"]
    c = lay.head[0]
    assert c.fields[0].ref == "curve"
    assert [_field(c, n).default for n in ("sidr", "sfa", "sfo", "offa", "offo", "dattyp", "lcint")] == [
        0,
        1.0,
        1.0,
        0.0,
        0.0,
        0,
        0,
    ]
    assert [f.width for f in lay.row[0].fields] == [20, 20] and _col(lay.row[0], "o1") == (21, 40)


def test_define_vector_and_coordinate_systems():
    (v,) = _layout("DEFINE_VECTOR").head
    assert _names(v) == "vid xt yt zt xh yh zh cid"
    assert v.fields[0].ref == "vector" and _field(v, "cid").ref == "coord"
    (n,) = _layout("DEFINE_COORDINATE_NODES").head
    assert _names(n) == "cid n1 n2 n3 flag dir"
    assert [f.ref for f in n.fields[:4]] == ["coord", "node", "node", "node"]
    assert _field(n, "dir").kind == STR and _field(n, "dir").default == "X"
    s1, s2 = _layout("DEFINE_COORDINATE_SYSTEM").head
    assert _names(s1) == "cid xo yo zo xl yl zl cidl" and _names(s2) == "xp yp zp"
    assert _field(s1, "cidl").ref == "coord" and _col(s1, "xl") == (41, 50)
    (cv,) = _layout("DEFINE_COORDINATE_VECTOR").head
    assert _names(cv) == "cid xx yx zx xv yv zv nid" and _field(cv, "nid").ref == "node"


def test_define_transformation_and_title():
    lay = _layout("DEFINE_TRANSFORMATION")
    assert [_names(c) for c in lay.head] == ["tranid"]
    assert [_names(c) for c in lay.row] == ["option a1 a2 a3 a4 a5 a6 a7"]
    assert _field(lay.row[0], "option").kind == STR and _col(lay.row[0], "a7") == (71, 80)
    (t,) = _layout("TITLE").head
    assert _names(t) == "title" and t.fields[0].width == 80 and t.fields[0].kind == STR


# --- a small deck through the reader --------------------------------------------

DECK = """\
*KEYWORD
*TITLE
crash box
*MAT_024_TITLE
steel
         1   7.85e-9  210000.0       0.3     250.0
                             7
*MAT_RIGID
         2   7.85e-9  210000.0       0.3
       1.0         4         7
*MAT_S01
         3     100.0
*HOURGLASS
         1         4
*SECTION_SHELL_TITLE
laminate
         1         2     0.833        10                             1
       1.5       1.5       1.5       1.5
       0.0      45.0     -45.0      90.0      90.0     -45.0      45.0       0.0
      30.0     -30.0
*SECTION_BEAM
         2         3
      12.5
*SECTION_BEAM
         3         6
     100.0       2.0         5
*DEFINE_CURVE
         7                 1.0     250.0
                 0.0                 1.0
                 0.1                 1.2
*DEFINE_COORDINATE_NODES
         5         1         2         3
*DEFINE_TRANSFORMATION
         9
TRANSL          10.0       0.0       0.0
SCALE            2.0       2.0       2.0
*END
"""


def test_small_deck_reads(tmp_path):
    p = tmp_path / "mats.k"
    p.write_text(DECK)
    recs = [r for r in read_records(p)[0] if isinstance(r, Record)]
    assert [r.keyword for r in recs] == [
        "TITLE",
        "MAT_PIECEWISE_LINEAR_PLASTICITY",
        "MAT_RIGID",
        "MAT_SPRING_ELASTIC",
        "HOURGLASS",
        "SECTION_SHELL",
        "SECTION_BEAM",
        "SECTION_BEAM",
        "DEFINE_CURVE",
        "DEFINE_COORDINATE_NODES",
        "DEFINE_TRANSFORMATION",
    ]
    title, m24, rigid, spring, hg, shell, truss, discrete, curve, cs, tr = recs
    assert title["title"] == "crash box"
    assert m24.title == "steel" and m24.id == 1 and m24["sigy"] == 250.0 and m24["lcss"] == 7
    assert m24["fail"] == 1e21 and m24["eps1"] == 0.0  # optional cards 3-4 absent
    assert rigid["cmo"] == 1.0 and rigid["con1"] == 4 and rigid["con2"] == 7 and rigid["lco"] == 0.0
    assert spring.id == 3 and spring["k"] == 100.0
    assert hg.id == 1 and hg["ihq"] == 4 and hg["qm"] == 0.1 and hg["qb"] is None
    assert shell.title == "laminate" and shell["nip"] == 10 and shell["icomp"] == 1
    assert shell["shrf"] == 0.833 and shell["t4"] == 1.5
    assert [shell[f"b{i}"] for i in range(1, 11)] == [0.0, 45.0, -45.0, 90.0, 90.0, -45.0, 45.0, 0.0, 30.0, -30.0]
    assert shell["b11"] == 0.0
    assert truss["elform"] == 3 and truss["a"] == 12.5 and truss["ts1"] == 0.0
    assert discrete["elform"] == 6 and discrete["vol"] == 100.0 and discrete["iner"] == 2.0
    assert discrete["cid"] == 5
    assert curve.id == 7 and curve["sfo"] == 250.0 and curve["sfa"] == 1.0
    assert curve.rows["a1"].tolist() == [0.0, 0.1] and curve.rows["o1"].tolist() == [1.0, 1.2]
    assert cs.id == 5 and cs["dir"] == "X" and cs["n3"] == 3
    assert tr.id == 9 and tr.rows["option"].tolist() == ["TRANSL", "SCALE"]
    assert tr.rows["a1"].tolist() == [10.0, 2.0]
