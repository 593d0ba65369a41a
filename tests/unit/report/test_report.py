"""The comparison report: one self-contained HTML page and summary.json."""

import base64
import json
import re
import sys
from pathlib import Path

import numpy as np
import pytest

from crashlite.report import write_report
from crashlite.report.build import jsonable
from crashlite.report.pictures import side_by_side, split_cells
from crashlite.verify.compare import Options, Run, compare
from crashlite.verify.fields import FieldStates

sys.path.insert(0, str(Path(__file__).parents[1] / "verify"))
from _histories import history  # noqa: E402  synthetic histories

PNG = b"\x89PNG\r\n\x1a\n"


def plate_states(scale):
    """A 2 x 1 quad plate and one brick whose free edge moves by 10·scale in x."""
    x0 = (
        np.array(
            [
                [0, 0, 0],
                [1, 0, 0],
                [2, 0, 0],
                [0, 1, 0],
                [1, 1, 0],
                [2, 1, 0],
                [0, 0, 1],
                [1, 0, 1],
                [1, 1, 1],
                [0, 1, 1],
            ],
            float,
        )
        * 100.0
    )
    u = np.zeros_like(x0)
    u[[2, 5], 0] = 10.0 * scale
    cells = [np.array([0, 1, 4, 3]), np.array([1, 2, 5, 4]), np.array([0, 1, 4, 3, 6, 7, 8, 9]), np.array([2, 5])]
    return FieldStates(np.array([0.0, 0.1]), np.stack([x0, x0 + u]), np.arange(1, 11, dtype=np.int64), cells, "p")


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    a = Run("detailed", "/virtual/a", history(parts=(1, 2, 3)), None, plate_states(1.0))
    b = Run("simplified", "/virtual/b", history(scale=1.1, parts=(1, 2)), None, plate_states(1.1))
    c = compare(a, b, Options(times=[0.05, 0.1]))
    out = tmp_path_factory.mktemp("report")
    paths = write_report(c, out)
    return c, paths, paths["html"].read_text(), json.loads(paths["summary"].read_text())


def test_page_is_self_contained_with_embedded_plots_and_pictures(report):
    c, paths, html, _ = report
    assert paths["html"].name == "index.html" and paths["summary"].name == "summary.json"
    imgs = re.findall(r'<img alt="([^"]*)" src="([^"]*)"', html)
    assert imgs and all(src.startswith("data:image/png;base64,") for _, src in imgs)
    for _, src in imgs:
        assert base64.b64decode(src.split(",", 1)[1])[:8] == PNG
    alts = [a for a, _ in imgs]
    assert "deformed at 0.05" in alts and "deformed at 0.1" in alts and "crash pulse" in alts
    assert len([a for a in alts if a.startswith("part ")]) == 2
    assert not re.search(r"<(script|link)\b|src=\"http", html)
    for heading in (
        "Runs and settings",
        "Crash pulse",
        "Global energies",
        "Internal energy per part",
        "Section forces",
        "Rigid-wall forces",
        "History-node displacements",
        "History-node accelerations",
        "Node fields and deformed structures",
        "Entities not matched",
    ):
        assert heading in html, heading


def test_summary_holds_every_figure(report):
    c, _, html, s = report
    assert {
        "reference",
        "comparison",
        "options",
        "time_range",
        "overall",
        "curves",
        "fields",
        "pulse",
        "timing",
        "mismatches",
        "notes",
        "report",
    } <= set(s)
    assert s["reference"]["name"] == "detailed" and s["time_range"] == [0.0, 0.1]
    (wall,) = s["curves"]["wall"]
    assert wall["peak_deviation_percent"] == pytest.approx(10.0, abs=1e-9)
    assert {"corridor", "phase", "magnitude", "slope", "overall", "grade"} <= set(wall["rating"])
    assert s["mismatches"]["part"]["only_ref"] == {"count": 1, "ids": [3]}
    f = s["fields"][-1]
    assert f["time"] == 0.1 and f["max_difference"] == pytest.approx(1.0)
    assert f["max_relative_deviation_percent"] == pytest.approx(10.0)
    assert s["fields"][0]["max_difference"] == pytest.approx(0.5)  # half way
    assert s["report"]["pictures"] == [0.05, 0.1]
    assert s["pulse"]["reference"]["v0"] == pytest.approx(15555.6)
    assert "+10.00 %" in html  # the wall's peak deviation in its table


def test_json_refuses_nan():
    assert jsonable({"a": np.float64(1.5), "b": [np.int64(2)], "c": None}) == {"a": 1.5, "b": [2], "c": None}
    with pytest.raises(ValueError, match="not a number"):
        jsonable({"x": float("nan")})


def test_cells_split_into_lines_facets_and_brick_faces():
    lines, polys = split_cells([np.array([0, 1]), np.array([0, 1, 2]), np.array([0, 1, 2, 3]), np.arange(8)])
    assert lines.tolist() == [[0, 1]]
    assert len(polys) == 2 + 6
    assert sorted(polys[2].tolist()) == [0, 1, 2, 3] and sorted(polys[3].tolist()) == [4, 5, 6, 7]


def test_pictures_without_cells_show_the_nodes():
    s = plate_states(1.0)
    s.cells = []
    assert side_by_side([("a", s), ("b", s)], 0.1, view="side")[:8] == PNG


def test_large_models_are_drawn_as_nodes(monkeypatch):
    from crashlite.report import pictures

    monkeypatch.setattr(pictures, "MAX_FACETS", 2)
    s = plate_states(1.0)
    assert side_by_side([("a", s), ("b", s)], 0.1)[:8] == PNG
