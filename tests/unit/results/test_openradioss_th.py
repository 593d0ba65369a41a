"""OpenRadioss time histories (``<run>T01``) read into LS-DYNA's categories.

Two kinds of files: ones written here by a small writer that follows the
format OpenRadioss's engine writes (``hist1.F``, ``hist2.F``; read by its
``th_to_csv``), with known values; and two real T01 files of OpenRadioss's
QA tests, fetched by ``tests/data/openradioss/fetch.sh`` (not redistributed:
their tests skip when the files are absent).
"""

from __future__ import annotations

import os
import struct
from pathlib import Path

import numpy as np
import pytest

from crashlite.results import load
from crashlite.results import openradioss_th as th
from crashlite.results.from_history import results_from_history

DATA = Path(os.environ.get("CRASHLITE_OPENRADIOSS_DATA", Path(__file__).parents[2] / "data" / "openradioss"))


# --- a writer following the format ------------------------------------------------
def _rec(payload: bytes) -> bytes:
    n = struct.pack(">i", len(payload))
    return n + payload + n


def _ints(*v: int) -> bytes:
    return struct.pack(f">{len(v)}i", *v)


def _reals(v) -> bytes:
    v = np.asarray(v, float).ravel()
    return struct.pack(f">{len(v)}f", *v)


def _title(text: str, n: int) -> bytes:
    return text.ljust(n).encode("latin-1")


def write_t01(path: Path, time, glob, parts, groups, code: int = 3050, cut: int = 0) -> Path:
    """``glob`` (n, n_glob) with codes 1..n_glob; ``parts``: [(id, title,
    codes, values (n, nvar))]; ``groups``: [(id, type, title, ids, codes,
    values (n, n_ent, nvar))]. ``cut`` bytes are cut off the end."""
    length = 100 if code >= 4021 else 80 if code >= 3041 else 40
    out = [_rec(_ints(code) + _title("a test run", 80)), _rec(_title("date and program", 80))]
    if code > 3050:
        out += [_rec(_ints(3)), _rec(_ints(length)), _rec(_reals([1.0, 1.0, 1.0]))]
    n_glob = glob.shape[1]
    out.append(_rec(_ints(len(parts), 1, 1, 0, len(groups), n_glob)))
    out.append(_rec(_ints(*range(1, n_glob + 1))))
    for pid, title, codes, _ in parts:
        out.append(_rec(_ints(pid) + _title(title, length) + _ints(1, pid, pid, len(codes))))
        if len(codes):
            out.append(_rec(_ints(*codes)))
    out.append(_rec(_ints(1) + _title("material", length)))
    out.append(_rec(_ints(1) + _title("property", length)))
    for gid, gtype, title, ids, codes, _ in groups:
        out.append(_rec(_ints(gid, gtype, 0, len(ids), len(codes)) + _title(title, length)))
        out += [_rec(_ints(i) + _title(f"entity {i}", length)) for i in ids]
        out.append(_rec(_ints(*codes)))
    for k, t in enumerate(time):
        out.append(_rec(_reals([t])))
        out.append(_rec(_reals(glob[k])))
        pv = [v[k] for *_, v in parts if v.shape[1]]
        if pv:
            out.append(_rec(_reals(np.concatenate(pv))))
        for *_, values in groups:
            out.append(_rec(_reals(values[k])))
    data = b"".join(out)
    path.write_bytes(data[: len(data) - cut] if cut else data)
    return path


T = np.array([0.0, 0.001, 0.002, 0.004])
N = len(T)


