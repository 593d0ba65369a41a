"""Write -> read of every LS-DYNA ASCII history file gives the arrays back
to the printed precision: a value printed with d significant digits is
within half a unit of its last digit, |read - written| <= 0.5e(1-d) |written|.
Digits per file (LS-DYNA's formats): glstat, deforc 6 (%14.5E); rwforc 7
(%15.6E; time %12.5E: 6); matsum, nodout, secforc, spcforc 5 (%..4E;
nodout time %14.7E: 8, secforc time %15.5E: 6, matsum time %13.4E: 5)."""

import numpy as np
import pytest

from crashlite.results.lsdyna_ascii import FILES, deforc, glstat, matsum, nodout, rwforc, secforc, spcforc

RNG = np.random.default_rng(7)


def values(*shape):
    """Signed values over 30 decades, with exact zeros and 3-digit
    exponents (columns touch: '-1.2345E-120-2.0000E+00')."""
    v = RNG.choice([-1.0, 1.0], size=shape) * 10.0 ** RNG.uniform(-12, 18, size=shape) * RNG.uniform(1, 10, size=shape)
    v.flat[::7] = 0.0
    v.flat[3::11] = -1.5e-120
    return v


def assert_printed(read, written, digits):
    read, written = np.asarray(read, float), np.asarray(written, float)
    assert read.shape == written.shape
    bound = 0.5 * 10.0 ** (1 - digits) * np.abs(written) * (1 + 1e-9)
    assert np.all(np.abs(read - written) <= bound), np.max(np.abs(read - written) / np.maximum(bound, 1e-300))


TIME = np.array([0.0, 1.23456789e-4, 2.5e-3, 0.15])


def test_glstat_round_trip(tmp_path):
    names = [
        "time_step",
        "kinetic_energy",
        "internal_energy",
        "stonewall_energy",
        "spring_and_damper_energy",
        "hourglass_energy",
        "sliding_interface_energy",
        "external_work",
        "total_energy",
        "energy_ratio",
        "added_mass",
    ]
    data = {"time": TIME, "cycle": np.array([0, 10, 200, 12000])} | {k: values(4) for k in names}
    back = glstat.read(glstat.write(tmp_path / "glstat", data, "round trip"))
    assert set(back) == set(data)
    assert back["cycle"].tolist() == [0, 10, 200, 12000]
    for k in ["time"] + names:
        assert_printed(back[k], data[k], 6)


def test_matsum_round_trip_with_nan_rules(tmp_path):
    ids = np.array([1, 7, 123456])  # IDs >= 100000 take the wide mat.# field
    n, m = len(TIME), len(ids)
    data = {
        "time": TIME,
        "ids": ids,
        "internal_energy": values(n, m),
        "kinetic_energy": values(n, m),
        "hourglass_energy": values(n, m),
        "mass": values(n, m),
    }
    for a in "xyz":
        data[f"{a}_momentum"] = values(n, m)
    rbv = values(n, m, 3)
    rbv[:, 1] = np.nan  # a deformable part
    for k, a in enumerate("xyz"):
        data[f"{a}_rbvelocity"] = rbv[:, :, k]
    back = matsum.read(matsum.write(tmp_path / "matsum", data))
    assert back["ids"].tolist() == ids.tolist()
    assert_printed(back["time"], TIME, 5)
    for k, v in data.items():
        if k not in ("time", "ids"):
            assert_printed(back[k], np.nan_to_num(v, nan=0.0), 5)  # LS-DYNA prints 0 rbv for deformable parts
    # a quantity the run did not record is written NAN and not read back
    del data["kinetic_energy"], data["mass"]
    back = matsum.read(matsum.write(tmp_path / "matsum2", data))
    assert "kinetic_energy" not in back and "mass" not in back and "internal_energy" in back


