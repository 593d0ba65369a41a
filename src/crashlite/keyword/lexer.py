"""Splitting deck files into keyword blocks, following *INCLUDE files.

A block is a keyword line plus its data lines (comments removed), with the
file and line numbers kept for messages. Line bounds are found by a Numba
kernel and kept as arrays so mesh blocks never become Python strings.
"""

from __future__ import annotations

import mmap
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .cards import I10, LONG, STD, FieldError, to_number
from .errors import Collector
from .fastparse import split_lines
from .layout import INT


@dataclass
class SourceFile:
    path: Path
    buf: np.ndarray  # (n_bytes,) uint8 (past a UTF-8 byte-order mark)
    starts: np.ndarray  # (n_lines,) int64 byte offset of each line
    ends: np.ndarray  # (n_lines,) int64 end offset (without \r\n)
    nul: int = -1  # offset of the first NUL byte in buf (-1: none): not a text file
    utf16: bool = False  # starts with a UTF-16 byte-order mark

    def text(self, i: int) -> str:
        return self.buf[self.starts[i] : self.ends[i]].tobytes().decode("latin-1")


@dataclass
class IncludeContext:
    """What an *INCLUDE_TRANSFORM applies to the blocks of its file."""

    offsets: dict  # reference kind -> ID offset
    tranid: int  # *DEFINE_TRANSFORMATION id (0: none)
    file: str
    line: int


@dataclass
class Block:
    keyword: str  # upper case, no '*', no format suffix
    line_text: str  # the keyword line as written
    mode: str  # STD, LONG or I10
    src: SourceFile
    kw_index: int  # 0-based line index of the keyword line
    data: np.ndarray  # (n,) int64 line indices of data lines (no comments)
    stop: int  # line index of the next keyword (end of this block)
    scope: int  # parameter scope (index into Lexer.scopes)
    contexts: tuple = ()  # IncludeContext chain, innermost last
    position: int = 0  # running index over the whole deck

    @property
    def file(self) -> str:
        return str(self.src.path)

    @property
    def line(self) -> int:
        return int(self.kw_index) + 1

    def line_no(self, j: int) -> int:
        return int(self.data[j]) + 1

    def text(self, j: int) -> str:
        return self.src.text(int(self.data[j]))

    def raw_lines(self) -> list[str]:
        """Every line after the keyword line, comments included."""
        return [self.src.text(i) for i in range(self.kw_index + 1, self.stop)]


# Card 2 of *INCLUDE_TRANSFORM, and which reference kinds each offset moves.
_OFFSET_FIELDS = ("IDNOFF", "IDEOFF", "IDPOFF", "IDMOFF", "IDSOFF", "IDFOFF", "IDDOFF")
_KINDS = {
    "IDNOFF": ("node",),
    "IDEOFF": ("elem",),
    "IDPOFF": ("part", "sec"),
    "IDMOFF": ("mat", "eos", "hg"),
    "IDSOFF": ("set_node", "set_part", "set_shell", "set_solid", "set_beam", "set_discrete", "set_segment", "set_any"),
    "IDFOFF": ("curve",),
    "IDDOFF": ("vector", "coord", "sdo"),
    "IDROFF": ("rigidwall", "contact", "sect"),
}


