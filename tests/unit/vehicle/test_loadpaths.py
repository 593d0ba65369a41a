"""Step 1: impulses and load-path shares from section forces."""

import numpy as np
import pytest

from crashlite.results.lsdyna_ascii import secforc
from crashlite.vehicle.steps.loadpaths import (
    axial_force,
    combined_shares,
    cumulative_impulse,
    deck_sections,
    from_history,
    from_run,
    load_paths,
    plot_forces,
    plot_impulses,
    plot_shares,
)

T = 0.08  # s, pulse duration
AMPS = {"tunnel": 120e3, "door sill left": 90e3, "door sill right": 80e3, "floor left": 10e3}  # N


def _pulses(n=4001):
    """Full-period sine pulses F = A sin(2πt/T): the impulse A·T/(2π)·(1 − cos 2πt/T)
    peaks at t = T/2 with A·T/π and returns to 0 (a rebound)."""
    t = np.linspace(0.0, T, n)
    f = np.outer(np.sin(2 * np.pi * t / T), list(AMPS.values()))
    return t, f


def test_impulse_of_a_sine_pulse_is_its_integral():
    t, f = _pulses()
    imp = cumulative_impulse(t, f)
    a = np.array(list(AMPS.values()))
    exact = np.outer(1 - np.cos(2 * np.pi * t / T), a * T / (2 * np.pi))
    np.testing.assert_allclose(imp, exact, rtol=0, atol=1e-6 * a.max() * T)
    assert imp[0] == pytest.approx(np.zeros(len(a)))


def test_shares_are_max_impulses_over_their_sum():
    t, f = _pulses()
    lp = load_paths(t, f, list(AMPS), load_case="US NCAP")
    a = np.array(list(AMPS.values()))
    np.testing.assert_allclose(lp.max_impulse, a * T / np.pi, rtol=1e-6)  # not the final impulse (≈ 0)
    np.testing.assert_allclose(lp.share, a / a.sum(), rtol=1e-6)
    assert lp.shares()["tunnel"] == pytest.approx(120 / 300, rel=1e-6)
    rows = lp.table()
    assert [r["assembly"] for r in rows] == list(AMPS)
    assert sum(r["share_percent"] for r in rows) == pytest.approx(100.0)
    assert rows[0]["max_force"] == pytest.approx(120e3, rel=1e-5)