def test_nodout_round_trip(tmp_path):
    ids = np.array([2, 40, 123456789])
    n, m = len(TIME), len(ids)
    data = {"time": TIME, "ids": ids, "cycle": np.array([0, 3, 50, 900])}
    for name in nodout.TRANSLATION:
        data[name] = values(n, m)
    back = nodout.read(nodout.write(tmp_path / "nodout", data))
    assert back["ids"].tolist() == ids.tolist() and back["cycle"].tolist() == [0, 3, 50, 900]
    assert_printed(back["time"], TIME, 8)
    for name in nodout.TRANSLATION:
        assert_printed(back[name], data[name], 5)
    # scripts cut nodout at fixed columns: [0:9] id, then 13 and 12 wide
    row = (tmp_path / "nodout").read_text().splitlines()[-1]
    assert int(row[:9]) == ids[-1] and float(row[9:22]) == pytest.approx(data["x_displacement"][-1, -1], rel=5e-5)
    assert len(row) == 9 + 13 + 11 * 12


def test_rwforc_round_trip(tmp_path):
    ids = np.array([1, 3])
    n, m = len(TIME), len(ids)
    g = {"time": TIME, "ids": ids} | {k: values(n, m) for k in rwforc.NAMES}
    back = rwforc.read(rwforc.write(tmp_path / "rwforc", {("forces", k): v for k, v in g.items()}))
    assert back[("forces", "ids")].tolist() == [1, 3]
    assert_printed(back[("forces", "time")], TIME, 6)
    for k in rwforc.NAMES:
        assert_printed(back[("forces", k)], g[k], 7)


def test_deforc_round_trip(tmp_path):
    ids = np.arange(1, 6) * 1000
    n, m = len(TIME), len(ids)
    data = {"time": TIME, "ids": ids} | {k: values(n, m) for k in deforc.NAMES}
    back = deforc.read(deforc.write(tmp_path / "deforc", data))
    assert back["ids"].tolist() == ids.tolist() and not back["irot"].any()
    for k in ["time"] + deforc.NAMES:
        assert_printed(back[k], data[k], 6)


def test_secforc_round_trip_magnitudes_from_components(tmp_path):
    ids = np.array([7, 8])
    n, m = len(TIME), len(ids)
    data = {"time": TIME, "ids": ids} | {f"{a}_{q}": values(n, m) for a in "xyz" for q in ("force", "moment")}
    back = secforc.read(secforc.write(tmp_path / "secforc", data))
    assert_printed(back["time"], TIME, 6)
    for k in data:
        if k not in ("time", "ids"):
            assert_printed(back[k], data[k], 5)
    total = np.sqrt(sum(data[f"{a}_force"] ** 2 for a in "xyz"))
    assert_printed(back["total_force"], total, 5)
    assert "area" not in back and "x_centroid" not in back  # not computed: NAN in the file


def test_spcforc_round_trip_with_moments(tmp_path):
    ids = np.array([5, 1, 9])
    mids = np.array([1])
    n = len(TIME)
    data = {"time": TIME, "ids": ids, "moment_ids": mids}
    data |= {k: values(n, 3) for k in spcforc.FORCES} | {k: values(n, 1) for k in spcforc.MOMENTS}
    back = spcforc.read(spcforc.write(tmp_path / "spcforc", data))
    order = np.argsort(ids)  # LS-DYNA lists nodes in increasing order
    assert back["ids"].tolist() == [1, 5, 9] and back["moment_ids"].tolist() == [1]
    for k in spcforc.FORCES:
        assert_printed(back[k], data[k][:, order], 5)
    for k in spcforc.MOMENTS:
        assert_printed(back[k], data[k], 5)
    # resultants: the sums of the printed forces, themselves printed with 5 digits
    for a in "xyz":
        np.testing.assert_allclose(
            back[f"{a}_resultant"],
            data[f"{a}_force"].sum(axis=1),
            rtol=5e-5,
            atol=5e-5 * np.abs(data[f"{a}_force"]).sum(axis=1).max(),
        )


@pytest.mark.parametrize("name", sorted(FILES))
def test_no_states_and_no_entities_do_not_crash(tmp_path, name):
    empty = {"time": np.zeros(0), "ids": np.zeros(0, np.int64)}
    if name == "rwforc":
        empty = {("forces", k): v for k, v in empty.items()}
    path = FILES[name].write(tmp_path / name, empty)
    assert FILES[name].read(path) == {}
