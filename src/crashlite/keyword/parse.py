"""Turning keyword blocks into typed records by their schema."""

from __future__ import annotations

import numpy as np

from . import cards
from .errors import Collector
from .fastparse import BLANK, FALLBACK, OVERFLOW, parse_int_rows, parse_rows
from .lexer import Block
from .schema import FLOAT, INT, STR, Card, Layout, Record, Spec


class _Lines:
    """Cursor over a block's data lines."""

    def __init__(self, blk: Block):
        self.blk = blk
        self.j = 0
        self.n = len(blk.data)

    def more(self) -> bool:
        return self.j < self.n

    def take(self) -> tuple[str, int]:
        t = self.blk.text(self.j), self.blk.line_no(self.j)
        self.j += 1
        return t


def parse_block(blk: Block, spec: Spec, options: frozenset, params: dict, problems: Collector) -> list[Record]:
    """All records of one block (keywords without rows may repeat their cards)."""
    if spec.sniff is not None and len(blk.data):
        options = spec.sniff(blk.text(0), options)
    lay: Layout = spec.layout(options)
    cur = _Lines(blk)
    records = []
    while True:
        rec = _parse_head(blk, spec, options, lay, cur, params, problems)
        if rec is None:
            break
        if lay.row:
            rec.rows = _parse_rows(blk, lay, cur, params, problems)
            records.append(rec)
            break
        records.append(rec)
        # further instances under the same keyword, unless only blank lines remain
        while cur.more() and not cur.blk.text(cur.j).strip():
            cur.j += 1
        if not cur.more():
            break
    return records


def _parse_head(blk, spec, options, lay, cur, params, problems) -> Record | None:
    rec = Record(spec.name, options, {}, None, None, (blk.file, blk.line))
    if lay.title_card or ("TITLE" in options and spec.title_option):
        rec.title = cur.take()[0].rstrip() if cur.more() else ""  # LS-DYNA: a blank title
    for c in lay.head:
        if c.when is not None and not c.when(rec.values, options):
            for f in c.fields:  # every field of the layout has a value
                rec.values.setdefault(f.name, f.default)
            continue
        if not cur.more():
            # LS-DYNA reads a card missing before the next keyword as a blank
            # card: its fields take their defaults, unless one has none
            needed = [f.name for f in c.fields if f.default is None and f.kind != STR]
            if needed and not c.optional:
                problems.error(
                    blk.file,
                    blk.line,
                    blk.keyword,
                    needed[0].upper(),
                    f"card with {', '.join(c.names)} missing: the keyword ended before it, "
                    f"and {needed[0].upper()} has no default",
                )
                return None
            for f in c.fields:
                rec.values[f.name] = f.default
            continue
        line, lineno = cur.take()
        _read_card(line, lineno, c, blk, params, problems, rec.values)
        for f in c.fields:
            rec.card_lines[f.name] = lineno
    return rec


def _read_card(line, lineno, c: Card, blk, params, problems, out: dict) -> bool:
    ok = True
    raw = cards.split(line, c.fields, blk.mode)
    for text, f in zip(raw, c.fields):
        try:
            out[f.name] = cards.convert(text, f, params)
        except cards.FieldError as e:
            problems.error(blk.file, lineno, blk.keyword, f.name.upper(), str(e))
            out[f.name] = f.default
            ok = False
    return ok


def _row_default(f):
    if f.default is not None:
        return f.default
    return "" if f.kind == STR else 0


