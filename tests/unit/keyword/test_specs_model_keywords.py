"""Schemas of the model keywords: sets, boundary conditions and loads, rigid
walls, contacts, constraints, controls and database outputs.

For every keyword and option: lookup finds it, every layout branch builds
within 80 columns, every card formats and reads back value by value, and the
card layouts (field names, order, columns, references) are those of the
LS-DYNA keyword manual.
"""

from itertools import chain, combinations

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

# keyword -> (options it must understand besides TITLE, whether "_TITLE" adds
# a free title line (title_option), group, id_field)
SET_OPTS = ("LIST", "GENERATE", "ADD")
CONTACT_OPTS = ("ID", "TITLE")
EXPECTED = {
    # sets
    "SET_NODE": (SET_OPTS, True, "sets", "sid"),
    "SET_PART": (SET_OPTS, True, "sets", "sid"),
    "SET_SHELL": (SET_OPTS, True, "sets", "sid"),
    "SET_SOLID": (SET_OPTS, True, "sets", "sid"),
    "SET_BEAM": (SET_OPTS, True, "sets", "sid"),
    "SET_DISCRETE": (SET_OPTS, True, "sets", "sid"),
    "SET_SEGMENT": ((), True, "sets", "sid"),
    # boundary conditions, initial velocities, loads, rigid walls
    "BOUNDARY_SPC_NODE": (("ID", "BIRTH", "DEATH"), None, "keywords", None),
    "BOUNDARY_SPC_SET": (("ID", "BIRTH", "DEATH"), None, "keywords", None),
    "BOUNDARY_PRESCRIBED_MOTION_NODE": (("ID",), None, "keywords", None),
    "BOUNDARY_PRESCRIBED_MOTION_SET": (("ID",), None, "keywords", None),
    "BOUNDARY_PRESCRIBED_MOTION_RIGID": (("ID",), None, "keywords", None),
    "INITIAL_VELOCITY": ((), None, "keywords", None),
    "INITIAL_VELOCITY_NODE": ((), None, "keywords", None),
    "INITIAL_VELOCITY_GENERATION": ((), None, "keywords", None),
    "LOAD_BODY_X": ((), None, "keywords", None),
    "LOAD_BODY_Y": ((), None, "keywords", None),
    "LOAD_BODY_Z": ((), None, "keywords", None),
    "RIGIDWALL_PLANAR": (("ID", "FINITE", "MOVING", "FORCES"), False, "keywords", "rwid"),
    "RIGIDWALL_GEOMETRIC_CYLINDER": (("ID", "MOTION", "DISPLAY"), False, "keywords", "rwid"),
    # contacts (_ID and _TITLE both give the "cid heading" card)
    "CONTACT_AUTOMATIC_SINGLE_SURFACE": (CONTACT_OPTS, False, "keywords", "cid"),
    "CONTACT_AUTOMATIC_NODES_TO_SURFACE": (CONTACT_OPTS, False, "keywords", "cid"),
    "CONTACT_AUTOMATIC_SURFACE_TO_SURFACE": (CONTACT_OPTS, False, "keywords", "cid"),
    "CONTACT_TIED_NODES_TO_SURFACE": (CONTACT_OPTS + ("OFFSET",), False, "keywords", "cid"),
    "CONTACT_TIED_SHELL_EDGE_TO_SURFACE": (CONTACT_OPTS + ("OFFSET", "BEAM"), False, "keywords", "cid"),
    # constraints
    "CONSTRAINED_NODAL_RIGID_BODY": (("INERTIA", "SPC"), True, "keywords", "pid"),
    "CONSTRAINED_EXTRA_NODES": (("NODE", "SET"), False, "keywords", None),
    "CONSTRAINED_RIGID_BODIES": ((), False, "keywords", None),
    "CONSTRAINED_SPOTWELD": (("ID",), False, "keywords", None),
    "CONSTRAINED_GENERALIZED_WELD_SPOT": (("ID",), False, "keywords", None),
    # controls and outputs
    "CONTROL_TERMINATION": ((), False, "keywords", None),
    "CONTROL_TIMESTEP": ((), False, "keywords", None),
    "CONTROL_ENERGY": ((), False, "keywords", None),
    "CONTROL_HOURGLASS": ((), False, "keywords", None),
    "CONTROL_CONTACT": ((), False, "keywords", None),
    "CONTROL_SHELL": ((), False, "keywords", None),
    **{
        f"DATABASE_{db}": ((), False, "keywords", None)
        for db in ("GLSTAT", "MATSUM", "NODOUT", "RWFORC", "SECFORC", "DEFORC", "RCFORC", "SPCFORC")
    },
    "DATABASE_BINARY_D3PLOT": ((), False, "keywords", None),
    "DATABASE_HISTORY_NODE": (("SET", "ID"), False, "keywords", None),
    "DATABASE_CROSS_SECTION_PLANE": (("ID",), False, "keywords", "csid"),
    "DATABASE_CROSS_SECTION_SET": (("ID",), False, "keywords", "csid"),
}
NAMES = sorted(EXPECTED)


