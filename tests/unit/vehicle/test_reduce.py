"""Steps 1–4 end to end on a two-rail shell model: full run, reduction from
its section forces, surrogate run, and the surrogate against the full run."""

import json

import numpy as np
import pytest
from _structures import E, shell_model, tube_mesh

from crashlite import read_deck, write_deck
from crashlite.model.mesh import Masses
from crashlite.solver import run
from crashlite.vehicle.car.records import id_list, record
from crashlite.vehicle.reduce import reduce_vehicle, section_assemblies
from crashlite.vehicle.verify.verification import verify_vehicle
from crashlite.vehicle.verify.verification_report import verification_page
from crashlite.verify.rating import iso_rating

B, L = 50.0, 500.0
T = {"rail left": 1.5, "rail right": 1.0}
V0 = 5000.0  # mm/s
END = 0.012


def _two_rails():
    parts = []
    for k, (name, t) in enumerate(T.items()):
        xyz, quads = tube_mesh(B, L, 4, 20)
        xyz = xyz + [0.0, (-1) ** k * 200.0, 0.0]
        parts.append((name, t, xyz, quads))
    xyz = np.vstack([p[2] for p in parts])
    n0 = len(parts[0][2])
    quads = np.vstack([parts[0][3], parts[1][3] + n0])
    pid = np.repeat([1, 2], len(parts[0][3]))
    m = shell_model(xyz, quads, pids=pid)
    for k, (name, t, _, _) in enumerate(parts):
        m.parts[k + 1]["heading"] = name
        for f in ("t1", "t2", "t3", "t4"):
            m.sections[k + 1][f] = t
    rear = np.flatnonzero(np.isclose(xyz[:, 0], 0.0))
    front = np.flatnonzero(np.isclose(xyz[:, 0], L))
    ms = Masses.zeros(len(rear) + len(front))
    ms.ids = np.arange(1, len(ms.ids) + 1) + 5000
    ms.node = np.concatenate([rear, front]).astype(np.int32)
    ms.mass = np.concatenate([np.full(len(rear), 0.3 / len(rear)), np.full(len(front), 0.05 / len(front))])
    m.masses = ms
    ids = m.nodes.ids
    m.sets[("NODE", 1)] = id_list("SET_NODE_LIST_TITLE", 1, ids[rear], title="rear axle attachment")
    m.sets[("NODE", 2)] = id_list("SET_NODE_LIST_TITLE", 2, ids, title="everything")
    m.sets[("NODE", 3)] = id_list("SET_NODE_LIST_TITLE", 3, ids[front], title="firewall nodes")
    m.sets[("PART", 1)] = id_list("SET_PART_LIST_TITLE", 1, [1], title="assembly rail left")
    m.sets[("PART", 2)] = id_list("SET_PART_LIST_TITLE", 2, [2], title="assembly rail right")
    m.keywords += [
        record("CONSTRAINED_NODAL_RIGID_BODY", pid=90, nsid=1),
        record("INITIAL_VELOCITY", nsid=2, vx=V0),
        record("RIGIDWALL_PLANAR_ID", rwid=1, heading="wall", nsid=2, xt=L + 1.0, xh=L),
        record("DATABASE_CROSS_SECTION_PLANE_ID", csid=1, title="rail left", psid=1, xct=L / 2, xch=L / 2 + 1),
        record("DATABASE_CROSS_SECTION_PLANE_ID", csid=2, title="rail right", psid=2, xct=L / 2, xch=L / 2 + 1),
        record(
            "DATABASE_HISTORY_NODE_ID",
            rows={"id": ids[[rear[0], front[0]]], "heading": np.array(["rear", "front"], object)},
        ),
        record("CONTROL_TERMINATION", endtim=END),
        record("CONTROL_TIMESTEP", tssfac=0.9),
        record("DATABASE_SECFORC", dt=5e-5),
        record("DATABASE_RWFORC", dt=5e-5),
        record("DATABASE_NODOUT", dt=5e-5),
        record("DATABASE_GLSTAT", dt=5e-5),
        record("DATABASE_MATSUM", dt=5e-5),
        record("DATABASE_BINARY_D3PLOT", dt=END / 12),
    ]
    return m, rear, front


