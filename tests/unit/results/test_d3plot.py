"""The d3plot a run writes beside its VTK states (*DATABASE_BINARY_D3PLOT),
read back with lasso-python: the deck's nodes and elements, the states'
times, coordinates, velocities and accelerations, the shells' stresses and
plastic strains, the solids', deleted elements; a run without lasso-python
says so once and still writes the VTK states; the output folder takes the
d3plot files for the run's own.

A strip of four shells (or solids) pulled past yield at one end, the last
element of a steel twice as strong (it stays elastic): a few hundred
cycles, about a second a run.
"""

import json
import re
import sys
from pathlib import Path

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.results.d3plot import _shell_global
from crashlite.results.folder import MANIFEST
from crashlite.results.vtk import read_points
from crashlite.solver import run

lasso_dyna = pytest.importorskip("lasso.dyna")
D3plot, A = lasso_dyna.D3plot, lasso_dyna.ArrayType

E, SY, ET, L = 200000.0, 200.0, 2000.0, 100.0
END, RAMP = 2e-3, 5e-4
F32 = 4 * np.finfo(np.float32).eps  # relative precision of the d3plot's single-precision words


def _strip(tmp_path, solid: bool = False, fail: float = 0.0, name: str = "strip.k") -> str:
    """Nodes 1.. along x (two or four per station), elements 100..103; the
    left end held along x, the right end pulled to 1.75 mm at up to 1 m/s;
    part 1 "strip" (mild steel, FAIL as given), part 2 "strong" (the last
    element, twice the yield stress); d3plot states every END / 4; the
    pulled nodes in nodout."""
    lines = ["*KEYWORD", "*TITLE", "d3plot strip", "*NODE"]
    corners = [(0.0, 0.0), (0.0, 10.0)] + ([(10.0, 0.0), (10.0, 10.0)] if solid else [])
    nid = {}
    for i, x in enumerate(np.linspace(0.0, L, 5)):
        for j, (z, y) in enumerate(corners):
            nid[i, j] = 1 + i * len(corners) + j
            lines.append(f"{nid[i, j]},{float(x)!r},{y!r},{z!r}")
    held = [nid[0, j] for j in range(len(corners))]
    pulled = [nid[4, j] for j in range(len(corners))]
    if solid:
        lines += ["*ELEMENT_SOLID"] + [
            f"{100 + i},{1 + i // 3},"
            + ",".join(
                str(nid[k, j])
                for k, j in ((i, 0), (i + 1, 0), (i + 1, 1), (i, 1), (i, 2), (i + 1, 2), (i + 1, 3), (i, 3))
            )
            for i in range(4)
        ]
        lines += ["*SECTION_SOLID", "1,1"]
    else:
        lines += ["*ELEMENT_SHELL"] + [
            f"{100 + i},{1 + i // 3},{nid[i, 0]},{nid[i + 1, 0]},{nid[i + 1, 1]},{nid[i, 1]}" for i in range(4)
        ]
        lines += ["*SECTION_SHELL", "1,2,1.0,3", "1.0,1.0,1.0,1.0"]
    lines += ["*PART", "strip", "1,1,1", "*PART", "strong", "2,1,2"]
    for mid, sy, f in ((1, SY, fail), (2, 2 * SY, 0.0)):
        lines += ["*MAT_PIECEWISE_LINEAR_PLASTICITY", f"{mid},7.85e-9,{E!r},0.3,{sy!r},{ET!r},{f!r}", "0.0,0.0", "", ""]
    lines += [
        "*SET_NODE_LIST",
        "1",
        ",".join(map(str, held)),
        "*SET_NODE_LIST",
        "2",
        ",".join(map(str, pulled)),
        "*BOUNDARY_SPC_SET",
        "1,0,1,0,0,0,0,0",
        "*BOUNDARY_SPC_NODE",
        f"{nid[0, 0]},0,0,1,1,0,0,0",
        "*DEFINE_CURVE",
        "5",
        "0.0,0.0",
        f"{RAMP!r},1000.0",
        "1.0,1000.0",
        "*BOUNDARY_PRESCRIBED_MOTION_SET",
        "2,1,0,5,1.0",
        "*DATABASE_HISTORY_NODE",
        ",".join(map(str, pulled)),
        "*CONTROL_TERMINATION",
        repr(END),
        "*DATABASE_BINARY_D3PLOT",
        repr(END / 4),
    ]
    lines += ["*CONTROL_TIMESTEP", "0.0,0.7", "*END"] if solid else ["*END"]
    p = tmp_path / name
    p.write_text("\n".join(lines) + "\n")
    return str(p)


