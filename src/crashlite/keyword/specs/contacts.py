"""Contacts: automatic (single surface, nodes/surface to surface) and tied."""

from ..layout import Layout, Spec, card, register

_ID = card("cid:i@contact heading:s70")
_C1 = card("ssid:i=0 msid:i=0 sstyp:i=0 mstyp:i=0 sboxid:i=0 mboxid:i=0 spr:i=0 mpr:i=0")
_C2 = card("fs:f=0 fd:f=0 dc:f=0 vc:f=0 vdc:f=0 penchk:i=0 bt:f=0 dt:f~1e20")
_C3 = card("sfs:f~1 sfm:f~1 sst:f=0 mst:f=0 sfst:f~1 sfmt:f~1 fsf:f~1 vsf:f~1")
_A = card(
    "soft:i=0 sofscl:f~0.1 lcidab:i=0@curve maxpar:f~1.025 sbopt:i~2 depth:i~2 bsort:i=0 frcfrq:i~1", optional=True
)
_B = card("penmax:f=0 thkopt:i=0 shlthk:i=0 snlog:i=0 isym:i=0 i2d3d:i=0 sldthk:f=0 sldstf:f=0", optional=True)
_CC = card("igap:i~1 ignore:i=0 dprfac:f=0 dtstif:f=0 edgek:f=0 unused:f=0 flangl:f=0 cid_rcf:i=0@coord", optional=True)


_D = card("q2tri:i=0 dtpchk:f=0 sfnbr:f=0 fnlscl:f=0 dnlscl:f=0 tcso:i=0 tiedid:i=0 shledg:i=0", optional=True)
_E = card("sharec:i=0 cparm8:i=0 ipback:i=0 srnde:i=0 fricsf:f~1 icor:i=0 ftorq:i=0 region:i=0", optional=True)
_F = card("pstiff:i=0 ignroff:i=0 unused_f:i=0 fstol:f~2 twodbinr:i=0 ssftyp:i=0 swtpr:i=0 tetfac:f=0", optional=True)
_G = card("unused_g1:f=0 unused_g2:f=0 unused_g3:f=0 unused_g4:f=0 shloff:f=0", optional=True)


def _layout(options: frozenset) -> Layout:
    head = (_ID,) if options & {"ID", "TITLE"} else ()
    return Layout(head=head + (_C1, _C2, _C3, _A, _B, _CC, _D, _E, _F, _G))


_DOC = (
    "SSID/MSID are interpreted by SSTYP/MSTYP (0 segment set, 1 shell set, 2 part set, "
    "3 part, 4 node set, 5 all); FS/FD friction, SFS/SFM penalty scales, SOFT=1 soft constraint."
)
for _name in (
    "CONTACT_AUTOMATIC_SINGLE_SURFACE",
    "CONTACT_AUTOMATIC_NODES_TO_SURFACE",
    "CONTACT_AUTOMATIC_SURFACE_TO_SURFACE",
):
    register(Spec(_name, _layout, options=("ID", "TITLE"), id_field="cid", title_option=False, doc=_DOC))
register(
    Spec(
        "CONTACT_TIED_NODES_TO_SURFACE",
        _layout,
        options=("OFFSET", "ID", "TITLE"),
        id_field="cid",
        title_option=False,
        doc=_DOC + " _OFFSET ties with the initial gap kept.",
    )
)
# _BEAM_OFFSET (the words BEAM and OFFSET): LS-DYNA's penalty tie whose beams carry moments across the gap
register(
    Spec(
        "CONTACT_TIED_SHELL_EDGE_TO_SURFACE",
        _layout,
        options=("BEAM", "OFFSET", "ID", "TITLE"),
        id_field="cid",
        title_option=False,
        doc=_DOC + " _OFFSET ties with the initial gap kept; _BEAM_OFFSET ties across the gap by beams "
        "that carry moments.",
    )
)
