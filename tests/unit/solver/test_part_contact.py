"""Part-based contact parameters (*PART_CONTACT) in the penalty contacts:
OPTT sets the gap two plates meet at, SSF scales the penalty (a resting
load's penetration halves at SSF 2), the thickness precedence OPTT > SST >
SFT·t > SFST·t, FS = -1 takes the parts' friction; SSID 0 of a single
surface takes every part, rigid solids by their exterior faces."""

from __future__ import annotations

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.solver import setup
from crashlite.solver.contact import ContactGroup
from crashlite.solver.loop import integrate
from crashlite.solver.setup import SetupError

RHO, E, NU = 7.85e-9, 210000.0, 0.3  # t/mm³, MPa
M_NODE = 1e-4  # point mass on each node of the upper plate [t]


def _deck(
    path,
    end: float,
    optt=(0.0, 0.0),
    ssf=(0.0, 0.0),
    sft=(0.0, 0.0),
    z0: float = 6.0,
    vz: float = 0.0,
    card2: str = "0,0,0,0,0",
    card3: str = "",
    gravity: float = 0.0,
    part_fs=(0.0, 0.0),
    solid: bool = False,
):
    """A fixed 20 x 20 mm plate (part 1, 4 x 4 shells, 1 mm) and a 10 x 10 mm
    plate (part 2, 2 x 2 shells, 1 mm) z0 above its centre, each node of it
    carrying M_NODE; both *PART_CONTACT (OPTT, SFT, SSF, FS per part), one
    *CONTACT_AUTOMATIC_SINGLE_SURFACE with SSID 0; ``solid``: a rigid
    brick (part 3) off to the side."""
    nodes, lines = [], []

    def plate(pid, n, h, x0, z):
        first = len(nodes) + 1
        for j in range(n + 1):
            for i in range(n + 1):
                nodes.append((x0 + i * h, x0 + j * h, z))
        ids = np.arange(first, first + (n + 1) ** 2).reshape(n + 1, n + 1)
        rows = []
        for j in range(n):
            for i in range(n):
                rows.append(
                    f"{pid * 100 + j * n + i + 1},{pid},{ids[j, i]},{ids[j, i + 1]},{ids[j + 1, i + 1]},{ids[j + 1, i]}"
                )
        return ids.ravel(), rows

    low, rows1 = plate(1, 4, 5.0, 0.0, 0.0)
    up, rows2 = plate(2, 2, 5.0, 5.0, z0)
    lines += ["*ELEMENT_SHELL", *rows1, *rows2]
    for p in (1, 2):
        lines += [
            "*PART_CONTACT",
            f"plate {p}",
            f"{p},1,1",
            f"{part_fs[p - 1]},{part_fs[p - 1]},0,0,{optt[p - 1]},{sft[p - 1]},{ssf[p - 1]}",
        ]
    lines += ["*SECTION_SHELL", "1,2,1.0,2", "1.0,1.0,1.0,1.0", "*MAT_ELASTIC", f"1,{RHO},{E},{NU}"]
    if solid:
        first = len(nodes) + 1
        nodes += [(x, y, z) for z in (0.0, 4.0) for (x, y) in ((40, 0), (44, 0), (44, 4), (40, 4))]
        lines += ["*ELEMENT_SOLID", "900,3," + ",".join(str(first + a) for a in range(8))]
        lines += [
            "*PART",
            "rigid brick",
            "3,2,2",
            "*SECTION_SOLID",
            "2,1",
            "*MAT_RIGID",
            f"2,{RHO},{E},{NU},,,,",
            "1,7,7",
        ]
    lines += ["*BOUNDARY_SPC_NODE"] + [f"{int(i)},0,1,1,1,1,1,1" for i in low]
    lines += ["*ELEMENT_MASS"] + [f"{800 + k},{int(n)},{M_NODE}" for k, n in enumerate(up)]
    if vz:
        lines += ["*INITIAL_VELOCITY_NODE"] + [f"{int(i)},0,0,{vz}" for i in up]
    if gravity:
        lines += ["*DEFINE_CURVE", "1", "0.0,1.0", "1.0,1.0", "*LOAD_BODY_Z", f"1,{gravity}"]
    lines += ["*DATABASE_HISTORY_NODE", ",".join(str(int(i)) for i in up)]
    lines += ["*CONTACT_AUTOMATIC_SINGLE_SURFACE", "0,0,0,0", card2, card3]
    text = ["*KEYWORD", "*NODE"] + [f"{i + 1},{x!r},{y!r},{z!r}" for i, (x, y, z) in enumerate(nodes)]
    text += lines + ["*CONTROL_TERMINATION", f"{end!r},", "*END"]
    path.write_text("\n".join(text) + "\n")
    return path


def _group(s) -> ContactGroup:
    (g,) = [g for g in s.groups if isinstance(g, ContactGroup)]
    return g


def _separation(r, z0):
    """(n_states,) mean height of the upper plate over the fixed one [mm]."""
    return z0 + r.node_displacement[:, :, 2].mean(axis=1)


