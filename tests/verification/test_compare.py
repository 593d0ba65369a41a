"""Model-to-model comparison of real crashlite runs: the mini car of
``tests/unit/verify/_mini_car.py`` (1 t at 56 km/h on four linear crush
springs into a rigid wall) with spring rates k and 2k, with an extra
bumper part, against itself and against a scaled LS-DYNA ASCII copy.

Closed form for the linear single-mass pulse: peak force v0·√(m·K), crush
v0·√(m/K), time to zero velocity (π/2)·√(m/K); so doubling K raises the
peak force by √2 − 1 = 41.42 % and shortens crush and stop time by
1 − 1/√2 = 29.29 %, while both runs keep their energy.
"""

import json
import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest

from crashlite.cli import main
from crashlite.results.lsdyna_ascii import read_folder, write_all
from crashlite.verify.compare import Options, compare_paths
from crashlite.verify.errors import CompareError
from crashlite.verify.rating import iso_rating

sys.path.insert(0, str(Path(__file__).parents[1] / "unit" / "verify"))
from _mini_car import MASS, V0, write_and_run  # noqa: E402

K = 672.0  # N/mm per spring; four springs: crush 300 mm


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    root = tmp_path_factory.mktemp("runs")
    out = {
        name: write_and_run(root / name, k, extra)
        for name, k, extra in (("soft", K, False), ("stiff", 2 * K, False), ("bumper", K, True))
    }
    out["root"] = root
    return out


def _scaled_ascii(src: Path, dst: Path, factor: float = 1.0, shift: float = 0.0, nodes: bool = False) -> Path:
    """The LS-DYNA ASCII files of a run with energies and forces times
    ``factor`` (with ``nodes`` also the history nodes' displacements and
    accelerations) and times moved by ``shift``."""
    data = read_folder(src)
    for name, cat in data.items():
        for key, v in cat.items():
            q = key[-1] if isinstance(key, tuple) else key
            if q == "time":
                cat[key] = v + shift
            elif q.endswith(("energy", "force")) and name in ("glstat", "matsum", "rwforc", "secforc"):
                cat[key] = v * factor
            elif nodes and name == "nodout" and q.endswith(("_displacement", "_acceleration")):
                cat[key] = v * factor
    write_all(dst, data)
    return dst


def test_identical_runs_rate_1_with_zero_deviations(runs):
    deck, out = runs["soft"]
    c = compare_paths(out, out, decks=(deck, deck))
    assert {p.group for p in c.pairs} == {"energy", "part", "section", "wall", "node_displacement", "node_acceleration"}
    for p in c.pairs:
        assert p.deviation["max_abs_difference"] == 0.0, p.name
        assert p.deviation["peak_deviation_percent"] in (0.0, None), p.name
        if p.rating is not None:
            assert p.rating.overall == pytest.approx(1.0, abs=1e-9), p.name
    (f,) = c.fields
    assert f.figures["max_difference"] == 0.0 and len(f.ids) == 8
    assert c.pulse["deviation_percent"]["dynamic_crush"] == 0.0
    assert not c.mismatches


def test_twice_the_stiffness_gives_the_closed_form_deviations(runs):
    (da, a), (db, b) = runs["soft"], runs["stiff"]
    c = compare_paths(a, b, decks=(da, db))
    root2 = math.sqrt(2.0)
    (wall,) = c.group("wall")
    k_total = 4 * K
    assert abs(wall.deviation["peak_ref"]) == pytest.approx(V0 * math.sqrt(MASS * k_total), rel=2e-3)
    assert wall.deviation["peak_deviation_percent"] == pytest.approx(100 * (root2 - 1), abs=0.3)
    assert wall.deviation["time_of_peak_cmp"] / wall.deviation["time_of_peak_ref"] == pytest.approx(1 / root2, rel=0.02)
    (sec,) = c.group("section")
    assert sec.deviation["peak_deviation_percent"] == pytest.approx(100 * (root2 - 1), abs=0.3)
    p = c.pulse
    assert p["node"] == 5  # the body node, not the front node stopped at the wall
    assert p["reference"]["dynamic_crush"] == pytest.approx(V0 * math.sqrt(MASS / k_total), rel=5e-3)
    assert p["deviation_percent"]["dynamic_crush"] == pytest.approx(100 * (1 / root2 - 1), abs=0.3)
    assert p["deviation_percent"]["time_to_zero_velocity"] == pytest.approx(100 * (1 / root2 - 1), abs=0.5)
    assert p["deviation_percent"]["peak_deceleration"] == pytest.approx(100 * (root2 - 1), abs=0.5)
    # energy balance: both runs keep 0.5 m v0^2, so the total energies agree
    (total,) = [q for q in c.group("energy") if q.name == "total energy"]
    assert total.deviation["peak_ref"] == pytest.approx(0.5 * MASS * V0**2, rel=1e-3)
    assert abs(total.deviation["value_deviation_percent"]) < 0.1
    assert total.deviation["max_abs_difference"] < 1e-3 * total.deviation["peak_ref"]
    # the shorter, harder pulse is no excellent match
    assert wall.rating.overall < 0.9 and wall.rating.grade != "excellent"


