"""*PART with its options _INERTIA and _CONTACT (any order, with _TITLE)."""

from ..layout import Layout, Spec, card, register

_HEADING = card("heading:s80")
_PART = card("pid:i@part secid:i@sec mid:i@mat eosid:i=0@eos hgid:i=0@hg grav:i=0 adpopt:i=0 tmid:i=0@part")
_INERTIA = (
    card("xc:f=0 yc:f=0 zc:f=0 tm:f=0 ircs:i=0 nodeid:i=0@node"),
    card("ixx:f=0 ixy:f=0 ixz:f=0 iyy:f=0 iyz:f=0 izz:f=0"),
    card("vtx:f=0 vty:f=0 vtz:f=0 vrx:f=0 vry:f=0 vrz:f=0"),
    # IRCS = 1: the tensor is given in a local system, defined by this card
    card(
        "xl:f=0 yl:f=0 zl:f=0 xlip:f=0 ylip:f=0 zlip:f=0 cid:i=0@coord",
        when=lambda values, options: int(values.get("ircs") or 0) == 1,
    ),
)
# part-based contact parameters (the manual's card after the inertia cards): friction FS FD DC VC (used by a
# contact whose FS is -1), contact thickness OPTT (0: the shells'), its scale SFT (0: none) and the penalty
# scale SSF (0 reads as 1)
_CONTACT = card("fs:f=0 fd:f=0 dc:f=0 vc:f=0 optt:f=0 sft:f=0 ssf:f~1 cparm8:i=0")


def _part_layout(options: frozenset) -> Layout:
    head = (_HEADING, _PART) + (_INERTIA if "INERTIA" in options else ())
    return Layout(head=head + ((_CONTACT,) if "CONTACT" in options else ()))


# *PART_TITLE (written by some pre-processors) is *PART: its heading card is
# already the title, so the option adds no card.
register(
    Spec(
        "PART",
        _part_layout,
        options=("INERTIA", "CONTACT", "TITLE"),
        group="parts",
        id_field="pid",
        title_option=False,
        doc="Part: section, material, hourglass; _INERTIA gives the rigid-body "
        "mass, CoG, inertia tensor and initial velocities; _CONTACT the part's "
        "contact friction, thickness (OPTT, SFT) and penalty scale (SSF).",
    )
)
