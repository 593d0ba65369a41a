"""``write_deck``: a Model as an LS-DYNA keyword deck.

Each keyword is written in the requested format (fixed columns by default).
A keyword whose values do not fit the columns without loss switches to long
format (suffix ``+``, 20-character fields), and a card that does not fit
even then is written in free format (commas). So every value reads back to
the same double, and LS-DYNA accepts every line.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

import numpy as np

from ..model.model import ENTITY_GROUPS, Model
from . import cards
from .cards import I10, LONG, STD
from .convert import mesh_records
from .fastformat import fixed_lines
from .schema import FLOAT, INT, STR, Field, RawKeyword, Record

FORMATS = {"fixed": STD, "std": STD, "long": LONG, "i10": I10, "free": "free"}
_SUFFIX = {STD: "-", LONG: "+", I10: "%"}


def _texts(values, f: Field, w: int | None) -> list[str]:
    """Text of each value: Python's shortest round-trip repr for reals (a
    compact form only where that is too wide for ``w``)."""
    if isinstance(values, np.ndarray) and values.dtype.kind == "f" and not np.isfinite(values).all():
        raise ValueError(f"field {f.name}: cannot write non-finite values")
    vals = values.tolist() if isinstance(values, np.ndarray) else list(values)
    if isinstance(values, np.ndarray) and values.dtype.kind in "iuf":  # no blanks: map in C
        txt = list(map(str, vals)) if f.kind == INT else list(map(repr, map(float, vals)))
        if f.kind == INT and values.dtype.kind == "f":
            txt = [str(int(v)) for v in vals]
        if f.kind == FLOAT and w is not None:
            for i, t in enumerate(txt):
                if len(t) > w:
                    txt[i] = cards.format_float(float(vals[i]), w) or t
        return txt
    if f.kind == STR:
        return ["" if v is None else str(v) for v in vals]
    if f.kind == INT:
        return ["" if v is None else str(int(v)) for v in vals]
    txt = ["" if v is None else repr(float(v)) for v in vals]
    if w is not None:
        for i, t in enumerate(txt):
            if len(t) > w:
                txt[i] = cards.format_float(float(vals[i]), w) or t
    return txt


def _card_lines(columns: list, fields: tuple[Field, ...], mode: str):
    """Lines of one card for n rows, and which rows fit the columns."""
    n = len(columns[0]) if columns else 0
    if mode == "free":
        cols = [_texts(c, f, None) for c, f in zip(columns, fields)]
        lines = [",".join(row).rstrip(",") for row in zip(*cols)]
        # a line without a comma would be read by columns: keep one
        return [ln if "," in ln else ln + "," for ln in lines], np.ones(n, bool)
    widths = [cards.width(f, mode) for f in fields]
    if n >= 1024 and all(
        f.kind != STR and isinstance(c, np.ndarray) and c.dtype.kind in "iuf" for c, f in zip(columns, fields)
    ):
        if not all(np.isfinite(c).all() for c in columns if c.dtype.kind == "f"):
            raise ValueError("cannot write non-finite values")
        fast = fixed_lines(columns, [0 if f.kind == INT else 1 for f in fields], widths)
        if fast is not None:  # mesh blocks: laid out by a Numba kernel
            return fast, np.ones(n, bool)
    cols = [_texts(c, f, w) for c, f, w in zip(columns, fields, widths)]
    fits = np.ones(n, dtype=bool)
    for col, w in zip(cols, widths):
        if max(map(len, col), default=0) > w:
            fits &= np.fromiter((len(t) <= w for t in col), bool, n)
    fmt = "".join(f"%-{w}s" if f.kind == STR else f"%{w}s" for f, w in zip(fields, widths))
    return [(fmt % row).rstrip() for row in zip(*cols)], fits


def _free_line(values: list, fields) -> str:
    return cards.format_free(values, fields)


def _record_cards(rec: Record):
    """(fields, columns) of every card of a record, in output order.

    Head cards give one-row columns; row cards give full columns.
    """
    lay = rec.spec.layout(rec.options)
    head = []
    for c in lay.head:
        if c.when is not None and not c.when(rec.values, rec.options):
            continue
        head.append((c.fields, [[rec.values.get(f.name)] for f in c.fields]))
    rows = [(c.fields, [rec.rows[f.name] for f in c.fields]) for c in lay.row] if rec.rows else []
    return lay, head, rows


def _trim_optional(rec: Record, lay, head):
    """Drop trailing optional head cards that hold only their defaults."""
    cards_used = [c for c in lay.head if c.when is None or c.when(rec.values, rec.options)]
    while (
        head
        and cards_used
        and cards_used[-1].optional
        and all(rec.values.get(f.name) == f.default for f in cards_used[-1].fields)
    ):
        head.pop()
        cards_used.pop()
    return head


def format_record(rec: Record, deck_mode: str) -> list[str]:
    lay, head, rows = _record_cards(rec)
    head = _trim_optional(rec, lay, head)
    attempts = [deck_mode] if deck_mode in ("free", LONG) else [deck_mode, LONG]
    for mode in attempts:
        blocks, all_fit = [], True
        for group in (head, rows):
            out = []
            for fields, cols in group:
                lines, fits = _card_lines(cols, fields, mode)
                if not fits.all():
                    if mode != attempts[-1]:
                        all_fit = False
                        break
                    for i in np.flatnonzero(~fits):  # last resort: free format
                        lines[i] = _free_line([c[i] for c in cols], fields)
                out.append(lines)
            if not all_fit:
                break
            blocks.append(out)
        if all_fit:
            break
    suffix = "" if mode == deck_mode else _SUFFIX[mode]
    text = [f"*{rec.name}{suffix}"]
    if rec.title is not None and "TITLE" in rec.options:
        text.append(rec.title)
    head_lines, row_lines = blocks
    text.extend(x[0] for x in head_lines)
    if len(row_lines) == 1:
        text.extend(row_lines[0])
    elif row_lines:  # interleave the cards of each row
        for row in zip(*row_lines):
            text.extend(row)
    return text


def format_raw(raw: RawKeyword, deck_mode: str) -> list[str]:
    words = raw.keyword_line.split(None, 1)
    rest = (" " + words[1]) if len(words) > 1 else ""
    suffix = "" if raw.mode == deck_mode else _SUFFIX.get(raw.mode, "")
    return [f"*{raw.keyword}{suffix}{rest}", *raw.lines]


def _parameter_lines(model: Model, mode: str) -> list[str]:
    out = []
    for p in model.parameters:
        kw = "PARAMETER_EXPRESSION" if p.expression else "PARAMETER"
        if p.local:
            kw += "_LOCAL"
        head = f"{p.type}{p.name}"
        body = (
            p.expression
            if p.expression
            else (str(p.value) if p.type == "C" else repr(p.value) if p.type == "R" else str(int(p.value)))
        )
        w = 20 if mode == LONG else 10
        if len(head) <= w and (p.expression or len(body) <= w) and mode != "free" and "," not in body:
            line = head.ljust(w) + (body if p.expression else body.rjust(w))
        else:
            line = f"{head},{body}"
        out += [f"*{kw}", line]
    return out


def deck_lines(model: Model, fmt: str = "fixed", mesh: bool = True, rest: bool = True) -> list[str]:
    mode = FORMATS[fmt]
    lines: list[str] = []
    if rest:
        lines += _parameter_lines(model, mode)
        items = list(model.keywords)
        for g in ENTITY_GROUPS:
            items += list(getattr(model, g).values())
        items += list(model.sets.values())
    else:
        items = []
    if mesh:
        items += mesh_records(model)
    for it in items:
        lines += format_raw(it, mode) if isinstance(it, RawKeyword) else format_record(it, mode)
    return lines


def _header(fmt: str) -> str:
    mode = FORMATS[fmt]
    return "*KEYWORD" + {LONG: " LONG=Y", I10: " I10=Y"}.get(mode, "")


def write_deck(model: Model, path: Path | str, fmt: str = "fixed", split: bool = False) -> list[Path]:
    """Write ``model`` to ``path``; returns the files written.

    ``fmt``: "fixed" (default), "long", "i10" or "free". ``split`` puts nodes
    and elements in an include file ``<stem>_mesh<suffix>`` next to ``path``.
    Refuses to write over a file the model was read from; files are written
    to a temporary name and renamed, so a failure leaves nothing half-written.
    """
    if fmt not in FORMATS:
        raise ValueError(f"unknown deck format {fmt!r}; use fixed, long, i10 or free")
    path = Path(path)
    inputs = {os.path.realpath(f) for f in model.files}
    targets = [path] + ([path.with_name(f"{path.stem}_mesh{path.suffix or '.k'}")] if split else [])
    for t in targets:
        if os.path.realpath(t) in inputs:
            raise FileExistsError(f"{t}: refusing to write over an input file of the model")
    moved = _matrix_files_from(model, path.parent)
    try:
        if split:
            mesh_path = targets[1]
            _atomic_write(mesh_path, [_header(fmt), *deck_lines(model, fmt, mesh=True, rest=False), "*END"])
            body = [_header(fmt), *deck_lines(model, fmt, mesh=False, rest=True), "*INCLUDE", mesh_path.name, "*END"]
        else:
            body = [_header(fmt), *deck_lines(model, fmt), "*END"]
        _atomic_write(path, body)
    finally:
        for rec, name in moved:
            rec["filename"] = name
    return targets


def _matrix_files_from(model: Model, out_dir: Path) -> list:
    """Point the relative FILENAME of each *ELEMENT_DIRECT_MATRIX_INPUT read
    from a deck elsewhere at its file from ``out_dir`` (or copy the file
    there where that path would not fit the card); returns (record, old
    name) to restore after writing."""
    from .dmig import matrix_file

    moved = []
    for rec in model.find("ELEMENT_DIRECT_MATRIX_INPUT"):
        orig = matrix_file(rec)
        if orig is None or os.path.isabs(str(rec["filename"]).strip()):
            continue
        if os.path.realpath(orig.parent) == os.path.realpath(out_dir) or not orig.exists():
            continue
        rel = os.path.relpath(orig, out_dir)
        if len(rel) > 80:
            out_dir.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(orig, out_dir / orig.name)
            rel = orig.name
        moved.append((rec, rec["filename"]))
        rec["filename"] = rel
    return moved


def _atomic_write(path: Path, lines: list[str]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="latin-1", newline="\n") as f:
            f.write("\n".join(lines))
            f.write("\n")
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