def test_scaled_lsdyna_ascii_copy_has_the_known_deviation(runs, tmp_path):
    deck, a = runs["soft"]
    scaled = _scaled_ascii(a, tmp_path / "lsdyna", 1.1)
    c = compare_paths(a, scaled, decks=(deck, None))
    assert c.cmp.history.source == str(scaled)  # read through the LS-DYNA ASCII reader
    (wall,) = c.group("wall")
    for k in ("peak", "value", "integral"):
        v = wall.deviation[f"{k}_deviation_percent"]
        assert v is None or v == pytest.approx(10.0, abs=0.01), k
    for p in c.group("part"):
        assert p.deviation["peak_deviation_percent"] == pytest.approx(10.0, abs=0.01), p.name
    expected = iso_rating(wall.t_ref, wall.y_ref, wall.t_ref, 1.1 * wall.y_ref)
    assert wall.rating.overall == pytest.approx(expected.overall, abs=2e-3)
    disp = c.group("node_displacement")
    assert disp and all(abs(p.deviation["peak_deviation_percent"]) < 0.01 for p in disp)
    # LS-DYNA ASCII files carry no field states: the node field is that of the history nodes
    (f,) = c.fields
    assert f.ids.tolist() == [1, 5] and len(c.ref.states.ids) == 8  # all nodes (node IDs from results.npz)
    assert f.figures["max_relative_deviation_percent"] < 0.5  # 5 digits of nodout, interpolated states
    assert "node field from its 2 history nodes" in " ".join(c.cmp.notes)


def test_every_quantity_of_two_lsdyna_ascii_folders(runs, tmp_path):
    """Two LS-DYNA ASCII output folders, the second with every energy,
    force, displacement and acceleration times 1.1: each pair deviates by
    +10 % (peak, value, integral), the filtered accelerations too (the CFC
    filter is linear), the intrusion field (history nodes) by 10 % of the
    largest displacement; d3hsp files give the time accounting."""
    _, out = runs["soft"]
    ref = _scaled_ascii(out, tmp_path / "detailed", 1.0, nodes=True)
    cmp = _scaled_ascii(out, tmp_path / "simplified", 1.1, nodes=True)
    for folder, seconds in ((ref, 20880), (cmp, 40)):
        (folder / "d3hsp").write_text(
            f" number of discrete elements . . . . . .   4\n Problem cycle      =  1000\n"
            f" Elapsed time {seconds} seconds for 1000 cycles using  1 SMP thread\n"
        )
    c = compare_paths(ref, cmp, Options(times=[0.04, 0.08]))
    assert {p.group for p in c.pairs} == {"energy", "part", "section", "wall", "node_displacement", "node_acceleration"}
    assert [p.name for p in c.group("node_acceleration")] == [
        "node 1 x-acceleration CFC 60",
        "node 5 x-acceleration CFC 60",
    ]
    for p in c.pairs:
        assert p.deviation["peak_deviation_percent"] in (None, pytest.approx(10.0, abs=0.02)), p.name  # magnitudes
        for k, ref_key in (("value", "value_ref"), ("integral", "integral_ref")):
            v = p.deviation[f"{k}_deviation_percent"]  # 100·(cmp − ref)/|ref|: −10 % for a negative ref
            assert v is None or v == pytest.approx(10.0 * np.sign(p.deviation[ref_key]), abs=0.02), (p.name, k, v)
    (wall,) = c.group("wall")
    assert wall.rating.overall == pytest.approx(
        iso_rating(wall.t_ref, wall.y_ref, wall.t_ref, 1.1 * wall.y_ref).overall, abs=1e-5
    )  # 5 digits
    assert [f.time for f in c.fields] == [0.04, 0.08]
    for f in c.fields:
        assert f.ids.tolist() == [1, 5]
        u = np.linalg.norm(f.u_ref, axis=1)
        assert f.figures["max_difference"] == pytest.approx(0.1 * u.max(), rel=1e-3)
        assert f.figures["max_relative_deviation_percent"] == pytest.approx(10.0, abs=0.01)
        assert f.figures["mean_relative_deviation_percent"] == pytest.approx(10.0 * u.mean() / u.max(), abs=0.01)
    body = c.fields[-1].u_ref[1, 0]  # node 5 at 80 ms: the body's crush, the history's displacement
    nod = c.ref.history.read("nodout", "x_displacement")[:, 1]
    t = c.ref.history.read("nodout", "time")
    assert body == pytest.approx(np.interp(0.08, t, nod), rel=1e-9)
    ref_row, cmp_row = c.timing
    assert ref_row["elements_by_type"] == {"discrete": 4} and ref_row["cycles"] == 1000
    assert cmp_row["wall_reduction_percent"] == pytest.approx(100 * (1 - 40 / 20880))
    assert c.pulse["deviation_percent"]["dynamic_crush"] == 0.0  # velocities were left as they are