@pytest.fixture(scope="module")
def full_run(tmp_path_factory):
    d = tmp_path_factory.mktemp("reduce")
    m, rear, front = _two_rails()
    full_deck = write_deck(m, d / "full.k")[0]
    return m, run(full_deck, out=d / "full"), full_deck, d


@pytest.fixture(scope="module", params=["condensed", "springs"])
def reduced(full_run, request):
    m, full, full_deck, root = full_run
    d = root / request.param
    # an elastic impact of a short structure: what reaches the cut comes back from the rear masses within
    # the run, which the cut dashpots (made for a crash's first passage into a large rear) would keep
    # (the wall impulse 7 % short); the condensation alone here
    red = reduce_vehicle(
        full_deck, [root / "full"], load_cases=["wall"], modes=4, connection=request.param, cut_dashpots=False
    )
    files = red.write(d / "simplified.k")
    sur = run(files["deck"], out=d / "simplified")
    return m, full, red, files, sur, d


def test_sections_name_the_assemblies():
    m, _, _ = _two_rails()
    asm, ids, point = section_assemblies(m)
    assert asm == {"rail left": [1], "rail right": [2]} and ids == {"rail left": 1, "rail right": 2}
    np.testing.assert_allclose(point, [L / 2, 0.0, 0.0])


@pytest.mark.slow
def test_reduction_figures(reduced):
    m, full, red, files, _, _ = reduced
    s = red.shares
    assert s["rail left"] + s["rail right"] == pytest.approx(1.0)
    assert s["rail left"] > s["rail right"]  # the thicker rail carries more
    # the rails in parallel, E·A/l each; the rigid interface loaded at its centre also yaws a little
    # (the rails differ), which the bending of the rails resists: K just below the sum
    k_rails = sum(E * 4 * B * t / (L / 2) for t in T.values())
    assert 0.93 * k_rails < red.stiffness.stiffness < 1.005 * k_rails
    rep = red.mass.structure.mass
    shells = m.mass_properties().mass - 0.35  # less the point masses
    assert rep == pytest.approx(0.3 + shells / 2, rel=1e-6)  # the rear masses and the rear halves
    summary = json.loads(files["summary"].read_text())
    conn = summary["connection_against_structure"]
    assert summary["step4_surrogate"]["connection"] == red.connection_kind
    if red.connection_kind == "condensed":
        # the condensed cut held rigid is the inertia-relief stiffness of step 3, a little softer across
        # (its shell rotations are free)
        c = summary["step4_surrogate"]["condensation"]
        assert c["nodes"] == 2 * 16 and c["left_out"] == 0
        assert summary["step4_surrogate"]["longitudinal_stiffness"] == pytest.approx(red.relief.stiffness, rel=0.03)
        assert conn["directions"]["axial"]["compliance_ratio"] == pytest.approx(1.0, rel=0.03)
        sim = read_deck(files["deck"])
        assert len(sim.find("ELEMENT_DIRECT_MATRIX_INPUT")) == 1 and not len(sim.discretes)
        return
    assert summary["step4_surrogate"]["longitudinal_stiffness"] == pytest.approx(red.spring_stiffness)
    assert red.springs == "relief" and summary["step3_stiffness"]["springs_from"] == "relief"
    # the rear point masses (0.3 of 0.35 + shells) dominate the replaced halves: under inertia relief the
    # rails shorten nearly to their far ends, a little stiffer than borne there
    assert red.stiffness.stiffness < red.spring_stiffness < 1.25 * red.stiffness.stiffness
    assert summary["model_size"]["simplified_elements"] < summary["model_size"]["full_elements"]
    # the springs share the rails' K as the rails do (shares from the impulses, near their thickness ratio):
    # along the axis the surrogate is about as compliant as the structure it replaces
    assert 0.8 < conn["directions"]["axial"]["compliance_ratio"] < 1.25
    modes = summary["replaced_structure_modes"]
    assert len(modes["held"]["frequencies"]) == len(modes["free"]["frequencies"]) == 4
    assert all(sum(v) <= 100.0 + 1e-6 for v in modes["held"]["effective_mass_percent"].values())
    page = files["html"].read_text()
    assert "Step 3" in page and "data:image/png;base64" in page and "effective mass" in page
    assert read_deck(files["deck"]) == red.surrogate.model


