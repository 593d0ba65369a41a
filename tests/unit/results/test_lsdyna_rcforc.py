"""rcforc, the resultant contact forces, read by ``crashlite.results``:
LS-DYNA's ASCII layout (l2a's ``translate_rcforc``: a slave and a master
line per interface and state, single surface contacts left out), a binout's
``rcforc`` branch through lasso-python, and crashlite's own runs; each as
``contact_force`` of ``results.from_history``: the slave lines, as
crashlite's solver gives it."""

from pathlib import Path

import numpy as np
import pytest

from crashlite.results import load
from crashlite.results.from_history import results_from_history
from crashlite.results.lsdyna_ascii import rcforc
from crashlite.solver.results import Results
from crashlite.study.responses import evaluate_responses, parse_response
from crashlite.units import system

# LS-DYNA's layout: title, version line, legend, then "  slave %11d time%12.5E  x %12.5E ...";
# interface 1 is a single surface contact (a note, no lines), interface 12 has an ID of its own
LSDYNA = """\
 box on barrier
                         ls-dyna R12.2.1 d                 date 04/05/2023

{BEGIN LEGEND}
 Entity #        Title
        3     box on barrier
       12     bumper

{END LEGEND}
 interface number,         1,is single surface-resultants are undefined
  slave           3 time 0.00000E+00  x  0.00000E+00  y  0.00000E+00  z  0.00000E+00 mass  0.00000E+00
  master          3 time 0.00000E+00  x  0.00000E+00  y  0.00000E+00  z  0.00000E+00 mass  0.00000E+00
  slave          12 time 0.00000E+00  x  0.00000E+00  y  0.00000E+00  z  0.00000E+00 mass  0.00000E+00
  master         12 time 0.00000E+00  x  0.00000E+00  y  0.00000E+00  z  0.00000E+00 mass  0.00000E+00
 interface number,         1,is single surface-resultants are undefined
  slave           3 time 1.00000E-03  x  1.25000E+03  y -2.00000E+01  z  3.50000E+00 mass  1.50000E-03
  master          3 time 1.00000E-03  x -1.25000E+03  y  2.00000E+01  z -3.50000E+00 mass  2.00000E-02
  slave          12 time 1.00000E-03  x -4.00000E+02  y  0.00000E+00  z  7.00000E+01 mass  2.50000E-03
  master         12 time 1.00000E-03  x  4.00000E+02  y  0.00000E+00  z -7.00000E+01 mass  3.00000E-03
"""

# with moments (mx my mz) and tied nodes, as LS-DYNA adds them after the mass (one line each)
MOMENTS = (
    " tied plate\n"
    "                         ls-dyna R12.2.1 d                 date 04/05/2023\n\n\n"
    "  slave           5 time 2.00000E-03  x  1.00000E+00  y  2.00000E+00  z  3.00000E+00 mass  4.00000E-01"
    "  mx  5.00000E+00  my -6.00000E+00  mz  7.00000E+00  tied          8  tied area  9.00000E+01\n"
    "  master          5 time 2.00000E-03  x -1.00000E+00  y -2.00000E+00  z -3.00000E+00 mass  4.50000E-01"
    "  mx -5.00000E+00  my  6.00000E+00  mz -7.00000E+00  tied          8  tied area  9.00000E+01\n"
)


def test_rcforc_in_lsdyna_layout(tmp_path):
    """Every line a column (Binout names: ids twice, side 0 slave / 1
    master); the single surface notes and the legend are passed over."""
    p = tmp_path / "rcforc"
    p.write_text(LSDYNA)
    d = rcforc.read(p)
    assert d["time"].tolist() == [0.0, 1e-3]
    assert d["ids"].tolist() == [3, 3, 12, 12] and d["side"].tolist() == [0, 1, 0, 1]
    assert d["x_force"][1].tolist() == [1250.0, -1250.0, -400.0, 400.0]
    assert d["y_force"][1].tolist() == [-20.0, 20.0, 0.0, 0.0]
    assert d["z_force"][1].tolist() == [3.5, -3.5, 70.0, -70.0]
    assert d["mass"][1].tolist() == [1.5e-3, 2e-2, 2.5e-3, 3e-3]
    assert "x_moment" not in d
    # contact_force: the slave lines, by interface
    res = results_from_history(load(p))
    assert res.contact_ids.tolist() == [3, 12]
    np.testing.assert_array_equal(res.contact_force[1], [[1250.0, -20.0, 3.5], [-400.0, 0.0, 70.0]])
    np.testing.assert_array_equal(res.contact_force[0], np.zeros((2, 3)))

    p.write_text(MOMENTS)
    d = rcforc.read(p)
    assert d["ids"].tolist() == [5, 5] and d["side"].tolist() == [0, 1]
    assert d["mass"][0].tolist() == [0.4, 0.45]
    assert [d[f"{a}_moment"][0, 0] for a in "xyz"] == [5.0, -6.0, 7.0]
    assert [d[f"{a}_force"][0, 1] for a in "xyz"] == [-1.0, -2.0, -3.0]


def _binout(path: Path, ids, side, time, forces) -> Path:
    """A binout's rcforc branch as LS-DYNA writes it (LSDA, lasso-python's
    writer): metadata ids and side, a directory per state with time and
    x/y/z_force and mass over the lines."""
    from lasso.dyna.lsda_py3 import Lsda

    f = Lsda(str(path), "w")
    f.cd("/rcforc/metadata")
    f.write("title", Lsda.I1, b"stand-in".ljust(80))
    f.write("ids", Lsda.I4, [int(i) for i in ids])
    f.write("side", Lsda.I4, [int(s) for s in side])
    for i, t in enumerate(time):
        f.cd(f"/rcforc/d{i + 1:06d}")
        f.write("time", Lsda.R4, [float(t)])
        for k, a in enumerate("xyz"):
            f.write(f"{a}_force", Lsda.R4, [float(v) for v in forces[i, :, k]])
        f.write("mass", Lsda.R4, [0.0] * forces.shape[1])
    f.close()
    return path


