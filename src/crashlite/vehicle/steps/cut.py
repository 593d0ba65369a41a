"""The interface cut: which structure the simplified vehicle replaces.

``cut_behind`` splits a Model at an interface plane through ``point`` with
the vehicle ``axis`` as normal (the car drives along +axis): an element
whose centroid lies behind the plane, (c − point)·axis < 0, is *replaced*,
the others are *kept*. A rigid part (*MAT_RIGID) goes whole, by the mean
of its element centroids. ``parts`` limits the replaced elements to some
parts.

Nodes:

- *interface* nodes belong to replaced and to kept elements (the cut), or
  are replaced nodes of a rigid group (nodal rigid body, spot weld, rigid
  part) that also holds kept nodes; they stay in the simplified model;
- *removed* nodes belong to replaced elements only (and nodes of no element
  behind the plane, e.g. lumped masses on their own, unless a rigid group
  ties them to kept nodes); their point masses go with the replaced mass.

Rigid groups are what ties nodes together without elements: nodal rigid
bodies, spot welds (*CONSTRAINED_SPOTWELD pairs, *CONSTRAINED_GENERALIZED_
WELD_SPOT sets) and rigid parts (their element nodes and extra nodes,
merged parts joined).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ...model.model import Model

ELEMENT_TABLES = ("shells", "solids", "beams", "discretes")


@dataclass
class RigidGroup:
    """Nodes that move as one rigid body (0-based node indices)."""

    kind: str  # "nodal rigid body", "spot weld", "rigid part"
    name: str
    nodes: np.ndarray  # (k,) int64


@dataclass
class Cut:
    """A Model split at the interface; masks are per element table."""

    model: Model
    point: np.ndarray  # (3,) a point of the interface plane [length]
    axis: np.ndarray  # (3,) unit vehicle axis, the plane normal (driving direction)
    replaced: dict  # table name -> (n_elements,) bool, True: replaced (behind the interface)
    interface_nodes: np.ndarray  # (k,) int64 node indices on the cut
    removed_nodes: np.ndarray  # (n_nodes,) bool: nodes that go with the replaced structure
    groups: list = field(default_factory=list)  # RigidGroup of the model
    notes: list = field(default_factory=list)

    def elements(self, table: str, replaced: bool = True) -> np.ndarray:
        """Indices of the replaced (or kept) elements of a table."""
        m = self.replaced[table]
        return np.flatnonzero(m if replaced else ~m)

    def replaced_nodes(self) -> np.ndarray:
        """(n_nodes,) bool: nodes of replaced elements (interface nodes included)."""
        out = np.zeros(len(self.model.nodes), bool)
        for t in ELEMENT_TABLES:
            conn = getattr(self.model, t).nodes[self.replaced[t]]
            conn = conn[conn >= 0]
            out[conn] = True
        return out

    def replaced_parts(self) -> np.ndarray:
        """Sorted part IDs with at least one replaced element."""
        pids = [getattr(self.model, t).pid[self.replaced[t]] for t in ELEMENT_TABLES]
        return np.unique(np.concatenate(pids)).astype(np.int64)

    def assembly_interface(self, assemblies: dict) -> dict:
        """Assembly name -> interface node indices of its replaced elements
        (``assemblies``: name -> part IDs). A node shared by assemblies goes
        to the first one in order, so no node is in two groups."""
        m = self.model
        taken = np.zeros(len(m.nodes), bool)
        on_cut = np.zeros(len(m.nodes), bool)
        on_cut[self.interface_nodes] = True
        out = {}
        for name, pids in assemblies.items():
            mine = np.zeros(len(m.nodes), bool)
            for t in ELEMENT_TABLES:
                tab = getattr(m, t)
                conn = tab.nodes[self.replaced[t] & np.isin(tab.pid, list(pids))]
                mine[conn[conn >= 0]] = True
            sel = mine & on_cut & ~taken
            taken |= sel
            out[name] = np.flatnonzero(sel)
        return out


def _centroids(model: Model, table: str) -> np.ndarray:
    tab = getattr(model, table)
    conn = tab.nodes[:, :2] if table in ("beams", "discretes") else tab.nodes
    xyz = model.nodes.xyz
    valid = conn >= 0
    s = np.where(valid[..., None], xyz[np.maximum(conn, 0)], 0.0).sum(axis=1)
    return s / np.maximum(valid.sum(axis=1), 1)[:, None]


def rigid_part_ids(model: Model) -> set:
    out = set()
    for pid, part in model.parts.items():
        mat = model.materials.get(part.get("mid"))
        if mat is not None and mat.keyword == "MAT_RIGID":
            out.add(int(pid))
    return out


def _node_set(model: Model, sid: int) -> np.ndarray:
    idx = model.node_index(model.set_members("NODE", int(sid))).astype(np.int64)
    return idx[idx >= 0]


def rigid_groups(model: Model) -> list[RigidGroup]:
    """The nodal rigid bodies, spot welds and rigid parts of a Model."""
    out = []
    for rec in model.find("CONSTRAINED_NODAL_RIGID_BODY"):
        out.append(
            RigidGroup("nodal rigid body", f"nodal rigid body {rec.get('pid')}", _node_set(model, int(rec["nsid"])))
        )
    for rec in model.find("CONSTRAINED_SPOTWELD"):
        ids = model.node_index(np.stack([rec.rows["n1"], rec.rows["n2"]], axis=1)).astype(np.int64)
        wid = rec.rows.get("wid", np.arange(1, len(ids) + 1))
        for w, pair in zip(wid, ids):
            if np.all(pair >= 0):
                out.append(RigidGroup("spot weld", f"spot weld {int(w)}", pair))
    for rec in model.find("CONSTRAINED_GENERALIZED_WELD_SPOT"):
        out.append(
            RigidGroup(
                "spot weld", f"generalized weld {rec.get('wid', '')}".strip(), _node_set(model, int(rec["nsid"]))
            )
        )
    rigid = rigid_part_ids(model)
    lead = {p: p for p in rigid}
    for rec in model.find("CONSTRAINED_RIGID_BODIES"):
        for a, b in zip(rec.rows["pidl"], rec.rows["pidc"]):
            if int(a) in lead and int(b) in lead:
                lead[int(b)] = lead[int(a)]
    nodes: dict = {}
    for t in ELEMENT_TABLES:
        tab = getattr(model, t)
        for p in np.unique(tab.pid):
            if int(p) in lead:
                conn = tab.nodes[tab.pid == p]
                nodes.setdefault(lead[int(p)], []).append(conn[conn >= 0].ravel())
    for rec in model.find("CONSTRAINED_EXTRA_NODES"):
        for i in range(len(rec.rows["pid"])):
            p = int(rec.rows["pid"][i])
            extra = (
                _node_set(model, int(rec.rows["nsid"][i]))
                if "SET" in rec.options
                else model.node_index([rec.rows["nid"][i]]).astype(np.int64)
            )
            if p in lead:
                nodes.setdefault(lead[p], []).append(extra[extra >= 0])
    for p, lists in nodes.items():
        out.append(RigidGroup("rigid part", f"rigid part {p}", np.unique(np.concatenate(lists))))
    return [g for g in out if len(g.nodes)]


def cut_behind(
    model: Model,
    point: ArrayLike | None = None,
    x: float | None = None,
    axis: ArrayLike = (1.0, 0.0, 0.0),
    parts: int | str | Iterable[int | str] | None = None,
) -> Cut:
    """Split ``model`` at the interface plane through ``point`` (or at
    coordinate ``x`` along ``axis`` from the origin) normal to the vehicle
    ``axis``. ``parts``: part IDs or titles that may be replaced (None: all)."""
    a = np.asarray(axis, float).reshape(3)
    if not np.linalg.norm(a) > 0:
        raise ValueError("axis has zero length")
    a = a / np.linalg.norm(a)
    if point is None:
        if x is None:
            raise ValueError("give the interface as a point or as x along the axis")
        point = float(x) * a
    p = np.asarray(point, float).reshape(3)
    allowed = None if parts is None else set(model.part_ids_of(parts).tolist())
    rigid = rigid_part_ids(model)
    replaced = {}
    rigid_sum: dict = {}
    for t in ELEMENT_TABLES:
        tab = getattr(model, t)
        behind = (_centroids(model, t) - p) @ a < 0.0 if len(tab) else np.zeros(0, bool)
        if allowed is not None:
            behind &= np.isin(tab.pid, list(allowed))
        replaced[t] = behind
        for pid in set(np.unique(tab.pid).tolist()) & rigid:
            sel = tab.pid == pid
            s = rigid_sum.setdefault(pid, [0.0, 0])
            s[0] += float(((_centroids(model, t)[sel] - p) @ a).sum())
            s[1] += int(sel.sum())
    notes = []
    for pid, (s, k) in rigid_sum.items():
        whole = s / k < 0.0 and (allowed is None or pid in allowed)
        for t in ELEMENT_TABLES:
            tab = getattr(model, t)
            sel = tab.pid == pid
            if sel.any() and (replaced[t][sel].any() != whole or replaced[t][sel].all() != whole):
                notes.append(
                    f"rigid part {pid} lies across the interface: taken whole as {'replaced' if whole else 'kept'}"
                )
            replaced[t][sel] = whole
    n = len(model.nodes)
    on_rep, on_kept = np.zeros(n, bool), np.zeros(n, bool)
    for t in ELEMENT_TABLES:
        conn = getattr(model, t).nodes
        for mask, flag in ((replaced[t], on_rep), (~replaced[t], on_kept)):
            c = conn[mask]
            flag[c[c >= 0]] = True
    orphan = ~on_rep & ~on_kept
    behind_node = (model.nodes.xyz - p) @ a < 0.0
    removed = (on_rep & ~on_kept) | (orphan & behind_node)
    kept_side = ~removed
    interface = on_rep & on_kept
    groups = rigid_groups(model)
    for g in groups:
        r = removed[g.nodes]
        if r.any() and kept_side[g.nodes].any():
            interface[g.nodes[r & on_rep[g.nodes]]] = True
            removed[g.nodes[r]] = False  # tied to the kept structure: they stay
            if not (r & on_rep[g.nodes]).any():
                continue
            notes.append(f"{g.name} ties replaced and kept nodes: its replaced nodes join the interface")
    return Cut(model, p, a, replaced, np.flatnonzero(interface).astype(np.int64), removed, groups, notes)