def _vtk_times(out) -> list[float]:
    return [float(t) for t in re.findall(r'timestep="([^"]+)"', (out / "states" / "states.pvd").read_text())]


def _close(a, b, scale=None):
    """a == b within the d3plot's single precision (relative to ``scale``,
    default the largest |b|)."""
    b = np.asarray(b, float)
    scale = float(np.abs(b).max()) if scale is None else scale
    np.testing.assert_allclose(np.asarray(a, float), b, rtol=0, atol=F32 * max(scale, 1e-30))


def test_a_shell_run_writes_its_states_as_a_d3plot(tmp_path):
    deck = _strip(tmp_path)
    out = tmp_path / "run"
    r = run(deck, out=out)
    model = read_deck(deck)
    assert (out / "d3plot").is_file() and (out / "states" / "states.pvd").is_file()  # both, ParaView's kept
    d = D3plot(str(out / "d3plot"))
    a = d.arrays
    # geometry: the deck's nodes, shells and parts
    assert a[A.node_ids].tolist() == model.nodes.ids.tolist()
    _close(a[A.node_coordinates], model.nodes.xyz)
    assert a[A.element_shell_ids].tolist() == [100, 101, 102, 103]
    assert a[A.element_shell_node_indexes].tolist() == model.shells.nodes.tolist()
    assert a[A.part_ids][a[A.element_shell_part_indexes]].tolist() == [1, 1, 1, 2]
    titles = dict(zip(a[A.part_titles_ids].tolist(), (t.decode().strip() for t in a[A.part_titles])))
    assert titles == {1: "strip", 2: "strong"}
    assert d.header.title.strip() == "d3plot strip"
    # the states: the VTK states' times and coordinates
    times = a[A.global_timesteps]
    assert len(times) == len(_vtk_times(out)) == len(r.states_time) == 5  # t = 0, END/4 .. the last
    _close(times, _vtk_times(out))
    _close(times, r.states_time)
    coords = a[A.node_displacement]  # d3plot keeps the current coordinates
    for k, vtk in enumerate(sorted((out / "states").glob("state_*.vtk"))):
        _close(coords[k], read_points(vtk)[0], scale=L)
    _close(coords[0], model.nodes.xyz, scale=L)
    _close(coords[-1], r.final_x, scale=L)
    rows = np.searchsorted(model.nodes.ids, r.history_nodes)  # the pulled nodes
    assert coords[-1, rows, 0] - L == pytest.approx((END - 0.5 * RAMP) * 1000.0, rel=1e-3)
    # velocities and accelerations: those of nodout at the same times (every state falls on an output cycle)
    for k, t in enumerate(r.states_time[1:], start=1):
        j = int(np.flatnonzero(r.time == t)[0])
        _close(a[A.node_velocity][k, rows], r.node_velocity[j], scale=1000.0)
        _close(
            a[A.node_acceleration][k, rows],
            r.node_acceleration[j],
            scale=max(np.abs(r.node_acceleration[j]).max(), 1.0),
        )
    assert np.abs(a[A.node_acceleration][1, rows]).max() > 1e5  # the end of the ramp: 2e6 mm/s² before it
    assert np.all(a[A.node_velocity][0] == 0.0)  # at rest at t = 0
    _close(a[A.node_velocity][-1, rows, 0], np.full(len(rows), 1000.0))
    # shells: effective plastic strain (mid-surface, inner, outer) as crashlite's, the strong one elastic
    eps = a[A.element_shell_effective_plastic_strain]
    assert eps.shape == (5, 4, 3)
    _close(eps[-1].max(axis=1), r.shell_plastic_strain)
    assert eps[-1, :3].min() > 0.01 and np.all(eps[-1, 3] == 0.0)
    assert np.all(eps[0] == 0.0)
    # stress: uniaxial along x, the same in every element (one force along the strip)
    sig = a[A.element_shell_stress][-1]
    assert sig.shape == (4, 3, 6)
    sxx = sig[..., 0]
    assert sxx.min() > SY and sxx.max() - sxx.min() < 0.05 * sxx.mean()
    assert np.abs(sig[..., 1:]).max() < 0.05 * sxx.mean()
    _close(a[A.element_shell_thickness][0], np.ones(4))
    assert np.all(a[A.element_shell_is_alive] == 1.0)
    # the kinetic and internal energies of the history at the states' times
    _close(a[A.global_internal_energy][-1], r.internal[-1])