def test_rcforc_of_a_binout(tmp_path):
    """A binout's rcforc through lasso-python: the slave lines are the
    contact forces; a contact without surfaces, listed with ID 0 but
    without forces, is dropped as l2a drops it."""
    pytest.importorskip("lasso.dyna", reason="reading a binout needs lasso-python")
    t = np.array([0.0, 1e-3, 2e-3])
    f = np.zeros((3, 4, 3))
    f[:, 0] = np.outer(t, [1.0e6, -2.0e5, 0.5e5])  # slave of 7
    f[:, 1] = -f[:, 0]  # master of 7
    f[:, 2] = np.outer(t, [0.0, 3.0e5, 0.0])  # slave of 2
    f[:, 3] = -f[:, 2]
    _binout(tmp_path / "binout", [7, 7, 2, 2], [0, 1, 0, 1], t, f)
    res = results_from_history(load(tmp_path))
    assert res.contact_ids.tolist() == [7, 2]
    np.testing.assert_allclose(res.contact_force, f[:, [0, 2]], rtol=1e-7)

    _binout(tmp_path / "binout", [0, 0, 7, 7], [0, 1, 0, 1], t, f[:, :2])
    res = results_from_history(load(tmp_path))
    assert res.contact_ids.tolist() == [7]
    np.testing.assert_allclose(res.contact_force[:, 0], f[:, 0], rtol=1e-7)


def _results(t: np.ndarray, cids: list, force: np.ndarray) -> Results:
    """A crashlite Results with contact forces and an energy history only."""
    n, e = len(t), np.zeros(0, np.int64)
    return Results(
        time=t,
        kinetic=np.ones(n),
        internal=np.zeros(n),
        wall=np.zeros(n),
        external=np.zeros(n),
        discrete_force=np.zeros((n, 0)),
        discrete_elong=np.zeros((n, 0)),
        wall_force=np.zeros((n, 0, 3)),
        wall_velocity=np.zeros((n, 0)),
        node_displacement=np.zeros((n, 0, 3)),
        node_velocity=np.zeros((n, 0, 3)),
        spc_force=np.zeros((n, 0, 3)),
        spc_nodes=e,
        history_nodes=e,
        discrete_ids=e,
        wall_ids=e,
        section_ids=e,
        section_force=np.zeros((n, 0, 3)),
        part_ids=e,
        part_internal=np.zeros((n, 0)),
        states_time=np.zeros(0),
        states_x=np.zeros((0, 0, 3)),
        final_x=np.zeros((0, 3)),
        final_v=np.zeros((0, 3)),
        contact_force=force,
        contact_ids=np.array(cids, np.int64),
    )


def test_crashlite_runs_write_rcforc_and_read_it_back(tmp_path):
    """A crashlite run's rcforc in LS-DYNA's layout: the slave line its
    contact_force, the master line the reaction; read back from the file
    alone, contact_force responses equal the run's own to the file's six
    digits, with the same IDs and signs."""
    t = np.linspace(0.0, 0.01, 11)
    force = np.zeros((11, 2, 3))
    force[:, 0] = np.outer(np.sin(300.0 * t), [2.5e4, -1.2e3, 40.0])  # nodes pushed up and aside
    force[:, 1] = np.outer(t, [0.0, 0.0, -7.0e5])
    res = _results(t, [4, 9], force)
    res.save(tmp_path / "run")
    lines = (tmp_path / "run" / "rcforc").read_text().splitlines()
    slave, master = [x for x in lines if x.startswith("  slave")], [x for x in lines if x.startswith("  master")]
    assert len(slave) == len(master) == 22
    assert slave[10].split()[:4] == ["slave", "4", "time", "5.00000E-03"]  # state 5: slave 4, slave 9 ...
    assert float(slave[10].split()[5]) == pytest.approx(force[5, 0, 0], rel=1e-5)
    assert float(master[10].split()[5]) == pytest.approx(-force[5, 0, 0], rel=1e-5)

    (tmp_path / "ascii").mkdir()
    (tmp_path / "ascii" / "rcforc").write_bytes((tmp_path / "run" / "rcforc").read_bytes())
    back = results_from_history(load(tmp_path / "ascii"))
    assert back.contact_ids.tolist() == [4, 9]
    np.testing.assert_allclose(back.contact_force, force, rtol=5e-6, atol=5e-6 * np.abs(force).max())
    npz = results_from_history(load(tmp_path / "run"))  # results.npz: full precision
    np.testing.assert_array_equal(npz.contact_force, force)

    tables = {
        f"{cid}_{c}_{stat}": {"type": "contact_force", "id": cid, "component": c, "stat": stat}
        for cid in (4, 9)
        for c in ("x", "y", "z", "magnitude")
        for stat in ("max", "min")
    }
    specs = {name: parse_response(name, table) for name, table in tables.items()}
    units = system("mm-t-s")
    own = evaluate_responses(specs, res, None, {}, units)
    read = evaluate_responses(specs, back, None, {}, units)
    assert own["4_x_max"] == pytest.approx(2.5e4 * np.sin(1.5), rel=1e-12)  # the sample nearest 90 degrees
    assert own["9_z_min"] == pytest.approx(-7.0e3, rel=1e-12)
    for name in specs:
        assert read[name] == pytest.approx(own[name], rel=1e-5, abs=1e-5 * np.abs(force).max()), name
