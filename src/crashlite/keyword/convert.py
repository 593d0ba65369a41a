"""Between schema records and the Model: deck IDs become indices here only."""

from __future__ import annotations

import numpy as np

from ..model.mesh import Beams, Discretes, Inertias, Masses, Nodes, Shells, Solids, index_map
from ..model.model import Model
from .errors import Collector
from .fastparse import first_duplicate
from .schema import RawKeyword, Record


def _rows(rec: Record, *names) -> list[np.ndarray]:
    return [rec.rows[n] for n in names]


def _block(rec: Record, *names) -> np.ndarray:
    """Columns side by side; a view of the parsed matrix where possible."""
    rows = rec.rows
    if hasattr(rows, "block"):
        return rows.block(*names)
    return np.stack([rows[n] for n in names], axis=1)


def _i64(a: np.ndarray) -> np.ndarray:
    return a.astype(np.int64, copy=False)


def _absent(shape, value, dtype=np.float64) -> np.ndarray:
    """A read-only array standing for 'not given' (assign a new array to set)."""
    return np.broadcast_to(np.asarray(value, dtype=dtype), shape)


def _nan0(a: np.ndarray) -> np.ndarray:
    """0 means 'not given' for optional element data: store NaN."""
    a = np.asarray(a, dtype=np.float64).copy()
    a[a == 0.0] = np.nan
    return a


def _codes(r: Record, name: str, problems: Collector) -> np.ndarray:
    """TC or RC of a *NODE block as int8, each checked to be 0 to 7 (a code
    out of range must not wrap round to another: 300 would read 44)."""
    col = np.asarray(r.rows[name])
    bad = np.flatnonzero((col < 0) | (col > 7))
    for i in bad[:10]:
        problems.error(
            *r.source,
            r.name,
            name.upper(),
            f"node {int(r.rows['nid'][i])}: {name.upper()} = {int(col[i])} is not a constraint code (0 to 7)",
        )
    if len(bad) > 10:
        problems.error(*r.source, r.name, name.upper(), f"... and {len(bad) - 10} more nodes")
    return np.where((col < 0) | (col > 7), 0, col).astype(np.int8)


def _positive_ids(r: Record, ids: np.ndarray, what: str, field: str, problems: Collector) -> None:
    """IDs must be positive: 0 reads as a blank ID, and LS-DYNA numbers entities from 1."""
    bad = np.flatnonzero(ids <= 0)
    for i in bad[:10]:
        problems.error(
            *r.source, r.name, field, f"{what} ID {int(ids[i])} (row {int(i) + 1} of the block): IDs must be positive"
        )
    if len(bad) > 10:
        problems.error(*r.source, r.name, field, f"... and {len(bad) - 10} more {what} IDs not positive")


