import textwrap
from pathlib import Path

import pytest


@pytest.fixture
def deck(tmp_path):
    """Write deck text (dedented) to files: deck("main.k", text) -> Path."""

    def write(name: str, text: str) -> Path:
        p = tmp_path / name
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(textwrap.dedent(text).lstrip("\n"))
        return p

    return write


@pytest.fixture
def two_threads():
    """Skip a 1-vs-2-thread comparison where Numba has one thread only (it
    needs two; CI has two cores)."""
    import numba

    if numba.config.NUMBA_NUM_THREADS < 2:
        pytest.skip("one thread only")