@pytest.mark.slow
def test_surrogate_run_matches_the_full_run(reduced):
    """The wall impulse and the rear body's velocity change within 3 %, its
    velocity history rated ≥ 0.9 (ISO/TS 18571), energy conserved within
    1 %: the rails stay elastic, so the surrogate (front halves + springs
    k_i = share_i·K + rear rigid body) carries the impact as the full
    model does (the peak wall force, a single sample of a ringing signal,
    is not compared)."""
    _, full, _, _, sur, _ = reduced
    imp = [np.trapezoid(r.wall_force[:, 0, 0], r.time) for r in (full, sur)]
    assert imp[1] == pytest.approx(imp[0], rel=0.03)
    rear = int(full.history_nodes[0])
    v = [r.node_velocity[:, list(r.history_nodes).index(rear), 0] for r in (full, sur)]
    assert v[0][0] - v[0][-1] > 1.5 * V0  # it rebounds
    assert v[1][0] - v[1][-1] == pytest.approx(v[0][0] - v[0][-1], rel=0.03)
    assert iso_rating(full.time, v[0], sur.time, v[1]).overall >= 0.9
    for r in (full, sur):
        assert np.all(np.abs(r.energy_ratio - 1.0) < 0.01)


@pytest.mark.slow
def test_verification_figures(reduced):
    """The figures of ``verify_vehicle`` against their direct computation;
    the front ring's compression towards the rear body (the "intrusion"
    here) within 5 % of the full model's at every node."""
    m, full, red, files, sur, d = reduced
    v = verify_vehicle(
        d.parent / "full",
        d / "simplified",
        d.parent / "full.k",
        files["deck"],
        load_case="wall",
        crash_boxes=("rail left", "rail right"),
        reference="rear",
        engine="front",
    )
    f = v.figures
    t_stop = f["deceleration_phase_end"]
    k = list(full.history_nodes).index(f["reference_node"])
    assert full.node_velocity[np.searchsorted(full.time, t_stop), k, 0] <= 0.0 < full.node_velocity[0, k, 0]
    e_full = np.interp(t_stop, full.time, full.part_internal.sum(axis=1))
    e_sur = np.interp(t_stop, sur.time, sur.part_internal[:, np.isin(sur.part_ids, [1, 2])].sum(axis=1))
    cb = f["crash_box_internal_energy"]
    assert cb["full"] == pytest.approx(e_full, rel=1e-6) and cb["simplified"] == pytest.approx(e_sur, rel=1e-6)
    assert f["crash_box_internal_energy_deviation_percent"] == pytest.approx(100 * (e_sur - e_full) / e_full)
    assert f["firewall_intrusion"]["max_intrusion_full"] > 0.1  # mm: the rails are compressed
    assert f["firewall_intrusion_max_deviation_percent"] < 5.0
    # the split at the interface uses the cut rings' nodes (16 a rail), not the surrogate's own new nodes
    assert f["firewall_intrusion"]["split"]["interface_nodes"] == 2 * 16
    assert f["energy_rating_min"] > 0.9  # kinetic and internal; the total is conserved, not rated:
    assert f["energies"]["total"]["rating"] is None and f["energies"]["total"]["max_difference_percent"] < 1.0
    assert f["time"]["elements_simplified"] < f["time"]["elements_full"]
    out = v.write(d / "verify")
    summary = json.loads(out["summary"].read_text())
    for key in (
        "crash_box_internal_energy_deviation_percent",
        "firewall_intrusion_max_deviation_percent",
        "firewall_intrusion_mean_deviation_percent",
        "energy_ratings_deceleration_phase",
        "time_reduction_percent",
    ):
        assert key in summary
    assert "data:image/png;base64" in out["html"].read_text()


