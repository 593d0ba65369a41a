"""Section forces (*DATABASE_CROSS_SECTION_PLANE / _SET) through discrete
elements, beams, shells and solids, as LS-DYNA's secforc reports it: the
internal force of the cut elements at their corners on the section (the
force those nodes exert on the elements), so that a member in tension along
the section normal reports a positive normal force and one in compression a
negative one.

PLANE: an element of the parts of PSID (all parts when 0) is cut when it
has nodes on both sides of the plane through (XCT, YCT, ZCT) with the
normal towards (XCH, YCH, ZCH); its corners on the side the normal points
to are the section's. A finite plane (LENL, LENM > 0, edge L towards
(XHEV, YHEV, ZHEV)) or a RADIUS > 0 keeps the shells and solids whose
centre lies inside it. SET: the elements of the element sets (HSID solids,
BSID beams, SSID shells, DSID discretes) with corners on the nodes of NSID;
those corners are the section's (discretes and beams: the elements with
one end in NSID).

The force is the sum of those corner forces, the moment their moment about
the centroid of the section's nodes plus the corner moments of shells and
beams (secforc's resultant force and moment). The sign is LS-DYNA's R10.1
secforc of a compressed solid (TU Graz's single-element deck, its binout in
tests/parity): -95.47 kN on the loaded face where the element pushes its
nodes with +95.5 kN."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field

import numpy as np

from ..keyword.errors import Problem
from ..model.model import Model
from .groups import ElementGroup


@dataclass
class Section:
    csid: int
    disc_elems: np.ndarray  # (k,) discrete element indices
    disc_ends: np.ndarray  # (k,) 0: the cut is at n1, 1: at n2
    beam_elems: np.ndarray  # (j,) beam element indices (in the solver's beam set)
    beam_ends: np.ndarray  # (j,)
    corners: dict = field(default_factory=dict)  # group kind ("shell", "solid") -> (elements (m,), corners (m,))

    def cuts(self) -> Iterator[tuple[str, np.ndarray, np.ndarray]]:
        """(group kind, element indices, corner indices) of the cut elements."""
        yield "discrete", self.disc_elems, self.disc_ends
        yield "beam", self.beam_elems, self.beam_ends
        for kind, (elems, corners) in self.corners.items():
            yield kind, elems, corners


def _ids(model: Model, kind: str, sid: int) -> np.ndarray:
    return model.set_members(kind, sid) if sid else np.zeros(0, np.int64)


def _continuum_cuts(model: Model, rec, groups, on, pids=None, region=None) -> dict:
    """kind -> (element indices, corner indices) of the shells and solids
    cut: PLANE (``pids`` given): elements of those parts with nodes on both
    sides (``on`` (n,) bool: the section side), corners on the section
    side; SET: elements of the set with corners on the section nodes."""
    out = {}
    sets = {"shell": ("ssid", "SHELL"), "solid": ("hsid", "SOLID")}
    for g in groups:
        kind = getattr(g, "kind", "")
        if kind not in sets or not len(g):
            continue
        conn = np.asarray(g.conn, np.int64)
        valid = conn >= 0
        side = np.where(valid, on[np.maximum(conn, 0)], False)
        if pids is not None:
            other = valid & ~side
            cut = side.any(axis=1) & other.any(axis=1) & np.isin(g.pid, pids)
            if region is not None:
                cut &= region(model.nodes.xyz[np.maximum(conn, 0)].mean(axis=1))
        else:
            fld, set_kind = sets[kind]
            sid = int(rec.get(fld) or 0)
            cut = np.isin(g.ids, _ids(model, set_kind, sid)) & side.any(axis=1)
        e, c = np.nonzero(side & cut[:, None])
        if len(e):
            out[kind] = (e.astype(np.int64), c.astype(np.int64))
    return out


def _region(rec, point: np.ndarray, normal: np.ndarray):
    """Test of element centres against a finite (LENL x LENM) or circular
    (RADIUS) section plane, None for an infinite plane."""
    radius = float(rec.get("radius") or 0.0)
    lenl, lenm = float(rec.get("lenl") or 0.0), float(rec.get("lenm") or 0.0)
    if radius > 0:

        def inside(c):
            d = c - point
            d -= np.outer(d @ normal, normal)
            return np.linalg.norm(d, axis=1) <= radius

        return inside
    if lenl > 0 and lenm > 0:
        edge = np.array([rec.get("xhev", 0.0), rec.get("yhev", 0.0), rec.get("zhev", 0.0)], float) - point
        edge -= (edge @ normal) * normal
        if not np.linalg.norm(edge):
            return None
        el = edge / np.linalg.norm(edge)
        em = np.cross(normal, el)

        def inside(c):
            d = c - point
            a, b = d @ el, d @ em
            return (a >= 0) & (a <= lenl) & (b >= 0) & (b <= lenm)

        return inside
    return None


def build_sections(
    model: Model, beam_ids: np.ndarray, problems: list, groups: Sequence[ElementGroup] = ()
) -> list[Section]:
    """The sections of a deck; ``groups`` the solver's element groups
    (shells and solids are cut through their group's element indices)."""
    out = []
    x = model.nodes.xyz
    d = model.discretes
    for k, rec in enumerate(model.find("DATABASE_CROSS_SECTION")):
        csid = int(rec.get("csid") or k + 1)
        bpos = {int(e): i for i, e in enumerate(beam_ids)}
        if rec.keyword == "DATABASE_CROSS_SECTION_SET":
            nodes = set(model.node_index(_ids(model, "NODE", int(rec.get("nsid") or 0))).tolist())
            dsel = np.flatnonzero(np.isin(d.ids, _ids(model, "DISCRETE", int(rec.get("dsid") or 0))))
            bsel = [bpos[int(e)] for e in _ids(model, "BEAM", int(rec.get("bsid") or 0)) if int(e) in bpos]
            on = lambda n: n in nodes  # noqa: B023, E731
            on_all = np.zeros(len(x), bool)
            on_all[list(nodes)] = True
            corners = _continuum_cuts(model, rec, groups, on_all)
        else:
            point = np.array([rec.get("xct", 0.0), rec.get("yct", 0.0), rec.get("zct", 0.0)], float)
            normal = np.array([rec.get("xch", 0.0), rec.get("ych", 0.0), rec.get("zch", 0.0)], float) - point
            if not np.linalg.norm(normal):
                problems.append(Problem(*rec.where("xch"), rec.name, "XCH", "section normal has zero length"))
                continue
            normal /= np.linalg.norm(normal)
            side = (x - point) @ normal > 0
            psid = int(rec.get("psid") or 0)
            pids = model.set_members("PART", psid) if psid else np.array(sorted(model.parts))
            dsel = np.flatnonzero(np.isin(d.pid, pids))
            bsel = [bpos[int(e)] for e, p in zip(model.beams.ids, model.beams.pid) if int(e) in bpos and p in pids]
            on = lambda n: bool(side[n])  # noqa: B023, E731
            corners = _continuum_cuts(model, rec, groups, side, pids, _region(rec, point, normal))
        de, dend = [], []
        for e in dsel:
            a, b = int(d.nodes[e, 0]), int(d.nodes[e, 1])
            if b >= 0 and on(a) != on(b):  # the element crosses the section
                de.append(e)
                dend.append(0 if on(a) else 1)
        be, bend = [], []
        for i in bsel:
            eid = beam_ids[i]
            row = np.flatnonzero(model.beams.ids == eid)[0]
            a, b = int(model.beams.nodes[row, 0]), int(model.beams.nodes[row, 1])
            if on(a) != on(b):
                be.append(i)
                bend.append(0 if on(a) else 1)
        out.append(
            Section(
                csid,
                np.array(de, np.int64),
                np.array(dend, np.int64),
                np.array(be, np.int64),
                np.array(bend, np.int64),
                corners,
            )
        )
    return out


def section_forces(
    sections: list[Section], groups: Sequence[ElementGroup], x: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Force and moment (n_sections, 3) through each section: minus the sum
    of the cut elements' corner forces on the section-side nodes (the
    elements' internal force there), and its moment (plus the corner moments
    of rotational elements, negated alike) about the centroid of those nodes
    (each counted once), as LS-DYNA's secforc reports them."""
    by_kind = {g.kind: g for g in groups}
    force = np.zeros((len(sections), 3))
    moment = np.zeros((len(sections), 3))
    cache = {}
    for k, s in enumerate(sections):
        rows, points, nodes, moments = [], [], [], []
        for kind, elems, ends in s.cuts():
            g = by_kind.get(kind)
            if g is None or not len(elems):
                continue
            if kind not in cache:
                cache[kind] = (g.corner_forces(), g.corner_moments())
            cf, cm = cache[kind]
            rows.append(cf[elems, ends])
            nodes.append(g.conn[elems, ends])
            points.append(x[nodes[-1]])
            if cm is not None:
                moments.append(cm[elems, ends])
        if not rows:
            continue
        f, p = np.concatenate(rows), np.concatenate(points)
        force[k] = f.sum(axis=0)
        centroid = x[np.unique(np.concatenate(nodes))].mean(axis=0)
        moment[k] = np.cross(p - centroid, f).sum(axis=0)
        for m in moments:
            moment[k] += m.sum(axis=0)
    return -force, -moment