def _sample(tmp_path: Path, name: str = "carT01", **kw) -> Path:
    glob = np.zeros((N, 22))
    glob[:, 0] = [0.0, 1.0, 3.0, 6.0]  # IE
    glob[:, 1] = [100.0, 99.0, 96.0, 90.0]  # KE
    glob[:, 2] = [-10.0, -9.0, -8.0, -7.0]  # XMOM
    glob[:, 5] = 2.0  # MASS
    glob[:, 6] = 1e-6  # DT
    glob[:, 7] = [1.0, 1.0, 0.5, 0.5]  # rotational KE
    glob[:, 8] = [0.0, 0.1, 0.2, 0.3]  # external work
    glob[:, 10] = [0.0, 0.0, 0.5, 1.0]  # contact energy
    glob[:, 11] = [0.0, 0.2, 0.4, 0.6]  # hourglass energy
    glob[:, 16] = 0.01  # added mass
    ie = np.stack([glob[:, 0] * 0.25, glob[:, 0] * 0.75], axis=1)
    parts = [
        (1, "rail", [1, 2, 7, 24], np.stack([ie[:, 0], [60.0, 59, 58, 57], [0, 0.1, 0.2, 0.3], [0.5] * 4], 1)),
        (2, "bumper", [1, 2, 7], np.stack([ie[:, 1], [40.0, 40, 38, 33], [0, 0.1, 0.2, 0.3]], 1)),
        (3, "no history", [], np.zeros((N, 0))),
    ]
    d = np.array([[0.0, -0.01, -0.02, -0.04]]).T  # x displacement over time
    node_a = np.zeros((N, 2, 9))  # DX DY DZ VX VY VZ AX AY AZ of nodes 101, 102
    node_a[:, 0, 0] = d[:, 0]
    node_a[:, 1, 0] = 2 * d[:, 0]
    node_a[:, :, 3] = -10.0
    node_a[:, 1, 8] = 9.81
    node_b = np.zeros((N, 1, 3))  # DX DY DZ of node 201 (and 101 again: read once)
    node_b[:, 0, 1] = 0.5
    impulse = np.outer(T, [-1000.0, 0.0, 0.0, 0.0, -50.0, 0.0])  # constant force (FN, FT)
    wall = impulse.reshape(N, 1, 6)
    inter = (2 * impulse).reshape(N, 1, 6)
    sec = np.concatenate([impulse, np.outer(T, [0.0, 0.0, 7.0])], axis=1).reshape(N, 1, 9)  # FN FT MX MY MZ
    groups = [
        (10, th.NODE, "nodes", [101, 102], list(range(1, 10)), node_a),
        (11, th.NODE, "more nodes", [201, 101], [1, 2, 3], np.concatenate([node_b, node_b], axis=1)),
        (12, th.RWALL, "walls", [7], [1, 2, 3, 4, 5, 6], wall),
        (13, th.INTER, "contacts", [3], [1, 2, 3, 4, 5, 6], inter),
        (14, th.SECTIO, "sections", [5], [1, 2, 3, 4, 5, 6, 31, 32, 33], sec),
    ]
    return write_t01(tmp_path / name, T, glob, parts, groups, **kw)


# --- the written files ----------------------------------------------------------
@pytest.mark.parametrize("code", [3040, 3041, 3050, 4021])
def test_header_and_states_of_every_format_code(tmp_path, code):
    f = th.read(_sample(tmp_path, code=code))
    assert f.code == code and f.title == "a test run"
    assert f.units == ((1.0, 1.0, 1.0) if code > 3050 else None)
    np.testing.assert_allclose(f.time, T, rtol=1e-6)
    assert f.part_ids.tolist() == [1, 2]  # part 3 asked for no variable
    assert [g.names for g in f.groups][:3] == [
        ["DX", "DY", "DZ", "VX", "VY", "VZ", "AX", "AY", "AZ"],
        ["DX", "DY", "DZ"],
        ["FNX", "FNY", "FNZ", "FTX", "FTY", "FTZ"],
    ]
    assert f.groups[4].names[-3:] == ["MX", "MY", "MZ"]


def test_glstat_follows_lsdyna(tmp_path):
    g = th.categories(th.read(_sample(tmp_path)))["glstat"]
    np.testing.assert_allclose(g["kinetic_energy"], [101.0, 100.0, 96.5, 90.5])  # translational + rotational
    np.testing.assert_allclose(g["internal_energy"], [0.0, 1.0, 3.0, 6.0])
    np.testing.assert_allclose(g["hourglass_energy"], [0.0, 0.2, 0.4, 0.6], rtol=1e-6)
    np.testing.assert_allclose(g["sliding_interface_energy"], [0.0, 0.0, 0.5, 1.0])
    np.testing.assert_allclose(g["external_work"], [0.0, 0.1, 0.2, 0.3], rtol=1e-6)
    np.testing.assert_allclose(g["total_energy"], g["kinetic_energy"] + [0, 1.2, 3.9, 7.6], rtol=1e-6)
    np.testing.assert_allclose(g["global_x_velocity"], [-5.0, -4.5, -4.0, -3.5])
    np.testing.assert_allclose(g["time_step"], 1e-6, rtol=1e-6)
    np.testing.assert_allclose(g["added_mass"], 0.01, rtol=1e-6)