def test_elastic_twin_splits_the_deviations(reduced, tmp_path, capsys):
    """`crashlite vehicle twin` of the elastic rails changes nothing (no
    elasto-plastic metal behind the cut, said so); verified with the full
    run as the twin's, the premise's deviations are zero and the
    surrogate's are the direct comparison's."""
    from crashlite.cli import main

    m, full, red, files, sur, d = reduced
    twin_deck = tmp_path / "twin.k"
    assert main(["vehicle", "twin", str(d.parent / "full.k"), "-o", str(twin_deck)]) == 0
    out = capsys.readouterr().out
    assert f"0 elements behind x = {L / 2:g} elastic" in out and "*MAT_ELASTIC left as they are: 1, 2" in out
    assert np.array_equal(read_deck(twin_deck).shells.pid, m.shells.pid)
    v = verify_vehicle(
        d.parent / "full",
        d / "simplified",
        d.parent / "full.k",
        files["deck"],
        load_case="wall",
        crash_boxes=("rail left", "rail right"),
        reference="rear",
        engine="front",
        twin=d.parent / "full",
        twin_deck=twin_deck,
    )
    f, tw = v.figures, v.figures["elastic_twin"]
    assert tw["premise"]["crash_box_internal_energy_deviation_percent"] == 0.0
    assert tw["premise"]["firewall_intrusion_max_deviation_percent"] == 0.0
    assert tw["surrogate"]["crash_box_internal_energy_deviation_percent"] == pytest.approx(
        f["crash_box_internal_energy_deviation_percent"], rel=1e-12
    )
    for k in ("max", "mean"):
        assert tw["surrogate"][f"firewall_intrusion_{k}_deviation_percent"] == pytest.approx(
            f[f"firewall_intrusion_{k}_deviation_percent"], rel=1e-12
        )
    assert "elastic premise" in verification_page(v)


def test_cli_reduce_with_modes_writes_a_deck_that_runs(full_run, tmp_path, capsys):
    """`crashlite vehicle reduce --condensed-modes 2`: the deck, its DMIG
    file beside it (two modal nodes with their y in the superelement),
    the cut dashpots, and a run of it that conserves energy (the
    dashpots' work counted as internal energy)."""
    from crashlite.cli import main

    _, _, full_deck, root = full_run
    out = tmp_path / "cut.k"
    assert (
        main(
            [
                "vehicle",
                "reduce",
                str(full_deck),
                "--results",
                str(root / "full"),
                "-o",
                str(out),
                "--condensed-modes",
                "2",
            ]
        )
        == 0
    )
    assert "wrote" in capsys.readouterr().out
    sim = read_deck(out)
    rec = sim.find("ELEMENT_DIRECT_MATRIX_INPUT")[0]
    assert rec["filename"] == "cut.dmig" and (tmp_path / "cut.dmig").exists()
    summary = json.loads((tmp_path / "reduction.json").read_text())
    assert summary["step4_surrogate"]["condensation"]["modes"] == 2
    modal = sim.node_index(summary["step4_surrogate"]["node_ids"]["modes"])
    assert np.all(sim.nodes.tc[modal] == 6)  # x and z held: the modal coordinate is y
    assert len(sim.discretes) == 2 * 16  # the cut dashpots (default), one per cut node
    r = run(out, out=tmp_path / "run")
    assert np.all(np.abs(r.energy_ratio - 1.0) < 0.01)
