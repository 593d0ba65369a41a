"""Dangling-reference checks: every ID a record names must be defined."""

from __future__ import annotations

import numpy as np

from ..model.model import Model
from .errors import Collector
from .schema import INT, RawKeyword, Record

# Families of keywords crashlite keeps verbatim whose first field still
# defines an ID others may reference (e.g. *DEFINE_TABLE for a MAT_024 LCSS).
_RAW_DEFINES = (
    ("MAT_", "mat"),
    ("SECTION_", "sec"),
    ("HOURGLASS", "hg"),
    ("EOS_", "eos"),
    ("DEFINE_CURVE", "curve"),
    ("DEFINE_TABLE", "curve"),
    ("DEFINE_FUNCTION", "curve"),
    ("DEFINE_VECTOR", "vector"),
    ("DEFINE_COORDINATE", "coord"),
    ("PART", "part"),
)


def _raw_id(raw: RawKeyword) -> int | None:
    lines = [ln for ln in raw.lines if ln.strip() and not ln.startswith("$")]
    if raw.keyword.endswith("_TITLE") or raw.keyword.startswith("PART"):
        lines = lines[1:]
    if not lines:
        return None
    tok = lines[0].split(",")[0] if "," in lines[0] else lines[0][:10]
    try:
        return int(float(tok))
    except ValueError:
        return None


def defined_ids(model: Model) -> dict[str, set]:
    d: dict[str, set] = {
        "part": set(model.parts),
        "sec": set(model.sections),
        "mat": set(model.materials),
        "hg": set(model.hourglasses),
        "curve": set(model.curves),
        "vector": set(model.vectors),
        "coord": set(model.coordinate_systems),
        "eos": set(),
        "sdo": {int(r["vid"]) for r in model.find("DEFINE_SD_ORIENTATION")},
    }
    for kind, sid in model.sets:
        d.setdefault("set_" + kind.lower(), set()).add(sid)
    for k in model.keywords:
        if isinstance(k, Record) and k.keyword == "DEFINE_TABLE" and k.id is not None:
            d["curve"].add(k.id)  # a table shares the curves' IDs: a LCSS names either
        if isinstance(k, RawKeyword):
            for prefix, kind in _RAW_DEFINES:
                if k.keyword.startswith(prefix):
                    i = _raw_id(k)
                    if i is not None:
                        d[kind].add(i)
                    break
            if k.keyword.startswith("SET_"):
                kind = "set_" + k.keyword.split("_")[1].lower()
                i = _raw_id(k)
                if i is not None:
                    d.setdefault(kind, set()).add(i)
    return d


_WHAT = {
    "part": "part",
    "sec": "section",
    "mat": "material",
    "hg": "hourglass control",
    "curve": "curve",
    "vector": "vector",
    "coord": "coordinate system",
    "sdo": "SD orientation",
    "set_node": "node set",
    "set_part": "part set",
    "set_shell": "shell set",
    "set_solid": "solid set",
    "set_beam": "beam set",
    "set_discrete": "discrete set",
    "set_segment": "segment set",
}


def _records(model: Model):
    for g in (
        "parts",
        "sections",
        "materials",
        "hourglasses",
        "curves",
        "vectors",
        "coordinate_systems",
        "transformations",
    ):
        yield from getattr(model, g).values()
    yield from model.sets.values()
    yield from (k for k in model.keywords if isinstance(k, Record))


def head_references(rec: Record):
    """(field, ID) of every positive ID the head cards of ``rec`` name
    (its own ID field excepted)."""
    own = rec.spec.id_field
    for c in rec.spec.layout(rec.options).head:
        for f in c.fields:
            if f.name == own or f.kind != INT or f.ref is None:
                continue
            v = rec.values.get(f.name)
            if isinstance(v, int) and v > 0:
                yield f, v


def check_references(model: Model, problems: Collector, bulk=()) -> None:
    """Report undefined IDs; ``bulk``: the mesh records (element part IDs)."""
    ids = defined_ids(model)
    node_ids = model.nodes.ids
    for rec in _records(model):
        lay = rec.spec.layout(rec.options)
        for f, v in head_references(rec):
            if f.ref == "node":
                if not np.isin(v, node_ids):
                    problems.error(*rec.where(f.name), rec.name, f.name.upper(), f"node {v} is not defined")
            elif f.ref in _WHAT and v not in ids.get(f.ref, set()):
                problems.error(*rec.where(f.name), rec.name, f.name.upper(), f"{_WHAT[f.ref]} {v} is not defined")
        if rec.rows:
            for f in lay.row_fields:
                if f.ref is None or f.kind != INT or f.name not in rec.rows:
                    continue
                col = np.asarray(rec.rows[f.name])
                col = col[col > 0]
                if not len(col):
                    continue
                if f.ref == "node":
                    missing = np.setdiff1d(col, node_ids)
                elif f.ref in _WHAT:
                    missing = np.setdiff1d(col, np.fromiter(ids.get(f.ref, set()), dtype=np.int64))
                else:
                    continue
                if f.ref == "part" and rec.spec.bulk:
                    pass  # element part references are checked below, once per part
                elif len(missing):
                    what = "node" if f.ref == "node" else _WHAT[f.ref]
                    listed = ", ".join(str(int(m)) for m in missing[:10])
                    more = f" and {len(missing) - 10} more" if len(missing) > 10 else ""
                    problems.error(*rec.source, rec.name, f.name.upper(), f"{what} {listed}{more} not defined")
    known_parts = np.fromiter(ids["part"], dtype=np.int64)
    for rec in bulk:
        if "pid" not in (rec.rows or {}) or rec.keyword in ("ELEMENT_MASS",):
            continue
        pid = rec.rows["pid"]
        missing = np.setdiff1d(np.unique(pid), known_parts)
        for p in missing[:20]:
            eid = int(rec.rows["eid"][np.argmax(pid == p)])
            problems.error(
                *rec.source,
                rec.name,
                "PID",
                f"element {eid} (and any other in this block with PID {int(p)}) "
                f"refers to part {int(p)}, which is not defined",
            )