def _mesh_tables(recs: dict[str, list[Record]], problems: Collector):
    nodes = Nodes.concat(
        [
            Nodes(
                _i64(r.rows["nid"]),
                np.ascontiguousarray(_block(r, "x", "y", "z")),
                _codes(r, "tc", problems),
                _codes(r, "rc", problems),
            )
            for r in recs.get("NODE", [])
        ]
    )
    for r in recs.get("NODE", []):
        _positive_ids(r, r.rows["nid"], "node", "NID", problems)
    for kw, what in (
        ("ELEMENT_SHELL", "shell"),
        ("ELEMENT_SOLID", "solid"),
        ("ELEMENT_BEAM", "beam"),
        ("ELEMENT_DISCRETE", "discrete"),
        ("ELEMENT_MASS", "mass"),
        ("ELEMENT_INERTIA", "inertia"),
    ):
        for r in recs.get(kw, []):
            _positive_ids(r, r.rows["eid"], what, "EID", problems)
    shell_parts = []
    for r in recs.get("ELEMENT_SHELL", []):
        n = len(r.rows["eid"])
        higher = np.flatnonzero(np.any(_block(r, "n5", "n6", "n7", "n8") != 0, axis=1))
        if len(higher):
            problems.error(
                *r.source, r.name, "N5", f"element {int(r.rows['eid'][higher[0]])}: 8-node shells are not supported"
            )
        # optional per-element data absent: read-only broadcast views cost no memory
        t = Shells(
            _i64(r.rows["eid"]),
            _i64(r.rows["pid"]),
            _block(r, "n1", "n2", "n3", "n4"),
            _absent((n, 4), np.nan),
            _absent(n, np.nan),
            _absent(n, 0, np.int64),
            _absent(n, np.nan),
        )
        if "thic1" in r.rows:
            t.thickness = _nan0(np.stack(_rows(r, "thic1", "thic2", "thic3", "thic4"), axis=1))
            if "MCID" in r.options:
                t.mcid = r.rows["beta"].astype(np.int64)
            else:
                t.beta = _nan0(r.rows["beta"])
        if "offset" in r.rows:
            t.offset = np.asarray(r.rows["offset"], dtype=np.float64)
        shell_parts.append((r, t))
    solid_parts = []
    for r in recs.get("ELEMENT_SOLID", []):
        if "TWO_CARD" in r.options and (np.any(r.rows["n9"] != 0) or np.any(r.rows["n10"] != 0)):
            problems.warn(*r.source, r.name, "N9", "10-node tetrahedra: only the corner nodes are used")
        t = Solids(_i64(r.rows["eid"]), _i64(r.rows["pid"]), _block(r, *[f"n{i}" for i in range(1, 9)]))
        solid_parts.append((r, t))
    beam_parts = []
    for r in recs.get("ELEMENT_BEAM", []):
        n = len(r.rows["eid"])
        t = Beams.zeros(n)
        t.ids, t.pid = _i64(r.rows["eid"]), _i64(r.rows["pid"])
        t.nodes = _block(r, "n1", "n2", "n3")
        t.releases = _i64(_block(r, "rt1", "rr1", "rt2", "rr2", "local"))
        if "parm1" in r.rows:
            t.params = np.stack(_rows(r, *[f"parm{i}" for i in range(1, 6)]), axis=1).astype(float)
        if "pid1" in r.rows:
            t.pid2 = _i64(_block(r, "pid1", "pid2"))
        if "wx1" in r.rows:
            t.offsets = np.stack(_rows(r, "wx1", "wy1", "wz1", "wx2", "wy2", "wz2"), axis=1).astype(float)
        if "vx" in r.rows:
            t.orientation = np.stack(_rows(r, "vx", "vy", "vz"), axis=1).astype(float)
        beam_parts.append((r, t))
    disc_parts = []
    for r in recs.get("ELEMENT_DISCRETE", []):
        t = Discretes(
            _i64(r.rows["eid"]),
            _i64(r.rows["pid"]),
            _block(r, "n1", "n2"),
            _i64(r.rows["vid"]),
            r.rows["s"],
            _i64(r.rows["pf"]),
            r.rows["offset"],
        )
        disc_parts.append((r, t))
    mass_parts = []
    for r in recs.get("ELEMENT_MASS", []):
        mass_parts.append((r, Masses(_i64(r.rows["eid"]), r.rows["id"], r.rows["mass"], _i64(r.rows["pid"]))))
    inertia_parts = []
    for r in recs.get("ELEMENT_INERTIA", []):
        off = np.stack(_rows(r, "x", "y", "z"), axis=1) if "x" in r.rows else np.full((len(r.rows["eid"]), 3), np.nan)
        inertia_parts.append(
            (
                r,
                Inertias(
                    _i64(r.rows["eid"]),
                    r.rows["nid"],
                    _i64(r.rows["csid"]),
                    np.stack(_rows(r, "ixx", "ixy", "ixz", "iyy", "iyz", "izz"), axis=1),
                    r.rows["mass"],
                    off,
                ),
            )
        )
    return nodes, shell_parts, solid_parts, beam_parts, disc_parts, mass_parts, inertia_parts


def _check_unique(ids: np.ndarray, what: str, parts, problems: Collector) -> None:
    if len(ids) < 2:
        return
    lo, hi = int(ids.min()), int(ids.max())
    if hi - lo < 8 * len(ids) + 1_000_000 and first_duplicate(ids, lo, hi) < 0:
        return  # the common case, decided in one linear pass
    s = np.sort(ids)
    dup = np.unique(s[1:][s[1:] == s[:-1]])
    if len(dup) == 0:
        return
    # name the blocks that define each of the first few duplicates
    for d in dup[:20]:
        where = [f"{r.source[0]}:{r.source[1]}" for r, t in parts if np.any(t.ids == d)]
        r = next(r for r, t in parts if np.any(t.ids == d))
        problems.error(
            r.source[0],
            r.source[1],
            r.name,
            None,
            f"{what} ID {int(d)} defined more than once (in blocks at {', '.join(where)})",
        )
    if len(dup) > 20:
        problems.error("", 0, "", None, f"... {len(dup) - 20} more duplicate {what} IDs")


