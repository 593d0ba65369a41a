"""Which contact a ``contact_force`` response (and rcforc) means: LS-DYNA
numbers each interface by its CID (``_ID``), else by its place among the
deck's contacts; crashlite's solver numbers its interfaces (and its rcforc)
alike, so ``id = N`` names the same card on a crashlite run and on an
LS-DYNA run of the same deck. OpenRadioss's LS-DYNA reader gives the cards
other /INTER IDs (cards with an ID first, by ID; the others after them, the
next free ID each, in deck order): a response on an OpenRadioss run is
mapped to the /INTER ID of its card."""

from pathlib import Path

import numpy as np
import pytest
from test_openradioss_th import write_t01  # the T01 writer of the format

from crashlite import read_deck
from crashlite.model.contacts import contact_cards, duplicates, openradioss_ids
from crashlite.results import load
from crashlite.results.from_history import results_from_history
from crashlite.results.lsdyna_ascii import rcforc
from crashlite.solver import run
from crashlite.study.responses import (
    check_external_response,
    evaluate_responses,
    parse_response,
)
from crashlite.units import system


def _plate(pid: int, z: float, first: int) -> tuple[list[str], list[str]]:
    """A 20 x 20 mm plate of 2 x 2 shells at height z: node rows, shell rows."""
    nodes = [f"{first + 3 * j + i},{10.0 * i},{10.0 * j},{z}" for j in range(3) for i in range(3)]
    shells = []
    for j in range(2):
        for i in range(2):
            n = first + 3 * j + i
            shells.append(f"{10 * pid + 2 * j + i},{pid},{n},{n + 1},{n + 4},{n + 3}")
    return nodes, shells


# a tied contact, a plain surface-to-surface contact, one with an ID (7) and a plain single surface one:
# LS-DYNA's interface numbers 1 (tied: no rcforc line in crashlite's), 2, 7 and 4
CONTACTS = """\
*CONTACT_TIED_NODES_TO_SURFACE
1,1,4,3
0,0
0,0
*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE
2,1,3,3
0.2,0.2
0,0
*CONTACT_AUTOMATIC_NODES_TO_SURFACE_ID
         7top on middle
3,2,3,3
0,0
0,0
*CONTACT_AUTOMATIC_SINGLE_SURFACE
3,0,3
0,0
0,0
"""


def _deck(path: Path, contacts: str = CONTACTS) -> Path:
    """Three plates 3 mm apart, the top two falling at 20 m/s onto the
    bottom one (held), and a point mass tied 0.5 mm above the bottom one."""
    nodes, shells = [], []
    for pid, z in ((1, 0.0), (2, 1.2), (3, 2.4)):
        n, s = _plate(pid, z, 100 * pid)
        nodes += n
        shells += s
    parts = "".join(f"*PART\nplate {p}\n{p},1,1\n" for p in (1, 2, 3))
    falling = ",".join(str(100 * p + k) for p in (2, 3) for k in range(9))
    bottom = ",".join(str(100 + k) for k in range(9))
    path.write_text(
        "*KEYWORD\n*NODE\n" + "\n".join(nodes) + "\n9001,5.0,5.0,0.5\n"
        "*ELEMENT_SHELL\n"
        + "\n".join(shells)
        + "\n*ELEMENT_MASS\n9001,9001,1e-6\n"
        + parts
        + "*SECTION_SHELL\n1,2,1.0,2\n1.0,1.0,1.0,1.0\n*MAT_ELASTIC\n1,7.85e-9,210000.0,0.3\n"
        "*SET_NODE_LIST\n1\n9001\n"
        f"*SET_NODE_LIST\n2\n{falling}\n*SET_NODE_LIST\n3\n{bottom}\n"
        "*BOUNDARY_SPC_SET\n3,0,1,1,1,1,1,1\n"
        "*INITIAL_VELOCITY\n2\n0.0,0.0,-2.0e4\n"
        + contacts
        + "*CONTROL_TERMINATION\n2.0e-5\n*DATABASE_RCFORC\n1.0e-6\n*END\n"
    )
    return path


def test_numbers_follow_lsdyna_with_and_without_ids(tmp_path):
    """CID where the card has one, else the place among the contacts (the
    tied one counts); OpenRadioss: the card with an ID keeps it, the plain
    ones follow it in deck order."""
    model = read_deck(_deck(tmp_path / "three.k"))
    cards = contact_cards(model)
    assert [(c.keyword, c.number) for c in cards] == [
        ("CONTACT_TIED_NODES_TO_SURFACE", 1),
        ("CONTACT_AUTOMATIC_SURFACE_TO_SURFACE", 2),
        ("CONTACT_AUTOMATIC_NODES_TO_SURFACE_ID", 7),
        ("CONTACT_AUTOMATIC_SINGLE_SURFACE", 4),
    ]
    assert not duplicates(cards)
    assert openradioss_ids(cards) == {7: 7, 1: 8, 2: 9, 4: 10}


