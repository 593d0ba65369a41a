"""Numba kernels that split a deck into lines and parse numeric card rows.

Mesh blocks (*NODE, *ELEMENT_*) are most of a deck's bytes; parsing them
field by field in Python costs ~60 s for 1.5 M shells. These kernels read
the raw bytes once. Floats are converted exactly (correctly rounded) when the
mantissa has at most 15 digits and the decimal exponent is within ±22
(Clinger's fast path); anything else — parameter references, longer
mantissas, unusual notation, malformed text — is flagged for the Python card
parser, which is slower but complete and gives the error message.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

OK, FALLBACK, BLANK, OVERFLOW = 0, 1, 2, 3

_POW10 = np.array([10.0**i for i in range(23)], dtype=np.float64)


def _chunks(nb: int) -> tuple[int, int]:
    nchunk = max(1, min(64, nb // (1 << 20)))
    return nchunk, (nb + nchunk - 1) // nchunk


@njit(cache=True, inline="always")
def _is_eol(buf, i, nb):
    """A line ends at buf[i]: a \\n, or a \\r not followed by \\n (old Mac
    files end lines with \\r alone; \\r\\n ends at its \\n)."""
    c = buf[i]
    return c == 10 or (c == 13 and (i + 1 == nb or buf[i + 1] != 10))


@njit(cache=True, parallel=True)
def _count_newlines(buf, nchunk, size, counts):
    nb = buf.shape[0]
    for c in prange(nchunk):
        k = 0
        for i in range(c * size, min(nb, (c + 1) * size)):
            if _is_eol(buf, i, nb):
                k += 1
        counts[c + 1] = k


@njit(cache=True, parallel=True)
def _fill_lines(buf, nchunk, size, counts, starts, ends):
    nb = buf.shape[0]
    for c in prange(nchunk):
        n = counts[c]
        for i in range(c * size, min(nb, (c + 1) * size)):
            if _is_eol(buf, i, nb):
                ends[n] = i - 1 if buf[i] == 10 and i > 0 and buf[i - 1] == 13 else i
                starts[n + 1] = i + 1  # the next line starts past the newline
                n += 1
    n = ends.shape[0]
    if nb > 0 and buf[nb - 1] != 10 and buf[nb - 1] != 13:  # last line without a newline
        ends[n - 1] = nb
    starts[0] = 0


def split_lines(buf: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Start and end byte offsets of every line of ``buf`` (uint8); ends
    exclude the newline: ``\\n``, ``\\r\\n`` or a lone ``\\r``. Two parallel
    passes over chunks: count, then fill."""
    nb = buf.shape[0]
    nchunk, size = _chunks(nb)
    counts = np.zeros(nchunk + 1, dtype=np.int64)
    if nb:
        _count_newlines(buf, nchunk, size, counts)
    np.cumsum(counts, out=counts)
    n = int(counts[-1]) + (1 if nb and buf[nb - 1] not in (10, 13) else 0)
    starts = np.empty(n + 1, dtype=np.int64)  # one spare: the start past the last newline
    ends = np.empty(n, dtype=np.int64)
    if n:
        _fill_lines(buf, nchunk, size, counts, starts, ends)
    return starts[:n], ends


