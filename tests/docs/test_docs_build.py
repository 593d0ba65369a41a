"""The documentation: the MkDocs site builds in strict mode (every page,
link, anchor and API page from the docstrings), the README stays short, and
every relative link of README.md and docs/ points at a file that exists."""

import os
import re
import subprocess
import sys
import unicodedata
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
README_MAX_LINES = 300

LINK = re.compile(r"!?\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
FENCE = re.compile(r"^\s*(```|~~~)")


def _markdown_files() -> list[Path]:
    return [ROOT / "README.md", *sorted(DOCS.rglob("*.md"))]


def _prose(text: str) -> str:
    """The text outside fenced code blocks and inline code spans."""
    out, fenced = [], False
    for line in text.splitlines():
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            out.append(re.sub(r"`[^`]*`", "", line))
    return "\n".join(out)


def _slug(heading: str) -> str:
    """Python-Markdown's toc slug (what MkDocs and GitHub anchor a heading by,
    for the plain headings used here)."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading)
    text = text.replace("`", "").replace("*", "")
    text = unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode("ascii")
    text = re.sub(r"[^\w\s-]", "", text).strip().lower()
    return re.sub(r"[-\s]+", "-", text)


def _anchors(path: Path) -> set[str]:
    anchors: set[str] = set()
    fenced = False
    for line in path.read_text(encoding="utf-8").splitlines():
        if FENCE.match(line):
            fenced = not fenced
            continue
        m = None if fenced else re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if m:
            slug, n = _slug(m.group(1)), 0
            while (slug if n == 0 else f"{slug}_{n}") in anchors:
                n += 1
            anchors.add(slug if n == 0 else f"{slug}_{n}")
    return anchors


def _relative_links(path: Path) -> list[str]:
    return [
        t
        for t in LINK.findall(_prose(path.read_text(encoding="utf-8")))
        if not re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", t)
    ]  # http:, https:, mailto:


def test_mkdocs_builds_strict(tmp_path):
    env = dict(os.environ, NO_MKDOCS_2_WARNING="1")
    proc = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "-d", str(tmp_path / "site")],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr
    for page in ("index.html", "method/index.html", "validation/index.html", "api/solver/index.html"):
        assert (tmp_path / "site" / page).is_file(), page


def test_readme_is_short():
    lines = (ROOT / "README.md").read_text(encoding="utf-8").splitlines()
    assert len(lines) <= README_MAX_LINES, f"README.md has {len(lines)} lines (at most {README_MAX_LINES})"


@pytest.mark.parametrize("path", _markdown_files(), ids=lambda p: str(p.relative_to(ROOT)))
def test_relative_links_resolve(path):
    broken = []
    for target in _relative_links(path):
        file_part, _, anchor = target.partition("#")
        dest = (path.parent / file_part).resolve() if file_part else path
        if not dest.exists():
            broken.append(f"{target}: no such file")
        elif anchor and dest.suffix == ".md" and anchor not in _anchors(dest):
            broken.append(f"{target}: no heading with anchor #{anchor}")
    assert not broken, f"{path.relative_to(ROOT)}: " + "; ".join(broken)


def test_the_link_check_sees_links(tmp_path):
    """The link pattern finds links outside code, ignores those inside it."""
    md = tmp_path / "x.md"
    md.write_text("# A title\n\n[a](b.md) ![p](img/p.png)\n`[c](d.md)`\n\n```\n[e](f.md)\n```\n[g](https://x.org)\n")
    assert _relative_links(md) == ["b.md", "img/p.png"]
    assert _anchors(md) == {"a-title"}
    assert _slug("The paper's time reduction (`bench/reduction.py`)") == "the-papers-time-reduction-benchreductionpy"