def test_optt_sets_the_gap_two_plates_meet_at(tmp_path):
    """The upper plate (1 mm shells, OPTT 3) falls at 1 m/s on the lower
    one (1 mm shells, OPTT 2): it stops and rebounds at a separation of
    (2 + 3)/2 = 2.5 mm less the penalty's v·√(m/k) (within 3 % of it), where
    the shells' own thickness would have let it come down to 1 mm; no
    energy made or lost beyond 1 %, the sliding energy ≥ -1 % of the
    energy. (OPTT stays below the 5 mm elements: a contact thickness
    beyond a plate's element size reaches the plate's own segments.)"""
    z0, v = 3.5, -1000.0
    s = setup.build(read_deck(_deck(tmp_path / "drop.k", 1.6e-3, optt=(2.0, 3.0), z0=z0, vz=v)))
    g = _group(s)
    np.testing.assert_allclose(np.unique(g.c.mthick), [2.0, 3.0])  # OPTT, not 40 % of the 5 mm edges
    r = integrate(s, 5e-6)
    sep = _separation(r, z0)
    assert 2.5 * (1 - 0.03) < sep.min() < 2.5
    assert r.final_v[:, 2].max() > 0.9 * abs(v)  # it bounced back
    total = r.kinetic + r.internal + r.hourglass + r.sliding
    assert np.abs(total - total[0]).max() < 0.01 * total[0]
    assert r.sliding.max() > 0.9 * total[0]  # the penalty took the energy at the stop
    assert r.sliding.min() >= -0.01 * total[0]


def _resting_penetration(tmp_path, ssf: float) -> float:
    """Penetration (2.5 mm less the separation) of the upper plate resting
    under a body load on the lower one, both OPTT 2.5 (VDC 70 % settles it)."""
    z0 = 2.5
    path = _deck(
        tmp_path / f"rest{ssf}.k", 1.5e-3, optt=(2.5, 2.5), ssf=(ssf, ssf), z0=z0, card2="0,0,0,0,70", gravity=2e7
    )
    r = integrate(setup.build(read_deck(path)), 1e-5)
    late = r.time > 1.0e-3
    return 2.5 - _separation(r, z0)[late].mean()


def test_ssf_scales_the_penalty(tmp_path):
    """SSF = 2 on both plates doubles every penalty spring: the resting
    load's penetration halves (within 5 %); it is small beside the gap."""
    d1, d2 = _resting_penetration(tmp_path, 0.0), _resting_penetration(tmp_path, 2.0)  # SSF 0 reads as 1
    assert 0 < d1 < 0.05 * 2.5
    assert d1 / d2 == pytest.approx(2.0, rel=0.05)


@pytest.mark.parametrize(
    "optt, sft, card3, want",
    [
        ((0.0, 0.0), (0.0, 0.0), "", (1.0, 1.0)),  # the shells' 1 mm (under 40 % of the 5 mm edges)
        ((0.0, 0.0), (3.0, 0.0), "", (2.0, 1.0)),  # SFT 3: 3 mm, limited to 40 % of the 5 mm edge
        ((0.0, 0.0), (1.5, 0.0), "1,1,0,0,1.8", (1.5, 1.8)),  # SFT over SFST, SFST where no SFT
        ((0.0, 0.0), (3.0, 0.0), "1,1,3.0", (3.0, 3.0)),  # SST over SFT: no limit
        ((4.0, 0.0), (0.0, 0.0), "1,1,3.0", (4.0, 3.0)),  # OPTT over SST, no limit
    ],
)
def test_thickness_precedence(tmp_path, optt, sft, card3, want):
    """LS-DYNA's order: shell thickness × SFT (else SFST), at most 40 % of
    the shortest edge in single surface; SST replaces it, OPTT replaces
    both, neither limited."""
    path = _deck(tmp_path / "t.k", 1e-5, optt=optt, sft=sft, card3=card3)
    g = _group(setup.build(read_deck(path)))
    pid = read_deck(path).shells.pid[g.c.owner]
    for p in (1, 2):
        np.testing.assert_allclose(g.c.mthick[pid == p], want[p - 1], rtol=1e-12)


def test_fs_minus_one_takes_the_parts_friction(tmp_path):
    """FS = -1 on the contact: FS FD of the parts' *PART_CONTACT (the same
    for both); a positive FS on the contact ignores them; parts that
    differ are refused, naming both."""
    g = _group(setup.build(read_deck(_deck(tmp_path / "a.k", 1e-5, part_fs=(0.3, 0.3), card2="-1"))))
    assert (g.c.fs, g.c.fd) == (0.3, 0.3)
    g = _group(setup.build(read_deck(_deck(tmp_path / "b.k", 1e-5, part_fs=(0.3, 0.3), card2="0.1,0.1"))))
    assert (g.c.fs, g.c.fd) == (0.1, 0.1)
    with pytest.raises(SetupError, match=r"FS = -1 with part-based friction that differs.*part 1.*part 2"):
        setup.build(read_deck(_deck(tmp_path / "c.k", 1e-5, part_fs=(0.3, 0.2), card2="-1")))
    with pytest.raises(SetupError, match=r"FS = -2 is not supported"):
        setup.build(read_deck(_deck(tmp_path / "d.k", 1e-5, card2="-2")))


def test_ssid_0_takes_every_part_rigid_solids_by_their_faces(tmp_path):
    """SSTYP 0, SSID 0 in a single surface: all parts; the rigid brick's 6
    exterior faces are segments, its 8 nodes slave nodes."""
    path = _deck(tmp_path / "all.k", 1e-5, solid=True)
    model = read_deck(path)
    g = _group(setup.build(model))
    assert int(g.c.solid.sum()) == 6 and set(model.solids.pid[g.c.owner[g.c.solid == 1]]) == {3}
    assert np.isin(model.solids.nodes[0], g.c.snode).all()  # node indices
    assert len(g.c.seg) == 16 + 4 + 6