def test_crashlite_run_and_lsdyna_run_mean_the_same_contact(tmp_path):
    """crashlite's run numbers its interfaces (results and the rcforc it
    writes) as LS-DYNA does; an rcforc in LS-DYNA's layout with LS-DYNA's
    numbers (single surface left out, as LS-DYNA writes it) gives every
    response the same value as the run's own."""
    model = read_deck(_deck(tmp_path / "three.k"))
    res = run(model, out=tmp_path / "run", quiet=True)
    assert res.contact_ids.tolist() == [2, 7, 4]
    assert np.abs(res.contact_force[:, :2]).max() > 0.0  # the plates met
    written = rcforc.read(tmp_path / "run" / "rcforc")
    assert sorted(set(written["ids"].tolist())) == [2, 4, 7]

    lsdyna = tmp_path / "lsdyna"  # what LS-DYNA writes for the deck: interfaces 2 and 7
    lsdyna.mkdir()
    keep = [0, 1]
    f = res.contact_force[:, keep]
    both = np.stack([f, -f], axis=2).reshape(len(res.time), 4, 3)
    rcforc.write(
        lsdyna / "rcforc",
        {
            "time": res.time,
            "ids": np.repeat([2, 7], 2),
            "side": np.tile([0, 1], 2),
            **{f"{a}_force": both[:, :, k] for k, a in enumerate("xyz")},
        },
    )
    other = results_from_history(load(lsdyna))
    specs = {
        f"{cid}_{c}": parse_response(f"{cid}_{c}", {"type": "contact_force", "id": cid, "component": c})
        for cid in (2, 7)
        for c in ("z", "magnitude")
    }
    for spec in specs.values():
        check_external_response(spec, model, "lsdyna")
    units = system("mm-t-s")
    own = evaluate_responses(specs, res, model, {}, units)
    read = evaluate_responses(specs, other, model, {}, units, solver="lsdyna")
    for name in specs:
        assert read[name] == pytest.approx(own[name], rel=1e-5, abs=1e-9), name
    assert own["2_magnitude"] != own["7_magnitude"]


def test_openradioss_run_maps_to_its_inter_ids(tmp_path):
    """An OpenRadioss run's time history names its interfaces by the /INTER
    IDs its reader gave the cards: the response for LS-DYNA's interface 2
    (a plain card) reads /INTER 9, the one for 7 reads /INTER 7."""
    from crashlite.results import openradioss_th as th

    model = read_deck(_deck(tmp_path / "three.k"))
    t = np.linspace(0.0, 2.0e-5, 5)
    inter = {  # /INTER 7, 8 (tied), 9, 10 (single surface): the normal force on the main side
        7: 100.0,
        8: 0.0,
        9: 300.0,
        10: 0.0,
    }
    ids = list(inter)
    values = np.zeros((len(t), len(ids), 6))
    for j, i in enumerate(ids):
        values[:, j, 2] = inter[i] * t  # FNZ: the impulse OpenRadioss writes (a constant force)
    folder = tmp_path / "or"
    folder.mkdir()
    groups = [(13, th.INTER, "contacts", ids, [1, 2, 3, 4, 5, 6], values)]
    write_t01(folder / "threeT01", t, np.zeros((len(t), 22)), [], groups)
    res = results_from_history(load(folder))
    assert res.contact_ids.tolist() == ids
    specs = {
        n: parse_response(n, {"type": "contact_force", "id": cid, "component": "z", "stat": "absmax"})
        for n, cid in (("plain", 2), ("with_id", 7))
    }
    for spec in specs.values():
        check_external_response(spec, model, "openradioss")
    got = evaluate_responses(specs, res, model, {}, system("mm-t-s"), solver="openradioss")
    assert got == pytest.approx({"plain": 300.0, "with_id": 100.0})


def test_refusals_say_why(tmp_path):
    """A single surface contact, a number two cards hold and a card the
    OpenRadioss reader does not convert are refused, each saying why."""
    model = read_deck(_deck(tmp_path / "three.k"))

    def check(cid, solver="openradioss", m=model):
        spec = parse_response("f", {"type": "contact_force", "id": cid})
        check_external_response(spec, m, solver)

    with pytest.raises(ValueError, match=r"interface 4 is a single surface contact"):
        check(4)
    with pytest.raises(ValueError, match=r"interface 5 is not in the deck \(interfaces: \[1, 2, 4, 7\]\)"):
        check(5, "lsdyna")
    clash = CONTACTS.replace("         7top", "         2top")  # CID 2: the plain card's place too
    m2 = read_deck(_deck(tmp_path / "clash.k", clash))
    assert list(duplicates(contact_cards(m2))) == [2]
    with pytest.raises(ValueError, match=r"interface 2 is ambiguous: .*give every contact an _ID"):
        check(2, "lsdyna", m2)
    plain = CONTACTS.replace("*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE\n", "*CONTACT_SURFACE_TO_SURFACE\n")
    m3 = read_deck(_deck(tmp_path / "plain.k", plain))
    with pytest.raises(ValueError, match=r"OpenRadioss's LS-DYNA reader makes no interface of \*CONTACT_SURFACE"):
        check(2, "openradioss", m3)