def _combos(spec):
    opts = list(spec.options) + (["TITLE"] if spec.title_option else [])
    return [frozenset(c) for c in chain.from_iterable(combinations(opts, k) for k in range(len(opts) + 1))]


def _cards(lay):
    return list(lay.head) + list(lay.row)


def _names(card):
    return " ".join(card.names)


def _layout(name, *opts):
    spec, options = lookup("_".join((name,) + opts))
    assert spec is not None and spec.name == name
    return spec.layout(options)


# --- lookup -------------------------------------------------------------------


@pytest.mark.parametrize("name", NAMES)
def test_lookup_finds_keyword_and_each_option(name):
    opts, title_option, group, id_field = EXPECTED[name]
    spec, options = lookup(name)
    assert spec is not None and spec.name == name and options == frozenset()
    assert set(spec.options) == set(opts)
    if title_option is not None:
        assert spec.title_option is title_option
    assert spec.group == group
    assert spec.id_field == id_field
    for o in opts:
        spec2, options2 = lookup(f"{name}_{o}")
        assert spec2 is spec and options2 == frozenset([o])
        assert lookup(f"{name}_{o}".lower())[0] is spec  # keyword names are case-blind
    assert lookup(f"{name}_NOSUCHOPTION") == (None, frozenset())


@pytest.mark.parametrize("name", ["CONTACT_AUTOMATIC_SINGLE_SURFACE", "CONTACT_TIED_SHELL_EDGE_TO_SURFACE"])
def test_contact_id_and_title_give_the_same_first_card(name):
    plain, with_id, with_title = (_layout(name), _layout(name, "ID"), _layout(name, "TITLE"))
    assert with_id.head == with_title.head
    assert _names(with_id.head[0]) == "cid heading"
    assert with_id.head[0].fields[0].ref == "contact"
    assert with_id.head[1:] == plain.head
    assert not with_title.title_card and not lookup(f"{name}_TITLE")[0].title_option
    spec, options = lookup(f"{name}_ID_TITLE")
    assert spec.layout(options).head == with_id.head


def test_options_combine_in_any_order():
    spec, o1 = lookup("RIGIDWALL_PLANAR_MOVING_FORCES_ID")
    spec2, o2 = lookup("RIGIDWALL_PLANAR_ID_FORCES_MOVING")
    assert spec is spec2 and o1 == o2 == frozenset({"MOVING", "FORCES", "ID"})
    assert lookup("CONTACT_TIED_NODES_TO_SURFACE_OFFSET_ID")[1] == frozenset({"OFFSET", "ID"})
    assert lookup("CONSTRAINED_NODAL_RIGID_BODY_SPC_INERTIA_TITLE")[1] == frozenset({"SPC", "INERTIA", "TITLE"})


def test_unsupported_variants_stay_unknown():
    for kw in (
        "RIGIDWALL_PLANAR_ORTHO",
        "CONSTRAINED_SPOTWELD_FILTERED_FORCE",
        "CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_MPP",
        "SET_NODE_LIST_GENERATE_INCREMENT",
    ):
        assert lookup(kw) == (None, frozenset())