@njit(cache=True, inline="always")
def _parse_number(buf, a, b, is_int, pow10):
    """Parse buf[a:b]. Returns (status, blank, int_value, float_value)."""
    while a < b and (buf[a] == 32 or buf[a] == 9):
        a += 1
    if is_int and a < b:  # fast path: plain digits then blanks
        i = a
        neg = buf[i] == 45
        if neg or buf[i] == 43:
            i += 1
        v = 0
        nd = 0
        while i < b and 48 <= buf[i] <= 57 and nd < 18:
            v = v * 10 + (buf[i] - 48)
            nd += 1
            i += 1
        j = i
        while j < b and buf[j] == 32:
            j += 1
        if j == b and nd > 0:
            return OK, False, -v if neg else v, 0.0
    while b > a and (buf[b - 1] == 32 or buf[b - 1] == 9):
        b -= 1
    if a == b:
        return OK, True, 0, 0.0
    i = a
    neg = False
    c = buf[i]
    if c == 45 or c == 43:  # - +
        neg = c == 45
        i += 1
    mant = 0
    ndig = 0  # significant digits kept in mant
    exp10 = 0
    seen_digit = False
    seen_dot = False
    while i < b:
        c = buf[i]
        if 48 <= c <= 57:
            seen_digit = True
            if mant > 0 or c != 48:
                if ndig >= 18:
                    return FALLBACK, False, 0, 0.0
                mant = mant * 10 + (c - 48)
                ndig += 1
            if seen_dot:
                exp10 -= 1
            i += 1
        elif c == 46 and not seen_dot:
            seen_dot = True
            i += 1
        else:
            break
    if not seen_digit:
        return FALLBACK, False, 0, 0.0
    has_exp = False
    if i < b:
        c = buf[i]
        if c == 101 or c == 69 or c == 100 or c == 68:  # e E d D
            has_exp = True
            i += 1
            eneg = False
            if i < b and (buf[i] == 45 or buf[i] == 43):
                eneg = buf[i] == 45
                i += 1
            if i >= b:
                return FALLBACK, False, 0, 0.0
            ev = 0
            while i < b:
                c = buf[i]
                if 48 <= c <= 57:
                    ev = ev * 10 + (c - 48)
                    if ev > 100000:
                        return FALLBACK, False, 0, 0.0
                    i += 1
                else:
                    return FALLBACK, False, 0, 0.0
            exp10 += -ev if eneg else ev
        else:
            return FALLBACK, False, 0, 0.0
    if is_int:
        if not seen_dot and not has_exp:
            return OK, False, -mant if neg else mant, 0.0
        # "12." or "1.2e1": accepted when integral
        if exp10 >= 0:
            if ndig + exp10 > 18:  # could pass int64: the Python parser decides
                return FALLBACK, False, 0, 0.0
            v = mant
            for _ in range(exp10):
                v *= 10
            return OK, False, -v if neg else v, 0.0
        d = 1
        for _ in range(-exp10):
            d *= 10
            if d > 10**18:
                return FALLBACK, False, 0, 0.0
        if mant % d != 0:
            return FALLBACK, False, 0, 0.0
        v = mant // d
        return OK, False, -v if neg else v, 0.0
    if mant == 0:
        return OK, False, 0, -0.0 if neg else 0.0
    if ndig > 15 or exp10 > 22 or exp10 < -22:
        return FALLBACK, False, 0, 0.0
    f = float(mant)
    if exp10 >= 0:
        f = f * pow10[exp10]
    else:
        f = f / pow10[-exp10]
    return OK, False, 0, -f if neg else f


@njit(cache=True)
def _free_token(buf, s, e, j):
    """Bounds of the j-th comma-separated token of line [s, e)."""
    k = 0
    a = s
    for i in range(s, e):
        if buf[i] == 44:
            if k == j:
                return a, i
            k += 1
            a = i + 1
    if k == j:
        return a, e
    return e, e


@njit(cache=True, inline="always")
def _parse_row(
    buf,
    starts,
    ends,
    r,
    lines_per_row,
    card_of,
    index_in_card,
    col,
    width,
    is_int,
    slot,
    def_i,
    def_f,
    out_i,
    out_f,
    free,
    card_end,
    pow10,
):
    for c in range(lines_per_row):
        li = r * lines_per_row + c
        free[c] = False
        # a comma past the card's columns (a comma inside them makes the
        # fixed-column parse fail, which is caught below)
        for i in range(starts[li] + card_end[c], ends[li]):
            if buf[i] == 44:
                free[c] = True
                break
    nf = card_of.shape[0]
    imax = np.iinfo(out_i.dtype).max
    # fixed columns first; a field that fails on a line holding a comma
    # switches that line to free format and the row is read again
    st = OK
    for attempt in range(2):
        st = OK
        all_blank = True
        for k in range(nf):
            c = card_of[k]
            li = r * lines_per_row + c
            s = starts[li]
            e = ends[li]
            if free[c]:
                a, b = _free_token(buf, s, e, index_in_card[k])
            else:
                a = min(s + col[k], e)
                b = min(a + width[k], e)
            code, blank, iv, fv = _parse_number(buf, a, b, is_int[k], pow10)
            all_blank = all_blank and blank
            if code == OK and is_int[k] and (iv > imax or iv < -imax):
                code = OVERFLOW
            if code != OK:
                st = code
                if attempt == 0 and not free[c] and code == FALLBACK:
                    for i in range(s, e):
                        if buf[i] == 44:
                            free[c] = True
                            break
                break
            if is_int[k]:
                out_i[slot[k], r] = def_i[k] if blank else iv
            else:
                out_f[r, slot[k]] = def_f[k] if blank else fv
        if st == OK:
            if all_blank:  # every line of the row is blank (or holds only spaces)
                any_free = False
                for c in range(lines_per_row):
                    any_free = any_free or free[c]
                if not any_free:
                    return BLANK
            break
        any_free = False
        for c in range(lines_per_row):
            any_free = any_free or free[c]
        if not any_free or st == OVERFLOW:
            break
    return st


