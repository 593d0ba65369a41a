"""Frontal load cases around a vehicle deck: US NCAP and Euro NCAP ODB,
read and set up by the solver; the CLI."""

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.barrier.spec import ODBSpec
from crashlite.cli import main
from crashlite.solver.setup import build
from crashlite.units import kmh
from crashlite.vehicle import generic_vehicle, odb_deck, usncap_deck


@pytest.fixture(scope="module")
def car_deck(tmp_path_factory):
    d = tmp_path_factory.mktemp("vehicle")
    return generic_vehicle(38.0).write(d / "car.k")


def _vehicle_nodes(m, car):
    return np.isin(m.nodes.ids, read_deck(car).nodes.ids)


def test_usncap_rigid_wall_at_56_kmh(car_deck, tmp_path):
    path = usncap_deck(car_deck, tmp_path / "lc" / "usncap.k")
    m = read_deck(path)
    s = build(m)
    assert s.end_time == pytest.approx(0.1)
    veh = _vehicle_nodes(m, car_deck)
    assert veh.all()  # the load case adds no nodes
    assert np.allclose(s.v0[:, 0], kmh(56.0)) and np.allclose(s.v0[:, 1:], 0.0)
    wall, ground = sorted(s.walls, key=lambda w: w.normal[2])
    front = m.nodes.xyz[:, 0].max()
    assert wall.point[0] == pytest.approx(front + 1.0) and wall.normal == pytest.approx([-1.0, 0.0, 0.0])
    assert len(wall.nodes) + len(wall.watch) == len(m.nodes)
    assert ground.normal == pytest.approx([0.0, 0.0, 1.0]) and ground.point[2] == 0.0
    assert m.find("DATABASE_RWFORC") and m.find("DATABASE_SECFORC")
    assert len(s.sections) == 11 and len(s.history_nodes) == 6
    assert len(s.bodies) == 2  # rigid engine and rear axle


@pytest.mark.parametrize("barrier", ["simplified", "detailed"])
def test_odb_offset_barrier_on_the_driver_side(car_deck, tmp_path, barrier):
    path = odb_deck(car_deck, tmp_path / "odb.k", barrier=barrier, element_size=40.0)
    assert (tmp_path / "odb_barrier.k").exists()
    m = read_deck(path)
    s = build(m)
    veh = _vehicle_nodes(m, car_deck)
    assert np.allclose(s.v0[veh, 0], kmh(64.0)) and np.allclose(s.v0[~veh], 0.0)
    assert m.nodes.ids[~veh].min() > m.nodes.ids[veh].max()  # barrier IDs above the vehicle's
    xb, xv = m.nodes.xyz[~veh], m.nodes.xyz[veh]
    assert xb[:, 0].min() == pytest.approx(xv[:, 0].max() + 1.0)
    width = np.ptp(xv[:, 1])
    # 40 % of the vehicle width overlapped, on the left (+y, driver side when driving in +x)
    assert xv[:, 1].max() - xb[:, 1].min() == pytest.approx(0.4 * width)
    assert xb[:, 1].max() > xv[:, 1].max()
    contacts = [g for g in s.groups if g.kind == "contact"]
    assert len(contacts) == 2  # vehicle self contact, vehicle to barrier
    # the test rig's rigid block: a finite wall over the main block's back face, facing the car, for its nodes,
    # and the same for the barrier's own nodes but the held back ones (honeycomb torn free is stopped there)
    rig, own = sorted((w for w in s.walls if w.len_l > 0), key=lambda w: len(w.nodes) + len(w.watch), reverse=True)
    back = xb[np.isclose(xb[:, 0], xb[:, 0].max())]
    for w in (rig, own):
        assert w.normal == pytest.approx([-1.0, 0.0, 0.0]) and w.point[0] == pytest.approx(back[:, 0].max())
        lo, hi = w.point, w.point + w.len_l * w.edge_l + w.len_m * w.edge_m
        assert lo[1:] == pytest.approx(back[:, 1:].min(axis=0)) and hi[1:] == pytest.approx(back[:, 1:].max(axis=0))
    assert set(m.nodes.ids[rig.nodes]) | set(m.nodes.ids[rig.watch]) == set(m.nodes.ids[veh])
    held = m.nodes.ids[~veh][np.isclose(xb[:, 0], xb[:, 0].max())]
    on_own = set(m.nodes.ids[own.nodes]) | set(m.nodes.ids[own.watch])
    assert on_own == set(m.nodes.ids[~veh]) - set(held)
    assert s.end_time == pytest.approx(0.12)
    # crushed-solid honeycomb elements are deleted (ERODE, DTMIN) instead of stopping the run
    solids = [g for g in s.groups if g.kind == "solid"]
    if barrier == "detailed":
        assert solids[0].s.erode and solids[0].s.erode_dtmin == pytest.approx(0.1) and s.dt_min == pytest.approx(0.1)
    else:
        assert not solids and s.dt_min == 0.0


def test_load_case_for_another_deck_in_other_units(deck, tmp_path):
    """Any vehicle deck: a steel plate in mm-kg-ms gets 56 km/h as mm/ms and
    the wall ahead of its front."""
    car = deck(
        "plate.k",
        """
        *KEYWORD
        *NODE
        1,0.0,0.0,300.0
        2,-100.0,0.0,300.0
        3,-100.0,100.0,300.0
        4,0.0,100.0,300.0
        *ELEMENT_SHELL
        7,3,1,2,3,4
        *PART
        plate
                 3         3         3
        *SECTION_SHELL
                 3         2
               1.0       1.0       1.0       1.0
        *MAT_ELASTIC
                 3   7.85e-6     210.0       0.3
        *END
        """,
    )
    m = read_deck(usncap_deck(car, tmp_path / "plate_usncap.k"))
    s = build(m)
    assert np.allclose(s.v0[:, 0], 56.0 / 3.6)  # mm/ms
    assert s.end_time == pytest.approx(100.0)  # ms
    assert max(w.point[0] for w in s.walls) == pytest.approx(1.0)
    assert {r["rwid"] for r in m.find("RIGIDWALL_PLANAR")} == {11, 12}  # above every ID of the deck