def _parse_rows(blk: Block, lay: Layout, cur: _Lines, params, problems) -> dict:
    """Row fields as columns. Numeric rows go through the Numba kernel."""
    idx = blk.data[cur.j :]
    src = blk.src
    starts, ends = src.starts[idx], src.ends[idx]
    keep = ends > starts
    if not keep.all():  # empty lines inside row data are skipped
        idx, starts, ends = idx[keep], starts[keep], ends[keep]
    nl = len(lay.row)
    fields = lay.row_fields
    numeric = all(f.kind != STR for f in fields)
    n_lines = len(idx)
    if n_lines % nl:
        ln = int(idx[-1]) + 1 if n_lines else blk.line
        problems.error(
            blk.file, ln, blk.keyword, None, f"each entry has {nl} cards but {n_lines} data lines were found"
        )
        n_lines -= n_lines % nl
        idx, starts, ends = idx[:n_lines], starts[:n_lines], ends[:n_lines]
    nrow = n_lines // nl
    ints = [k for k, f in enumerate(fields) if f.kind == INT]
    flts = [k for k, f in enumerate(fields) if f.kind == FLOAT]
    # Integers column-major (each field's column contiguous, element node
    # blocks taken as views), int32 while the columns cannot hold more than
    # 9 digits; floats row-major (node coordinates are then one (n, 3) block).
    # The kernels fill one layout only, int64 (field, row), so that Numba
    # compiles each of them once: out_i is its transpose.
    narrow = all(cards.width(f, blk.mode) <= 9 for f in fields if f.kind == INT)
    ints_t = np.zeros((len(ints), nrow), dtype=np.int64)
    out_f = np.zeros((nrow, len(flts)), dtype=np.float64)
    status = np.full(nrow, FALLBACK, dtype=np.int8)
    if numeric and nrow:
        card_of, index_in, col, width = [], [], [], []
        for ci, c in enumerate(lay.row):
            pos = 0
            for fi, f in enumerate(c.fields):
                w = cards.width(f, blk.mode)
                card_of.append(ci), index_in.append(fi), col.append(pos), width.append(w)
                pos += w
        args = (
            np.array(card_of, np.int64),
            np.array(index_in, np.int64),
            np.array(col, np.int64),
            np.array(width, np.int64),
            np.array([f.kind == INT for f in fields]),
            np.array([ints.index(k) if k in ints else flts.index(k) for k in range(len(fields))], np.int64),
            np.array([int(_row_default(f)) if f.kind == INT else 0 for f in fields], np.int64),
            np.array([float(_row_default(f)) if f.kind == FLOAT else 0.0 for f in fields]),
        )
        widths = {w for w in width}
        if nl == 1 and not flts and len(widths) == 1:  # element cards: all-integer fast path
            parse_int_rows(src.buf, starts, ends, width[0], args[6], ints_t, status)
            redo = np.flatnonzero(status == FALLBACK)
            if len(redo):  # free format, parameters, ...: the general kernel
                sub = np.full(len(redo), FALLBACK, dtype=np.int8)
                tmp_i = np.zeros((len(ints), len(redo)), dtype=np.int64)
                parse_rows(src.buf, starts[redo], ends[redo], nl, *args, tmp_i, out_f[redo], sub)
                ints_t[:, redo] = tmp_i
                status[redo] = sub
        else:
            parse_rows(src.buf, starts, ends, nl, *args, ints_t, out_f, status)
        status[status == OVERFLOW] = FALLBACK  # beyond int64: the Python parser says so
    out_i = ints_t.T
    slow = np.flatnonzero(status == FALLBACK)
    strs = {k: np.empty(nrow, dtype=object) for k, f in enumerate(fields) if f.kind == STR}
    for r in slow:
        vals: dict = {}
        texts = [src.text(int(idx[r * nl + ci])) for ci in range(nl)]
        if not any(t.strip(cards.BLANKS) for t in texts):
            status[r] = BLANK
            continue
        for ci, c in enumerate(lay.row):
            li = int(idx[r * nl + ci])
            if texts[ci].strip(cards.BLANKS):
                _read_card(texts[ci], li + 1, c, blk, params, problems, vals)
        for k, f in enumerate(fields):
            v = vals.get(f.name)
            if v is None:
                v = _row_default(f)
            if f.kind == INT:
                out_i[r, ints.index(k)] = v
            elif f.kind == FLOAT:
                out_f[r, flts.index(k)] = v
            else:
                strs[k][r] = v
    for k, f in enumerate(fields):  # LS-DYNA's "EQ.0: default" fields
        if f.zero_default:
            col = out_i[:, ints.index(k)] if f.kind == INT else out_f[:, flts.index(k)]
            col[col == 0] = f.default
    if narrow and out_i.size and -(2**31) < out_i.min() and out_i.max() < 2**31:
        out_i = out_i.astype(np.int32, order="F")
    keep = status != BLANK
    if not keep.all():
        out_i, out_f = out_i[keep], out_f[keep]
        strs = {k: v[keep] for k, v in strs.items()}
    rows = RowColumns()
    for k, f in enumerate(fields):
        if f.kind == INT:
            rows.add(f.name, out_i, ints.index(k))
        elif f.kind == FLOAT:
            rows.add(f.name, out_f, flts.index(k))
        else:
            rows[f.name] = strs[k]
    cur.j = cur.n
    return rows


class RowColumns(dict):
    """Row fields by name (column views); remembers the column-major matrix
    each came from so that adjacent fields are taken without a copy."""

    def __init__(self, *a, **kw):
        super().__init__(*a, **kw)
        self._where: dict = {}

    def add(self, name, matrix, j) -> None:
        super().__setitem__(name, matrix[:, j])
        self._where[name] = (matrix, j)

    def __setitem__(self, name, value) -> None:
        super().__setitem__(name, value)
        self._where.pop(name, None)  # replaced: no longer a view of the matrix

    def block(self, *names) -> np.ndarray:
        """(n, len(names)) array of the named columns (a view when adjacent)."""
        w = [self._where.get(n) for n in names]
        if (
            all(x is not None for x in w)
            and all(x[0] is w[0][0] for x in w)
            and [x[1] for x in w] == list(range(w[0][1], w[0][1] + len(w)))
        ):
            return w[0][0][:, w[0][1] : w[0][1] + len(w)]
        return np.stack([self[n] for n in names], axis=1)
