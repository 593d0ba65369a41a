"""Where Numba keeps crashlite's compiled kernels.

Numba's own cache sits beside each source file and is checked against that
file's time stamp only. A kernel that inlines or calls a function of
another module (the shell kernel the plane-stress return mapping, the wall
kernel its contact update) is then loaded from the cache unchanged after
that other module changed: stale machine code that runs the old physics.
So the cache goes into a folder named by a digest of every crashlite source
that holds Numba code: any change to one of them compiles them all afresh.

The folder is under $NUMBA_CACHE_DIR if set, else the user's cache folder
($XDG_CACHE_HOME or ~/.cache) /crashlite/numba; the newest few digests are
kept. Imported by the package before any kernel is defined.
"""

from __future__ import annotations

import hashlib
import os
import shutil
from pathlib import Path

KEEP = 4  # digests kept side by side (branches, versions)


def _sources(root: Path) -> list[Path]:
    out = []
    for p in sorted(root.rglob("*.py")):
        try:
            text = p.read_bytes()
        except OSError:
            continue
        if b"numba" in text:
            out.append(p)
    return out


def digest(root: Path | None = None) -> str:
    """Digest of the package's Numba sources (their paths and contents)."""
    root = root or Path(__file__).resolve().parent
    h = hashlib.sha1()
    for p in _sources(root):
        h.update(str(p.relative_to(root)).encode())
        h.update(p.read_bytes())
    return h.hexdigest()[:16]


def configure() -> Path | None:
    """Point Numba's cache at this version's folder (None: left as it was)."""
    try:
        import numba
    except ImportError:  # pragma: no cover - numba is a dependency
        return None
    try:
        base = os.environ.get("NUMBA_CACHE_DIR")
        base = Path(base) if base else Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "crashlite"
        folder = (base if os.environ.get("NUMBA_CACHE_DIR") else base / "numba") / digest()
        folder.mkdir(parents=True, exist_ok=True)
    except (OSError, RuntimeError):  # no home, or a read-only one: Numba's default (beside the sources)
        return None
    base = folder.parent
    numba.config.CACHE_DIR = str(folder)
    _prune(base, folder)
    return folder


def _prune(base: Path, keep: Path) -> None:
    try:
        others = sorted((p for p in base.iterdir() if p.is_dir() and p != keep), key=lambda p: p.stat().st_mtime)
    except OSError:
        return
    for p in others[: max(len(others) - (KEEP - 1), 0)]:
        shutil.rmtree(p, ignore_errors=True)
    os.utime(keep)  # the one in use is the newest
