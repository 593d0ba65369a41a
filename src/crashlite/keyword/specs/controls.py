"""*CONTROL_* settings and *DATABASE_* outputs."""

from ..layout import Layout, Spec, card, fixed, register


def _control(name, *cards_, doc=""):
    register(Spec(name, fixed(*cards_), title_option=False, doc=doc))


_control(
    "CONTROL_TERMINATION",
    card("endtim:f=0 endcyc:i=0 dtmin:f=0 endeng:f=0 endmas:f~1e8 nosol:i=0"),
    doc="End time, end cycle, minimum time step factor, energy and mass limits.",
)
_control(
    "CONTROL_TIMESTEP",
    card("dtinit:f=0 tssfac:f~0.9 isdo:i=0 tslimt:f=0 dt2ms:f=0 lctm:i=0@curve erode:i=0 ms1st:i=0"),
    card("dt2msf:f=0 dt2mslc:i=0@curve imscl:i=0 unused1:f=0 unused2:f=0 rmscl:f=0", optional=True),
    doc="Time-step scale factor TSSFAC; DT2MS < 0 mass-scales to |DT2MS|.",
)
_control(
    "CONTROL_ENERGY",
    card("hgen:i~1 rwen:i~2 slnten:i~1 rylen:i~1 irgen:i~2 maten:i~1 drlen:i~1 disen:i~1"),
    doc="Which energies are computed (2: on).",
)
_control("CONTROL_HOURGLASS", card("ihq:i~1 qh:f~0.1"), doc="Default hourglass type and coefficient.")
_control(
    "CONTROL_CONTACT",
    card("slsfac:f~0.1 rwpnal:f=0 islchk:i~1 shlthk:i=0 penopt:i~1 thkchg:i=0 orien:i~1 enmass:i=0"),
    card("usrstr:i=0 usrfrc:i=0 nsbcs:i=0 interm:i=0 xpene:f~4 ssthk:i=0 ecdt:i=0 tiedprj:i=0", optional=True),
    card("sfric:f=0 dfric:f=0 edc:f=0 vfc:f=0 th:f=0 th_sf:f=0 pen_sf:f=0 ptscl:f~1", optional=True),
    card("ignore:i=0 frceng:i=0 skiprwg:i=0 outseg:i=0 spotstp:i=0 spotdel:i=0 spothin:f=0", optional=True),
    card("isym:i=0 nserod:i=0 rwgaps:i~1 rwgdth:f=0 rwksf:f~1 icov:i=0 swradf:f=0 ithoff:i=0", optional=True),
    doc="Contact defaults: penalty scale SLSFAC, thickness options, ...",
)
_control(
    "CONTROL_SHELL",
    card("wrpang:f~20 esort:i=0 irnxx:i~-1 istupd:i=0 theory:i~2 bwc:i~2 miter:i~1 proj:i=0"),
    card("rotascl:f~1 intgrd:i=0 lamsht:i=0 cstyp6:i~1 thshel:i=0", optional=True),
    card("psstupd:i=0 sidt4tu:i=0 cntco:i=0 itsflg:i=0 irquad:i=0 w_mode:f=0 stretch:f=0 icrq:i=0", optional=True),
    doc="Shell defaults: warping angle, thickness update ISTUPD, default formulation THEORY.",
)
_control(
    "CONTROL_BULK_VISCOSITY",
    card("q1:f~1.5 q2:f~0.06 type:i~1 btype:i=0 tstype:i=0"),
    doc="Bulk viscosity: quadratic Q1 and linear Q2 (0 reads as the default: a tiny value turns it off), "
    "TYPE < 0 also on shells.",
)
_control(
    "CONTROL_ACCURACY",
    card("osu:i=0 inn:i~1 pidosu:i=0@set_part iacc:i=0 exacc:f=0"),
    doc="Accuracy options: second-order objective stress update OSU, invariant node numbering INN.",
)
_control(
    "CONTROL_SOLUTION",
    card("soln:i=0 nlq:i=0 isnan:i=0 lcint:i~100 lcacc:i=0 ncdcf:i~1 nocop:i=0"),
    doc="Analysis type SOLN (0 structural), NaN check, curve discretisation LCINT.",
)

for _db in ("GLSTAT", "MATSUM", "NODOUT", "RWFORC", "SECFORC", "DEFORC", "RCFORC", "SPCFORC"):
    _control(
        f"DATABASE_{_db}",
        card("dt:f=0 binary:i=0 lcur:i=0@curve ioopt:i~1"),
        doc=f"ASCII/binout output {_db.lower()} every DT.",
    )
_control(
    "DATABASE_BINARY_D3PLOT",
    card("dt:f=0 lcdt:i=0@curve beam:i=0 npltc:i=0 psetid:i=0@set_part"),
    card("ioopt:i=0", optional=True),
    doc="d3plot state interval.",
)


def _history(options: frozenset) -> Layout:
    ref = "set_node" if "SET" in options else "node"
    if "ID" in options:
        return Layout(row=(card(f"id:i@{ref} heading:s70"),))
    return Layout(row=(card(" ".join(f"id{i}:i=0@{ref}" for i in range(1, 9))),))


register(
    Spec(
        "DATABASE_HISTORY_NODE",
        _history,
        options=("SET", "ID"),
        title_option=False,
        doc="Nodes (or node sets) written to nodout.",
    )
)


def _section(fields):
    def layout(options: frozenset) -> Layout:
        head = (card("csid:i@sect title:s70"),) if "ID" in options else ()
        return Layout(head=head + fields)

    return layout


register(
    Spec(
        "DATABASE_CROSS_SECTION_PLANE",
        _section(
            (
                card("psid:i=0@set_part xct:f=0 yct:f=0 zct:f=0 xch:f=0 ych:f=0 zch:f=0 radius:f=0"),
                card("xhev:f=0 yhev:f=0 zhev:f=0 lenl:f=0 lenm:f=0 id:i=0 itype:i=0", optional=True),
            )
        ),
        options=("ID",),
        id_field="csid",
        title_option=False,
        doc="Section force output through a plane: normal from (XCT..) to (XCH..), of the parts in PSID.",
    )
)
register(
    Spec(
        "DATABASE_CROSS_SECTION_SET",
        _section(
            (
                card(
                    "nsid:i=0@set_node hsid:i=0@set_solid bsid:i=0@set_beam ssid:i=0@set_shell tsid:i=0 "
                    "dsid:i=0@set_discrete id:i=0 itype:i=0"
                ),
            )
        ),
        options=("ID",),
        id_field="csid",
        title_option=False,
        doc="Section force output through a node set and the element sets cut.",
    )
)