def _map_nodes(parts, cols, node_of, problems: Collector, what: str, allow_zero=True):
    """Replace node IDs by indices in-place; report dangling ones."""
    for r, t in parts:
        ids = getattr(t, cols)
        idx = node_of(ids)
        bad = idx < 0
        if allow_zero:
            bad &= ids != 0
        if bad.any():
            rows, cols_ = np.nonzero(bad.reshape(len(ids), -1))
            for i in range(min(len(rows), 20)):
                eid = int(t.ids[rows[i]])
                nid = int(ids.reshape(len(ids), -1)[rows[i], cols_[i]])
                field = f"N{cols_[i] + 1}" if ids.ndim == 2 else ("NID" if what == "inertia" else "ID")
                problems.error(
                    r.source[0], r.source[1], r.name, field, f"{what} {eid} refers to node {nid}, which is not defined"
                )
            if len(rows) > 20:
                problems.error(
                    r.source[0], r.source[1], r.name, None, f"... {len(rows) - 20} more undefined node references"
                )
        setattr(t, cols, idx.astype(np.int32, copy=False))


def build_model(records: list[Record | RawKeyword], problems: Collector) -> tuple[Model, list[Record]]:
    """A Model from records in deck order, and the mesh records it came from
    (for reference checks); problems collected, not raised."""
    model = Model()
    bulk: dict[str, list[Record]] = {}
    for rec in records:
        if isinstance(rec, RawKeyword):
            model.keywords.append(rec)
            continue
        spec = rec.spec
        g = spec.group
        if spec.bulk and not (rec.keyword == "ELEMENT_MASS" and "SET" in rec.options):
            bulk.setdefault(rec.keyword, []).append(rec)
        elif g == "sets":
            kind = rec.keyword.split("_", 1)[1]
            _add_entity(model.sets, (kind, rec.id), rec, problems, f"*SET_{kind}")
        elif g in ("keywords", "nodes", "masses"):
            model.keywords.append(rec)
        else:
            _add_entity(getattr(model, g), rec.id, rec, problems, g[:-1])
    nodes, shells, solids, beams, discs, masses, inertias = _mesh_tables(bulk, problems)
    _check_unique(
        nodes.ids,
        "node",
        [(r, t) for r in bulk.get("NODE", []) for t in [Nodes(r.rows["nid"], None, None, None)]],
        problems,
    )
    node_of = index_map(nodes.ids)
    for parts, what, col in (
        (shells, "shell", "nodes"),
        (solids, "solid", "nodes"),
        (beams, "beam", "nodes"),
        (discs, "discrete", "nodes"),
        (masses, "mass", "node"),
        (inertias, "inertia", "node"),
    ):
        _map_nodes(parts, col, node_of, problems, what)
    model.nodes = nodes
    for name, parts, cls, what in (
        ("shells", shells, Shells, "shell"),
        ("solids", solids, Solids, "solid"),
        ("beams", beams, Beams, "beam"),
        ("discretes", discs, Discretes, "discrete"),
        ("masses", masses, Masses, "mass"),
        ("inertias", inertias, Inertias, "inertia"),
    ):
        setattr(model, name, cls.concat([t for _, t in parts]))
        _check_unique(getattr(model, name).ids, what, parts, problems)
    # shells: triangles written as n4 = 0 or n4 = n3 are stored with n4 = n3
    sh = model.shells.nodes
    if len(sh):
        tri = sh[:, 3] < 0
        sh[tri, 3] = sh[tri, 2]
    return model, [r for rs in bulk.values() for r in rs]


def _add_entity(store: dict, key, rec: Record, problems: Collector, what: str) -> None:
    if (key[1] if isinstance(key, tuple) else key) is None:
        # blank, or unreadable (already reported): nothing can refer to it
        fld = rec.spec.id_field
        file, line = rec.where(fld)
        if not any(p.file == file and p.line == line and p.field == fld.upper() for p in problems.problems):
            problems.error(file, line, rec.name, fld.upper(), f"{fld.upper()} is blank: the definition needs an ID")
        return
    if key in store:
        first = store[key].source
        problems.error(
            rec.source[0],
            rec.source[1],
            rec.name,
            None,
            f"{what} ID {key if not isinstance(key, tuple) else key[1]} defined twice (first at {first[0]}:{first[1]})",
        )
        return
    store[key] = rec


# --- Model -> records (for the writer) ---------------------------------------


def _split(mask: np.ndarray):
    return [m for m in (~mask, mask) if m.any()]


