"""Initial penetrations, as LS-DYNA treats them by default (IGNORE = 0): the
slave nodes that start inside the contact thickness are moved out before
the first cycle, so the contact never gives back energy it did not store.

Two 2 mm steel plates 0.5 mm apart (mid-surfaces): each reaches 1 mm from
its mid-surface, so they overlap by 1.5 mm. At rest, without the move, the
penalty springs would blow them apart; with it nothing moves.
"""

from __future__ import annotations

import numpy as np
import pytest
from _contact_decks import Deck, run

from crashlite import read_deck
from crashlite.solver import run as run_deck
from crashlite.solver import setup

GAP, T = 0.5, 2.0


def _overlapping(tmp_path, fix_lower=False, v=None, ignore=0):
    """Plate 1 (z = 0) and plate 2 (z = GAP, shifted 5 mm in x and y), 4 × 4
    elements of 10 mm; node IDs 1..25 and 26..50 (index = ID - 1)."""
    d = Deck()
    low = d.plate(1, 4, 4, 40.0, 40.0, z=0.0, thick=T)
    up = d.plate(2, 4, 4, 40.0, 40.0, z=GAP, x0=5.0, y0=5.0, thick=T)
    if fix_lower:
        d.fix(low)
    if v is not None:
        d.velocity(up, v)
    d.lines += ["*SET_PART_LIST", "1", "1,2"]
    if ignore:  # on card C (IGNORE, after cards A and B at their defaults)
        d.lines += ["*CONTACT_AUTOMATIC_SINGLE_SURFACE_ID", "7", "1,0,2", "0", "0", "0", "0", f"0,{ignore}"]
    else:
        d.contact("SINGLE_SURFACE", "1,0,2", cid=7)
    return d.write(tmp_path / "deck.k", 2e-4), low, up


def test_plates_that_start_overlapping_are_moved_apart_and_stay_at_rest(tmp_path):
    path, low, up = _overlapping(tmp_path)
    r, contacts, s = run(path, output_dt=2e-5)
    # the overlap is gone at t = 0: no entry penetrates, the nodes moved along the normal (z),
    # the upper plate up and the lower one down, each by no more than the overlap
    (g,) = contacts
    assert g.penetrations(s.x0)[1].max() <= 1e-6
    d = s.x0 - read_deck(path).nodes.xyz
    assert np.abs(d[:, :2]).max() <= 0.05 * (T - GAP)  # (closest points near the tilted edges: nearly z)
    assert d[up - 1, 2].min() >= 0.0 and d[low - 1, 2].max() <= 0.0
    assert np.abs(d[:, 2]).max() <= T - GAP + 1e-9
    over_up = up[(s.x0[up - 1, 0] <= 40.0) & (s.x0[up - 1, 1] <= 40.0)] - 1
    assert (d[over_up, 2] >= 0.5 * (T - GAP) - 1e-9).all()  # at least their half of the overlap
    assert all(m.moved for m in s.moved) and {m.node for m in s.moved} == set(np.flatnonzero(d[:, 2]))
    assert max(m.depth for m in s.moved) == pytest.approx(T - GAP, rel=1e-6)
    # nothing pushes: no motion, no energy of any kind (left in place, the 1.5 mm overlap on a penalty
    # of ~1e5 N/mm would release ~1e5 N·mm per node)
    assert np.abs(r.kinetic).max() < 1e-6 and np.abs(r.sliding).max() < 1e-6
    assert not any("sliding energy" in w for w in r.info["warnings"])
    assert any("contact 7" in str(w) and "moved out" in str(w) for w in s.warnings)


def test_moved_nodes_are_listed_in_the_results_folder(tmp_path):
    path, low, up = _overlapping(tmp_path)
    res = run_deck(path, out=tmp_path / "out")
    rows = (tmp_path / "out" / "initial_penetrations.csv").read_text().splitlines()
    assert rows[0] == "contact,node,depth,moved,tracked"
    assert any("contact 7" in w and "initial_penetrations.csv" in w for w in res.info["warnings"])
    assert {int(r.split(",")[0]) for r in rows[1:]} == {7}
    assert all(float(r.split(",")[2]) == pytest.approx(T - GAP, rel=1e-6) for r in rows[1:])


def test_a_contact_that_gives_back_energy_it_did_not_store_is_named(tmp_path):
    """The lower plate held, so its overlapped nodes cannot move out: their
    contact pushes the upper plate away from t = 0 (energy from nowhere).
    The run says so: the interface, the time, and its deepest nodes."""
    path, low, up = _overlapping(tmp_path, fix_lower=True)
    r, contacts, s = run(path, output_dt=1e-5)
    assert r.sliding.min() < -0.01 * max(r.internal.max(), 1e-9)  # the case is what it claims
    (w,) = [w for w in r.info["warnings"] if "sliding energy" in w]
    assert "CONTACT_AUTOMATIC_SINGLE_SURFACE_ID 7" in w and "deepest slave nodes" in w


def test_a_held_node_that_cannot_move_out_is_named(tmp_path):
    """The lower plate held: its nodes stay where they are; the upper plate
    moves clear, but the lower plate's edge nodes under the upper plate's
    edge segments still penetrate them, and the report names them."""
    path, low, up = _overlapping(tmp_path, fix_lower=True)
    s = setup.build(read_deck(path))
    stuck = [m for m in s.moved if not m.moved]
    assert stuck and {m.node for m in stuck} <= set(low - 1)
    (w,) = [w for w in s.warnings if "contact 7" in str(w)]
    assert "could not move" in str(w) and f" {stuck[0].node + 1}" in str(w)


@pytest.mark.parametrize("ignore", [1, 2])
def test_ignore_keeps_the_initial_penetrations_and_pushes_only_beyond_them(tmp_path, ignore):
    """IGNORE 1, 2: nothing moves at set-up, the plates stay at rest; pressed
    further together they are pushed apart (the penetration beyond the
    initial one), pulled apart they leave freely."""
    path, low, up = _overlapping(tmp_path, ignore=ignore)
    r, contacts, s = run(path, output_dt=2e-5)
    np.testing.assert_array_equal(s.x0, read_deck(path).nodes.xyz)
    assert np.abs(r.kinetic).max() < 1e-6 and np.abs(r.sliding).max() < 1e-6
    assert any("contact 7" in str(w) and "tracks" in str(w) for w in s.warnings)
    assert all(m.tracked for m in s.moved) and max(m.depth for m in s.moved) == pytest.approx(T - GAP, rel=1e-6)
    # pulled apart: no contact force at all, the upper plate keeps its speed
    path, low, up = _overlapping(tmp_path, v=(0.0, 0.0, 1.0e3), ignore=ignore)
    r, contacts, s = run(path, output_dt=2e-5)
    np.testing.assert_allclose(r.final_v[up - 1, 2], 1.0e3, rtol=1e-9)
    # pressed together: the lower plate is pushed down, momentum kept (what the coarse plates' face-to-face
    # contact gives back through the step is the discretisation effect of docs/parity.md)
    path, low, up = _overlapping(tmp_path, v=(0.0, 0.0, -1.0e3), ignore=ignore)
    r, contacts, s = run(path, output_dt=2e-5)
    p_low = (s.mass[low - 1] * r.final_v[low - 1, 2]).sum()
    p0 = (s.mass[up - 1] * -1.0e3).sum()
    assert p_low < 0.1 * p0  # it took at least a tenth of the upper plate's momentum
    assert (s.mass * r.final_v[:, 2]).sum() == pytest.approx(p0, rel=1e-9)
