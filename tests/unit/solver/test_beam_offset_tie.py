"""*CONTACT_TIED_SHELL_EDGE_TO_SURFACE_BEAM_OFFSET: two shell strips tied
across a gap carry a bending moment as one beam; the search distance from
SST/MST; momentum and energy of a free tied pair; one warning per card."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.solver import setup
from crashlite.solver.loop import integrate
from crashlite.solver.tied import TiedContact, build_tied

E, RHO = 210000.0, 7.85e-9  # MPa, t/mm³


class _Strips:
    """Flat shell strips (part p: node IDs from 1000·p + 1), ν = 0, elastic."""

    def __init__(self, t: float):
        self.t = t
        self.nodes: list[tuple[int, float, float, float]] = []
        self.elems: list[tuple[int, int, list[int]]] = []
        self.cards: list[str] = []

    def strip(self, pid: int, x0: float, x1: float, nx: int, b: float, z: float = 0.0) -> np.ndarray:
        ids = np.zeros((2, nx + 1), np.int64)
        for j, y in enumerate((0.0, b)):
            for i, x in enumerate(np.linspace(x0, x1, nx + 1)):
                ids[j, i] = 1000 * pid + j * (nx + 1) + i + 1
                self.nodes.append((int(ids[j, i]), float(x), y, z))
        for i in range(nx):
            self.elems.append((1000 * pid + i + 1, pid, [ids[0, i], ids[0, i + 1], ids[1, i + 1], ids[1, i]]))
        return ids

    def add(self, text: str) -> None:
        self.cards.append(text.strip())

    def node_set(self, sid: int, ids) -> None:
        self.add(f"*SET_NODE_LIST\n{sid}\n" + ",".join(str(int(i)) for i in np.ravel(ids)))

    def write(self, path, end_time: float):
        out = ["*KEYWORD", "*NODE"] + [f"{i},{x!r},{y!r},{z!r}" for i, x, y, z in self.nodes]
        out += ["*ELEMENT_SHELL"] + [f"{e},{p}," + ",".join(str(int(n)) for n in q) for e, p, q in self.elems]
        for p in sorted({e[1] for e in self.elems}):
            out += ["*PART", f"strip {p}", f"{p},1,1,0,1"]
        out += ["*SECTION_SHELL", "1,2,0.8333,2", f"{self.t},{self.t},{self.t},{self.t}"]
        out += ["*MAT_ELASTIC", f"1,{RHO},{E},0.0", "*HOURGLASS", "1,4,0.1", *self.cards]
        out += ["*CONTROL_TERMINATION", f"{end_time!r},", "*END"]
        path.write_text("\n".join(out) + "\n")
        return path


def _ramp(lcid: int, amplitude: float, t_ramp: float, t_end: float, n: int = 41) -> str:
    s = np.linspace(0.0, 1.0, n)
    rows = [f"{float(a * t_ramp)!r},{float(amplitude * 0.5 * (1 - np.cos(np.pi * a)))!r}" for a in s]
    rows.append(f"{float(max(t_end, 1.01 * t_ramp))!r},{float(amplitude)!r}")
    return f"*DEFINE_CURVE\n{lcid}\n" + "\n".join(rows)


T, B, GAP = 2.0, 10.0, 3.0  # strip thickness, width, gap between the mid-surfaces [mm]


def _pair(sst: float = 3.0, kind: str = "BEAM_OFFSET_ID") -> _Strips:
    """Strip 1 (x 0..60) and strip 2 (x 50..100) 3 mm above it, strip 2's
    edge at x = 50 (node set 1) tied to strip 1 (part 1): SST = MST = 3
    make the search distance 0.6·(3 + 3) = 3.6 mm; the shells' own 2 mm
    give 2.4 mm, short of the gap."""
    P = _Strips(T)
    P.strip(1, 0, 60, 6, B)
    c = P.strip(2, 50, 100, 5, B, z=GAP)
    P.node_set(1, c[:, 0])
    head = f"*CONTACT_TIED_SHELL_EDGE_TO_SURFACE_{kind}" + ("\n7,beam offset" if kind.endswith("_ID") else "")
    P.add(f"{head}\n1,1,4,3\n0,0\n0,0,{sst},{sst}")
    return P


def test_the_card_is_read_written_and_numbered_by_its_cid(tmp_path):
    from crashlite.keyword.writer import write_deck
    from crashlite.model.contacts import contact_cards

    model = read_deck(_pair().write(tmp_path / "pair.k", 1e-3))
    (rec,) = model.find("CONTACT_TIED_SHELL_EDGE_TO_SURFACE")
    assert rec.options == {"BEAM", "OFFSET", "ID"} and rec.name == "CONTACT_TIED_SHELL_EDGE_TO_SURFACE_BEAM_OFFSET_ID"
    assert (rec["sst"], rec["mst"], rec["sfst"], rec["sfmt"]) == (3.0, 3.0, 1.0, 1.0)
    assert [(c.number, c.keyword) for c in contact_cards(model)] == [(7, rec.name)]
    write_deck(model, tmp_path / "back.k")
    (back,) = read_deck(tmp_path / "back.k").find("CONTACT_TIED_SHELL_EDGE_TO_SURFACE")
    assert back == rec


def test_search_distance_from_sst_mst_and_one_warning(tmp_path):
    """LS-DYNA's tied search: 0.6·(t_s + t_m), SST/MST in place of the
    shells' thickness: the 3 mm gap is tied with SST = MST = 3 (3.6 mm),
    not with the 2 mm shells alone (2.4 mm: both edge nodes left free and
    reported)."""
    problems, warnings = [], []
    (tie,) = build_tied(read_deck(_pair().write(tmp_path / "a.k", 1e-3)), problems, warnings)
    assert not problems and len(tie) == 2 and len(tie.untied) == 0
    np.testing.assert_allclose(tie.gap, GAP, rtol=1e-12)
    assert tie.cid == 7 and tie.offset and tie.rotations
    (w,) = warnings
    assert w.keyword == "CONTACT_TIED_SHELL_EDGE_TO_SURFACE_BEAM_OFFSET_ID" and "BEAM_OFFSET" in w.message
    problems, warnings = [], []
    (tie,) = build_tied(read_deck(_pair(sst=0.0).write(tmp_path / "b.k", 1e-3)), problems, warnings)
    assert len(tie) == 0 and len(tie.untied) == 2 and len(warnings) == 2


def test_beam_without_offset_is_refused(tmp_path):
    problems: list = []
    build_tied(read_deck(_pair(kind="BEAM").write(tmp_path / "c.k", 1e-3)), problems)
    assert len(problems) == 1 and "BEAM_OFFSET" in problems[0].message


def test_cantilever_of_two_strips_tied_across_the_gap_bends_as_one_beam(tmp_path):
    """Strip 1 clamped at x = 0, the tip of strip 2 (x = 100) pushed
    quasi-statically by 1 mm: the tie carries the bending moment across the
    3 mm offset, so the pair is a 100 mm cantilever: clamp reaction (mean
    over the hold) 3EI·δ/L³ within 5 %, strain energy ½·F·δ within 5 %."""
    L, d = 100.0, 1.0
    ei = E * B * T**3 / 12
    per = 2 * math.pi * L**2 / 1.8751**2 * math.sqrt(RHO * B * T / ei)  # first bending period
    t_ramp, t_end = 3 * per, 4 * per
    P = _pair()
    P.add("*BOUNDARY_SPC_NODE\n" + "\n".join(f"{i},0,1,1,1,1,1,1" for i in (1001, 1008)))
    P.node_set(2, [2006, 2012])
    P.add(_ramp(1, -d, t_ramp, t_end))
    P.add("*BOUNDARY_PRESCRIBED_MOTION_SET\n2,3,2,1,1.0")
    s = setup.build(read_deck(P.write(tmp_path / "cantilever.k", t_end)))
    r = integrate(s, per / 50)
    (tie,) = [c for c in s.constraints if isinstance(c, TiedContact)]
    assert len(tie) == 2 and tie.mrot.all()
    k = 3 * ei / L**3
    hold = r.time >= t_ramp
    reaction = r.spc_force[:, :, 2].sum(axis=1)
    assert reaction[hold].mean() == pytest.approx(k * d, rel=0.05)
    assert r.internal[-1] == pytest.approx(0.5 * k * d**2, rel=0.05)


def test_free_tied_pair_keeps_momentum_and_energy(tmp_path):
    """The tied pair free in space, strip 2 thrown up at 1 m/s and spun
    about y (strip 1 at rest): the tie shares the motion at set-up keeping
    the momentum; afterwards the momentum stays the initial one to
    round-off and the energy (kinetic + internal + hourglass) within 1 %
    while the pair vibrates."""
    P = _pair()
    rows = [f"{n},0.0,0.0,{1000.0 + 40.0 * (x - 75.0)!r}" for n, x, _, _ in P.nodes if n > 2000]
    P.add("*INITIAL_VELOCITY_NODE\n" + "\n".join(rows))
    P.add("*CONTROL_TIMESTEP\n0.0,0.5")
    path = P.write(tmp_path / "free.k", 2e-3)
    s = setup.build(read_deck(path))
    r = integrate(s, 2e-5)
    m_free = setup.build(read_deck(_free_copy(P, tmp_path)))
    p0 = (m_free.mass[:, None] * m_free.v0).sum(axis=0)
    assert s.mass.sum() == pytest.approx(m_free.mass.sum(), rel=1e-14)
    p1 = (s.mass[:, None] * r.final_v).sum(axis=0)
    np.testing.assert_allclose(p1, p0, rtol=0, atol=1e-10 * np.abs(p0).max())
    total = r.kinetic + r.internal + r.hourglass
    assert r.internal.max() > 0.05 * total[0]  # it does bend
    assert np.abs(total - total[0]).max() < 0.01 * total[0]


def _free_copy(P: _Strips, tmp_path):
    """The same deck without the tie (the momentum before set-up shares it)."""
    Q = _Strips(P.t)
    Q.nodes, Q.elems = P.nodes, P.elems
    Q.cards = [c for c in P.cards if not c.startswith("*CONTACT_TIED")]
    return Q.write(tmp_path / "untied.k", 2e-3)
