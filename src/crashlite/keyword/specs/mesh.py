"""Nodes and elements: bulk rows read by the fast parser."""

from ..layout import Layout, Spec, card, fixed, register

_NODES8 = " ".join(f"n{i}:i8=0@node" for i in range(1, 9))

register(
    Spec(
        "NODE",
        fixed(row=[card("nid:i8@node x:f16=0 y:f16=0 z:f16=0 tc:i8=0 rc:i8=0")]),
        group="nodes",
        bulk=True,
        title_option=False,
        doc="Node coordinates with translational/rotational constraint codes.",
    )
)

_SHELL = card(f"eid:i8@elem pid:i8@part {_NODES8}")
_SHELL_THICK = card("thic1:f16=0 thic2:f16=0 thic3:f16=0 thic4:f16=0 beta:f16=0")
_SHELL_OFFSET = card("offset:f16=0")


def _shell_layout(options: frozenset) -> Layout:
    row = [_SHELL]
    if options & {"THICKNESS", "BETA", "MCID"}:
        row.append(_SHELL_THICK)
    if "OFFSET" in options:
        row.append(_SHELL_OFFSET)
    return Layout(row=tuple(row))


register(
    Spec(
        "ELEMENT_SHELL",
        _shell_layout,
        options=("THICKNESS", "BETA", "MCID", "OFFSET"),
        group="shells",
        bulk=True,
        title_option=False,
        doc="Shells; _THICKNESS/_BETA/_MCID give nodal thicknesses and the "
        "material angle (BETA) or coordinate system (MCID).",
    )
)

_SOLID_1 = card(f"eid:i8@elem pid:i8@part {_NODES8}")
_SOLID_2 = (card("eid:i8@elem pid:i8@part"), card(f"{_NODES8} n9:i8=0@node n10:i8=0@node"))


def _solid_layout(options: frozenset) -> Layout:
    return Layout(row=_SOLID_2 if "TWO_CARD" in options else (_SOLID_1,))


def _solid_sniff(first_line: str, options: frozenset) -> frozenset:
    """Since R10 LS-DYNA also reads EID PID on one card and N1-N10 on the
    next; a first card with nothing past column 16 is that format."""
    body = first_line.split(",")[2:] if "," in first_line else [first_line[16:]]
    if not "".join(body).strip():
        return options | {"TWO_CARD"}
    return options


register(
    Spec(
        "ELEMENT_SOLID",
        _solid_layout,
        group="solids",
        bulk=True,
        title_option=False,
        sniff=_solid_sniff,
        doc="Solids: 8 nodes on one card, or EID PID then N1-N10 (10-node "
        "tetrahedra keep their corner nodes; crashlite uses 8).",
    )
)

_BEAM = card(
    "eid:i8@elem pid:i8@part n1:i8@node n2:i8@node n3:i8=0@node rt1:i8=0 rr1:i8=0 rt2:i8=0 rr2:i8=0 local:i8~2"
)
_BEAM_THICK = card("parm1:f16=0 parm2:f16=0 parm3:f16=0 parm4:f16=0 parm5:f16=0")
_BEAM_PID = card("pid1:i8=0@part pid2:i8=0@part")
_BEAM_OFFSET = card("wx1:f16=0 wy1:f16=0 wz1:f16=0 wx2:f16=0 wy2:f16=0")
_BEAM_OFFSET2 = card("wz2:f16=0")
_BEAM_ORIENT = card("vx:f16=0 vy:f16=0 vz:f16=0")


def _beam_layout(options: frozenset) -> Layout:
    row = [_BEAM]
    if options & {"THICKNESS", "SECTION"}:
        row.append(_BEAM_THICK)
    if "PID" in options:
        row.append(_BEAM_PID)
    if "OFFSET" in options:
        row += [_BEAM_OFFSET, _BEAM_OFFSET2]
    if "ORIENTATION" in options:
        row.append(_BEAM_ORIENT)
    return Layout(row=tuple(row))