# --- every layout branch ------------------------------------------------------


@pytest.mark.parametrize("name", NAMES)
def test_every_layout_branch_builds(name):
    spec = registered()[name]
    for options in _combos(spec):
        lay = spec.layout(options)
        assert lay.head or lay.row
        seen = set()
        for c in _cards(lay):
            assert c.fields
            assert sum(f.width for f in c.fields) <= 80
            for f in c.fields:
                assert f.kind in (INT, FLOAT, STR)
                assert f.ref is None or f.ref in REF_KINDS
                assert f.name == f.name.lower()
                assert f.name not in seen, f"{name} {sorted(options)}: {f.name} twice"
                seen.add(f.name)
        # head cards that may be absent come after every mandatory card
        optional = [c.optional for c in lay.head]
        assert optional == sorted(optional)
        # the field naming the instance is there (for walls, contacts and cross
        # sections only with the option that adds the ID card)
        if spec.id_field and (options & {"ID", "TITLE"} or spec.title_option):
            assert spec.id_field in seen


# --- format, split and convert round trip --------------------------------------


def _sample(f, k):
    if f.kind == STR:
        return f"t{k}x"[: max(1, min(f.width, 8))]
    if f.kind == INT:
        return (k * 37 + 3) % (10 ** (min(f.width, 9) - 1))
    return [1.5, -2.25, 1e-9, 210000.0, 0.3, 7.85e-9, 1e20, -0.125][k % 8]


@pytest.mark.parametrize("name", NAMES)
def test_every_card_round_trips(name):
    spec = registered()[name]
    for options in _combos(spec):
        for c in _cards(spec.layout(options)):
            values = [_sample(f, k) for k, f in enumerate(c.fields)]
            line = cards.format_card(values, c.fields, "std")
            assert line is not None and len(line) <= 80
            back = [cards.convert(t, f, {}) for t, f in zip(cards.split(line, c.fields, "std"), c.fields)]
            assert back == values, f"{name} {sorted(options)} {_names(c)}"
            # blank fields read as the schema's default
            blank = cards.format_card([None] * len(c.fields), c.fields, "std")
            assert [cards.convert(t, f, {}) for t, f in zip(cards.split(blank, c.fields, "std"), c.fields)] == [
                f.default for f in c.fields
            ]
            # free format too
            free = cards.format_free(values, c.fields)
            assert [cards.convert(t, f, {}) for t, f in zip(cards.split(free, c.fields, "std"), c.fields)] == values


# --- card layouts as in the manual -------------------------------------------


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


KIND_OF_MEMBER = {"NODE": "node", "PART": "part", "SHELL": "elem", "SOLID": "elem", "BEAM": "elem", "DISCRETE": "elem"}
SET_HEAD = {
    "NODE": "sid da1 da2 da3 da4 solver",
    "PART": "sid da1 da2 da3 da4 solver",
    "SHELL": "sid da1 da2 da3 da4",
    "SOLID": "sid solver",
    "BEAM": "sid",
    "DISCRETE": "sid",
}


@pytest.mark.parametrize("kind", sorted(KIND_OF_MEMBER))
def test_sets(kind):
    name = f"SET_{kind}"
    own = f"set_{kind.lower()}"
    plain, lst, gen, add = (_layout(name), _layout(name, "LIST"), _layout(name, "GENERATE"), _layout(name, "ADD"))
    assert plain == lst  # plain *SET_x is the LIST form
    for lay in (plain, gen, add):
        assert [_names(c) for c in lay.head] == [SET_HEAD[kind]]
        assert lay.head[0].fields[0].ref == own
        assert len(lay.row) == 1 and len(lay.row[0].fields) == 8
        assert all(f.kind == INT and f.width == 10 and f.default == 0 for f in lay.row[0].fields)
    assert _names(lst.row[0]) == " ".join(f"k{i}" for i in range(1, 9))
    assert {f.ref for f in lst.row[0].fields} == {KIND_OF_MEMBER[kind]}
    assert _names(gen.row[0]) == "b1beg b1end b2beg b2end b3beg b3end b4beg b4end"
    assert {f.ref for f in gen.row[0].fields} == {KIND_OF_MEMBER[kind]}
    assert {f.ref for f in add.row[0].fields} == {own}
    head = plain.head[0]
    if "solver" in head.names:
        assert _field(head, "solver").kind == STR and _field(head, "solver").default == "MECH"
    assert _col(lst.row[0], "k8") == (71, 80)


