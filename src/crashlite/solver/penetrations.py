"""Initial penetrations of the contacts, removed before the first cycle as
LS-DYNA does by default (*CONTACT_AUTOMATIC_... and *CONTROL_CONTACT
IGNORE = 0: "move nodes to eliminate initial penetrations"), or tracked
(IGNORE = 1, 2: only the penetration beyond the initial one pushes, and
the tracked value shrinks as the node moves out, kernels.contact).

A slave node that starts inside the contact thickness of a segment would
be pushed out by a penalty spring that nothing compressed: the contact
would give back energy it never stored (negative sliding energy). Each such
node is moved out along the contact normal by its penetration, before any
element sees it (the elements' formulations are incremental, so the moved
geometry is the initial one), and reported. Nodes that cannot move (held
in all three translations, on rigid bodies, driven by a prescribed motion)
stay, and are reported as such. Where the segment's nodes move out of the
node's way in the same pass (two shells overlapping each other in a single
surface), each side moves half the penetration; a few passes take care of
what a first move leaves or causes.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..keyword.errors import Problem
    from .contact import ContactGroup

MAX_PASSES = 12


@dataclass(frozen=True)
class Moved:
    cid: int  # contact interface ID
    node: int  # node index
    depth: float  # initial penetration [length]
    moved: bool  # moved out (False: held, rigid or driven, or tracked)
    tracked: bool = False  # IGNORE 1, 2: kept and tracked


def remove_initial_penetrations(contacts: list[ContactGroup], x: np.ndarray, movable: np.ndarray) -> list[Moved]:
    """Move the penetrating slave nodes of ``contacts`` (ContactGroup, active
    at t = 0) out of their segments in ``x`` (n, 3), in place; ``movable``
    (n,) bool. Contacts with IGNORE 1 or 2 keep them: their groups' offsets
    track them instead. Returns one Moved per node and interface (the
    deepest penetration it had there)."""
    found: dict[tuple[int, int], Moved] = {}
    active = [g for g in contacts if g.c.birth <= 0.0 and not g.c.ignore]
    for _ in range(MAX_PASSES):
        depth = np.zeros(len(x))
        shift = np.zeros_like(x)
        hits = []
        for g in active:
            normal, gap, seg = g.penetrations(x)
            for i in np.flatnonzero(gap > 0.0):
                node = int(g.c.snode[i])
                prev = found.get((g.cid, node))
                ok = bool(movable[node])
                found[(g.cid, node)] = Moved(g.cid, node, max(float(gap[i]), prev.depth if prev else 0.0), ok)
                if ok and gap[i] > depth[node]:  # the deepest of the node's penetrations this pass
                    depth[node] = gap[i]
                    hits.append((node, gap[i] * normal[i], seg[i]))
        if not hits:
            break
        for node, d, seg in hits:
            if depth[node] * (1.0 - 1e-12) <= np.linalg.norm(d):  # the node's deepest
                others = seg[seg >= 0]
                shift[node] = d * (0.5 if (depth[others] > 0).any() else 1.0)
        x += shift * (1.0 + 1e-9)  # just clear of the contact thickness
    for g in contacts:  # IGNORE 1, 2: the initial penetrations stay (where the moves left them), tracked
        if g.c.birth <= 0.0 and g.c.ignore:
            g.offset[:] = g.penetrations(x)[1]
            for i in np.flatnonzero(g.offset > 0.0):
                found[(g.cid, int(g.c.snode[i]))] = Moved(g.cid, int(g.c.snode[i]), float(g.offset[i]), False, True)
    return list(found.values())


def report(moved: list[Moved], names: dict[int, str], node_ids: np.ndarray, source: str) -> list[Problem]:
    """One warning (keyword.errors.Problem) per interface with initial
    penetrations: how many nodes were moved, the deepest, those that could not."""
    from ..keyword.errors import Problem

    out = []
    for cid in sorted({m.cid for m in moved}):
        mine = [m for m in moved if m.cid == cid]
        kept = [m for m in mine if m.tracked]
        if kept:
            deep = max(kept, key=lambda m: m.depth)
            out.append(
                Problem(
                    source,
                    0,
                    names.get(cid, "CONTACT"),
                    None,
                    f"contact {cid}: {len(kept)} slave node(s) start inside the contact thickness; "
                    f"IGNORE keeps and tracks their penetration (deepest {deep.depth:.4g} at node "
                    f"{int(node_ids[deep.node])}); every node in initial_penetrations.csv",
                )
            )
            continue
        done = [m for m in mine if m.moved]
        stuck = [m for m in mine if not m.moved]
        text = f"contact {cid}: {len(done)} slave node(s) started inside the contact thickness and were moved out"
        if done:
            deep = max(done, key=lambda m: m.depth)
            text += f" (deepest {deep.depth:.4g} at node {int(node_ids[deep.node])})"
        if stuck:
            text += (
                f"; {len(stuck)} could not move (held, rigid or driven): "
                + ", ".join(str(int(node_ids[m.node])) for m in stuck[:10])
                + (" ..." if len(stuck) > 10 else "")
                + " — their contact pushes them out and creates energy"
            )
        text += "; every node in initial_penetrations.csv"
        out.append(Problem(source, 0, names.get(cid, "CONTACT"), None, text))
    return out


def write_csv(path: Path, moved: list[Moved], node_ids: np.ndarray) -> None:
    """contact, node ID, initial penetration, moved out (1) or not (0), tracked (1: IGNORE 1, 2)."""
    lines = ["contact,node,depth,moved,tracked"]
    lines += [
        f"{m.cid},{int(node_ids[m.node])},{m.depth:.6g},{int(m.moved)},{int(m.tracked)}"
        for m in sorted(moved, key=lambda m: (m.cid, int(node_ids[m.node])))
    ]
    path.write_text("\n".join(lines) + "\n")
