"""*SET_NODE, _PART, _SHELL, _SOLID, _BEAM, _DISCRETE (LIST, GENERATE, ADD) and _SEGMENT."""

from ..layout import Layout, Spec, card, register

_MEMBER = {"NODE": "node", "PART": "part", "SHELL": "elem", "SOLID": "elem", "BEAM": "elem", "DISCRETE": "elem"}
_HEAD = {
    "NODE": "da1:f=0 da2:f=0 da3:f=0 da4:f=0 solver:s=MECH",
    "PART": "da1:f=0 da2:f=0 da3:f=0 da4:f=0 solver:s=MECH",
    "SHELL": "da1:f=0 da2:f=0 da3:f=0 da4:f=0",
    "SOLID": "solver:s=MECH",
    "BEAM": "",
    "DISCRETE": "",
}


def _set_layout(kind):
    own = f"set_{kind.lower()}"

    def layout(options: frozenset) -> Layout:
        head = (card(f"sid:i@{own} {_HEAD[kind]}"),)
        if "GENERATE" in options:
            ref = _MEMBER[kind]
            row = card(" ".join(f"b{i}beg:i=0@{ref} b{i}end:i=0@{ref}" for i in range(1, 5)))
        elif "ADD" in options:
            row = card(" ".join(f"k{i}:i=0@{own}" for i in range(1, 9)))
        else:
            row = card(" ".join(f"k{i}:i=0@{_MEMBER[kind]}" for i in range(1, 9)))
        return Layout(head=head, row=(row,))

    return layout


for _kind in _MEMBER:
    register(
        Spec(
            f"SET_{_kind}",
            _set_layout(_kind),
            options=("LIST", "GENERATE", "ADD"),
            group="sets",
            id_field="sid",
            doc=f"{_kind.lower()} set: members listed (LIST), as ranges (GENERATE) or as other sets (ADD).",
        )
    )

register(
    Spec(
        "SET_SEGMENT",
        lambda o: Layout(
            head=(card("sid:i@set_segment da1:f=0 da2:f=0 da3:f=0 da4:f=0 solver:s=MECH"),),
            row=(card("n1:i@node n2:i@node n3:i@node n4:i=0@node a1:f=0 a2:f=0 a3:f=0 a4:f=0"),),
        ),
        group="sets",
        id_field="sid",
        doc="Segments (3 or 4 nodes) for contact and loads.",
    )
)
