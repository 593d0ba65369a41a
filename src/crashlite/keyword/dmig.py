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


def _assemble(cols: dict, form: dict) -> dict:
    """name -> (dofs, matrix) from per-matrix arrays (column grid, column
    component, row grid, row component, value) and the column DOFs listed."""
    out = {}
    for name, (cg, cc, rg, rc, val, listed) in cols.items():
        # one integer per DOF, ordered as the (grid, component) pairs (components 0-6)
        ckey, rkey = cg * 10 + cc, rg * 10 + rc
        keys = np.unique(np.concatenate([listed, rkey]))
        ci, ri = np.searchsorted(keys, ckey), np.searchsorted(keys, rkey)
        mat = np.zeros((len(keys), len(keys)))
        mat[ri, ci] = val
        if form[name] == 6:
            mat[ci, ri] = val
        out[name] = (np.stack([keys // 10, keys % 10], axis=1).astype(np.int64), mat)
    return out


def _read_large_field(lines: list[str]) -> dict | None:
    """The matrices of a file written as ``write_dmig`` writes them (large
    field, one (G, C, A) row per continuation line), parsed column-wise at
    NumPy's speed; None for any other layout or anything it cannot parse
    (the general reader then reads it, and names the line at fault)."""
    is_d = np.fromiter((ln.startswith("DMIG*") for ln in lines), bool, len(lines))
    is_c = np.fromiter((ln.startswith("*") for ln in lines), bool, len(lines))
    if not len(lines) or not is_d[0] or not (is_d | is_c).all():
        return None
    entry = np.cumsum(is_d) - 1
    names, form, col_g, col_c, header = [], {}, [], [], []
    for i in np.flatnonzero(is_d):
        f = _fields(lines[i])
        names.append(f[1])
        header.append(f[2] == "0")
        if header[-1]:
            form[f[1]] = int(f[3])
            if form[f[1]] not in (1, 6):
                return None
            col_g.append(0), col_c.append(0)
        else:
            col_g.append(int(f[2])), col_c.append(int(f[3] or 1))
    if any(n not in form for n, h in zip(names, header) if not h):
        return None
    rows = np.flatnonzero(is_c & ~np.array(header)[entry])
    # the row lines' four 16-character fields (G, C, A, B), as one fixed-width byte array
    body = "".join([lines[i][8:72].ljust(64) for i in rows]).encode("ascii")
    f = np.frombuffer(body, dtype="S16").reshape(-1, 4)
    blank = b" " * 16
    keep = f[:, 0] != blank
    if (f[keep, 1] == blank).any() or (f[keep, 2] == blank).any():
        return None  # defaults (C = 1, A = 0): the general reader
    rows, e = rows[keep], entry[rows[keep]]
    g, c, a = f[keep, 0].astype(np.int64), f[keep, 1].astype(np.int64), f[keep, 2].astype(float)
    col_g, col_c, names = np.array(col_g, np.int64), np.array(col_c, np.int64), np.array(names)
    cols = {}
    for name in form:
        mine = names[e] == name
        listed = np.flatnonzero((names == name) & ~np.array(header))
        cols[name] = (col_g[e[mine]], col_c[e[mine]], g[mine], c[mine], a[mine], col_g[listed] * 10 + col_c[listed])
    return _assemble(cols, form)


def read_dmig(path) -> dict:
    """name -> (dofs (k, 2) [grid, component], (k, k) matrix) of every DMIG
    in ``path``; symmetric matrices (IFO 6) filled from the triangle given.
    Errors name the file and line."""
    path = Path(path)
    text = path.read_text()
    if "," not in text:
        try:
            fast = _read_large_field([ln for ln in text.splitlines() if ln.strip() and not ln.startswith("$")])
        except (ValueError, IndexError):
            fast = None
        if fast is not None:
            return fast
    entries: list = []  # (line number, [fields]) per entry, continuations joined
    for no, line in enumerate(text.splitlines(), start=1):
        if not line.strip() or line.startswith("$"):
            continue
        f = _fields(line)
        if f[0].upper().startswith("DMIG"):
            entries.append((no, f[1:]))
        elif entries and (f[0] in ("", "*", "+") or f[0].startswith(("*", "+"))):
            entries[-1][1].extend(f[1:])
        else:
            raise ValueError(f"{path}:{no}: not a DMIG entry or continuation: {line.strip()[:40]!r}")
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
    arrays = {}
    for name, c in cols.items():
        rows = [(gj, cj, g, comp, v) for (gj, cj), col in c.items() for (g, comp), v in col.items()]
        cg, cc, rg, rc = (np.array([r[i] for r in rows], np.int64) for i in range(4))
        listed = np.array([gj * 10 + cj for gj, cj in c], np.int64)
        arrays[name] = (cg, cc, rg, rc, np.array([r[4] for r in rows], float), listed)
    return _assemble(arrays, form)
