"""The kept structure of a ``Cut`` as a Model of its own (step 4's start).

``truncate`` deletes the replaced elements and the nodes that go with them
(``Cut.removed_nodes``) and mends every reference the deck made to them,
so the truncated deck reads back without a dangling ID and runs in
LS-DYNA and crashlite:

- elements, point masses and inertias on removed nodes go (their mass is
  the replaced mass of step 2); parts left without elements go, unless a
  kept point mass names them;
- node, part and element sets lose the removed members (rewritten as a
  _LIST with the same ID, title and head values when some went); a set left
  empty goes;
- a row of a row keyword (spot weld pair, history node, SPC node, ...) that
  names a removed node, part or element goes; a keyword whose head names a
  removed node, part or set goes, and so does a contact whose slave or
  master side is gone; a nodal rigid body left with fewer than two nodes
  goes;
- ``keep`` names removed nodes to keep anyway (massless, e.g. history
  nodes the surrogate moves with its rear body).

Everything dropped is listed in ``Truncated.notes``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ...keyword.references import head_references
from ...keyword.schema import INT, Record
from ...model.model import Model
from ..car.records import id_list
from .cut import ELEMENT_TABLES, Cut

_MEMBER_REF = {
    "NODE": "node",
    "PART": "part",
    "SHELL": "shell",
    "SOLID": "solid",
    "BEAM": "beam",
    "DISCRETE": "discrete",
}
_TABLE_OF = {"SHELL": "shells", "SOLID": "solids", "BEAM": "beams", "DISCRETE": "discretes"}
# contact side types (LS-DYNA SSTYP/MSTYP) -> what the ID names
_CONTACT_SIDE = {0: "set_segment", 1: "set_shell", 2: "set_part", 3: "part", 4: "set_node", 6: "set_part"}


@dataclass
class Truncated:
    """The truncated Model and how its nodes map to the full one."""

    model: Model
    node_map: np.ndarray  # (n_full_nodes,) int64 new node index of each full-model node, -1: deleted
    kept_parts: np.ndarray  # (k,) int64 part IDs left
    dropped_parts: np.ndarray  # (j,) int64 part IDs deleted
    notes: list = field(default_factory=list)


def _elements_kept(cut: Cut) -> dict:
    return {t: ~cut.replaced[t] for t in ELEMENT_TABLES}


def truncate(cut: Cut, keep: ArrayLike | None = None) -> Truncated:
    """The kept structure of ``cut`` (module docstring). ``keep``: node
    indices of the full model to keep although the cut removes them."""
    full = cut.model
    notes: list = []
    keep_el = _elements_kept(cut)
    alive = ~cut.removed_nodes.copy()
    b = full.beams
    if len(b):  # orientation nodes of kept beams stay
        k3 = b.nodes[keep_el["beams"], 2]
        alive[k3[k3 >= 0]] = True
    if keep is not None:
        alive[np.asarray(keep, np.int64)] = True
    node_map = np.full(len(full.nodes), -1, np.int64)
    node_map[alive] = np.arange(int(alive.sum()))
    m = Model()
    m.nodes = full.nodes.take(alive)
    for t in ELEMENT_TABLES:
        tab = getattr(full, t).take(keep_el[t])
        conn = tab.nodes
        tab.nodes = np.where(conn >= 0, node_map[np.maximum(conn, 0)], -1).astype(conn.dtype)
        setattr(m, t, tab)
    for t in ("masses", "inertias"):  # point masses of removed nodes are replaced mass, also on kept ones
        tab = getattr(full, t)
        sel = ~cut.removed_nodes[tab.node] if len(tab) else np.zeros(0, bool)
        tab = tab.take(sel)
        tab.node = node_map[tab.node].astype(tab.node.dtype)
        setattr(m, t, tab)
    used = set()
    for t in ELEMENT_TABLES:
        used |= set(np.unique(getattr(m, t).pid).tolist())
    used |= set(np.unique(m.masses.pid[m.masses.pid > 0]).tolist())
    kept_parts = np.array(sorted(p for p in full.parts if p in used), np.int64)
    dropped = np.array(sorted(p for p in full.parts if p not in used), np.int64)
    m.parts = {int(p): full.parts[int(p)] for p in kept_parts}
    for g in ("sections", "materials", "hourglasses", "curves", "vectors", "coordinate_systems", "transformations"):
        setattr(m, g, dict(getattr(full, g)))
    alive_ids = {
        "node": m.nodes.ids,
        "part": kept_parts,
        **{_MEMBER_REF[k]: getattr(m, t).ids for k, t in _TABLE_OF.items()},
    }
    m.sets, gone_sets = _prune_sets(full, alive_ids, notes)
    if len(dropped):
        notes.append(f"{len(dropped)} part(s) left without elements deleted")
    gone = {"node": np.setdiff1d(full.nodes.ids, m.nodes.ids), "part": dropped, **gone_sets}
    for t, ref in (("shells", "shell"), ("solids", "solid"), ("beams", "beam"), ("discretes", "discrete")):
        gone[ref] = getattr(full, t).ids[~keep_el[t]]
    m.keywords = []
    for rec in full.keywords:
        kept = _prune_record(rec, gone, m, notes)
        if kept is not None:
            m.keywords.append(kept)
    m.parameters = list(full.parameters)
    m.source = None
    return Truncated(m, node_map, kept_parts, dropped, notes)


def _prune_sets(full: Model, alive: dict, notes: list) -> tuple[dict, dict]:
    """Sets with the deleted members taken out; the IDs of sets left empty by kind."""
    out, gone = {}, {}
    for (kind, sid), rec in full.sets.items():
        ref = _MEMBER_REF.get(kind)
        if ref is None:
            if kind == "SEGMENT":
                seg = full.set_members(kind, sid)
                ok = ((seg <= 0) | np.isin(seg, alive["node"])).all(axis=1)
                if ok.all():
                    out[(kind, sid)] = rec
                elif ok.any():
                    rows = {k: np.asarray(v)[ok] for k, v in rec.rows.items()}
                    out[(kind, sid)] = Record(rec.keyword, rec.options, dict(rec.values), rows, rec.title)
                else:
                    gone.setdefault("set_segment", []).append(sid)
                continue
            out[(kind, sid)] = rec
            continue
        members = full.set_members(kind, sid)
        left = members[np.isin(members, alive[ref])]
        if len(left) == len(members):
            out[(kind, sid)] = rec
        elif len(left):
            head = {k: v for k, v in rec.values.items() if k != "sid"}
            out[(kind, sid)] = id_list(
                f"SET_{kind}_LIST" + ("_TITLE" if rec.title is not None else ""), sid, left, title=rec.title, **head
            )
        else:
            gone.setdefault(f"set_{kind.lower()}", []).append(sid)
            notes.append(f"*SET_{kind} {sid}{_title(rec)} is empty without the replaced structure: deleted")
    return out, {k: np.array(v, np.int64) for k, v in gone.items()}


def _title(rec) -> str:
    t = str(rec.title or rec.get("title", "") or rec.get("heading", "") or "").strip()
    return f" ({t})" if t else ""


def _prune_record(rec, gone: dict, m: Model, notes: list):
    """``rec`` with rows naming deleted entities taken out, or None when
    its head names one (or nothing is left)."""
    if not isinstance(rec, Record):
        return rec
    lay = rec.spec.layout(rec.options)
    for f, v in head_references(rec):
        if f.ref in gone and np.isin(v, gone[f.ref]):
            notes.append(
                f"*{rec.name}{_title(rec)} names deleted {f.ref.replace('_', ' ')} {v} ({f.name.upper()}): deleted"
            )
            return None
    if rec.keyword.startswith("CONTACT_"):
        for side, typ in (("ssid", "sstyp"), ("msid", "mstyp")):
            kind = _CONTACT_SIDE.get(int(rec.get(typ, 0) or 0))
            v = int(rec.get(side, 0) or 0)
            if kind and v > 0 and kind in gone and np.isin(v, gone[kind]):
                notes.append(f"*{rec.name}{_title(rec)}: its {side.upper()} {v} is deleted: contact deleted")
                return None
    if rec.rows:
        ok = np.ones(len(next(iter(rec.rows.values()))), bool)
        for f in lay.row_fields:
            if f.ref is None or f.kind != INT or f.name not in rec.rows:
                continue
            col = np.asarray(rec.rows[f.name])
            if f.ref in gone and len(gone[f.ref]):
                ok &= ~((col > 0) & np.isin(col, gone[f.ref]))
        if not ok.all():
            if not ok.any():
                notes.append(f"*{rec.name}{_title(rec)}: every row names deleted structure: deleted")
                return None
            notes.append(f"*{rec.name}{_title(rec)}: {int((~ok).sum())} row(s) naming deleted structure deleted")
            rows = {k: np.asarray(v)[ok] for k, v in rec.rows.items()}
            rec = Record(rec.keyword, rec.options, dict(rec.values), rows, rec.title)
    if rec.keyword == "CONSTRAINED_NODAL_RIGID_BODY":
        sid = int(rec["nsid"])
        if ("NODE", sid) not in m.sets or len(m.set_members("NODE", sid)) < 2:
            notes.append(f"*{rec.name} {rec.get('pid')}: fewer than two nodes left: deleted")
            return None
    return rec