def test_set_segment():
    lay = _layout("SET_SEGMENT")
    assert [_names(c) for c in lay.head] == ["sid da1 da2 da3 da4 solver"]
    assert lay.head[0].fields[0].ref == "set_segment"
    assert [_names(c) for c in lay.row] == ["n1 n2 n3 n4 a1 a2 a3 a4"]
    assert [f.ref for f in lay.row[0].fields[:4]] == ["node"] * 4
    assert _col(lay.row[0], "a1") == (41, 50)


@pytest.mark.parametrize(
    "name,first,ref", [("BOUNDARY_SPC_NODE", "nid", "node"), ("BOUNDARY_SPC_SET", "nsid", "set_node")]
)
def test_boundary_spc(name, first, ref):
    lay = _layout(name)
    assert not lay.head
    assert [_names(c) for c in lay.row] == [f"{first} cid dofx dofy dofz dofrx dofry dofrz"]
    assert lay.row[0].fields[0].ref == ref and _field(lay.row[0], "cid").ref == "coord"
    assert _col(lay.row[0], "dofrz") == (71, 80)
    with_id = _layout(name, "ID")  # one ID card names all the data cards that follow
    assert [_names(c) for c in with_id.head] == ["id heading"]
    assert [_names(c) for c in with_id.row] == [_names(lay.row[0])]
    assert _field(with_id.head[0], "heading").width == 70


@pytest.mark.parametrize(
    "name,first,ref",
    [
        ("BOUNDARY_PRESCRIBED_MOTION_NODE", "nid", "node"),
        ("BOUNDARY_PRESCRIBED_MOTION_SET", "nsid", "set_node"),
        ("BOUNDARY_PRESCRIBED_MOTION_RIGID", "pid", "part"),
    ],
)
def test_prescribed_motion(name, first, ref):
    lay = _layout(name)
    card = lay.row[0]
    assert _names(card) == f"{first} dof vad lcid sf vid death birth"
    assert card.fields[0].ref == ref and _field(card, "lcid").ref == "curve"
    assert _field(card, "vid").ref == "vector"
    assert _field(card, "death").default == 1e28 and _field(card, "sf").default == 1.0
    assert _field(card, "vad").default == 0 and _field(card, "birth").default == 0
    assert _col(card, "death") == (61, 70)
    # _ID: every motion carries its own ID card (LS-DYNA reads ID/data pairs)
    assert _layout(name, "ID").head == ()
    assert [_names(c) for c in _layout(name, "ID").row] == ["id heading", _names(card)]


MOTION_PAIRS = """\
*KEYWORD
*BOUNDARY_PRESCRIBED_MOTION_NODE_ID
         5first
         3         3         1         1       0.6         0       10.        0.
         6
         2         3         1         1       0.6
         8
        15         3         1         1      1.15            0       38.        0.
*BOUNDARY_SPC_NODE_BIRTH_DEATH_ID
         2
       205                   1         1         1         1         1         1
        0.      38.
       204                   1
        0.        0.
*END
"""