def test_parts_nodes_and_forces(tmp_path):
    c = th.categories(th.read(_sample(tmp_path)))
    m = c["matsum"]
    assert m["ids"].tolist() == [1, 2]
    np.testing.assert_allclose(m["internal_energy"].sum(axis=1), [0.0, 1.0, 3.0, 6.0])
    np.testing.assert_allclose(m["kinetic_energy"][-1], [57.5, 33.0])  # part 1 with its rotational energy
    n = c["nodout"]
    assert n["ids"].tolist() == [101, 102, 201]
    np.testing.assert_allclose(n["x_displacement"][-1], [-0.04, -0.08, 0.0], rtol=1e-6)
    np.testing.assert_allclose(n["y_displacement"][:, 2], 0.5)
    np.testing.assert_allclose(n["x_velocity"][:, :2], -10.0)
    assert np.isnan(n["x_velocity"][:, 2]).all()  # node 201's group has no velocities
    np.testing.assert_allclose(n["z_acceleration"][0, 1], 9.81, rtol=1e-6)
    w = c["rwforc"]
    assert w[("forces", "ids")].tolist() == [7]
    np.testing.assert_allclose(w[("forces", "x_force")][:, 0], -1000.0, rtol=1e-5)  # impulse -> force
    np.testing.assert_allclose(w[("forces", "y_force")][:, 0], -50.0, rtol=1e-5)
    np.testing.assert_allclose(w[("forces", "normal_force")][:, 0], 1000.0, rtol=1e-5)
    r = c["rcforc"]
    assert r["ids"].tolist() == [3, 3] and r["side"].tolist() == [0, 1]
    np.testing.assert_allclose(r["x_force"][1], [2000.0, -2000.0], rtol=1e-5)  # secondary side: the opposite
    s = c["secforc"]
    np.testing.assert_allclose(s["x_force"][:, 0], -1000.0, rtol=1e-5)
    np.testing.assert_allclose(s["z_moment"][:, 0], 7.0, rtol=1e-5)
    np.testing.assert_allclose(s["total_force"][:, 0], np.hypot(1000.0, 50.0), rtol=1e-5)


def test_rate_is_th_to_csv_differences():
    t = np.array([0.0, 1.0, 3.0, 4.0])
    y = np.array([0.0, 1.0, 9.0, 16.0])
    np.testing.assert_allclose(th.rate(t, y), [1.0, 3.0, 5.0, 7.0])
    np.testing.assert_allclose(th.rate(np.array([0.0, 0.0]), np.array([1.0, 2.0])), [0.0, 0.0])


def test_a_state_cut_short_is_left_out(tmp_path):
    f = th.read(_sample(tmp_path, cut=10))
    assert len(f.time) == N - 1
    assert f.groups[0].values.shape == (N - 1, 2, 9)


def test_not_a_time_history(tmp_path):
    p = tmp_path / "junkT01"
    p.write_bytes(b"*KEYWORD\n*END\n")
    with pytest.raises(th.FormatError, match="not an OpenRadioss time history"):
        th.read(p)


def test_results_load_reads_a_folder_with_a_t01(tmp_path):
    _sample(tmp_path)
    h = load(tmp_path)
    assert h.source.endswith("carT01")
    assert h.categories() == ["glstat", "matsum", "nodout", "rcforc", "rwforc", "secforc"]
    np.testing.assert_allclose(h.read("rwforc", "forces", "x_force")[:, 0], -1000.0, rtol=1e-5)
    assert load(tmp_path / "carT01").categories() == h.categories()
    res = results_from_history(h)  # what studies, vehicle reduce/verify read
    np.testing.assert_allclose(res.kinetic, [101.0, 100.0, 96.5, 90.5])
    assert res.history_nodes.tolist() == [101, 102, 201]
    assert res.wall_ids.tolist() == [7] and res.section_ids.tolist() == [5]
    np.testing.assert_allclose(res.contact_force[-1, 0], [2000.0, 100.0, 0.0], rtol=1e-5, atol=1e-6)  # slave side


