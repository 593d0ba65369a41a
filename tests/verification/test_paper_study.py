"""The paper study (``paper_study``) end to end on the coarsest car and
barrier over the first milliseconds: one surrogate from both load cases'
runs, its combined shares, the runs it verifies against each other and the
time reductions it reports. (The crash-length figures are in the README
and bench/reduction.py.)"""

import json

import numpy as np
import pytest

from crashlite.solver.results import Results
from crashlite.vehicle.workflow import paper_study


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    return paper_study(
        tmp_path_factory.mktemp("paper"),
        mesh_size=60.0,
        barrier_size=100.0,
        usncap_end=0.01,
        odb_end=0.01,
        variants=False,
        say=lambda *a: None,
    )


@pytest.mark.slow
def test_one_surrogate_takes_the_mean_shares_of_both_load_cases(study):
    red = json.loads((study.out / "reduction.json").read_text())
    cases = {p["load_case"]: p for p in red["step1_load_paths"]}
    assert set(cases) == {"US NCAP", "Euro NCAP ODB"}
    used = red["shares_used"]
    assert used["basis"] == "combined"
    for name, share in used["shares_percent"].items():
        own = [next(a["share_percent"] for a in cases[c]["assemblies"] if a["assembly"] == name) for c in cases]
        assert share == pytest.approx(np.mean(own), abs=1e-9)
    # the ODB loads the driver's side: its own shares differ from the US NCAP ones
    dev = used["max_deviation_percent_points"]
    assert dev["Euro NCAP ODB"] > 1.0 and dev["US NCAP"] > 1.0


@pytest.mark.slow
def test_each_run_conserves_energy_and_the_barriers_take_their_part(study):
    assert set(study.runs) == {
        "usncap full",
        "usncap simplified",
        "odb full car, detailed barrier",
        "odb simplified car, simplified barrier",
    }
    for name, run in study.runs.items():
        r = Results.load(run["results"])
        assert np.all(np.abs(r.energy_ratio - 1.0) < 0.02), name
        assert r.kinetic[-1] < 0.99 * r.kinetic[0], name  # decelerating
    for name, word in (
        ("odb full car, detailed barrier", "detailed ODB"),
        ("odb simplified car, simplified barrier", "simplified ODB"),
    ):
        r = Results.load(study.runs[name]["results"])
        from crashlite import read_deck

        m = read_deck(study.runs[name]["deck"])
        # (the surrogate's nodal rigid bodies report under IDs that are no *PART)
        barrier = [
            k for k, p in enumerate(r.part_ids) if str(m.parts.get(int(p), {}).get("heading", "")).startswith(word)
        ]
        assert barrier and r.part_internal[-1, barrier].sum() > 0.2 * r.internal[-1], name


@pytest.mark.slow
def test_summary_pairs_the_runs_and_reports_their_time_reductions(study):
    s = json.loads((study.out / "summary.json").read_text())
    loop = {k: v["loop_time_s"] for k, v in s["runs"].items()}
    t = s["time"]
    assert t["us_ncap"]["vehicle_reduction_percent"] == pytest.approx(
        100.0 * (1.0 - loop["usncap simplified"] / loop["usncap full"])
    )
    assert t["odb"]["combined_reduction_percent"] == pytest.approx(
        100.0 * (1.0 - loop["odb simplified car, simplified barrier"] / loop["odb full car, detailed barrier"])
    )
    assert "barrier_reduction_percent" not in t["odb"]  # no single-simplification runs asked for
    assert s["front"] == "generic"
    odb = s["verification"]["Euro NCAP ODB"]
    assert odb["names"] == ["full + detailed barrier", "simplified + simplified barrier"]
    assert odb["time"]["full"]["cycles"] == s["runs"]["odb full car, detailed barrier"]["cycles"]
    assert s["verification"]["US NCAP"]["time"]["simplified"]["cycles"] == s["runs"]["usncap simplified"]["cycles"]
    from crashlite.vehicle.verify.study_report import verification_lines

    lines = verification_lines(s)
    assert [ln.split(":")[0] for ln in lines] == ["US NCAP", "Euro NCAP ODB"]
    cb = s["verification"]["US NCAP"]["crash_box_internal_energy_deviation_percent"]
    assert f"crash-box energy {cb:.1f} %" in lines[0]
    page = (study.out / "index.html").read_text()
    for href in ("reduction.html", "verify/us_ncap/index.html", "verify/euro_ncap_odb/index.html"):
        assert f'href="{href}"' in page and (study.out / href).is_file()


@pytest.mark.slow
def test_summary_and_page_give_each_runs_hourglass_share(study):
    s = json.loads((study.out / "summary.json").read_text())
    for name, run in study.runs.items():
        r = Results.load(run["results"])
        hg = s["runs"][name]["hourglass_percent"]
        assert hg["end_percent"] == pytest.approx(100.0 * r.hourglass[-1] / r.internal[-1], rel=1e-9), name
        assert hg["max_percent"] >= hg["end_percent"] - 1e-9
        assert hg["part"]["hourglass"] == pytest.approx(r.part_hourglass[-1].max(), rel=1e-9)
        assert s["runs"][name]["deleted_elements"] == r.part_deleted[-1].sum(), name
    page = (study.out / "index.html").read_text()
    assert "Hourglass energy" in page and "elements deleted" in page
    detailed = s["runs"]["odb full car, detailed barrier"]["hourglass_percent"]
    assert f"{detailed['end_percent']:.1f} %" in page