def test_motion_id_pairs_and_spc_birth_death(tmp_path):
    """Four motions under one *BOUNDARY_PRESCRIBED_MOTION_NODE_ID, each with
    its ID card (as a pre-processor writes them and LS-DYNA reads them), the
    last one's fields shifted by three columns as written: DEATH reads its
    blank-and-0 field as 1e28, BIRTH the 38. (LS-DYNA's d3hsp echoes motion
    ID8 with birth 38, death 1e28); an SPC with _BIRTH_DEATH reads each
    node's times (DEATH 0: 1e20)."""
    p = tmp_path / "d.k"
    p.write_text(MOTION_PAIRS)
    recs = {r.keyword: r for r in read_records(p)[0] if isinstance(r, Record)}
    mo = recs["BOUNDARY_PRESCRIBED_MOTION_NODE"].rows
    assert mo["id"].tolist() == [5, 6, 8] and mo["nid"].tolist() == [3, 2, 15]
    assert mo["sf"].tolist() == [0.6, 0.6, 1.15] and mo["lcid"].tolist() == [1, 1, 1]
    assert mo["death"].tolist() == [10.0, 1e28, 1e28] and mo["birth"].tolist() == [0.0, 0.0, 38.0]
    spc = recs["BOUNDARY_SPC_NODE"]
    assert spc["id"] == 2 and spc.rows["nid"].tolist() == [205, 204]
    assert spc.rows["dofz"].tolist() == [1, 0] and spc.rows["dofx"].tolist() == [1, 1]
    assert spc.rows["birth"].tolist() == [0.0, 0.0] and spc.rows["death"].tolist() == [38.0, 1e20]


def test_initial_velocity():
    lay = _layout("INITIAL_VELOCITY")
    assert [_names(c) for c in lay.head] == [
        "nsid nsidex boxid irigid icid",
        "vx vy vz vxr vyr vzr",
        "vxe vye vze vxre vyre vzre",
    ]
    third = lay.head[2]
    assert third.when is not None  # only with an exempted node set
    assert not third.when({"nsidex": 0}, frozenset()) and not third.when({"nsidex": None}, frozenset())
    assert third.when({"nsidex": 5}, frozenset())
    assert lay.head[0].fields[0].ref == "set_node" and lay.head[0].fields[1].ref == "set_node"
    node = _layout("INITIAL_VELOCITY_NODE")
    assert [_names(c) for c in node.row] == ["nid vx vy vz vxr vyr vzr icid"]
    gen = _layout("INITIAL_VELOCITY_GENERATION")
    assert not gen.row  # instances repeat under one keyword
    assert [_names(c) for c in gen.head] == ["id styp omega vx vy vz ivatn icid", "xc yc zc nx ny nz phase irigid"]


@pytest.mark.parametrize("axis", "XYZ")
def test_load_body(axis):
    lay = _layout(f"LOAD_BODY_{axis}")
    assert [_names(c) for c in lay.head] == ["lcid sf lciddr xc yc zc cid"]
    assert _field(lay.head[0], "lcid").ref == "curve" and _field(lay.head[0], "sf").default == 1.0
    assert _field(lay.head[0], "cid").ref == "coord"


def test_rigidwall_planar():
    base = ["nsid nsidex boxid offset birth death rwksf", "xt yt zt xh yh zh fric wvel"]
    assert [_names(c) for c in _layout("RIGIDWALL_PLANAR").head] == base
    lay = _layout("RIGIDWALL_PLANAR", "ID", "FINITE", "MOVING", "FORCES")
    assert [_names(c) for c in lay.head] == ["rwid heading"] + base + [
        "xhev yhev zhev lenl lenm",
        "mass v0",
        "soft ssid n1 n2 n3 n4",
    ]
    assert lay.head[0].fields[0].ref == "rigidwall"
    c1, c2 = lay.head[1], lay.head[2]
    assert _field(c1, "death").default == 1e20 and _field(c1, "rwksf").default == 1.0
    assert _col(c2, "fric") == (61, 70)  # manual: card 2, columns 61-70
    assert _col(c1, "rwksf") == (61, 70)
    assert [_names(c) for c in _layout("RIGIDWALL_PLANAR", "MOVING").head][-1] == "mass v0"


