"""NASTRAN DMIG matrices (``keyword.dmig``): written and read back."""

import numpy as np
import pytest

from crashlite.keyword.dmig import read_dmig, write_dmig


def test_symmetric_matrix_round_trip_to_ten_digits(tmp_path):
    rng = np.random.default_rng(3)
    a = rng.normal(size=(9, 9))
    k = a @ a.T * 1e5
    k[0, 5] = k[5, 0] = 0.0  # zeros are not written
    dofs = np.array([[n, c] for n in (12, 40, 7) for c in (1, 2, 3)])
    write_dmig(tmp_path / "k.dmig", {"KAAX": (dofs, k), "M1": (dofs[:3], np.eye(3) * 0.5)})
    got = read_dmig(tmp_path / "k.dmig")
    d, m = got["KAAX"]
    order = np.lexsort((dofs[:, 1], dofs[:, 0]))  # read back in (grid, component) order
    np.testing.assert_array_equal(d, dofs[order])
    np.testing.assert_allclose(m, k[np.ix_(order, order)], rtol=1e-9, atol=1e-9 * np.abs(k).max())
    np.testing.assert_allclose(got["M1"][1], np.eye(3) * 0.5)
    assert all(len(line) <= 72 for line in (tmp_path / "k.dmig").read_text().splitlines())


def test_written_files_read_column_wise_as_the_general_reader_reads_them(tmp_path, monkeypatch):
    """What write_dmig writes is read column-wise at NumPy's speed; the
    matrices are exactly those of the general line-by-line reader, for a
    square (IFO 1, large-field by hand) and a symmetric matrix."""
    from crashlite.keyword import dmig

    rng = np.random.default_rng(5)
    a = rng.normal(size=(12, 12))
    dofs = np.array([[n, c] for n in (3, 900, 41, 2) for c in (1, 4, 6)])
    write_dmig(tmp_path / "k.dmig", {"K": (dofs, a @ a.T), "M": (dofs[:2], np.diag([2.0, 3.0]))})
    square = "DMIG*   Q                      0               1               2\n*                      0\n"
    square += (
        "DMIG*   Q                      5               2\n*                      5               2 4.000000000E+00\n"
    )
    square += "*                      7               1-1.000000000E+00\n"
    (tmp_path / "q.dmig").write_text(square)
    for f in ("k.dmig", "q.dmig"):
        fast = read_dmig(tmp_path / f)
        with monkeypatch.context() as m:
            m.setattr(dmig, "_read_large_field", lambda lines: None)
            slow = read_dmig(tmp_path / f)
        assert fast.keys() == slow.keys()
        for name in fast:
            np.testing.assert_array_equal(fast[name][0], slow[name][0])
            np.testing.assert_array_equal(fast[name][1], slow[name][1])
    q = read_dmig(tmp_path / "q.dmig")["Q"]
    np.testing.assert_array_equal(q[0], [[5, 2], [7, 1]])
    np.testing.assert_array_equal(q[1], [[4.0, 0.0], [-1.0, 0.0]])  # not mirrored: IFO 1


def test_small_field_with_nastran_exponents(tmp_path):
    text = (
        "DMIG    STIF    0       6       2\n"
        "DMIG    STIF    27      1               27      1       3.+5\n"
        "        28      1       -1.5+5\n"
        "DMIG    STIF    28      1               28      1       2.5+5\n"
    )
    (tmp_path / "s.dmig").write_text(text)
    dofs, k = read_dmig(tmp_path / "s.dmig")["STIF"]
    np.testing.assert_array_equal(dofs, [[27, 1], [28, 1]])
    np.testing.assert_allclose(k, [[3e5, -1.5e5], [-1.5e5, 2.5e5]])


def test_errors_name_file_and_line(tmp_path):
    (tmp_path / "b.dmig").write_text("DMIG    STIF    0       6       2\nGRID    1\n")
    with pytest.raises(ValueError, match=r"b.dmig:2"):
        read_dmig(tmp_path / "b.dmig")
    with pytest.raises(ValueError, match="not symmetric"):
        write_dmig(tmp_path / "u.dmig", {"K": (np.array([[1, 1], [2, 1]]), np.array([[1.0, 2.0], [0.0, 1.0]]))})


def test_deck_written_elsewhere_still_finds_its_matrix(tmp_path):
    """*ELEMENT_DIRECT_MATRIX_INPUT names its file relative to the deck: a
    deck read from one folder and written to another points at the same
    file from there (the Model keeps its own name)."""
    from crashlite import read_deck, write_deck

    (tmp_path / "a").mkdir()
    write_dmig(tmp_path / "a" / "m.dmig", {"K": (np.array([[1, 1], [2, 1]]), np.array([[1.0, -1.0], [-1.0, 1.0]]))})
    (tmp_path / "a" / "x.k").write_text(
        "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n*ELEMENT_DIRECT_MATRIX_INPUT\n5,1\nm.dmig\n,,K\n*END\n"
    )
    m = read_deck(tmp_path / "a" / "x.k")
    out = write_deck(m, tmp_path / "b" / "y.k")[0]
    name = read_deck(out).find("ELEMENT_DIRECT_MATRIX_INPUT")[0]["filename"]
    assert (out.parent / name).resolve() == (tmp_path / "a" / "m.dmig").resolve()
    assert m.find("ELEMENT_DIRECT_MATRIX_INPUT")[0]["filename"] == "m.dmig"
