"""*PART and *PART_INERTIA."""

from ..layout import Layout, Spec, card, register

_HEADING = card("heading:s80")
_PART = card("pid:i@part secid:i@sec mid:i@mat eosid:i=0@eos hgid:i=0@hg grav:i=0 adpopt:i=0 tmid:i=0@part")
_INERTIA = (
    card("xc:f=0 yc:f=0 zc:f=0 tm:f=0 ircs:i=0 nodeid:i=0@node"),
    card("ixx:f=0 ixy:f=0 ixz:f=0 iyy:f=0 iyz:f=0 izz:f=0"),
    card("vtx:f=0 vty:f=0 vtz:f=0 vrx:f=0 vry:f=0 vrz:f=0"),
)


def _part_layout(options: frozenset) -> Layout:
    head = (_HEADING, _PART) + (_INERTIA if "INERTIA" in options else ())
    return Layout(head=head)


# *PART_TITLE (written by some pre-processors) is *PART: its heading card is
# already the title, so the option adds no card.
register(
    Spec(
        "PART",
        _part_layout,
        options=("INERTIA", "TITLE"),
        group="parts",
        id_field="pid",
        title_option=False,
        doc="Part: section, material, hourglass; _INERTIA gives the rigid-body "
        "mass, CoG, inertia tensor and initial velocities.",
    )
)