def test_rigidwall_geometric_cylinder():
    lay = _layout("RIGIDWALL_GEOMETRIC_CYLINDER", "ID", "MOTION", "DISPLAY")
    assert [_names(c) for c in lay.head] == [
        "rwid heading",
        "nsid nsidex boxid birth death",
        "xt yt zt xh yh zh fric",
        "radcyl lencyl",
        "lcid opt vx vy vz",
        "pid ro e pr",
    ]
    assert [_names(c) for c in _layout("RIGIDWALL_GEOMETRIC_CYLINDER", "DISPLAY").head][-1] == "pid ro e pr"
    display = lay.head[-1]
    assert (_field(display, "ro").default, _field(display, "e").default, _field(display, "pr").default) == (
        1e-9,
        1e-4,
        0.3,
    )


CONTACT_NAMES = [n for n in NAMES if n.startswith("CONTACT_")]


@pytest.mark.parametrize("name", CONTACT_NAMES)
def test_contact_cards(name):
    lay = _layout(name)
    assert not lay.row
    assert [_names(c) for c in lay.head] == [
        "ssid msid sstyp mstyp sboxid mboxid spr mpr",
        "fs fd dc vc vdc penchk bt dt",
        "sfs sfm sst mst sfst sfmt fsf vsf",
        "soft sofscl lcidab maxpar sbopt depth bsort frcfrq",
        "penmax thkopt shlthk snlog isym i2d3d sldthk sldstf",
        "igap ignore dprfac dtstif edgek unused flangl cid_rcf",
        "q2tri dtpchk sfnbr fnlscl dnlscl tcso tiedid shledg",
        "sharec cparm8 ipback srnde fricsf icor ftorq region",
        "pstiff ignroff unused_f fstol twodbinr ssftyp swtpr tetfac",
        "unused_g1 unused_g2 unused_g3 unused_g4 shloff",
    ]
    assert [c.optional for c in lay.head] == [False] * 3 + [True] * 7
    c1, c2, c3, a, _, cc = lay.head[:6]
    assert _col(c2, "fs") == (1, 10)  # manual: card 2 FS in columns 1-10
    assert _col(c2, "dt") == (71, 80) and _field(c2, "dt").default == 1e20
    assert [_field(c3, n).default for n in ("sfs", "sfm", "sfst", "sfmt", "fsf", "vsf")] == [1.0] * 6
    assert _field(a, "sofscl").default == 0.1 and _field(a, "maxpar").default == 1.025
    assert _field(a, "lcidab").ref == "curve"
    assert _field(cc, "igap").default == 1 and _field(cc, "cid_rcf").ref == "coord"
    assert _col(cc, "flangl") == (61, 70)
    assert all(f.kind == INT for f in c1.fields)


def test_constrained_nodal_rigid_body():
    assert [_names(c) for c in _layout("CONSTRAINED_NODAL_RIGID_BODY").head] == [
        "pid cid nsid pnode iprt drflag rrflag"
    ]
    lay = _layout("CONSTRAINED_NODAL_RIGID_BODY", "INERTIA")
    assert [_names(c) for c in lay.head] == [
        "pid cid nsid pnode iprt drflag rrflag",
        "xc yc zc tm ircs nodeid",
        "ixx ixy ixz iyy iyz izz",
        "vtx vty vtz vrx vry vrz",
    ]
    assert _field(lay.head[0], "nsid").ref == "set_node" and _field(lay.head[0], "pnode").ref == "node"
    spc = _layout("CONSTRAINED_NODAL_RIGID_BODY", "SPC")
    assert [_names(c) for c in spc.head][1:] == ["cmo con1 con2"]
    spec, options = lookup("CONSTRAINED_NODAL_RIGID_BODY_INERTIA_TITLE")
    assert "TITLE" in options and spec.title_option


def test_constrained_extra_nodes_and_rigid_bodies():
    node, plain, nset = (
        _layout("CONSTRAINED_EXTRA_NODES", "NODE"),
        _layout("CONSTRAINED_EXTRA_NODES"),
        _layout("CONSTRAINED_EXTRA_NODES", "SET"),
    )
    assert node == plain
    assert [_names(c) for c in node.row] == ["pid nid iflag"]
    assert [_names(c) for c in nset.row] == ["pid nsid iflag"]
    assert [f.ref for f in node.row[0].fields] == ["part", "node", None]
    assert [f.ref for f in nset.row[0].fields] == ["part", "set_node", None]
    rb = _layout("CONSTRAINED_RIGID_BODIES")
    assert [_names(c) for c in rb.row] == ["pidl pidc iflag"]
    assert [f.ref for f in rb.row[0].fields] == ["part", "part", None]