def test_a_solid_run_writes_its_solids(tmp_path):
    deck = _strip(tmp_path, solid=True)
    out = tmp_path / "run"
    r = run(deck, out=out)
    model = read_deck(deck)
    a = D3plot(str(out / "d3plot")).arrays
    assert a[A.element_solid_ids].tolist() == [100, 101, 102, 103]
    assert a[A.element_solid_node_indexes].tolist() == model.solids.nodes.tolist()
    assert a[A.part_ids][a[A.element_solid_part_indexes]].tolist() == [1, 1, 1, 2]
    _close(a[A.global_timesteps], _vtk_times(out))
    _close(a[A.node_displacement][-1], r.final_x, scale=L)
    eps = a[A.element_solid_effective_plastic_strain]
    assert eps.shape == (5, 4, 1)
    _close(eps[-1, :, 0], r.solid_plastic_strain)
    assert eps[-1, :3, 0].min() > 0.01 and eps[-1, 3, 0] == 0.0
    sig = a[A.element_solid_stress][-1, :, 0]
    assert sig[:, 0].min() > SY and np.abs(sig[:, 1:]).max() < 0.05 * sig[:, 0].mean()
    assert np.all(a[A.element_solid_is_alive] == 1.0)


def test_eroded_shells_are_deleted_in_the_d3plot(tmp_path):
    """FAIL = 0.01 in the strip's steel: the shells whose points all reach
    it are deleted, the others are not."""
    fail = 0.01
    deck = _strip(tmp_path, fail=fail)
    r = run(deck, out=tmp_path / "run")
    alive = D3plot(str(tmp_path / "run" / "d3plot")).arrays[A.element_shell_is_alive]
    gone = r.shell_plastic_strain >= fail
    assert gone.any() and not gone.all()
    assert np.all(alive[0] == 1.0)
    assert alive[-1].tolist() == (~gone).astype(float).tolist()


def test_shell_stresses_turn_from_the_element_frame_to_global_axes():
    """A square shell turned about an oblique axis: σx σy τxy τyz τzx in
    its frame (e1 along side 1-2, e3 its normal) come out as R σ Rᵀ."""
    ax = np.array([1.0, 2.0, 3.0]) / np.sqrt(14.0)
    th = 0.7
    k = np.array([[0, -ax[2], ax[1]], [ax[2], 0, -ax[0]], [-ax[1], ax[0], 0]])
    rot = np.eye(3) + np.sin(th) * k + (1 - np.cos(th)) * k @ k
    x = np.array([[0.0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]]) @ rot.T + [5.0, -1.0, 2.0]
    local = np.array([[[100.0, -30.0, 20.0, 5.0, -7.0]]])
    g = _shell_global(local, x, np.array([[0, 1, 2, 3]]))[0, 0]
    s = np.array([[100.0, 20.0, -7.0], [20.0, -30.0, 5.0], [-7.0, 5.0, 0.0]])
    want = rot @ s @ rot.T
    np.testing.assert_allclose(g, [want[0, 0], want[1, 1], want[2, 2], want[0, 1], want[1, 2], want[0, 2]], atol=1e-9)