def include_context(blk: Block, problems: Collector) -> IncludeContext | None:
    """Offsets and TRANID of an *INCLUDE_TRANSFORM block (cards 2-5)."""
    lines = [(blk.text(j), blk.line_no(j)) for j in range(len(blk.data))]
    if not lines:
        problems.error(blk.file, blk.line, blk.keyword, "FILENAME", "file name card missing")
        return None

    def fields(k, names, kind="f"):
        if k >= len(lines):
            return {n: 0 for n in names}
        text, ln = lines[k]
        toks = text.split(",") if "," in text else [text[i : i + 10] for i in range(0, 10 * len(names), 10)]
        out = {}
        for n, t in zip(names, toks + [""] * len(names)):
            t = t.strip()
            try:
                out[n] = to_number(t, kind) if t else 0
            except FieldError as e:
                problems.error(blk.file, ln, blk.keyword, n, str(e))
                out[n] = 0
        return out

    c2 = fields(1, _OFFSET_FIELDS, INT)
    c3 = fields(2, ("IDROFF",), INT)
    c4 = fields(3, ("FCTMAS", "FCTTIM", "FCTLEN"))
    c5 = fields(4, ("TRANID",), INT)
    for name in ("FCTMAS", "FCTTIM", "FCTLEN"):
        if c4[name] not in (0.0, 1.0):
            problems.error(
                blk.file,
                lines[3][1],
                blk.keyword,
                name,
                "unit conversion factors of *INCLUDE_TRANSFORM are not supported; "
                "convert the included file's units first",
            )
    offsets = {}
    for key, val in {**c2, **c3}.items():
        for kind in _KINDS[key]:
            offsets[kind] = int(val)
    return IncludeContext(offsets, int(c5["TRANID"]), blk.file, blk.line)


def read_source(path: Path) -> SourceFile:
    # memory-mapped: the kernels read the page cache directly, no copy
    size = path.stat().st_size
    if size:
        with open(path, "rb") as f:
            # MAP_POPULATE reads the file in at once instead of page by page
            if hasattr(mmap, "MAP_SHARED"):
                flags = mmap.MAP_SHARED | getattr(mmap, "MAP_POPULATE", 0)
                mm = mmap.mmap(f.fileno(), 0, flags=flags, prot=mmap.PROT_READ)
            else:
                mm = mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ)
            buf = np.frombuffer(mm, dtype=np.uint8)
            nul = mm.find(b"\x00")  # memchr: a text deck has none
            utf16 = mm[:2] in (b"\xff\xfe", b"\xfe\xff")
    else:
        buf, nul, utf16 = np.zeros(0, np.uint8), -1, False
    if buf[:3].tobytes() == _BOM:  # a UTF-8 byte-order mark is no part of the first line
        buf = buf[3:]
        nul = nul - 3 if nul >= 0 else nul
    starts, ends = split_lines(buf)
    return SourceFile(path, buf, starts, ends, nul, utf16)


_BOM = b"\xef\xbb\xbf"


def keyword_mode(kw_line: str, default: str) -> tuple[str, str]:
    """Keyword name and card format of a keyword line (suffix + - %)."""
    word = kw_line.split()[0] if kw_line.split() else "*"
    name = word[1:]
    mode = default
    if name.endswith("+"):
        name, mode = name[:-1], LONG
    elif name.endswith("-"):
        name, mode = name[:-1], STD
    elif name.endswith("%"):
        name, mode = name[:-1], I10
    return name.upper(), mode


def blocks_of(src: SourceFile) -> list[tuple[int, np.ndarray]]:
    """(keyword line, data line indices, end line) for each keyword in a file."""
    n = len(src.starts)
    if n == 0:
        return []
    nonempty = src.ends > src.starts
    first = np.zeros(n, dtype=np.uint8)
    first[nonempty] = src.buf[src.starts[nonempty]]
    is_kw = first == ord("*")
    is_comment = first == ord("$")
    kws = np.flatnonzero(is_kw)
    out = []
    for k, kw in enumerate(kws):
        stop = kws[k + 1] if k + 1 < len(kws) else n
        idx = np.arange(kw + 1, stop, dtype=np.int64)
        idx = idx[~is_comment[kw + 1 : stop]]
        out.append((int(kw), idx, int(stop)))
    return out


#: Deeper *INCLUDE nesting than this is an error (LS-DYNA nests includes,
#: but a chain this deep is a mistake; Python's recursion would end it anyway).
MAX_INCLUDE_DEPTH = 100


