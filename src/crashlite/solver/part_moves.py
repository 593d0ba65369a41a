"""*PART_MOVE: parts placed by a translation before the run is set up.

LS-DYNA moves the nodes of a part's elements by (XMOV, YMOV, ZMOV), given in
the system CID when it is not 0, as the deck is read: element geometry,
contacts, rigid bodies and mass properties all see the moved coordinates.
``moved_model`` does the same on a copy of the Model (the deck's Model keeps
its coordinates and its *PART_MOVE cards, so writing it back gives the deck
as it was).

Each card moves every node of its part (IFSET 1: of the parts of its part
set) once. A node that a part not moved shares with it moves too (it is a
node of the moved part's elements, as in LS-DYNA), which stretches the other
part's elements there: the run says so with one warning per card. Two cards
naming the same node move it twice: the moves are increments.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..model.model import Model
from .frames import axes
from .records import _problem
from .rigid_parts import _elements_nodes


def _parts_of(model: Model, rec, ident: int, ifset: int, problems: list) -> list[int] | None:
    """The parts a row moves, or None (a Problem added)."""
    if ifset == 1:
        try:
            pids = [int(p) for p in model.set_members("PART", ident)]
        except KeyError:
            problems.append(_problem(rec, "pid", f"part set {ident} is not defined (IFSET = 1)"))
            return None
        missing = [p for p in pids if p not in model.parts]
        if missing:
            problems.append(_problem(rec, "pid", f"part set {ident} names undefined part(s) {missing[:10]}"))
            return None
        return pids
    if ifset != 0:
        problems.append(_problem(rec, "ifset", f"IFSET = {ifset}: 0 (part) or 1 (part set) expected"))
        return None
    if ident not in model.parts:
        problems.append(_problem(rec, "pid", f"part {ident} is not defined"))
        return None
    return [ident]


def moved_model(model: Model, problems: list, warnings: list | None = None) -> Model:
    """The Model with every *PART_MOVE applied to its node coordinates and
    the cards themselves taken out (so applying it again changes nothing);
    the Model itself when it has none. Cards that cannot be applied add a
    Problem to ``problems``; nodes shared with parts not moved, a warning."""
    cards = model.find("PART_MOVE")
    if not cards:
        return model
    xyz = model.nodes.xyz.astype(float, copy=True)
    for rec in cards:
        rows = rec.rows or {}
        for k in range(len(rows.get("pid", []))):
            pids = _parts_of(model, rec, int(rows["pid"][k]), int(rows["ifset"][k]), problems)
            if pids is None:
                continue
            d = np.array([rows["xmov"][k], rows["ymov"][k], rows["zmov"][k]], float)
            cid = int(rows["cid"][k])
            if cid:
                try:
                    d = axes(model, cid).T @ d  # local components -> global
                except (KeyError, ValueError) as e:
                    problems.append(_problem(rec, "cid", str(e).strip("'\"")))
                    continue
            nodes = _elements_nodes(model, pids)
            if not len(nodes):
                problems.append(_problem(rec, "pid", f"part(s) {pids} have no elements: there is nothing to move"))
                continue
            xyz[nodes] += d
            moved = set(pids)
            others = [p for p in model.parts if p not in moved]
            shared = np.intersect1d(nodes, _elements_nodes(model, others)) if others else []
            if len(shared) and warnings is not None:
                ids = ", ".join(str(int(i)) for i in model.nodes.ids[shared[:5]])
                warnings.append(
                    _problem(
                        rec,
                        "pid",
                        f"{len(shared)} node(s) of part(s) {pids} (e.g. {ids}) are shared with parts not moved: "
                        "they move with the part, as in LS-DYNA, and stretch the other parts' elements there",
                    )
                )
    done = {id(rec) for rec in cards}
    keywords = [k for k in model.keywords if id(k) not in done]
    return replace(model, nodes=replace(model.nodes, xyz=xyz), keywords=keywords)