register(
    Spec(
        "ELEMENT_BEAM",
        _beam_layout,
        options=("THICKNESS", "SECTION", "PID", "OFFSET", "ORIENTATION"),
        group="beams",
        bulk=True,
        title_option=False,
        doc="Beams; n3 is the orientation node (0: none).",
    )
)

register(
    Spec(
        "ELEMENT_DISCRETE",
        fixed(row=[card("eid:i8@elem pid:i8@part n1:i8@node n2:i8=0@node vid:i8=0@sdo s:f16~1 pf:i8=0 offset:f16=0")]),
        group="discretes",
        bulk=True,
        title_option=False,
        doc="Springs/dampers between two nodes (n2=0: grounded); VID orientation, "
        "S scale factor, PF print flag, OFFSET initial offset.",
    )
)


def _mass_layout(options: frozenset) -> Layout:
    ref = "set_node" if "NODE_SET" in options or "SET" in options else "node"
    return Layout(row=(card(f"eid:i8@elem id:i8@{ref} mass:f16=0 pid:i8=0@part"),))


register(
    Spec(
        "ELEMENT_MASS",
        _mass_layout,
        options=("NODE", "SET"),
        group="masses",
        bulk=True,
        title_option=False,
        doc="Lumped masses on a node (or node set with _NODE_SET).",
    )
)

_MASS_PART = card("pid:i8@part addmass:f16=0 finmass:f16=0 lcid:i8=0@curve")
_MASS_PART_SET = card("pid:i8@set_part addmass:f16=0 finmass:f16=0 lcid:i8=0@curve")

register(
    Spec(
        "ELEMENT_MASS_PART",
        lambda o: Layout(row=(_MASS_PART_SET if "SET" in o else _MASS_PART,)),
        options=("SET",),
        group="keywords",
        title_option=False,
        doc="Translational mass ADDMASS added to a part (_SET: a part set), or the part(s) brought to the final "
        "mass FINMASS (> 0: ADDMASS is then ignored), spread over the nodes in proportion to their mass; "
        "LCID: a load curve making the added mass vary in time.",
    )
)

# PID names a part (IFSET 0) or a part set (IFSET 1): a reference kind cannot follow another field,
# so the reader leaves it unchecked and the solver names a missing part or set
register(
    Spec(
        "PART_MOVE",
        fixed(row=[card("pid:i8 xmov:f16=0 ymov:f16=0 zmov:f16=0 cid:i8=0@coord ifset:i8=0")]),
        title_option=False,
        doc="Translate every node of a part (IFSET 1: of the parts of a part set) by (XMOV, YMOV, ZMOV), "
        "in the local system CID when given, before the run starts.",
    )
)


def _inertia_layout(options: frozenset) -> Layout:
    row = [
        card("eid:i8@elem nid:i8@node csid:i8=0@coord"),
        card("ixx:f=0 ixy:f=0 ixz:f=0 iyy:f=0 iyz:f=0 izz:f=0 mass:f=0"),
    ]
    if "OFFSET" in options:
        row.append(card("x:f=0 y:f=0 z:f=0"))
    return Layout(row=tuple(row))


register(
    Spec(
        "ELEMENT_INERTIA",
        _inertia_layout,
        options=("OFFSET",),
        group="inertias",
        bulk=True,
        title_option=False,
        doc="Lumped mass and inertia tensor on a node (CSID: local system).",
    )
)

register(
    Spec(
        "ELEMENT_DIRECT_MATRIX_INPUT",
        fixed(card("eid:i@elem ifrmt:i=0"), card("filename:s80"), card("mass:s damp:s stif:s inert:s")),
        title_option=False,
        doc="A linear superelement: the stiffness (and mass, damping) matrices named MASS, DAMP, STIF "
        "in the NASTRAN DMIG file FILENAME (relative to the deck), on the grid points' DOFs.",
    )
)