@njit(cache=True, parallel=True)
def parse_rows(
    buf,
    starts,
    ends,
    lines_per_row,
    card_of,
    index_in_card,
    col,
    width,
    is_int,
    slot,
    def_i,
    def_f,
    out_i,
    out_f,
    status,
):
    """Parse rows of numeric fields, in parallel chunks of rows.

    ``starts``/``ends``: bounds of the data lines of the block (comments
    removed), ``lines_per_row`` consecutive lines per row. Per field k:
    card_of[k] (line within the row), index_in_card[k] (for free format),
    col/width (fixed columns), is_int, slot (column in out_i or out_f),
    def_i/def_f (value for a blank field). A line holding a comma is read as
    free format. Each row writes only its own outputs, so the result does not
    depend on the thread count. Status per row: OK, FALLBACK (Python parser
    needed), BLANK (only blank lines), OVERFLOW (integer too large for out_i).
    """
    nrow = starts.shape[0] // lines_per_row
    nf = card_of.shape[0]
    card_end = np.zeros(lines_per_row, dtype=np.int64)
    for k in range(nf):
        card_end[card_of[k]] = max(card_end[card_of[k]], col[k] + width[k])
    chunk = 65536
    nchunk = (nrow + chunk - 1) // chunk
    for ch in prange(nchunk):
        free = np.zeros(lines_per_row, dtype=np.bool_)
        pow10 = _POW10
        for r in range(ch * chunk, min(nrow, (ch + 1) * chunk)):
            status[r] = _parse_row(
                buf,
                starts,
                ends,
                r,
                lines_per_row,
                card_of,
                index_in_card,
                col,
                width,
                is_int,
                slot,
                def_i,
                def_f,
                out_i,
                out_f,
                free,
                card_end,
                pow10,
            )
    return nrow


@njit(cache=True, parallel=True)
def gather_index(table, ids, out):
    """out[i, j] = table[ids[i, j]], -1 outside the table (dense ID lookup).

    ``ids`` may be a strided view (a column block of the parsed matrix).
    """
    n = table.shape[0]
    for i in prange(ids.shape[0]):
        for j in range(ids.shape[1]):
            v = ids[i, j]
            out[i, j] = table[v] if 0 <= v < n else -1


@njit(cache=True)
def first_duplicate(ids, lo, hi):
    """Index of the first repeated ID in ``ids`` (all within [lo, hi]), or -1."""
    seen = np.zeros(hi - lo + 1, dtype=np.bool_)
    for i in range(ids.shape[0]):
        k = ids[i] - lo
        if seen[k]:
            return i
        seen[k] = True
    return -1


@njit(cache=True, parallel=True)
def parse_int_rows(buf, starts, ends, width, def_i, out_i, status):
    """Fast path for element cards: one line per row, integer fields of equal
    ``width``. Anything but blanks, a sign and digits in a field (a comma, a
    decimal point, a parameter) leaves status FALLBACK for the general kernel.
    """
    nrow = starts.shape[0]
    nf = def_i.shape[0]
    imax = np.iinfo(out_i.dtype).max
    chunk = 65536
    nchunk = (nrow + chunk - 1) // chunk
    for ch in prange(nchunk):
        for r in range(ch * chunk, min(nrow, (ch + 1) * chunk)):
            s = starts[r]
            e = ends[r]
            st = OK
            blank_row = True
            for k in range(nf):
                a = s + k * width
                b = min(a + width, e)
                v = 0
                neg = False
                seen = False
                ended = False
                i = a
                while i < b:
                    c = buf[i]
                    if c == 32:
                        if seen:
                            ended = True
                    elif 48 <= c <= 57 and not ended:
                        if v >= 100000000000000000:  # a 19th digit could wrap int64
                            st = FALLBACK
                            break
                        v = v * 10 + (c - 48)
                        seen = True
                    elif (c == 45 or c == 43) and not seen and not ended and not neg:
                        neg = c == 45
                    else:
                        st = FALLBACK
                        break
                    i += 1
                if st != OK:
                    break
                if seen:
                    blank_row = False
                    out_i[k, r] = -v if neg else v
                    if v > imax:
                        st = OVERFLOW
                        break
                else:
                    out_i[k, r] = def_i[k]
            if st == OK and e > s + nf * width:  # text past the last field
                for i in range(s + nf * width, e):
                    if buf[i] != 32:
                        st = FALLBACK
                        break
            if st == OK and blank_row:
                st = BLANK
            status[r] = st
    return nrow