def test_results_load_refuses_several_t01(tmp_path):
    _sample(tmp_path, "aT01")
    _sample(tmp_path, "bT01")
    with pytest.raises(FileNotFoundError, match="several OpenRadioss time histories"):
        load(tmp_path)


# --- real files of OpenRadioss's QA tests ---------------------------------------
def _real(name: str) -> Path:
    p = DATA / name
    if not p.is_file():
        pytest.skip(f"{p} absent: run tests/data/openradioss/fetch.sh")
    return p


def test_real_ball_on_a_moving_wall():
    f = th.read(_real("BOULE1V4T01"))
    assert (f.code, f.title, len(f.time)) == (3040, "BOULE1V4", 130)
    assert f.time[-1] == pytest.approx(0.12902343)
    assert f.part_ids.tolist() == [1, 2] and f.part_titles == ["BOULE", "COQUE ARRIERE"]
    c = th.categories(f)
    g = c["glstat"]
    assert g["internal_energy"][-1] == pytest.approx(2240.6624, rel=1e-6)
    np.testing.assert_allclose(c["matsum"]["internal_energy"].sum(axis=1), g["internal_energy"], rtol=1e-5)
    n = c["nodout"]
    assert n["ids"].tolist() == [1141, 1147, 1148]
    np.testing.assert_allclose(n["x_velocity"][1:, 2], 10.0)  # the wall's node moves at 10 m/s (from 0 at t = 0)
    np.testing.assert_allclose(n["x_displacement"][:, 2], 10.0 * f.time, rtol=1e-5)
    w = f.of_type(th.RWALL)[0]
    assert (w.ids.tolist(), w.names[:3]) == ([1148], ["FNX", "FNY", "FNZ"])
    assert w.values[-1, 0, 0] == pytest.approx(-129.26369)  # the impulse, as th_to_csv reads it


def test_real_box_beam_into_a_wall():
    f = th.read(_real("BOX1BLT01"))
    assert len(f.time) == 100
    assert [(g.type, len(g.ids)) for g in f.groups] == [(102, 1), (104, 8), (0, 14), (3, 14), (103, 1)]
    c = th.categories(f)
    np.testing.assert_allclose(c["nodout"]["x_velocity"][0], -8.0)  # the deck's initial velocity
    ke0 = f.global_value("KE")[0]
    assert ke0 == pytest.approx(0.5 * f.global_value("MASS")[0] * 8.0**2, rel=1e-5)
    # the wall is the only external force: its impulse is the box's loss of x momentum
    w = f.of_type(th.RWALL)[0]
    impulse = w.quantity("FNX")[:, 0] + w.quantity("FTX")[:, 0]
    xmom = f.global_value("XMOM")
    np.testing.assert_allclose(xmom - xmom[0], -impulse, atol=1e-3 * abs(xmom[0]))
    fx = c["rwforc"][("forces", "x_force")][:, 0]
    assert fx[-1] == pytest.approx(-49.589, rel=1e-4)  # the nodes push the wall along their motion (-x)
    assert c["secforc"]["ids"].tolist() == list(range(1, 9))


def test_results_load_reads_an_openradioss_run_folder(tmp_path):
    """The folder ``crashlite run --solver openradioss`` leaves: the log,
    the manifest, the listings, animation files and the time history."""
    for name in ("crashlite-solver.log", "crashlite-solver.json", "car_0000.out", "car_0001.out", "carA001"):
        (tmp_path / name).write_text("x\n")
    _sample(tmp_path, "carT01")
    h = load(tmp_path)
    assert h.source == str(tmp_path / "carT01")
    np.testing.assert_allclose(h.read("glstat", "internal_energy"), [0.0, 1.0, 3.0, 6.0])