def test_constrained_spotweld_and_generalized_weld():
    sw = _layout("CONSTRAINED_SPOTWELD")
    assert [_names(c) for c in sw.row] == ["n1 n2 sn ss n m tf ep"]
    assert [_names(c) for c in _layout("CONSTRAINED_SPOTWELD", "ID").row] == ["wid", "n1 n2 sn ss n m tf ep"]
    assert _field(sw.row[0], "tf").default == 1e20 and _field(sw.row[0], "ep").default == 1e20
    gws = _layout("CONSTRAINED_GENERALIZED_WELD_SPOT")
    assert [_names(c) for c in gws.head] == ["nsid cid filter window npr nprt", "tfail epsf sn ss n m"]
    assert _names(_layout("CONSTRAINED_GENERALIZED_WELD_SPOT", "ID").head[0]) == "wid"


def test_controls():
    def head(name):
        return [_names(c) for c in _layout(name).head]

    assert head("CONTROL_TERMINATION") == ["endtim endcyc dtmin endeng endmas nosol"]
    assert _field(_layout("CONTROL_TERMINATION").head[0], "endmas").default == 1e8
    ts = _layout("CONTROL_TIMESTEP")
    assert head("CONTROL_TIMESTEP")[0] == "dtinit tssfac isdo tslimt dt2ms lctm erode ms1st"
    assert ts.head[1].optional and ts.head[1].names[:3] == ("dt2msf", "dt2mslc", "imscl")
    assert _col(ts.head[1], "rmscl") == (51, 60)
    assert _field(ts.head[0], "tssfac").default == 0.9
    assert head("CONTROL_ENERGY") == ["hgen rwen slnten rylen irgen maten drlen disen"]
    assert [f.default for f in _layout("CONTROL_ENERGY").head[0].fields] == [1, 2, 1, 1, 2, 1, 1, 1]
    assert head("CONTROL_HOURGLASS") == ["ihq qh"]
    cc = _layout("CONTROL_CONTACT")
    assert head("CONTROL_CONTACT")[:2] == [
        "slsfac rwpnal islchk shlthk penopt thkchg orien enmass",
        "usrstr usrfrc nsbcs interm xpene ssthk ecdt tiedprj",
    ]
    assert not cc.head[0].optional and all(c.optional for c in cc.head[1:])
    assert _field(cc.head[0], "slsfac").default == 0.1 and _field(cc.head[1], "xpene").default == 4.0
    sh = _layout("CONTROL_SHELL")
    assert head("CONTROL_SHELL")[:2] == [
        "wrpang esort irnxx istupd theory bwc miter proj",
        "rotascl intgrd lamsht cstyp6 thshel",
    ]
    assert all(c.optional for c in sh.head[1:])
    assert _field(sh.head[0], "irnxx").default == -1 and _field(sh.head[0], "theory").default == 2


@pytest.mark.parametrize("db", ["GLSTAT", "MATSUM", "NODOUT", "RWFORC", "SECFORC", "DEFORC", "RCFORC", "SPCFORC"])
def test_database_ascii_outputs(db):
    lay = _layout(f"DATABASE_{db}")
    assert [_names(c) for c in lay.head] == ["dt binary lcur ioopt"]
    assert _field(lay.head[0], "lcur").ref == "curve"