def test_without_lasso_the_run_says_so_once_and_writes_the_vtk_states(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "lasso", None)
    monkeypatch.setitem(sys.modules, "lasso.dyna", None)
    out = tmp_path / "run"
    r = run(_strip(tmp_path), out=out)
    said = [w for w in r.info["warnings"] if "d3plot" in w]
    assert said == ["d3plot needs lasso-python: pip install crashlite[lsdyna]"]
    assert len(list((out / "states").glob("state_*.vtk"))) == 5
    assert not list(out.glob("d3plot*"))


def test_the_output_folder_takes_the_d3plot_files_for_the_run_s_own(tmp_path, capsys):
    """A reused folder loses the earlier run's d3plot files (also ones the
    new run does not write); a d3plot file no run wrote refuses the run
    unless forced."""
    from crashlite.cli import main

    deck = _strip(tmp_path)
    out = tmp_path / "out"
    assert main(["run", deck, "-o", str(out), "--quiet"]) == 0
    listed = json.loads((out / MANIFEST).read_text())["files"]
    assert "d3plot" in listed and "d3plot01" in listed
    (out / "d3plot02").write_bytes(b"an earlier run's further state file")  # as if that run had written it
    manifest = json.loads((out / MANIFEST).read_text())
    manifest["files"].append("d3plot02")
    (out / MANIFEST).write_text(json.dumps(manifest))
    assert main(["run", deck, "-o", str(out), "--quiet"]) == 0
    assert not (out / "d3plot02").exists()
    assert len(D3plot(str(out / "d3plot")).arrays[A.global_timesteps]) == 5
    (out / "d3plot07").write_bytes(b"LS-DYNA's")
    assert main(["run", deck, "-o", str(out), "--quiet"]) == 2
    assert "d3plot07" in capsys.readouterr().err and (out / "d3plot07").read_bytes() == b"LS-DYNA's"
    assert main(["run", deck, "-o", str(out), "--quiet", "--force"]) == 0
    assert not (out / "d3plot07").exists()


def test_field_states_of_a_run_kept_as_d3plot_only(tmp_path):
    """A run folder with a d3plot and no results.npz (as LS-DYNA's) gives
    its field states through the d3plot: the states crashlite saved, to
    single precision, with the deck's node IDs and the shells as cells."""
    from crashlite.verify.fields import load_states

    deck = _strip(tmp_path)
    out = tmp_path / "run"
    run(deck, out=out)
    full = load_states(out)
    (out / "results.npz").unlink()
    st = load_states(out)
    assert st is not None and st.source.endswith("(d3plot)")
    assert st.ids.tolist() == read_deck(deck).nodes.ids.tolist()
    np.testing.assert_allclose(st.time, full.time, rtol=1e-6)
    _close(st.x, full.x)
    assert np.ptp(st.x[:, :, 0], axis=0).max() > 0.1  # the strip moved
    assert [c.tolist() for c in st.cells] == read_deck(deck).shells.nodes.tolist()


def test_field_states_of_an_lsdyna_d3plot():
    """LS-DYNA R12.2.1's d3plot of lasso-python's SPH test model
    (tests/data/lsdyna_r12_sph): states every DT = 0.004 of its
    *DATABASE_BINARY_D3PLOT, first-state coordinates those of its *NODE
    cards."""
    from crashlite.verify.fields import load_states

    folder = Path(__file__).parents[2] / "data" / "lsdyna_r12_sph"
    st = load_states(folder)
    assert len(st.time) == 10 and st.time[0] == 0.0
    np.testing.assert_allclose(np.diff(st.time[:9]), 0.004, rtol=0.01)
    deck = {
        int(ln.split()[0]): [float(v) for v in ln.split()[1:4]]
        for ln in (folder / "sph_test.k").read_text().split("*NODE")[1].split("*")[0].splitlines()[2:]
        if ln.strip()
    }
    k = [list(st.ids).index(i) for i in deck]
    np.testing.assert_allclose(st.x[0, k], np.array(list(deck.values())), rtol=1e-6, atol=1e-6)
    assert np.abs(st.x[-1] - st.x[0]).max() > 0.1  # the particles moved
