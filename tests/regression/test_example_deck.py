"""The bundled example deck: read, summarised, written and re-read."""

import json

import numpy as np
import pytest

from crashlite import read_deck, write_deck
from crashlite.cli import main
from crashlite.demo import example_deck
from crashlite.keyword.equality import model_differences


@pytest.fixture(scope="module")
def tube():
    return read_deck(example_deck("tube"))


def test_example_contents(tube):
    assert len(tube.nodes) == 1969 and len(tube.shells) == 1920 and len(tube.masses) == 1
    assert tube.sections[1]["t1"] == 1.5
    assert tube.materials[1]["sigy"] == pytest.approx(235.0 * 1.05, rel=1e-15)
    assert tube.masses.mass[0] == 0.05
    assert tube.set_members("NODE", 1).size == 49  # impact ring + mass node
    # 60 x 60 x 200 tube of 1.5 mm steel plus the 50 kg mass
    m = tube.mass_properties()
    shell_mass = 7.85e-9 * 4 * 60 * 200 * 1.5
    assert m.mass == pytest.approx(shell_mass + 0.05, rel=1e-12)
    assert m.cog[2] == pytest.approx((shell_mass * 100 + 0.05 * 200) / (shell_mass + 0.05), rel=1e-12)
    assert not tube.warnings


@pytest.mark.parametrize("fmt", ["fixed", "long", "i10", "free"])
def test_example_roundtrip(tube, tmp_path, fmt):
    out = tmp_path / f"tube_{fmt}.k"
    write_deck(tube, out, fmt=fmt)
    assert model_differences(tube, read_deck(out)) == []


def test_info_json(capsys):
    assert main(["info", str(example_deck("tube")), "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["counts"]["shells"] == 1920
    assert s["units"].startswith("mm-t-s")
    assert s["keywords"]["ELEMENT_SHELL"] == 1920
    assert [p["title"] for p in s["parts"]] == ["tube"]
    np.testing.assert_allclose(s["total"]["cog"][:2], [0.0, 0.0], atol=1e-9)
    assert s["parameters"]["thick"] == 1.5


def test_info_text(capsys):
    assert main(["info", str(example_deck("tube"))]) == 0
    out = capsys.readouterr().out
    assert "mm-t-s" in out and "ELEMENT_SHELL" in out and "tube" in out


def test_demo_runs_and_pulse_matches_closed_form(tmp_path, capsys):
    from crashlite.demo import main as demo

    assert demo([str(tmp_path / "demo"), "--skip-vehicle"]) == 0  # the vehicle stage: test_vehicle_reduction
    out = capsys.readouterr().out
    assert "re-read: identical" in out and "dynamic crush" in out
    assert (tmp_path / "demo" / "pulse" / "results.npz").is_file()


def test_impactor_on_crush_springs_matches_closed_form():
    """5 t at 15 km/h on a 230 kN S08 bank: stroke m v0²/(2F), stop time
    m v0/F, plateau F and rebound sqrt(F²/(K m)) within 2 %."""
    import math

    from crashlite.solver import run

    model = read_deck(example_deck("impactor"))
    r = run(model)
    v = r.wall_velocity[:, 0]
    stroke = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(r.time))])
    m, v0, f, k = 5.0, 4166.67, 230000.0, 230000.0
    assert stroke.max() == pytest.approx(m * v0**2 / (2 * f), rel=0.02)
    assert r.time[np.argmax(stroke)] == pytest.approx(m * v0 / f, rel=0.02)
    assert np.abs(r.wall_force[:, 0, 0]).max() == pytest.approx(f, rel=0.02)
    assert -v[-1] == pytest.approx(math.sqrt(f**2 / k / m), rel=0.02)