def test_database_d3plot_history_and_cross_sections():
    d3 = _layout("DATABASE_BINARY_D3PLOT")
    assert [_names(c) for c in d3.head] == ["dt lcdt beam npltc psetid", "ioopt"]
    assert d3.head[1].optional and _field(d3.head[0], "psetid").ref == "set_part"
    hist = _layout("DATABASE_HISTORY_NODE")
    assert [_names(c) for c in hist.row] == [" ".join(f"id{i}" for i in range(1, 9))]
    assert {f.ref for f in hist.row[0].fields} == {"node"}
    assert {f.ref for f in _layout("DATABASE_HISTORY_NODE", "SET").row[0].fields} == {"set_node"}
    assert [_names(c) for c in _layout("DATABASE_HISTORY_NODE", "ID").row] == ["id heading"]
    assert _layout("DATABASE_HISTORY_NODE", "SET", "ID").row[0].fields[0].ref == "set_node"
    plane = _layout("DATABASE_CROSS_SECTION_PLANE", "ID")
    assert [_names(c) for c in plane.head] == [
        "csid title",
        "psid xct yct zct xch ych zch radius",
        "xhev yhev zhev lenl lenm id itype",
    ]
    assert plane.head[0].fields[0].ref == "sect" and _field(plane.head[0], "title").width == 70
    cs_set = _layout("DATABASE_CROSS_SECTION_SET")
    assert [_names(c) for c in cs_set.head] == ["nsid hsid bsid ssid tsid dsid id itype"]
    assert [f.ref for f in cs_set.head[0].fields[:6]] == [
        "set_node",
        "set_solid",
        "set_beam",
        "set_shell",
        None,
        "set_discrete",
    ]


# --- a small deck through the reader --------------------------------------------

DECK = """\
*KEYWORD
*SET_NODE_LIST_TITLE
fixed nodes
         7       0.0       0.0       0.0       0.0MECH
         1         2         3
*SET_PART_GENERATE
        20
         1         5
*BOUNDARY_SPC_SET_ID
         3base
         7         0         1         1         1         0         0         0
*RIGIDWALL_PLANAR_MOVING_ID
         4barrier
         7
       0.0       0.0       0.0       1.0       0.0       0.0       0.2
     800.0     -15.6
*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_TITLE
        12door to frame
        20        21         2         2
       0.1      0.08
       1.0       1.0
         2
*CONTROL_TERMINATION
     0.120
*DATABASE_HISTORY_NODE
         1         2
*END
"""


def test_small_deck_reads(tmp_path):
    p = tmp_path / "model.k"
    p.write_text(DECK)
    recs = [r for r in read_records(p)[0] if isinstance(r, Record)]
    by = {r.keyword: r for r in recs}
    s = by["SET_NODE"]
    assert s.title == "fixed nodes" and s.id == 7 and s["solver"] == "MECH"
    assert s.rows["k1"].tolist() == [1] and s.rows["k3"].tolist() == [3]
    g = by["SET_PART"]
    assert g.options == frozenset({"GENERATE"}) and g.rows["b1beg"].tolist() == [1]
    assert g.rows["b1end"].tolist() == [5]
    spc = by["BOUNDARY_SPC_SET"]
    assert spc["id"] == 3 and spc["heading"] == "base"
    assert spc.rows["nsid"].tolist() == [7] and spc.rows["dofz"].tolist() == [1]
    rw = by["RIGIDWALL_PLANAR"]
    assert rw.id == 4 and rw["heading"] == "barrier" and rw["nsid"] == 7
    assert rw["xh"] == 1.0 and rw["fric"] == 0.2 and rw["death"] == 1e20
    assert rw["mass"] == 800.0 and rw["v0"] == -15.6
    c = by["CONTACT_AUTOMATIC_SURFACE_TO_SURFACE"]
    assert c.id == 12 and c["heading"] == "door to frame" and c.title is None
    assert (c["ssid"], c["msid"], c["sstyp"], c["mstyp"]) == (20, 21, 2, 2)
    assert (c["fs"], c["fd"], c["dt"]) == (0.1, 0.08, 1e20)
    assert c["soft"] == 2 and c["sofscl"] == 0.1 and c["igap"] == 1  # optional cards: defaults
    assert by["CONTROL_TERMINATION"]["endtim"] == 0.12
    assert by["DATABASE_HISTORY_NODE"].rows["id2"].tolist() == [2]