def test_crashlite_results_need_no_deck(runs):
    """results.npz holds the node IDs and element counts: without the decks
    the field comparison and time accounting come out as with them."""
    (da, a), (db, b) = runs["soft"], runs["stiff"]
    bare = compare_paths(a, b, Options(times=[0.03, 0.06]))
    full = compare_paths(a, b, Options(times=[0.03, 0.06]), decks=(da, db))
    assert len(bare.fields) == 2 and not any("history nodes" in n for n in bare.summary()["notes"])
    for f, g in zip(bare.fields, full.fields):
        assert f.ids.tolist() == list(range(1, 9))
        np.testing.assert_array_equal(f.u_ref, g.u_ref)
        assert f.figures == g.figures
    assert bare.fields[0].figures["max_displacement_ref"] > 100.0  # the body has crushed the springs
    for row in bare.timing:
        assert row["elements_by_type"] == {"discrete": 4, "mass": 8} and row["cycles"] > 100
        assert row["wall_time"] > 0 and row["cpu_time"] > 0 and row["setup_time"] > 0
    assert bare.timing == full.timing


def test_extra_entities_are_listed(runs):
    (da, a), (dc, cc) = runs["soft"], runs["bumper"]
    c = compare_paths(a, cc, decks=(da, dc), options=Options(parts=["crash box L", "bumper", "set:7"]))
    assert c.mismatches["part"]["only_cmp"]["ids"] == ["bumper"]
    assert c.mismatches["node"]["only_cmp"]["ids"] == [9]
    assert c.mismatches["field node"]["only_cmp"]["ids"] == [9, 10]
    assert [p.name for p in c.group("part")] == [
        "crash box L (part 1) internal energy",
        "part set 7 (parts 1, 2) internal energy",
    ]


def test_cli_writes_the_report(runs, tmp_path, capsys):
    (da, a), (dc, cc) = runs["soft"], runs["bumper"]
    rc = main(
        [
            "compare",
            str(a),
            str(cc),
            "-o",
            str(tmp_path / "rep"),
            "--deck-ref",
            str(da),
            "--deck-cmp",
            str(dc),
            "--names",
            "detailed",
            "simplified",
            "--parts",
            "crash box L",
            "set:7",
            "--time",
            "0.02",
            "0.04",
            "--view",
            "side",
        ]
    )
    assert rc == 0
    printed = capsys.readouterr().out
    assert "curve pairs" in printed and "index.html" in printed
    s = json.loads((tmp_path / "rep" / "summary.json").read_text())
    assert s["reference"]["name"] == "detailed" and s["comparison"]["title"] == "mini car k=672 with bumper"
    assert [f["time"] for f in s["fields"]] == [0.02, 0.04] and s["report"]["pictures"] == [0.02, 0.04]
    assert s["timing"][0]["elements_by_type"] == {"discrete": 4, "mass": 8}
    assert s["timing"][1]["elements"] == 5 + 9  # springs, point masses
    for row in s["timing"]:  # the time loop compared, the start-up listed apart
        assert row["wall_time"] > 0 and row["setup_time"] > 0 and row["compile_time"] >= 0
        assert row["total_wall_time"] == pytest.approx(row["wall_time"] + row["setup_time"], rel=1e-9)
    assert s["timing"][1]["wall_reduction_percent"] == pytest.approx(
        100 * (1 - s["timing"][1]["wall_time"] / s["timing"][0]["wall_time"]), rel=1e-12
    )
    assert s["reference"]["controls"]["CONTROL_TIMESTEP"]["tssfac"] == 0.5
    html = (tmp_path / "rep" / "index.html").read_text()
    assert html.count("data:image/png;base64,") >= 10 and "Time accounting" in html and "start-up" in html
    assert not re.search(r"<(script|link)\b|src=\"(?!data:)", html)  # self-contained: nothing fetched
    assert "NaN" not in (tmp_path / "rep" / "summary.json").read_text()


def test_cli_errors_are_clear_messages(runs, tmp_path, capsys):
    deck, a = runs["soft"]
    later = _scaled_ascii(a, tmp_path / "later", 1.0, shift=1.0)
    assert main(["compare", str(a), str(later), "-o", str(tmp_path / "r1")]) == 2
    err = capsys.readouterr().err
    assert "no common time range" in err and "[1, 1.08" in err
    assert main(["compare", str(a), str(a), "-o", str(tmp_path / "r2"), "--nodes", "42", "43"]) == 2
    assert "no requested node ID is in both runs" in capsys.readouterr().err
    assert main(["compare", str(a), str(tmp_path / "nowhere"), "-o", str(tmp_path / "r3")]) == 2
    assert "no such results folder" in capsys.readouterr().err
    assert not (tmp_path / "r1").exists()  # nothing written on bad input
    with pytest.raises(CompareError, match="outside the common range"):
        compare_paths(a, a, Options(at=0.5))