@dataclass
class Lexer:
    """Walks a deck and its includes in input order."""

    problems: Collector
    blocks: list[Block] = field(default_factory=list)
    scopes: list[int] = field(default_factory=list)  # parent scope of each scope (-1 root)
    include_paths: list[Path] = field(default_factory=list)
    files: list[Path] = field(default_factory=list)

    def new_scope(self, parent: int) -> int:
        self.scopes.append(parent)
        return len(self.scopes) - 1

    def resolve(self, name: str, here: Path, relative_to: list[Path]) -> Path | None:
        p = Path(name.strip())
        if p.is_absolute():
            return p if _is_file(p) else None
        for base in [here.parent, *relative_to, Path.cwd()]:
            cand = base / p
            if _is_file(cand):
                return cand
        return None

    def walk(
        self,
        path: Path,
        parent_scope: int = -1,
        contexts: tuple = (),
        stack: tuple = (),
        mode: str = STD,
        via: tuple | None = None,
    ) -> None:
        """Blocks of ``path`` and its includes; ``via``: (file, line, keyword)
        of the *INCLUDE that names it (None for the deck itself)."""
        path = Path(path)
        if path.resolve() in stack:
            self.problems.error(path, 0, "INCLUDE", None, "file includes itself (include loop)")
            return
        if len(stack) >= MAX_INCLUDE_DEPTH:
            chain = [p.name for p in stack] + [path.name]
            shown = " -> ".join(chain[:3] + ["..."] + chain[-3:])
            self.problems.error(
                via[0],
                via[1],
                via[2],
                "FILENAME",
                f"includes nested more than {MAX_INCLUDE_DEPTH} deep ({shown}); "
                "an include chain this deep is a mistake (or a loop through copies)",
            )
            return
        try:
            src = read_source(path)
        except OSError as e:
            self.problems.error(path, 0, "", None, f"cannot read file: {e.strerror or e}")
            return
        self.files.append(path)
        blocks = blocks_of(src)
        if not self._is_deck_text(src, blocks, via):
            return
        scope = self.new_scope(parent_scope)
        stack = (*stack, path.resolve())
        relative_paths: list[Path] = []
        for kw_index, data, stop in blocks:
            line_text = src.text(kw_index)
            name, kmode = keyword_mode(line_text, mode)
            if name == "KEYWORD":
                mode = _keyword_flags(line_text, mode)
                continue
            if name == "END":
                break
            blk = Block(name, line_text, kmode, src, kw_index, data, stop, scope, contexts, len(self.blocks))
            if name.startswith("INCLUDE"):
                self._include(blk, relative_paths, scope, contexts, stack, mode)
                continue
            self.blocks.append(blk)

    def _is_deck_text(self, src: SourceFile, blocks, via) -> bool:
        """False (with the error) for a file that is no keyword deck: binary
        data, UTF-16 text, or text without a keyword (LS-DYNA refuses these;
        reading them as empty decks would lose a model without a word)."""
        path = src.path
        from_ = f" (included at {via[0]}:{via[1]})" if via else ""
        if src.utf16:
            self.problems.error(path, 0, "", None, f"UTF-16 text{from_}: save the deck as ASCII or UTF-8")
            return False
        if src.nul >= 0:
            line = int(np.searchsorted(src.starts, src.nul, side="right"))
            self.problems.error(
                path, line, "", None, f"binary data (a NUL byte at line {line}){from_}: not a keyword deck"
            )
            return False
        head = src.buf[:65536]
        ctrl = int(np.count_nonzero(((head < 32) & ~np.isin(head, (9, 10, 12, 13))) | (head == 127)))
        if ctrl > max(8, len(head) // 100):  # text has next to none; a stray one is a field's problem
            self.problems.error(
                path,
                0,
                "",
                None,
                f"binary data ({ctrl} control bytes in the first {len(head)}){from_}: not a keyword deck",
            )
            return False
        first = blocks[0][0] if blocks else len(src.starts)
        data = [i for i in range(first) if src.text(i).strip(" \t") and not src.text(i).startswith("$")]
        if not blocks:
            if via is None:
                what = "the file is empty" if not len(src.buf) else "no keyword (a line starting with *)"
                self.problems.error(path, 0, "", None, f"not a keyword deck: {what}; a deck starts with *KEYWORD")
            elif data:
                self.problems.error(
                    path, data[0] + 1, "", None, f"holds text but no keyword{from_}: not a keyword deck"
                )
            else:
                self.problems.warn(path, 0, "", None, f"holds no keyword{from_}")
            return bool(not data and via is not None)
        if data:
            self.problems.warn(path, data[0] + 1, "", None, f"{len(data)} line(s) before the first keyword ignored")
        return True

    def _include(self, blk: Block, relative_paths, scope, contexts, stack, mode) -> None:
        name = blk.keyword
        lines = [blk.text(j) for j in range(len(blk.data))]
        if name in ("INCLUDE_PATH", "INCLUDE_PATH_RELATIVE"):
            base = blk.src.path.parent
            for ln in lines:
                if ln.strip():
                    p = Path(ln.strip())
                    if not p.is_absolute():
                        p = (
                            base / p
                            if name == "INCLUDE_PATH_RELATIVE"
                            else (Path.cwd() / p if _is_dir(Path.cwd() / p) else base / p)
                        )
                    (relative_paths if name == "INCLUDE_PATH_RELATIVE" else self.include_paths).append(p)
            return
        if name == "INCLUDE":
            names = _file_names(lines)
            if not names:
                self.problems.error(blk.file, blk.line, name, "FILENAME", "no file name given")
            for j, fname in names:
                self._walk_named(blk, j, fname, relative_paths, scope, contexts, stack, mode)
            return
        if name == "INCLUDE_TRANSFORM":
            ctx = include_context(blk, self.problems)
            if ctx is None or not lines:
                return
            self._walk_named(blk, 0, lines[0], relative_paths, scope, (*contexts, ctx), stack, mode)
            return
        self.problems.error(
            blk.file,
            blk.line,
            name,
            None,
            "unsupported include keyword (use *INCLUDE, *INCLUDE_PATH, *INCLUDE_PATH_RELATIVE or *INCLUDE_TRANSFORM)",
        )

    def _walk_named(self, blk, j, fname, relative_paths, scope, contexts, stack, mode):
        fname = fname.strip()
        if not fname:
            self.problems.error(
                blk.file,
                blk.line_no(j) if len(blk.data) else blk.line,
                blk.keyword,
                "FILENAME",
                "the file name is blank",
            )
            return
        target = self.resolve(fname, blk.src.path, [*relative_paths, *self.include_paths])
        if target is None:
            self.problems.error(
                blk.file,
                blk.line_no(j),
                blk.keyword,
                "FILENAME",
                f"include file {fname!r} not found (looked in {os.fspath(blk.src.path.parent)} and the include paths)",
            )
            return
        self.walk(target, scope, contexts, stack, mode, (blk.file, blk.line_no(j), blk.keyword))


def _is_file(p: Path) -> bool:
    """Path.is_file, False also for a name the system refuses (too long, a
    NUL byte): such a name is then reported as not found."""
    try:
        return p.is_file()
    except (OSError, ValueError):
        return False


def _is_dir(p: Path) -> bool:
    try:
        return p.is_dir()
    except (OSError, ValueError):
        return False


def _file_names(lines: list[str]) -> list[tuple[int, str]]:
    """File names of an *INCLUDE card list; a line ending in ' +' continues
    on the next (names longer than one card)."""
    out, buf, start = [], "", None
    for j, ln in enumerate(lines):
        if not ln.strip():
            continue
        start = j if start is None else start
        if ln.rstrip().endswith(" +"):
            buf += ln.rstrip()[:-2].strip()
            continue
        out.append((start, buf + ln.strip()))
        buf, start = "", None
    if buf:
        out.append((start, buf))
    return out


def _keyword_flags(line: str, mode: str) -> str:
    up = line.upper().replace(" =", "=").replace("= ", "=")
    for tok in up.split()[1:]:
        if tok.startswith("LONG="):
            mode = LONG if tok[5:6] in ("Y", "S", "K") else STD
        elif tok.startswith("I10="):
            mode = I10 if tok[4:5] == "Y" else mode
    return mode
