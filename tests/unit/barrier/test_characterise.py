"""Reduction of a block's force–crush characteristic to the simplified
curve, on curves with known answers, and the curves file."""

import numpy as np
import pytest

from crashlite.barrier.characterise import Characteristic, characterised_spec, read_curves, reduce_curve, write_curves
from crashlite.barrier.spec import BlockCurve, ODBSpec


def _sampled(curve: BlockCurve, depth: float, upto: float = 0.95, n: int = 4000, noise: float = 0.0):
    x, f = curve.points(depth)
    xs = np.linspace(0.0, upto * depth, n)
    fs = np.interp(xs, x, f)
    if noise:
        fs = fs * (1.0 + noise * np.sin(xs * 2.0))  # ringing of a few % about the curve
    return xs, fs


@pytest.mark.parametrize(
    "curve, depth",
    [
        (BlockCurve(plateau=500e3, peak=1000e3, rise=3.0, drop_end=12.0), 90.0),  # the paper's bumper
        (BlockCurve(plateau=230e3, peak=230e3), 450.0),  # the paper's main block
        (BlockCurve(plateau=300e3, peak=420e3, rise=5.0, drop_end=20.0, compaction=0.7, full=0.85), 300.0),
    ],
)
def test_a_sampled_curve_reduces_to_itself(curve, depth):
    x, f = _sampled(curve, depth)
    r = reduce_curve(x, f, depth, curve)
    assert r.plateau == pytest.approx(curve.plateau, rel=1e-3)
    assert r.peak == pytest.approx(curve.peak, rel=1e-2)
    assert r.rise == pytest.approx(curve.rise, abs=depth / 4000 * 2)
    if curve.peak != curve.plateau:
        assert r.drop_end == pytest.approx(curve.drop_end, rel=0.05)
    # the onset is where the force leaves 1.2 x plateau: 0.2/7 of the way to full compaction
    expected_onset = curve.compaction + 0.2 / (curve.full_factor - 1.0) * (curve.full - curve.compaction)
    assert r.compaction == pytest.approx(expected_onset, abs=2e-3)
    assert r.full == pytest.approx(curve.full, abs=2e-3)


def test_ringing_does_not_move_the_plateau_and_a_short_test_extrapolates_full_compaction():
    curve = BlockCurve(plateau=230e3, peak=230e3, compaction=0.8, full=0.92)
    x, f = _sampled(curve, 450.0, upto=0.86, noise=0.05)
    r = reduce_curve(x, f, 450.0, curve)
    assert r.plateau == pytest.approx(230e3, rel=0.01)
    assert r.full == pytest.approx(0.92, abs=0.01)  # extrapolated along the measured stiffening


def test_too_short_a_test_is_a_clear_error():
    x, f = _sampled(BlockCurve(plateau=230e3, peak=230e3), 450.0, upto=0.5)
    with pytest.raises(ValueError, match="at least 65 %"):
        reduce_curve(x, f, 450.0)
    x, f = _sampled(BlockCurve(plateau=230e3, peak=230e3), 450.0, upto=0.78)
    with pytest.raises(ValueError, match="no compaction"):
        reduce_curve(x, f, 450.0)


def test_curves_file_round_trip_into_the_spec(tmp_path):
    k = BlockCurve(plateau=240e3, peak=260e3, rise=7.0, drop_end=11.0, compaction=0.78, full=0.91)
    c = Characteristic("main block", 450.0, np.linspace(0, 400, 5), np.ones(5), np.ones(5), k, 50.0, 2e4, 10, 5, 1.0)
    path = write_curves({"main block": c}, tmp_path / "curves.json")
    curves = read_curves(path)
    assert curves["main block"] == k
    spec = characterised_spec(curves)
    assert spec.main.curve == k and spec.bumper.curve == ODBSpec().bumper.curve
    bad = tmp_path / "bad.json"
    bad.write_text('{"main block": {}}')
    with pytest.raises(ValueError, match="bad.json"):
        read_curves(bad)
