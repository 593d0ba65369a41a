"""Cards that give nodes a negative or no mass, named where they are: a
negative *ELEMENT_MASS, a shell thickness <= 0, a beam area <= 0, an inverted
solid. Checked before the elements are built, so a run is refused naming the
card, not a node left without mass.
"""

from __future__ import annotations

import numpy as np

from ..keyword.errors import Problem
from ..model.model import Model
from .records import row_line


def massless_cards(model: Model, rigid: np.ndarray) -> list[Problem]:
    """Cards that give nodes a negative or no mass, named where they are
    (negative *ELEMENT_MASS, shell thickness <= 0, beam area <= 0, an
    inverted solid); checked before the elements are built, so the run is
    refused naming the card, not a node left without mass."""
    out: list[Problem] = []
    str(model.source or "")
    m = model.masses
    for i in np.flatnonzero(m.mass < 0)[:10]:
        eid, nid = int(m.ids[i]), int(model.nodes.ids[m.node[i]]) if m.node[i] >= 0 else -1
        out.append(
            Problem(
                *row_line(model, "ELEMENT_MASS", eid),
                "ELEMENT_MASS",
                "MASS",
                f"element {eid} on node {nid} has mass {float(m.mass[i]):g} < 0: a mass must be >= 0",
            )
        )
    sh = model.shells
    for p in np.unique(sh.pid[~np.isin(sh.pid, rigid)]):
        part = model.parts.get(int(p))
        sec = model.sections.get(part.get("secid")) if part is not None else None
        if sec is None or sec.keyword != "SECTION_SHELL":
            continue  # the shell builder names it
        t1 = float(sec.get("t1", 0.0) or 0.0)
        t = np.array([float(sec.get(f"t{k}", 0.0) or 0.0) for k in range(1, 5)])
        t = np.where(t > 0, t, t1)
        rows = np.flatnonzero(sh.pid == p)
        given = sh.thickness[rows]
        tn = np.where(np.isfinite(given) & (given > 0), given, t)
        bad = rows[tn.mean(axis=1) <= 0]
        if len(bad):
            ids = ", ".join(str(int(e)) for e in sh.ids[bad[:5]]) + (", ..." if len(bad) > 5 else "")
            out.append(
                Problem(
                    *sec.where("t1"),
                    sec.name,
                    "T1",
                    f"section {sec.get('secid')} (part {int(p)}): shell thickness T1 = {t1:g} <= 0 and "
                    f"{len(bad)} shell(s) give none of their own ({ids}): a shell needs a thickness > 0",
                )
            )
    bm = model.beams
    for p in np.unique(bm.pid[~np.isin(bm.pid, rigid)]):
        part = model.parts.get(int(p))
        sec = model.sections.get(part.get("secid")) if part is not None else None
        if sec is None or sec.keyword != "SECTION_BEAM" or int(sec.get("elform", 1) or 1) in (3, 6, 9):
            continue  # the beam builder names it; trusses of ELFORM 3, discrete beams: not here
        from ..model.properties import section_area

        a = section_area(sec)
        if not a > 0:
            given = int(sec.get("elform", 1) or 1) in (2, 12, 13) or sec.get("ts1") is None
            fld = "A" if given else "TS1"
            n = int((bm.pid == p).sum())
            out.append(
                Problem(
                    *sec.where(fld.lower()),
                    sec.name,
                    fld,
                    f"section {sec.get('secid')} (part {int(p)}, {n} beam(s)): cross-section area "
                    f"{a:g} <= 0: a beam needs an area > 0" + ("" if given else " (from TS1, TT1 and CST)"),
                )
            )
    so = model.solids
    deformable = np.flatnonzero(~np.isin(so.pid, rigid) & np.all(so.nodes[:, :4] >= 0, axis=1))
    if len(deformable):
        from .kernels.solid import N_CHUNKS, N_WORK, solid_volumes

        conn = so.nodes[deformable].astype(np.int64)
        conn = np.where(conn >= 0, conn, conn[:, 3:4])  # unset N5-N8: a tetrahedron's repeated N4
        vol = np.empty(len(conn))
        solid_volumes(model.nodes.xyz.astype(float), conn, np.zeros((N_CHUNKS, N_WORK)), vol)
        for i in np.flatnonzero(vol <= 0)[:10]:
            eid = int(so.ids[deformable[i]])
            out.append(
                Problem(
                    *row_line(model, "ELEMENT_SOLID", eid),
                    "ELEMENT_SOLID",
                    "N1",
                    f"solid {eid} has volume {vol[i]:.4g} <= 0: its nodes N1-N4 and N5-N8 are "
                    "in inverted order (or the element is flat)",
                )
            )
    return out
