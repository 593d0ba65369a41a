"""Random models written in every format read back equal, value by value."""

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from crashlite import read_deck, write_deck
from crashlite.keyword.equality import model_differences
from crashlite.keyword.schema import Record
from crashlite.model.mesh import Discretes, Masses, Nodes, Shells, Solids
from crashlite.model.model import Model

_F = st.floats(allow_nan=False, allow_infinity=False, width=64)


@st.composite
def models(draw):
    n = draw(st.integers(4, 30))
    ids = np.sort(draw(st.lists(st.integers(1, 10**9), min_size=n, max_size=n, unique=True)))
    xyz = draw(arrays(np.float64, (n, 3), elements=_F))
    nodes = Nodes(
        np.array(ids, np.int64),
        xyz,
        np.array(draw(st.lists(st.integers(0, 7), min_size=n, max_size=n)), np.int8),
        np.zeros(n, np.int8),
    )
    m = Model(nodes=nodes)
    k = draw(st.integers(1, 10))
    conn = draw(arrays(np.int32, (k, 4), elements=st.integers(0, n - 1)))
    sh = Shells.zeros(k)
    sh.ids = np.arange(1, k + 1, dtype=np.int64) * 7
    sh.pid[:] = 1
    sh.nodes = conn
    if draw(st.booleans()):
        sh.thickness = draw(arrays(np.float64, (k, 4), elements=st.floats(0.1, 10.0)))
        sh.beta = draw(arrays(np.float64, k, elements=st.floats(-90.0, 90.0).filter(lambda v: v != 0)))
    m.shells = sh
    j = draw(st.integers(0, 5))
    so = Solids.zeros(j)
    so.ids = np.arange(1, j + 1, dtype=np.int64) + 10**6
    so.pid[:] = 1
    so.nodes = draw(arrays(np.int32, (j, 8), elements=st.integers(0, n - 1)))
    m.solids = so
    d = Discretes.zeros(2)
    d.ids[:] = [5, 6]
    d.pid[:] = 2
    d.nodes[:] = [[0, 1], [2, -1]]
    d.scale[:] = draw(arrays(np.float64, 2, elements=_F.filter(lambda v: v != 0)))  # 0 reads as 1 (LS-DYNA)
    m.discretes = d
    ms = Masses.zeros(1)
    ms.ids[:] = 99
    ms.node[:] = n - 1
    ms.mass[:] = draw(st.floats(1e-9, 1e3))
    m.masses = ms
    m.parts[1] = Record(
        "PART",
        frozenset(),
        {"heading": "p1", "pid": 1, "secid": 1, "mid": 1, "eosid": 0, "hgid": 0, "grav": 0, "adpopt": 0, "tmid": 0},
    )
    m.parts[2] = Record(
        "PART",
        frozenset(),
        {"heading": "spring", "pid": 2, "secid": 2, "mid": 2, "eosid": 0, "hgid": 0, "grav": 0, "adpopt": 0, "tmid": 0},
    )
    return m


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(model=models())
def test_model_roundtrip_every_format(tmp_path, model):
    # sections and materials as verbatim keywords: references resolve, values kept
    from crashlite.keyword.schema import RawKeyword

    model.keywords = [
        RawKeyword("*SECTION_SHELL", ["1,2", "1.0"]),
        RawKeyword("*SECTION_DISCRETE", ["2"]),
        RawKeyword("*MAT_ELASTIC", ["1,1e-9,1.0,0.3"]),
        RawKeyword("*MAT_SPRING_ELASTIC", ["2,1.0"]),
    ]
    write_deck(model, tmp_path / "first.k")
    first = read_deck(tmp_path / "first.k")  # the verbatim cards are typed from here on
    for table in ("nodes", "shells", "solids", "discretes", "masses"):
        assert getattr(first, table).equals(getattr(model, table)), table
    for fmt in ("fixed", "long", "i10", "free"):
        out = tmp_path / f"m_{fmt}.k"
        write_deck(first, out, fmt=fmt)
        back = read_deck(out)
        assert model_differences(first, back) == [], fmt
        np.testing.assert_array_equal(back.nodes.xyz, model.nodes.xyz)


@settings(max_examples=5, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(seed=st.integers(0, 2**32 - 1), wide=st.booleans())
def test_large_blocks_take_the_fast_layout_and_stay_exact(tmp_path, seed, wide):
    """Blocks of thousands of rows are laid out by the Numba kernel; values
    that do not fit (wide=True) send the block to long or free format."""
    rng = np.random.default_rng(seed)
    n = 3000
    xyz = np.round(rng.normal(0, 500, (n, 3)), 3)
    if wide:
        xyz[rng.integers(0, n, 5)] = rng.normal(0, 1, (5, 3)) / 3.0  # 17 digits: never fits 16
    ids = np.sort(rng.choice(np.arange(1, 10**7), n, replace=False)).astype(np.int64)
    tc = rng.integers(0, 8, n).astype(np.int8)
    model = Model(nodes=Nodes(ids, xyz, tc, np.zeros(n, np.int8)))
    for fmt in ("fixed", "long", "i10", "free"):
        out = tmp_path / f"big_{fmt}.k"
        write_deck(model, out, fmt=fmt)
        back = read_deck(out)
        assert back.nodes.equals(model.nodes), fmt
        if fmt == "fixed":
            assert ("*NODE+" in out.read_text()) == wide