def test_half_sine_and_triangle_pulses_of_different_durations():
    t = np.linspace(0.0, 0.1, 20001)
    half = np.where(t <= 0.06, 50e3 * np.sin(np.pi * t / 0.06), 0.0)  # impulse 2·A·T/π
    tri = np.interp(t, [0.0, 0.02, 0.05, 0.1], [0.0, 40e3, 0.0, 0.0])  # impulse ½·0.05·40e3
    pull = -np.interp(t, [0.0, 0.05, 0.1], [0.0, 5e3, 0.0])  # tension only: share 0
    lp = load_paths(t, np.stack([half, tri, pull], axis=1), ["a", "b", "c"])
    ia, ib = 2 * 50e3 * 0.06 / np.pi, 0.5 * 0.05 * 40e3
    np.testing.assert_allclose(lp.max_impulse, [ia, ib, 0.0], rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(lp.share, [ia / (ia + ib), ib / (ia + ib), 0.0], rtol=1e-6)


def test_no_compressive_impulse_is_an_error():
    t = np.linspace(0, 1, 11)
    with pytest.raises(ValueError, match="no assembly carries"):
        load_paths(t, -np.ones((11, 2)), ["a", "b"]).share  # noqa: B018


def test_axial_force_is_compression_positive_whichever_way_the_normal_points():
    # secforc is tension positive along the normal: with forward normals a
    # compressed assembly shows F·x < 0
    f = np.array([[[-3.0, 1.0, 0.0], [2.0, 0.0, -5.0]]])  # one state, two sections
    np.testing.assert_allclose(axial_force(f), [[3.0, -2.0]])
    # a normal pointing rearwards: the section side is the rear, compression shows as F·x > 0
    np.testing.assert_allclose(axial_force(f, normals=[[1, 0, 0], [-1, 0, 0]]), [[3.0, 2.0]])
    np.testing.assert_allclose(axial_force(f, axis=(0, 0, 2.0)), [[0.0, 5.0]])
    with pytest.raises(ValueError, match="perpendicular"):
        axial_force(f, normals=[[0, 1, 0], [1, 0, 0]])


def _write_secforc(folder, t, f, ids):
    folder.mkdir(parents=True, exist_ok=True)
    data = {"time": t, "ids": np.asarray(ids)}
    for k, c in enumerate("xyz"):
        data[f"{c}_force"] = f[:, :, k]
    secforc.write(folder / "secforc", data)


def test_from_an_lsdyna_ascii_secforc_with_the_deck_sections(tmp_path):
    from crashlite.vehicle import generic_vehicle

    v = generic_vehicle(38.0)
    sections = deck_sections(v.model)
    assert {name: s[0] for name, s in sections.items()} == v.sections
    assert all(np.allclose(n, [1, 0, 0]) for _, n in sections.values())
    t, f1 = _pulses(801)
    ids = [v.sections[n] for n in AMPS]
    f = np.zeros((len(t), len(ids), 3))
    f[:, :, 0] = -f1  # compression: -x with the car's forward normals (tension positive)
    f[:, :, 2] = 7e3  # a vertical component does not count
    _write_secforc(tmp_path / "run", t, f, ids)
    lp = from_run(tmp_path / "run", v.model, sections={n: v.sections[n] for n in AMPS}, load_case="US NCAP")
    a = np.array(list(AMPS.values()))
    np.testing.assert_allclose(lp.share, a / a.sum(), rtol=1e-3)  # 5 significant digits in the file
    assert list(lp.section_ids) == ids and lp.load_case == "US NCAP" and not lp.notes
    with pytest.raises(KeyError, match="no section force"):
        from_history(tmp_path / "run", {"windshield": v.sections["windshield"]})
    every = from_history(tmp_path / "run")  # no names: every section of the run, normals along x
    assert every.names == tuple(f"section {i}" for i in ids) and every.notes


def test_from_a_crashlite_run_of_springs_shares_follow_their_stiffness(tmp_path):
    """A block (nodal rigid body) runs into springs held at the wall end:
    assembly "soft" two springs of k at y = ±50, assembly "stiff" one of
    6k at y = 0 (symmetric: the block does not turn); all shorten alike,
    so the impulse shares are 2k : 6k = 25 % : 75 %."""
    from crashlite import read_deck
    from crashlite.solver import run

    text = "\n".join(
        [
            "*KEYWORD",
            "*NODE",
            "1,0,50,0,7,7",
            "2,0,-50,0,7,7",
            "5,0,0,0,7,7",
            "3,100,50,0,0,7",
            "4,100,-50,0,0,7",
            "6,100,0,0,0,7",
            "*ELEMENT_MASS",
            "10,3,0.05",
            "11,4,0.05",
            "12,6,0.05",
            "*SET_NODE_LIST",
            "1",
            "3,4,6",
            "*CONSTRAINED_NODAL_RIGID_BODY",
            "100,0,1",
            "*ELEMENT_DISCRETE",
            "1,1,1,3",
            "2,1,2,4",
            "3,2,5,6",
            "*PART",
            "soft",
            "1,1,1",
            "*PART",
            "stiff",
            "2,1,2",
            "*SECTION_DISCRETE",
            "1,0",
            "*MAT_SPRING_ELASTIC",
            "1,50.0",
            "*MAT_SPRING_ELASTIC",
            "2,300.0",
            "*SET_PART_LIST",
            "1",
            "1",
            "*SET_PART_LIST",
            "2",
            "2",
            "*INITIAL_VELOCITY_NODE",
            "3,-1000.0,0,0",
            "4,-1000.0,0,0",
            "6,-1000.0,0,0",
            "*DATABASE_CROSS_SECTION_PLANE_ID",
            "5,soft",
            "1,50,0,0,51,0,0",
            "*DATABASE_CROSS_SECTION_PLANE_ID",
            "6,stiff",
            "2,50,0,0,51,0,0",
            "*CONTROL_TERMINATION",
            "0.03",
            "*CONTROL_TIMESTEP",
            ",0.1",
            "*END",
        ]
    )
    p = tmp_path / "springs.k"
    p.write_text(text)
    model = read_deck(p)
    run(model, output_dt=2e-4).save(tmp_path / "out")
    lp = from_run(tmp_path / "out", model)
    assert lp.names == ("soft", "stiff")
    assert lp.force.max() > 0 and lp.force.min() > -1e-6 * lp.force.max()  # compression positive
    np.testing.assert_allclose(lp.share, [0.25, 0.75], rtol=1e-3)


def test_combined_shares_of_two_load_cases():
    t, f = _pulses()
    a = load_paths(t, f, list(AMPS), load_case="US NCAP")
    b = load_paths(t, f[:, ::-1], list(AMPS), load_case="ODB")
    c = combined_shares([a, b])
    ea = a.share
    mean = 0.5 * (ea + ea[::-1])
    np.testing.assert_allclose(list(c["shares"].values()), mean, rtol=1e-9)
    assert c["deviation"]["US NCAP"] == pytest.approx(np.abs(ea - mean).max())
    only_a = combined_shares([a, b], weights=[1.0, 0.0])
    np.testing.assert_allclose(list(only_a["shares"].values()), ea, rtol=1e-9)


def test_figures_are_png():
    t, f = _pulses(201)
    lp = load_paths(t, f, list(AMPS), load_case="US NCAP")
    lp2 = load_paths(t, f[:, ::-1], list(AMPS), load_case="Euro NCAP ODB")
    for png in (plot_forces(lp), plot_impulses(lp), plot_shares([lp, lp2]), plot_shares(lp)):
        assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 5000