def test_cli_generic_and_load_cases(tmp_path, capsys):
    car = tmp_path / "car.k"
    assert main(["vehicle", "generic", "-o", str(car), "--mesh-size", "45", "--mass", "1300"]) == 0
    out = capsys.readouterr().out
    assert "shells" in out and "mass 1300.0 kg" in out
    assert read_deck(car).mass_properties().mass * 1e3 == pytest.approx(1300.0, rel=1e-6)
    assert main(["vehicle", "loadcase", "usncap", str(car), "-o", str(tmp_path / "us.k"), "--end-time", "80"]) == 0
    assert read_deck(tmp_path / "us.k").find("CONTROL_TERMINATION")[0]["endtim"] == pytest.approx(0.08)
    assert main(["vehicle", "loadcase", "odb", str(car), "-o", str(tmp_path / "odb.k"), "--barrier", "simplified"]) == 0
    assert (tmp_path / "odb_barrier.k").exists()
    # --barrier-beams: the simplified barrier's grid, 20 across × (12 main-block rows, 6 of them the bumper's)
    odb = ["vehicle", "loadcase", "odb", str(car), "--barrier", "simplified"]
    assert main([*odb, "-o", str(tmp_path / "grid.k"), "--barrier-beams", "20", "12", "6"]) == 0
    paper, grid = (read_deck(tmp_path / f"{n}_barrier.k") for n in ("odb", "grid"))
    assert (len(paper.discretes), len(grid.discretes)) == (36 * 20 + 36 * 10, 20 * 12 + 20 * 6)
    assert grid.mass_properties().mass == pytest.approx(paper.mass_properties().mass, rel=1e-9)


def test_cli_detailed_barrier_options(tmp_path):
    """--barrier-face-size refines the detailed honeycomb's rows and columns
    (depth at --barrier-size), --barrier-elform, --barrier-slip and
    --barrier-shear-strength reach its *SECTION_SOLID, SSEF and transverse
    shear curves (slip over the element size; 'cell': each
    block's own cell, 19.14 and 6.4 mm; 'columns': split columns, links
    torn at the cell, elements at a cell's slip across a cell); a slip
    that is none of these is refused."""
    car = tmp_path / "car.k"
    assert main(["vehicle", "generic", "-o", str(car), "--mesh-size", "100"]) == 0
    base = ["vehicle", "loadcase", "odb", str(car), "--barrier", "detailed", "--barrier-size", "100"]
    assert main([*base, "-o", str(tmp_path / "coarse.k")]) == 0
    assert main([*base, "-o", str(tmp_path / "fine.k"), "--barrier-face-size", "50", "--barrier-elform", "2"]) == 0
    assert main([*base, "-o", str(tmp_path / "strong.k"), "--barrier-shear-strength", "1.4"]) == 0
    assert main([*base, "-o", str(tmp_path / "slip.k"), "--barrier-slip", "90"]) == 0
    coarse, fine, slip = (read_deck(tmp_path / f"{n}_barrier.k") for n in ("coarse", "fine", "slip"))
    (xc, yc, zc), (xf, yf, zf) = ([np.unique(np.round(m.nodes.xyz[:, a], 6)) for a in range(3)] for m in (coarse, fine))
    assert np.array_equal(xc, xf)  # depth at --barrier-size
    assert np.diff(yf).max() <= 55.0 < np.diff(yc).min() and np.diff(zf).max() <= 55.0 < np.diff(zc).min()
    assert {int(r["elform"]) for r in fine.sections.values()} == {2}
    assert {int(r["elform"]) for r in coarse.sections.values()} == {1}
    assert [float(m["ssef"]) for m in slip.materials.values()] == pytest.approx([0.9, 0.9])
    # the transverse shears' curves (LCAB, LCCA) hold the given strength × each block's plateau stress
    strong = read_deck(tmp_path / "strong_barrier.k")
    honeycombs = [m for m in strong.materials.values() if m.keyword == "MAT_HONEYCOMB"]
    for m, b in zip(honeycombs, (ODBSpec().main, ODBSpec().bumper), strict=True):
        for key in ("lcab", "lcca"):
            assert np.allclose(np.asarray(strong.curves[int(m[key])].rows["o1"], float), 1.4 * b.plateau_stress)
    assert main([*base, "-o", str(tmp_path / "cell.k"), "--barrier-slip", "cell"]) == 0
    cell = read_deck(tmp_path / "cell_barrier.k")
    assert sorted(float(m["ssef"]) for m in cell.materials.values()) == pytest.approx([0.064, 0.1914])
    assert main([*base, "-o", str(tmp_path / "cols.k"), "--barrier-slip", "columns"]) == 0
    cols = read_deck(tmp_path / "cols_barrier.k")
    # split columns: the elements tear at a cell's slip across a cell, the links at a cell's slip across the wall
    assert [float(m["ssef"]) for m in cols.materials.values() if m.keyword == "MAT_HONEYCOMB"] == [1.0, 1.0]
    assert len(cols.discretes) > 0 and len(cols.nodes) > len(cell.nodes)
    with pytest.raises(SystemExit):
        main([*base, "-o", str(tmp_path / "bad.k"), "--barrier-slip", "wide"])
