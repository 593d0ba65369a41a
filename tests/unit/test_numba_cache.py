"""The kernels' cache folder is named by the Numba sources: a change to any
of them (a callee another module inlines, too) compiles them all afresh."""

import numba

from crashlite import _numba_cache as nc


def test_the_digest_follows_the_numba_sources_only(tmp_path):
    (tmp_path / "kernel.py").write_text("from numba import njit\n")
    (tmp_path / "cli.py").write_text("import argparse\n")
    first = nc.digest(tmp_path)
    (tmp_path / "cli.py").write_text("import argparse  # changed\n")
    assert nc.digest(tmp_path) == first
    (tmp_path / "kernel.py").write_text("from numba import njit  # changed\n")
    assert nc.digest(tmp_path) != first


def test_the_cache_goes_to_a_folder_of_the_digest_and_old_ones_are_pruned(tmp_path, monkeypatch):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(numba.config, "CACHE_DIR", numba.config.CACHE_DIR)  # restored afterwards
    for k in range(nc.KEEP + 2):
        (tmp_path / f"old{k}").mkdir()
    folder = nc.configure()
    assert folder == tmp_path / nc.digest() and numba.config.CACHE_DIR == str(folder)
    assert folder.is_dir() and len([p for p in tmp_path.iterdir() if p.is_dir()]) == nc.KEEP
