"""The simplified ODB deck: counts, shares, mass, placement, units, re-read."""

import numpy as np
import pytest

from crashlite import read_deck, write_deck
from crashlite.barrier import ODBSpec, offset_placement, simplified_barrier
from crashlite.keyword.equality import model_differences
from crashlite.units import SYSTEMS


@pytest.fixture(scope="module")
def deck(tmp_path_factory):
    d = tmp_path_factory.mktemp("odb")
    b = simplified_barrier(id_offset=7_000_000)
    path = b.write(d / "odb.k")
    return b, read_deck(path), d


def test_counts_of_the_paper(deck):
    b, m, _ = deck
    assert b.beams == 1080 == len(m.discretes)
    assert np.count_nonzero(m.discretes.pid == 7_000_001) == 720  # main block
    assert np.count_nonzero(m.discretes.pid == 7_000_002) == 360  # bumper
    assert len(m.shells) == b.shells > 0
    assert m.nodes.ids.min() > 7_000_000  # every ID above the offset


def test_rereads_identically(deck):
    _, m, d = deck
    write_deck(m, d / "again.k")
    assert model_differences(m, read_deck(d / "again.k")) == []


def test_beam_shares_cover_each_face_once(deck):
    _, m, _ = deck
    for pid in (7_000_001, 7_000_002):
        assert m.discretes.scale[m.discretes.pid == pid].sum() == pytest.approx(1.0, rel=1e-12)


def test_mass_is_the_specified_barrier_mass(deck):
    b, m, _ = deck
    spec = ODBSpec()
    assert b.mass == pytest.approx(spec.mass, rel=1e-12)
    assert m.mass_properties().mass == pytest.approx(spec.mass, rel=1e-9)


def test_face_dimensions_and_heights(deck):
    b, m, _ = deck
    xyz = m.nodes.xyz
    front = xyz[np.isin(m.nodes.ids, b.node_ids["bumper_front"])]
    block = xyz[np.isin(m.nodes.ids, b.node_ids["block_front"])]
    back = xyz[np.isin(m.nodes.ids, b.node_ids["back"])]
    assert np.ptp(block[:, 1]) == pytest.approx(1000.0) and np.ptp(block[:, 2]) == pytest.approx(650.0)
    assert (front[:, 2].min(), front[:, 2].max()) == pytest.approx((280.0, 610.0))
    assert (block[:, 2].min(), block[:, 2].max()) == pytest.approx((200.0, 850.0))
    assert np.allclose(front[:, 0], 0.0) and np.allclose(block[:, 0], 90.0) and np.allclose(back[:, 0], 540.0)
    # bumper rows are rows of the block: the bumper beams end on block-front nodes
    assert set(np.round(front[:, 2], 9)) <= set(np.round(block[:, 2], 9))


def test_offset_placement_covers_the_overlap_on_the_driver_side():
    w = 1700.0
    pl = offset_placement(w, overlap=0.4, side="left")  # vehicle moving +x: left is +y
    assert pl.y_min == pytest.approx(w / 2 - 0.4 * w)  # inner edge of the barrier
    pr = offset_placement(w, overlap=0.4, side="right")
    assert pr.y_min + 1000.0 == pytest.approx(-(w / 2 - 0.4 * w))
    pm = offset_placement(w, overlap=0.4, side="left", direction=-1)  # moving -x: left is -y
    assert pm.y_min + 1000.0 == pytest.approx(-(w / 2 - 0.4 * w))
    with pytest.raises(ValueError, match="overlap"):
        offset_placement(w, overlap=40)


def test_units_scale_every_quantity(tmp_path):
    si = simplified_barrier(units=SYSTEMS["m-kg-s"], cladding=False)
    mm = simplified_barrier(cladding=False)
    a, b = read_deck(si.write(tmp_path / "si.k")), read_deck(mm.write(tmp_path / "mm.k"))
    assert np.allclose(a.nodes.xyz * 1e3, b.nodes.xyz)
    assert a.mass_properties().mass == pytest.approx(b.mass_properties().mass * 1e3, rel=1e-9)
    assert a.curves.keys() == b.curves.keys()
    for k in a.curves:  # force–crush curves: metres vs millimetres, newtons in both
        np.testing.assert_allclose(a.curves[k].rows["a1"] * 1e3, b.curves[k].rows["a1"], rtol=1e-12)
        np.testing.assert_allclose(a.curves[k].rows["o1"], b.curves[k].rows["o1"], rtol=1e-12)


def test_bumper_must_fit_the_block():
    from dataclasses import replace

    spec = ODBSpec()
    bad = replace(spec, bumper=replace(spec.bumper, z_low=100.0))
    with pytest.raises(ValueError, match="bumper"):
        simplified_barrier(bad)


def test_cli_writes_a_placed_barrier_and_a_runnable_impactor_case(tmp_path, capsys):
    from crashlite.cli import main

    assert (
        main(
            [
                "barrier",
                "simplified",
                "-o",
                str(tmp_path / "odb.k"),
                "--vehicle-width",
                "1700",
                "--id-offset",
                "5000000",
            ]
        )
        == 0
    )
    m = read_deck(tmp_path / "odb.k")
    assert len(m.discretes) == 1080 and m.nodes.ids.min() > 5_000_000
    assert m.nodes.xyz[:, 1].min() == pytest.approx(850.0 - 0.4 * 1700.0)
    assert (
        main(
            ["barrier", "impactor", "-o", str(tmp_path / "imp"), "--overlap", "40", "--no-cladding", "--end-time", "20"]
        )
        == 0
    )
    assert main(["run", str(tmp_path / "imp" / "main.k"), "-o", str(tmp_path / "out"), "--quiet"]) == 0
    assert "energy ratio" in capsys.readouterr().out


def test_cli_strip_impactor_is_a_finite_wall_of_the_strips_height(tmp_path):
    """`crashlite barrier impactor --height 390 500`: the moving wall is
    finite, its lower edge 390 mm above ground and 110 mm high, even at
    100 % overlap (the full width)."""
    from crashlite.barrier.loadcases import Impactor, impactor_deck
    from crashlite.barrier.simplified import Placement
    from crashlite.cli import main

    assert main(["barrier", "impactor", "-o", str(tmp_path), "--height", "390", "500", "--end-time", "5"]) == 0
    lines = (tmp_path / "main.k").read_text().splitlines()
    k = lines.index("*RIGIDWALL_PLANAR_MOVING_FINITE")
    origin, extent = lines[k + 2].split(","), lines[k + 3].split(",")
    assert float(origin[2]) == 390.0
    assert [float(v) for v in extent[3:5]] == [1000.0, 110.0]
    with pytest.raises(ValueError, match="low edge below"):
        impactor_deck("b.k", 1, Placement(), Impactor(height=(500.0, 390.0)), 0.01)
