"""What ``crashlite info`` shows: counts, parts with mass and CoG, totals."""

from __future__ import annotations

from collections import Counter

import numpy as np

from ..keyword.schema import RawKeyword, Record
from .model import ENTITY_GROUPS, MESH_TABLES, Model

_ELEMENT_TABLES = ("shells", "solids", "beams", "discretes", "masses", "inertias")


def keyword_counts(model: Model) -> dict[str, int]:
    """Instances per keyword (mesh keywords count their rows)."""
    c: Counter = Counter()
    c["NODE"] = len(model.nodes)
    for t, kw in zip(
        _ELEMENT_TABLES,
        ("ELEMENT_SHELL", "ELEMENT_SOLID", "ELEMENT_BEAM", "ELEMENT_DISCRETE", "ELEMENT_MASS", "ELEMENT_INERTIA"),
    ):
        c[kw] += len(getattr(model, t))
    for g in ENTITY_GROUPS:
        for r in getattr(model, g).values():
            c[r.keyword] += 1
    for r in model.sets.values():
        c[r.keyword] += 1
    for k in model.keywords:
        if isinstance(k, RawKeyword):
            c[k.keyword + " (verbatim)"] += 1
        elif isinstance(k, Record):
            c[k.keyword] += 1
    return {k: v for k, v in sorted(c.items()) if v}


def summary(model: Model, placed: Model | None = None) -> dict:
    """Everything ``crashlite info`` prints, as JSON-ready data; masses,
    centres of gravity and the bounding box from ``placed`` when given (the
    Model with its *PART_MOVE cards applied, as the run sets it up)."""
    geo = model if placed is None else placed
    parts = []
    for pid, rec in sorted(model.parts.items()):
        n_el = {
            t: int(np.count_nonzero(getattr(model, t).pid == pid)) for t in ("shells", "solids", "beams", "discretes")
        }
        mp = geo.mass_properties([pid])
        parts.append(
            {
                "id": pid,
                "title": rec.get("heading", ""),
                "secid": rec.get("secid"),
                "mid": rec.get("mid"),
                "elements": {k: v for k, v in n_el.items() if v},
                "mass": mp.mass,
                "cog": mp.cog.tolist(),
            }
        )
    total = geo.mass_properties()
    xyz = geo.nodes.xyz
    bbox = [xyz.min(0).tolist(), xyz.max(0).tolist()] if len(xyz) else None
    return {
        "deck": model.source,
        "title": model.title,
        "files": model.files,
        "units": model.unit_system(),
        "counts": {t: len(getattr(model, t)) for t in MESH_TABLES},
        "keywords": keyword_counts(model),
        "parts": parts,
        "total": {"mass": total.mass, "cog": total.cog.tolist(), "inertia": total.inertia.tolist()},
        "bounding_box": bbox,
        "parameters": {p.name: p.value for p in model.parameters},
        "warnings": [str(w) for w in model.warnings],
    }


def _v(x) -> str:
    return "(" + ", ".join(f"{c:.6g}" for c in x) + ")"


def format_summary(s: dict) -> str:
    out = [f"deck      {s['deck']}"]
    if s["title"]:
        out.append(f"title     {s['title']}")
    if len(s["files"]) > 1:
        out.append(f"files     {len(s['files'])} ({', '.join(s['files'][1:])} included)")
    out.append(f"units     {s['units']} (guessed from densities)")
    if s["bounding_box"]:
        lo, hi = s["bounding_box"]
        out.append(f"bounds    {_v(lo)} .. {_v(hi)}")
    t = s["total"]
    out.append(f"mass      {t['mass']:.6g} at CoG {_v(t['cog'])}")
    out.append("")
    out.append("keywords")
    for k, v in s["keywords"].items():
        out.append(f"  {k:<44} {v:>10}")
    out.append("")
    out.append(f"parts ({len(s['parts'])})")
    out.append(f"  {'id':>8}  {'title':<28} {'elements':>9} {'mass':>12}  cog")
    for p in s["parts"]:
        out.append(
            f"  {p['id']:>8}  {str(p['title'])[:28]:<28} {sum(p['elements'].values()):>9} "
            f"{p['mass']:>12.5g}  {_v(p['cog'])}"
        )
    if s["parameters"]:
        out.append("")
        out.append("parameters  " + ", ".join(f"{k}={v}" for k, v in s["parameters"].items()))
    if s["warnings"]:
        out.append("")
        out.append(f"warnings ({len(s['warnings'])})")
        out += [f"  {w}" for w in s["warnings"]]
    return "\n".join(out)
