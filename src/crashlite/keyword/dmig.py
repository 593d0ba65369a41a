"""NASTRAN DMIG matrices: the file *ELEMENT_DIRECT_MATRIX_INPUT names.

A DMIG matrix is a header entry (NAME, "0", IFO, TIN, TOUT, POLAR, NCOL)
and one column entry per column: the column's grid point and component,
then (grid, component, value) per non-zero row. ``write_dmig`` writes
symmetric matrices (IFO 6, the lower triangle with the diagonal, column by
column) in large-field format (``DMIG*``, 16-character fields: ten
significant digits, LS-DYNA's IFRMT ≠ 0), so that a superelement's rigid
motions stay free of stiffness to round-off. ``read_dmig`` reads small-
field (8 characters), large-field and free-field (comma) entries.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np


def _real(v: float) -> str:
    return f"{v:16.9E}"


def _large(fields: list, first: str) -> str:
    """One large-field line: an 8-character name field and four of 16."""
    cells = [f"{first:<8s}"] + [f"{str(f):>16s}" if not isinstance(f, float) else _real(f) for f in fields]
    cells += [" " * 16] * (5 - len(cells))
    return "".join(cells).rstrip() + "\n"


def write_dmig(path, matrices: dict) -> Path:
    """Write ``matrices``: name -> (dofs (k, 2) [grid ID, component 1–6],
    symmetric (k, k) matrix). Names up to 8 characters."""
    path = Path(path)
    out = []
    for name, (dofs, mat) in matrices.items():
        name = str(name)
        if not 0 < len(name) <= 8:
            raise ValueError(f"DMIG name {name!r}: 1 to 8 characters")
        dofs = np.asarray(dofs, np.int64)
        mat = np.asarray(mat, float)
        k = len(dofs)
        if mat.shape != (k, k):
            raise ValueError(f"DMIG {name}: matrix {mat.shape} for {k} DOFs")
        if not np.allclose(mat, mat.T, rtol=1e-12, atol=1e-300 + 1e-14 * np.abs(mat).max(initial=0.0)):
            raise ValueError(f"DMIG {name}: the matrix is not symmetric")
        out.append(_large([name, 0, 6, 2], "DMIG*"))
        out.append(_large([0, "", "", ""], "*"))  # TOUT, POLAR, NCOL unused for IFO 6
        for j in range(k):
            rows = np.flatnonzero(mat[j:, j] != 0.0) + j
            out.append(_large([name, int(dofs[j, 0]), int(dofs[j, 1]), ""], "DMIG*"))
            for i in rows:
                out.append(_large([int(dofs[i, 0]), int(dofs[i, 1]), float(mat[i, j]), ""], "*"))
    path.write_text("".join(out))
    return path


def matrix_file(rec, fallback_dir=None) -> Path | None:
    """The file an *ELEMENT_DIRECT_MATRIX_INPUT record names: FILENAME as
    given where absolute, else relative to the deck file the record was read
    from (or ``fallback_dir`` for a record built in memory); None where the
    record names none or nothing anchors a relative name."""
    name = str(rec.get("filename", "") or "").strip()
    if not name:
        return None
    path = Path(name)
    if path.is_absolute():
        return path
    base = Path(rec.source[0]).parent if rec.source and rec.source[0] else fallback_dir
    return None if base is None else Path(base) / path


def _fields(line: str) -> list[str]:
    """The data fields of one line (name field dropped for continuations)."""
    if "," in line:
        return [f.strip() for f in line.rstrip("\n").split(",")]
    head = line[:8]
    if head.strip().endswith("*") or head.startswith("*"):
        body = line[8:72].ljust(64)  # (blank trailing fields may be cut off)
        return [head.strip()] + [body[i : i + 16].strip() for i in range(0, len(body), 16)]
    body = line[8:72].ljust(64)
    return [head.strip()] + [body[i : i + 8].strip() for i in range(0, len(body), 8)]


def _number(text: str) -> float:
    t = text.strip().upper().replace("D", "E")
    if not t:
        return 0.0
    try:
        return float(t)
    except ValueError:  # NASTRAN's exponent without E: 1.5+3, -2.-4
        k = max(t.rfind("+"), t.rfind("-"))
        if k <= 0:
            raise
        return float(t[:k] + "E" + t[k:])


def read_dmig(path) -> dict:
    """name -> (dofs (k, 2) [grid, component], (k, k) matrix) of every DMIG
    in ``path``; symmetric matrices (IFO 6) filled from the triangle given.
    Errors name the file and line."""
    path = Path(path)
    entries: list = []  # (line number, [fields]) per entry, continuations joined
    for no, line in enumerate(path.read_text().splitlines(), start=1):
        if not line.strip() or line.startswith("$"):
            continue
        f = _fields(line)
        if f[0].upper().startswith("DMIG"):
            entries.append((no, f[1:]))
        elif entries and (f[0] in ("", "*", "+") or f[0].startswith(("*", "+"))):
            entries[-1][1].extend(f[1:])
        else:
            raise ValueError(f"{path}:{no}: not a DMIG entry or continuation: {line.strip()[:40]!r}")
    out: dict = {}
    cols: dict = {}
    form: dict = {}
    for no, f in entries:
        name = f[0]
        try:
            if f[1] == "0":  # header
                form[name] = int(f[2])
                if form[name] not in (1, 6):
                    raise ValueError(f"IFO {form[name]}: only square (1) and symmetric (6) matrices")
                cols[name] = {}
                continue
            if name not in cols:
                raise ValueError(f"column of DMIG {name} before its header")
            gj, cj = int(f[1]), int(f[2] or 1)
            rest = f[4:]
            col = cols[name].setdefault((gj, cj), {})
            for i in range(0, len(rest) - 2, 4):  # (G, C, A, B) per row in either field width
                if not rest[i]:
                    continue
                col[(int(rest[i]), int(rest[i + 1] or 1))] = _number(rest[i + 2])
        except (ValueError, IndexError) as e:
            raise ValueError(f"{path}:{no}: DMIG {name}: {e}") from None
    for name, c in cols.items():
        keys = sorted(set(c) | {r for col in c.values() for r in col})
        at = {k: i for i, k in enumerate(keys)}
        mat = np.zeros((len(keys), len(keys)))
        for cj, col in c.items():
            for ri, v in col.items():
                mat[at[ri], at[cj]] = v
                if form[name] == 6:
                    mat[at[cj], at[ri]] = v
        out[name] = (np.array(keys, np.int64).reshape(-1, 2), mat)
    return out
