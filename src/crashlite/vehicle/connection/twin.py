"""The elastic twin: the full model with the structure a cut replaces made elastic.

The simplified vehicle rests on one premise: the structure behind the
interface stays elastic in the crash, so an elastic surrogate may stand in
for it. The twin measures what that premise costs, apart from how well any
surrogate is built: every replaced shell and solid of an elasto-plastic
metal (*MAT_003, *MAT_024) gets a *MAT_ELASTIC of the same density, Young's
modulus and Poisson ratio; mesh, masses, connections, contacts and the kept
structure stay as they are. Run in the same load case:

- full vs twin is the premise's error: no elastic surrogate at that
  interface, however faithful to the elastic rear, comes closer to the full
  model (its inertia and stiffness are the full model's own);
- twin vs simplified is the surrogate's own error.

A part wholly behind the interface takes the elastic material itself; a part
the interface crosses is split: its replaced elements go to a twin part
(same section and hourglass control, ID above the deck's largest) that joins
every part set of the original, so contacts, cross sections and assemblies
over part sets still see them; an *ELEMENT_MASS_PART row of a split part
is shared between the two in proportion to their element mass (as the
keyword spreads it: the mass stays where it was). Other records that name
a split part directly (a contact side of type 3, ...) keep naming only its
kept elements: they are listed in ``ElasticTwin.notes``. Other materials
(rigid, honeycomb, foam, springs) stay as they are, also listed.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field

import numpy as np

from ...keyword.references import head_references
from ...keyword.schema import Record
from ...model.model import Model
from ..car.records import id_list, record
from ..steps.cut import Cut

PLASTIC = ("MAT_PLASTIC_KINEMATIC", "MAT_PIECEWISE_LINEAR_PLASTICITY")
_TABLES = ("shells", "solids")


@dataclass
class ElasticTwin:
    """The twin Model and what changed."""

    model: Model
    elastic_parts: dict = field(default_factory=dict)  # original part ID -> part ID now elastic (same: whole part)
    materials: dict = field(default_factory=dict)  # original material ID -> its *MAT_ELASTIC ID
    elements: int = 0  # replaced elements made elastic
    notes: list = field(default_factory=list)

    def summary(self) -> dict:
        split = {p: q for p, q in self.elastic_parts.items() if p != q}
        return {
            "elements_made_elastic": self.elements,
            "parts_made_elastic": len(self.elastic_parts),
            "parts_split": len(split),
            "elastic_materials": len(self.materials),
            "notes": list(self.notes),
        }


def elastic_twin(cut: Cut) -> ElasticTwin:
    """The full model of ``cut`` with its replaced elasto-plastic elements
    elastic (module docstring); ``cut.model`` is not changed."""
    full = cut.model
    m = copy.copy(full)
    m.parts, m.materials, m.sets = dict(full.parts), dict(full.materials), dict(full.sets)
    twin = ElasticTwin(m)
    next_pid = max(full.parts, default=0) + 1
    next_mid = max(full.materials, default=0) + 1
    untouched: dict = {}
    for table in _TABLES:
        tab = getattr(full, table)
        if not len(tab):
            continue
        tab = copy.deepcopy(tab)
        setattr(m, table, tab)
        replaced = cut.replaced[table]
        for pid in np.unique(tab.pid[replaced]):
            pid = int(pid)
            part = full.parts.get(pid)
            mat = full.materials.get(int(part["mid"])) if part is not None else None
            if mat is None or mat.keyword not in PLASTIC:
                kind = mat.keyword if mat is not None else "no material"
                untouched.setdefault(kind, []).append(pid)
                continue
            mid = int(mat["mid"])
            if mid not in twin.materials:
                twin.materials[mid] = next_mid
                m.materials[next_mid] = record(
                    "MAT_ELASTIC_TITLE",
                    card_title=f"elastic {mat.title or mid}",
                    mid=next_mid,
                    ro=mat["ro"],
                    e=mat["e"],
                    pr=mat["pr"],
                )
                next_mid += 1
            mine = tab.pid == pid
            behind = mine & replaced
            target = pid
            if behind.sum() < mine.sum():  # the interface crosses the part: split it
                target, next_pid = next_pid, next_pid + 1
                tab.pid[behind] = target
            new = Record(part.keyword, part.options, dict(part.values), part.rows, part.title)
            new.values.update(pid=target, mid=twin.materials[mid])
            if target != pid:
                new.values["heading"] = f"{part.get('heading', '') or pid} (elastic twin)"
            m.parts[target] = new
            twin.elastic_parts[pid] = target
            twin.elements += int(behind.sum())
    split = {p: q for p, q in twin.elastic_parts.items() if p != q}
    if split:
        _extend_part_sets(m, full, split)
        _share_part_masses(m, full, split)
        _note_direct_references(m, split, twin.notes)
    for kind, pids in sorted(untouched.items()):
        twin.notes.append(
            f"{len(pids)} replaced part(s) of *{kind} left as they are: "
            f"{', '.join(str(p) for p in sorted(pids)[:10])}{' ...' if len(pids) > 10 else ''}"
        )
    return twin


def _extend_part_sets(m: Model, full: Model, split: dict) -> None:
    """Every part set that holds a split part also holds its twin part
    (rewritten as a _LIST with the same ID, title and head values)."""
    for (kind, sid), rec in full.sets.items():
        if kind != "PART" or "ADD" in rec.options:
            continue  # an _ADD set takes the twins through its member sets
        members = full.set_members(kind, sid)
        extra = [split[int(p)] for p in members if int(p) in split]
        if not extra:
            continue
        head = {k: v for k, v in rec.values.items() if k != "sid"}
        new = id_list(
            "SET_PART_LIST" + ("_TITLE" if rec.title is not None else ""),
            sid,
            np.concatenate([members, extra]),
            title=rec.title,
            **head,
        )
        m.sets[(kind, sid)] = new


def _share_part_masses(m: Model, full: Model, split: dict) -> None:
    """*ELEMENT_MASS_PART rows naming a split part: ADDMASS and FINMASS
    shared between the part and its twin part by their element mass."""
    from ..steps.massprops import element_moments

    recs = [
        r
        for r in full.keywords
        if isinstance(r, Record)
        and r.keyword == "ELEMENT_MASS_PART"
        and "SET" not in r.options
        and np.isin(r.rows["pid"], list(split)).any()
    ]
    if not recs:
        return
    mo = element_moments(full)

    def mass(model, pid):
        return sum(float(x.mass[getattr(model, t).pid == pid].sum()) for t, x in mo.items())

    swap = {}
    for rec in recs:
        rows = {k: [] for k in rec.rows}
        for i, pid in enumerate(rec.rows["pid"]):
            pid = int(pid)
            shares = [(pid, 1.0)]
            if pid in split:
                total = mass(full, pid)
                kept = mass(m, pid) / total if total > 0 else 1.0
                shares = [(pid, kept), (split[pid], 1.0 - kept)]
            for p, f in shares:
                for k, col in rec.rows.items():
                    rows[k].append(p if k == "pid" else col[i] * f if k in ("addmass", "finmass") else col[i])
        swap[id(rec)] = Record(
            rec.keyword,
            rec.options,
            dict(rec.values),
            {k: np.asarray(v, dtype=np.asarray(rec.rows[k]).dtype) for k, v in rows.items()},
            rec.title,
        )
    m.keywords = [swap.get(id(r), r) for r in m.keywords]


def _note_direct_references(m: Model, split: dict, notes: list) -> None:
    """Records that name a split part by its ID (not through a set)."""
    pids = np.array(sorted(split), np.int64)
    for rec in m.keywords:
        if not isinstance(rec, Record) or rec.keyword.startswith("SET_"):
            continue
        named = [int(v) for f, v in head_references(rec) if f.ref == "part" and np.isin(v, pids)]
        if rec.rows and rec.keyword != "ELEMENT_MASS_PART":  # rows of that one are shared already
            for f in rec.spec.layout(rec.options).row_fields:
                if f.ref == "part" and f.name in rec.rows:
                    col = np.asarray(rec.rows[f.name])
                    named += sorted({int(v) for v in col[np.isin(col, pids)]})
        if rec.keyword.startswith("CONTACT_"):
            for side, typ in (("ssid", "sstyp"), ("msid", "mstyp")):
                if int(rec.get(typ, 0) or 0) == 3 and int(rec.get(side, 0) or 0) in split:
                    named.append(int(rec[side]))
        for p in named:
            notes.append(
                f"*{rec.name} names part {p} directly: it keeps the part's kept elements only, not its "
                f"elastic twin part {split[p]}"
            )
