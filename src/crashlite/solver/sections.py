"""Section forces (*DATABASE_CROSS_SECTION_PLANE / _SET) through discrete
elements and beams: the force the cut elements exert on their ends on the
section (SET: the nodes of NSID; PLANE: the ends on the side the normal
points to). Shells and solids join when the solver runs them."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..keyword.errors import Problem
from ..model.model import Model


@dataclass
class Section:
    csid: int
    disc_elems: np.ndarray  # (k,) discrete element indices
    disc_ends: np.ndarray  # (k,) 0: the cut is at n1, 1: at n2
    beam_elems: np.ndarray  # (j,) beam element indices (in the solver's beam set)
    beam_ends: np.ndarray  # (j,)

    def cuts(self):
        """(group kind, element indices, corner indices) of the cut elements."""
        yield "discrete", self.disc_elems, self.disc_ends
        yield "beam", self.beam_elems, self.beam_ends


def _ids(model: Model, kind: str, sid: int) -> np.ndarray:
    return model.set_members(kind, sid) if sid else np.zeros(0, np.int64)


def build_sections(model: Model, beam_ids: np.ndarray, problems: list) -> list[Section]:
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
            on = lambda n: n in nodes  # noqa: E731
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
            bsel = [bpos[int(e)] for e, p in zip(model.beams.ids, model.beams.pid)
                    if int(e) in bpos and p in pids]
            on = lambda n: bool(side[n])  # noqa: E731
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
        out.append(Section(csid, np.array(de, np.int64), np.array(dend, np.int64),
                           np.array(be, np.int64), np.array(bend, np.int64)))
    return out


def section_forces(sections: list[Section], groups, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Force and moment (n_sections, 3) through each section: the sum of the
    cut elements' corner forces ON the section-side nodes, and their moment
    (plus the corner moments of rotational elements) about the centroid of
    those nodes, as LS-DYNA's secforc reports them."""
    by_kind = {g.kind: g for g in groups}
    force = np.zeros((len(sections), 3))
    moment = np.zeros((len(sections), 3))
    cache = {}
    for k, s in enumerate(sections):
        rows, points, moments = [], [], []
        for kind, elems, ends in s.cuts():
            g = by_kind.get(kind)
            if g is None or not len(elems):
                continue
            if kind not in cache:
                cache[kind] = (g.corner_forces(), g.corner_moments())
            cf, cm = cache[kind]
            rows.append(cf[elems, ends])
            points.append(x[g.conn[elems, ends]])
            if cm is not None:
                moments.append(cm[elems, ends])
        if not rows:
            continue
        f, p = np.concatenate(rows), np.concatenate(points)
        force[k] = f.sum(axis=0)
        moment[k] = np.cross(p - p.mean(axis=0), f).sum(axis=0)
        for m in moments:
            moment[k] += m.sum(axis=0)
    return force, moment
