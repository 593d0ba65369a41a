"""Nodal rigid bodies, extra nodes, merged rigid bodies and spot welds."""

from ..layout import Layout, Spec, card, register

_INERTIA = (
    card("xc:f=0 yc:f=0 zc:f=0 tm:f=0 ircs:i=0 nodeid:i=0@node"),
    card("ixx:f=0 ixy:f=0 ixz:f=0 iyy:f=0 iyz:f=0 izz:f=0"),
    card("vtx:f=0 vty:f=0 vtz:f=0 vrx:f=0 vry:f=0 vrz:f=0"),
)


def _nrb(options: frozenset) -> Layout:
    head = [card("pid:i cid:i=0@coord nsid:i@set_node pnode:i=0@node iprt:i=0 drflag:i=0 rrflag:i=0")]
    if "SPC" in options:
        head.append(card("cmo:f=0 con1:f=0 con2:f=0"))
    if "INERTIA" in options:
        head += _INERTIA
    return Layout(head=tuple(head))


register(
    Spec(
        "CONSTRAINED_NODAL_RIGID_BODY",
        _nrb,
        options=("INERTIA", "SPC"),
        id_field="pid",
        doc="Nodes of NSID move as one rigid body (PID names it); _INERTIA gives its mass, CoG and inertia.",
    )
)


def _extra(options: frozenset) -> Layout:
    ref = "nsid:i@set_node" if "SET" in options else "nid:i@node"
    return Layout(row=(card(f"pid:i@part {ref} iflag:i=0"),))


register(
    Spec(
        "CONSTRAINED_EXTRA_NODES",
        _extra,
        options=("NODE", "SET"),
        title_option=False,
        doc="Nodes (or a node set) added to rigid part PID.",
    )
)
register(
    Spec(
        "CONSTRAINED_RIGID_BODIES",
        lambda o: Layout(row=(card("pidl:i@part pidc:i@part iflag:i=0"),)),
        title_option=False,
        doc="Rigid part PIDC merged into lead rigid part PIDL.",
    )
)


def _spotweld(options: frozenset) -> Layout:
    data = card("n1:i@node n2:i@node sn:f=0 ss:f=0 n:f=0 m:f=0 tf:f~1e20 ep:f~1e20")
    return Layout(row=(card("wid:i"), data) if "ID" in options else (data,))


register(
    Spec(
        "CONSTRAINED_SPOTWELD",
        _spotweld,
        options=("ID",),
        title_option=False,
        doc="Rigid weld between two nodes until the force criterion (SN, SS, N, M) or time TF or plastic strain EP.",
    )
)


def _gws(options: frozenset) -> Layout:
    head = (card("wid:i"),) if "ID" in options else ()
    return Layout(
        head=head
        + (
            card("nsid:i@set_node cid:i=0@coord filter:i=0 window:i=0 npr:i=0 nprt:i=0"),
            card("tfail:f~1e20 epsf:f~1e20 sn:f=0 ss:f=0 n:f=0 m:f=0"),
        )
    )


register(
    Spec(
        "CONSTRAINED_GENERALIZED_WELD_SPOT",
        _gws,
        options=("ID",),
        title_option=False,
        doc="Rigid weld of a node set until failure (time, plastic strain or forces).",
    )
)
