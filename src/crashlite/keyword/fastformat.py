"""Numba kernel that lays out numeric card rows in fixed columns.

Integers are written here; reals arrive as the bytes of their shortest
round-trip text (Python's repr), so the kernel only places them.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange


@njit(cache=True, parallel=True)
def layout_rows(ints, reals, real_len, kind, slot, width, out):
    """Write row r of every field right-justified into out[r] (uint8, the
    line). kind 0: integer ints[slot]; 1: real text reals[slot] of length
    real_len[slot]. Returns 1 when every value fits its width, else 0."""
    n = out.shape[0]
    nf = kind.shape[0]
    ok = np.ones(n, dtype=np.uint8)
    for r in prange(n):
        pos = 0
        for k in range(nf):
            w = width[k]
            end = pos + w
            for i in range(pos, end):
                out[r, i] = 32
            if kind[k] == 0:
                v = ints[slot[k], r]
                neg = v < 0
                if neg:
                    v = -v
                i = end - 1
                if v == 0:
                    out[r, i] = 48
                    i -= 1
                while v > 0 and i >= pos:
                    out[r, i] = 48 + v % 10
                    v //= 10
                    i -= 1
                if v > 0 or (neg and i < pos):
                    ok[r] = 0
                elif neg:
                    out[r, i] = 45
            else:
                m = real_len[slot[k], r]
                if m > w:
                    ok[r] = 0
                else:
                    for j in range(m):
                        out[r, end - m + j] = reals[slot[k], r, j]
            pos = end
    return ok.min()


def fixed_lines(columns, kinds, widths) -> list[str] | None:
    """Lines of numeric row columns in fixed widths, or None when a value
    does not fit (the caller then falls back to the general path)."""
    n = len(columns[0])
    ints = [np.asarray(c, np.int64) for c, k in zip(columns, kinds) if k == 0]
    texts = [list(map(repr, np.asarray(c, np.float64).tolist())) for c, k in zip(columns, kinds) if k == 1]
    longest = max((max(map(len, t), default=0) for t in texts), default=1)
    reals = np.zeros((len(texts), n, max(longest, 1)), np.uint8)
    real_len = np.zeros((len(texts), n), np.int64)
    for j, t in enumerate(texts):
        b = np.array(t, dtype=f"S{max(longest, 1)}")
        reals[j] = b.view(np.uint8).reshape(n, -1)
        real_len[j] = np.char.str_len(b)
    slot, ci, cr = [], 0, 0
    for k in kinds:
        slot.append(ci if k == 0 else cr)
        ci, cr = ci + (k == 0), cr + (k == 1)
    int_arr = np.stack(ints) if ints else np.zeros((0, n), np.int64)
    total = int(sum(widths))
    out = np.empty((n, total + 1), np.uint8)
    out[:, total] = 10  # newline: one decode and one split make the lines
    if not layout_rows(
        int_arr, reals, real_len, np.array(kinds, np.int64), np.array(slot, np.int64), np.array(widths, np.int64), out
    ):
        return None
    return out.tobytes()[:-1].decode("latin-1").split("\n")
