"""*PART_CONTACT: the manual's card FS FD DC VC OPTT SFT SSF CPARM8 after
the part card (and after the _INERTIA cards, the IRCS = 1 card included),
its defaults, with _TITLE and _INERTIA in any order, and the writer's round
trip; *CONTACT_TIED_SHELL_EDGE_TO_SURFACE_BEAM_OFFSET read and written."""

from __future__ import annotations

import pytest

from crashlite import read_deck
from crashlite.keyword.schema import lookup
from crashlite.keyword.writer import write_deck

_HEAD = """*KEYWORD
*SECTION_SHELL
1,16,,5
1.0,1.0,1.0,1.0
*MAT_ELASTIC
81,7.85e-6,70.0,0.3
"""


def _read(tmp_path, body: str, name: str = "d.k"):
    path = tmp_path / name
    path.write_text(_HEAD + body + "*END\n")
    return read_deck(path)


def test_the_hat_decks_cards(tmp_path):
    """Fixed columns as the public hat-profile deck writes them."""
    model = _read(
        tmp_path,
        "*PART_CONTACT\nProfile\n"
        "         1         1        81         0         0         0         0         0\n"
        "       0.0       0.0       0.0       0.0       2.0       0.0       0.0\n",
    )
    part = model.parts[1]
    assert part.options == {"CONTACT"} and part.name == "PART_CONTACT" and part["heading"] == "Profile"
    assert (part["secid"], part["mid"]) == (1, 81)
    got = {f: part[f] for f in ("fs", "fd", "dc", "vc", "optt", "sft", "ssf", "cparm8")}
    assert got == {"fs": 0.0, "fd": 0.0, "dc": 0.0, "vc": 0.0, "optt": 2.0, "sft": 0.0, "ssf": 1.0, "cparm8": 0}


@pytest.mark.parametrize("card", ["", "0,0,0,0,0,0,0,0", ",,,,,,,"])
def test_defaults(tmp_path, card):
    """A missing, zero or blank contact card: every field 0 but SSF, whose 0 reads as 1."""
    model = _read(tmp_path, f"*PART_CONTACT\np\n1,1,81\n{card}\n" if card else "*PART_CONTACT\np\n1,1,81\n")
    part = model.parts[1]
    assert [part[f] for f in ("fs", "fd", "dc", "vc", "optt", "sft", "ssf", "cparm8")] == [0, 0, 0, 0, 0, 0, 1.0, 0]


@pytest.mark.parametrize("keyword", ["PART_INERTIA_CONTACT", "PART_CONTACT_INERTIA", "PART_CONTACT_INERTIA_TITLE"])
@pytest.mark.parametrize("ircs", [0, 1])
def test_with_inertia_the_contact_card_comes_after_the_inertia_cards(tmp_path, keyword, ircs):
    local = "1.0,0.0,0.0,0.0,1.0,0.0,0\n" if ircs else ""
    model = _read(
        tmp_path,
        f"*{keyword}\nrigid\n1,1,81\n0.0,0.0,0.0,2.0,{ircs},0\n1.0,0.0,0.0,1.0,0.0,1.0\n0,0,0,0,0,0\n"
        f"{local}0.2,0.1,0.5,0.0,1.5,2.0,3.0,0\n",
    )
    part = model.parts[1]
    assert {"INERTIA", "CONTACT"} <= part.options and part["tm"] == 2.0 and part["ircs"] == ircs
    assert (part["fs"], part["fd"], part["dc"], part["optt"], part["sft"], part["ssf"]) == (
        0.2,
        0.1,
        0.5,
        1.5,
        2.0,
        3.0,
    )
    if ircs:
        assert (part["xl"], part["ylip"]) == (1.0, 1.0)


@pytest.mark.parametrize("fmt", ["fixed", "long"])
def test_round_trip(tmp_path, fmt):
    model = _read(
        tmp_path,
        "*PART_CONTACT\nsheet\n2,1,81\n0.3,0.2,0.1,0.0,2.0,1.5,2.0,0\n"
        "*PART_INERTIA_CONTACT\nrigid\n3,1,81\n0,0,0,2.0,1,0\n1,0,0,1,0,1\n0,0,0,0,0,0\n1,0,0,0,1,0,0\n0,0,0,0,4.0\n"
        "*SET_NODE_LIST\n1\n1\n*NODE\n1,0,0,0\n"
        "*CONTACT_TIED_SHELL_EDGE_TO_SURFACE_BEAM_OFFSET_ID\n20,Tied Contact\n1,2,4,3\n0,0,0,0,20\n0,0,2.0,2.0\n",
    )
    write_deck(model, tmp_path / "back.k", fmt=fmt)
    back = read_deck(tmp_path / "back.k")
    for pid in (2, 3):
        assert back.parts[pid] == model.parts[pid]
    text = (tmp_path / "back.k").read_text()
    assert "*PART_CONTACT\n" in text and "*PART_INERTIA_CONTACT\n" in text
    assert "*CONTACT_TIED_SHELL_EDGE_TO_SURFACE_BEAM_OFFSET_ID\n" in text
    (a,) = model.find("CONTACT_TIED_SHELL_EDGE_TO_SURFACE")
    (b,) = back.find("CONTACT_TIED_SHELL_EDGE_TO_SURFACE")
    assert a == b and (b["cid"], b["sst"], b["mst"], b["vdc"]) == (20, 2.0, 2.0, 20.0)


def test_beam_offset_is_an_option_of_the_shell_edge_tie_only():
    spec, opts = lookup("CONTACT_TIED_SHELL_EDGE_TO_SURFACE_BEAM_OFFSET_ID")
    assert spec.name == "CONTACT_TIED_SHELL_EDGE_TO_SURFACE" and opts == {"BEAM", "OFFSET", "ID"}
    assert lookup("CONTACT_TIED_NODES_TO_SURFACE_BEAM_OFFSET")[0] is None  # kept verbatim, refused by the solver