def mesh_records(model: Model) -> list[Record]:
    """Mesh tables as schema records; elements with optional data get their
    own block with the option, the rest a plain block."""
    out = []
    nid = model.nodes.ids

    def ids_of(idx):
        idx = np.asarray(idx)
        return np.where(idx >= 0, nid[np.clip(idx, 0, max(len(nid) - 1, 0))] if len(nid) else 0, 0)

    n = model.nodes
    if len(n):
        out.append(
            Record(
                "NODE",
                frozenset(),
                {},
                {
                    "nid": n.ids,
                    "x": n.xyz[:, 0],
                    "y": n.xyz[:, 1],
                    "z": n.xyz[:, 2],
                    "tc": n.tc.astype(np.int64),
                    "rc": n.rc.astype(np.int64),
                },
            )
        )
    s = model.shells
    if len(s):
        has_t = ~np.all(np.isnan(s.thickness), axis=1) | ~np.isnan(s.beta) | (s.mcid != 0)
        has_o = ~np.isnan(s.offset)
        groups = {}
        key = has_t.astype(int) * 2 + has_o.astype(int)
        for k in np.unique(key):
            groups[int(k)] = key == k
        for k, m in sorted(groups.items()):
            t = s.take(m)
            conn = ids_of(t.nodes)
            rows = {"eid": t.ids, "pid": t.pid}
            for i in range(4):
                rows[f"n{i + 1}"] = conn[:, i]
            for i in range(4, 8):
                rows[f"n{i + 1}"] = np.zeros(len(t), dtype=np.int64)
            opts = set()
            if k & 2:  # the thickness card; its 5th field is BETA, or MCID with _MCID
                for i in range(4):
                    rows[f"thic{i + 1}"] = np.nan_to_num(t.thickness[:, i])
                if (t.mcid != 0).any():
                    opts.add("MCID")
                    rows["beta"] = t.mcid.astype(np.float64)
                else:
                    opts.add("THICKNESS")
                    rows["beta"] = np.nan_to_num(t.beta)
            if k & 1:
                opts.add("OFFSET")
                rows["offset"] = t.offset
            out.append(Record("ELEMENT_SHELL", frozenset(opts), {}, rows))
    so = model.solids
    if len(so):
        conn = ids_of(so.nodes)
        rows = {"eid": so.ids, "pid": so.pid}
        rows.update({f"n{i + 1}": conn[:, i] for i in range(8)})
        out.append(Record("ELEMENT_SOLID", frozenset(), {}, rows))
    b = model.beams
    if len(b):
        opt_cols = {
            "THICKNESS": ~np.all(np.isnan(b.params), axis=1),
            "PID": np.any(b.pid2 != 0, axis=1),
            "OFFSET": ~np.all(np.isnan(b.offsets), axis=1),
            "ORIENTATION": ~np.all(np.isnan(b.orientation), axis=1),
        }
        key = sum(v.astype(int) << i for i, v in enumerate(opt_cols.values()))
        for k in np.unique(key):
            t = b.take(key == k)
            opts = {o for i, o in enumerate(opt_cols) if (int(k) >> i) & 1}
            conn = ids_of(t.nodes)
            rows = {"eid": t.ids, "pid": t.pid, "n1": conn[:, 0], "n2": conn[:, 1], "n3": conn[:, 2]}
            rows.update(dict(zip(("rt1", "rr1", "rt2", "rr2", "local"), t.releases.T)))
            if "THICKNESS" in opts:
                rows.update({f"parm{i + 1}": np.nan_to_num(t.params[:, i]) for i in range(5)})
            if "PID" in opts:
                rows.update({"pid1": t.pid2[:, 0], "pid2": t.pid2[:, 1]})
            if "OFFSET" in opts:
                rows.update(dict(zip(("wx1", "wy1", "wz1", "wx2", "wy2", "wz2"), np.nan_to_num(t.offsets).T)))
            if "ORIENTATION" in opts:
                rows.update(dict(zip(("vx", "vy", "vz"), np.nan_to_num(t.orientation).T)))
            out.append(Record("ELEMENT_BEAM", frozenset(opts), {}, rows))
    d = model.discretes
    if len(d):
        conn = ids_of(d.nodes)
        out.append(
            Record(
                "ELEMENT_DISCRETE",
                frozenset(),
                {},
                {
                    "eid": d.ids,
                    "pid": d.pid,
                    "n1": conn[:, 0],
                    "n2": conn[:, 1],
                    "vid": d.vid,
                    "s": d.scale,
                    "pf": d.pf,
                    "offset": d.offset,
                },
            )
        )
    m = model.masses
    if len(m):
        out.append(
            Record("ELEMENT_MASS", frozenset(), {}, {"eid": m.ids, "id": ids_of(m.node), "mass": m.mass, "pid": m.pid})
        )
    it = model.inertias
    if len(it):
        has_off = ~np.all(np.isnan(it.offset), axis=1)
        for mask in _split(has_off):
            t = it.take(mask)
            rows = {"eid": t.ids, "nid": ids_of(t.node), "csid": t.csid, "mass": t.mass}
            rows.update(dict(zip(("ixx", "ixy", "ixz", "iyy", "iyz", "izz"), t.tensor.T)))
            opts = frozenset()
            if has_off[mask].all():
                opts = frozenset({"OFFSET"})
                rows.update(dict(zip(("x", "y", "z"), np.nan_to_num(t.offset).T)))
            out.append(Record("ELEMENT_INERTIA", opts, {}, rows))
    return out
