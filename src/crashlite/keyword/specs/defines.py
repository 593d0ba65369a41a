"""*DEFINE_CURVE, vectors, coordinate systems, transformations, *TITLE."""

from ..layout import Spec, card, fixed, register

register(
    Spec(
        "DEFINE_CURVE",
        fixed(
            card("lcid:i@curve sidr:i=0 sfa:f~1 sfo:f~1 offa:f=0 offo:f=0 dattyp:i=0 lcint:i=0"),
            row=[card("a1:f20=0 o1:f20=0")],
        ),
        group="curves",
        id_field="lcid",
        doc="Curve: abscissa A1, ordinate O1, scaled by SFA/SFO and offset by OFFA/OFFO.",
    )
)
register(
    Spec(
        "DEFINE_TABLE",
        fixed(card("tbid:i@curve sfa:f~1 offa:f=0"), row=[card("value:f20=0 lcid:i20@curve")]),
        id_field="tbid",
        doc="Table: one curve LCID per VALUE (scaled by SFA, offset by OFFA), e.g. the yield "
        "curve of each strain rate of a MAT_024 or MAT_081 LCSS; the curves follow the table.",
    )
)
register(
    Spec(
        "DEFINE_VECTOR",
        fixed(card("vid:i@vector xt:f=0 yt:f=0 zt:f=0 xh:f=0 yh:f=0 zh:f=0 cid:i=0@coord")),
        group="vectors",
        id_field="vid",
        doc="Vector from tail (XT..) to head (XH..).",
    )
)
register(
    Spec(
        "DEFINE_SD_ORIENTATION",
        fixed(card("vid:i@sdo iop:i=0 xt:f=0 yt:f=0 zt:f=0 nid1:i=0@node nid2:i=0@node")),
        id_field="vid",
        doc="Orientation of discrete elements (VID of *ELEMENT_DISCRETE): IOP 0 a "
        "fixed vector XT, YT, ZT; 2 the vector from NID1 to NID2.",
    )
)
register(
    Spec(
        "DEFINE_COORDINATE_NODES",
        fixed(card("cid:i@coord n1:i@node n2:i@node n3:i@node flag:i=0 dir:s=X")),
        group="coordinate_systems",
        id_field="cid",
        doc="Local system from three nodes (x along N1-N2, N3 in the x-y plane).",
    )
)
register(
    Spec(
        "DEFINE_COORDINATE_SYSTEM",
        fixed(
            card("cid:i@coord xo:f=0 yo:f=0 zo:f=0 xl:f=0 yl:f=0 zl:f=0 cidl:i=0@coord"), card("xp:f=0 yp:f=0 zp:f=0")
        ),
        group="coordinate_systems",
        id_field="cid",
        doc="Local system: origin, a point on x, a point in the x-y plane.",
    )
)
register(
    Spec(
        "DEFINE_COORDINATE_VECTOR",
        fixed(card("cid:i@coord xx:f=0 yx:f=0 zx:f=0 xv:f=0 yv:f=0 zv:f=0 nid:i=0@node")),
        group="coordinate_systems",
        id_field="cid",
        doc="Local system from two vectors.",
    )
)
register(
    Spec(
        "DEFINE_TRANSFORMATION",
        fixed(card("tranid:i"), row=[card("option:s a1:f=0 a2:f=0 a3:f=0 a4:f=0 a5:f=0 a6:f=0 a7:f=0")]),
        group="transformations",
        id_field="tranid",
        doc="Steps (TRANSL, SCALE, ROTATE, ...) applied by *INCLUDE_TRANSFORM.",
    )
)
register(Spec("TITLE", fixed(card("title:s80")), title_option=False, doc="Deck title."))
