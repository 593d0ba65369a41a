"""No module under src/crashlite is longer than 800 lines (issue 32): a
newcomer reads one concept per module. A module that grows past the limit is
split by concept, not trimmed."""

from __future__ import annotations

from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src" / "crashlite"
MAX_LINES = 800


def line_count(path: Path) -> int:
    return len(path.read_text(encoding="utf-8").splitlines())


def too_long(root: Path = SRC, limit: int = MAX_LINES) -> list[str]:
    """'path: n lines' for each module under ``root`` longer than ``limit``."""
    out = []
    for path in sorted(root.rglob("*.py")):
        n = line_count(path)
        if n > limit:
            out.append(f"{path.relative_to(root.parent).as_posix()}: {n} lines")
    return out


def test_no_module_above_the_limit() -> None:
    long = too_long()
    assert not long, f"modules above {MAX_LINES} lines (split them by concept):\n  " + "\n  ".join(long)


def test_the_check_finds_a_long_module(tmp_path: Path) -> None:
    (tmp_path / "pkg").mkdir()
    (tmp_path / "pkg" / "short.py").write_text("x = 1\n" * 3)
    (tmp_path / "pkg" / "long.py").write_text("x = 1\n" * 5)
    assert too_long(tmp_path / "pkg", limit=4) == ["pkg/long.py: 5 lines"]
