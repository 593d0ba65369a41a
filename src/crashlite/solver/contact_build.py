"""Penalty contact from the Model: *CONTACT_AUTOMATIC_SINGLE_SURFACE,
_NODES_TO_SURFACE and _SURFACE_TO_SURFACE as time-loop groups
(contact.ContactGroup), one per interface.

Segments are the shells of the surface's parts (both sides) and the exterior faces
of their solids (faces used by one element of the surface, outward normals,
zero thickness); where solids may be deleted (*CONTROL_TIMESTEP ERODE = 1, a
material failure strain) also every inner face, once for each of its two
solids, that is surface once the solid across it is gone (as LS-DYNA's
eroding contacts do: the honeycomb behind a deleted element still bears).
Slave entries are nodes facing segments:

- single surface: every surface node against every segment not holding it;
- nodes to surface: the slave nodes (node set or the parts' element nodes)
  against the master segments;
- surface to surface: both passes, slave nodes against master segments and
  master nodes against slave segments (symmetric treatment).

Shell contact thickness (LS-DYNA's order): the shell thickness scaled by
the part's SFT (*PART_CONTACT) where given, else by SFST/SFMT, at most 40 %
of the shortest edge in single-surface contact unless SSTHK = 1; replaced
by SST/MST where given, and by the part's OPTT over both (the 40 % limit
then does not apply). Rigid parts are surface like any other part: a
single surface with SSID 0 takes every part, rigid solids by their
exterior faces.

Penalty stiffness (LS-DYNA, SOFT = 0): k = SLSFAC·SF·K·A/min(diagonal)
for shells, SLSFAC·SF·K·A²/V for solid faces (K the bulk modulus
E/(3(1−2ν)) of the segment's material, SF = SFS for slave, SFM for master
segments), and for a pair the smaller of the segment's and the slave node's
(the largest of its own segments; none for nodes without segments); the
slave side's segments also scaled by their part's SSF (*PART_CONTACT, "the
default slave penalty stiffness"; in a single surface every segment is
slave). SOFT = 1 and friction: see ``contact``; FS = −1 takes FS FD DC VC
of the interface's parts (*PART_CONTACT, 0 for a part without it), run
where they are the same for every part of the interface. Options that would change the physics and are
not run are refused with a Problem naming the field.
"""

from __future__ import annotations

from collections.abc import Sequence
from types import SimpleNamespace

import numpy as np
from numpy.typing import ArrayLike

from ..keyword.errors import Problem
from ..keyword.schema import Record
from ..model.contacts import interface_numbers
from ..model.model import Model
from .contact import BSORT_DEFAULT, ContactGroup, Interface, Surface, concat
from .groups import ElementGroup
from .kernels.solid import N_CHUNKS, N_WORK, solid_volumes

KINDS = (
    "CONTACT_AUTOMATIC_SINGLE_SURFACE",
    "CONTACT_AUTOMATIC_NODES_TO_SURFACE",
    "CONTACT_AUTOMATIC_SURFACE_TO_SURFACE",
)

# fields whose non-default values are not run: field -> (accepted values, what it does)
_FIXED = {
    "sboxid": ((0,), "box-limited slave surface"),
    "mboxid": ((0,), "box-limited master surface"),
    "vc": ((0.0,), "viscous friction limit VC"),
    "penchk": ((0,), "penetration check"),
    "lcidab": ((0,), "airbag thickness curve (SOFT = 2)"),
    "frcfrq": ((0, 1), "friction every FRCFRQ cycles"),
    "penmax": ((0.0,), "release of deeply penetrated nodes"),
    "thkopt": ((0,), "thickness option"),
    "isym": ((0,), "symmetry planes"),
    "i2d3d": ((0,), "2D/3D segment priority"),
    "sldthk": ((0.0,), "solid contact thickness"),
    "sldstf": ((0.0,), "solid contact stiffness"),
    "dprfac": ((0.0,), "depth of penetration reduction"),
    "cid_rcf": ((0,), "rcforc in a local system"),
    "q2tri": ((0,), "quad splitting"),
    "dtpchk": ((0.0,), "penetration time step check"),
    "sfnbr": ((0.0,), "neighbour segment scale"),
    "fnlscl": ((0.0,), "non-linear penalty"),
    "dnlscl": ((0.0,), "non-linear penalty depth"),
    "tcso": ((0,), "segment-orientation option"),
    "tiedid": ((0,), "tied incremental displacement"),
    "shledg": ((0,), "shell edge treatment"),
    "sharec": ((0,), "shared edge constraint"),
    "cparm8": ((0,), "spot weld exclusion"),
    "ipback": ((0,), "backup penalty"),
    "srnde": ((0,), "non-extended rounded edges"),
    "fricsf": ((1.0,), "friction scale on the tangent"),
    "icor": ((0,), "coefficient of restitution"),
    "ftorq": ((0,), "friction torque"),
    "region": ((0,), "contact region"),
    "pstiff": ((0,), "stiffness from the master segment only"),
    "ignroff": ((0,), "ignore thickness offsets"),
    "twodbinr": ((0,), "2D binary output"),
    "ssftyp": ((0,), "SSF type"),
    "swtpr": ((0,), "tapered shell thickness"),
    "tetfac": ((0.0,), "tetrahedra factor"),
    "shloff": ((0.0,), "shell offset"),
}
_CONTROL_FIXED = {
    "sfric": ((0.0,), "default friction"),
    "penopt": ((0, 1), "penalty other than the smaller of segment and node (PENOPT 0/1)"),
    "thkchg": ((0,), "shell thickness changes in contact"),
    "dfric": ((0.0,), "default friction"),
    "edc": ((0.0,), "default friction decay"),
    "vfc": ((0.0,), "default viscous friction"),
}

# LS-DYNA hexahedron faces (0-based, outward normals by the right-hand rule)
_HEX_FACES = np.array([[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]])


def _problem(rec, fld, msg) -> Problem:
    f, line = rec.where(fld) if rec is not None and hasattr(rec, "where") else ("", 0)
    return Problem(f, line, getattr(rec, "name", ""), fld.upper() if fld else None, msg)


def _num(rec, fld, default=0.0) -> float:
    v = rec.get(fld) if rec is not None else None
    return default if v is None else float(v)


def _control(model: Model, problems: list) -> tuple[float, int, int]:
    """(SLSFAC, IGNORE, SSTHK) of *CONTROL_CONTACT (0.1, 0, 0 without it)."""
    recs = model.find("CONTROL_CONTACT")
    if not recs:
        return 0.1, 0, 0
    r = recs[0]
    for fld, (ok, what) in _CONTROL_FIXED.items():
        if r.get(fld) is not None and float(r.get(fld)) not in ok:
            problems.append(_problem(r, fld, f"{what} ({fld.upper()} = {r.get(fld)}) is not supported"))
    return _num(r, "slsfac", 0.1) or 0.1, _ignore(r, problems), int(_num(r, "ssthk"))


def _ignore(rec, problems: list) -> int:
    """IGNORE: 0 initial penetrations moved out, 1 tracked, 2 tracked (LS-DYNA also prints them)."""
    val = int(_num(rec, "ignore"))
    if val not in (0, 1, 2):
        problems.append(
            _problem(
                rec, "ignore", f"IGNORE {val} is not supported (0 move nodes, 1 and 2 track the initial penetrations)"
            )
        )
        return 0
    return val


def _shell_thickness(model: Model, sel: np.ndarray, conn: np.ndarray, problems: list, rec) -> np.ndarray:
    sh = model.shells
    n = int(sel.sum())
    tsec = np.zeros((n, 4))
    pids = sh.pid[sel]
    for p in np.unique(pids):
        part = model.parts.get(int(p))
        sec = model.sections.get(part.get("secid")) if part is not None else None
        if sec is None or sec.keyword != "SECTION_SHELL":
            problems.append(_problem(rec, None, f"part {int(p)} of the contact surface needs a *SECTION_SHELL"))
            continue
        t = [_num(sec, f"t{i}") for i in range(1, 5)]
        tsec[pids == p] = [ti if ti > 0 else t[0] for ti in t]
    given = sh.thickness[sel]
    tn = np.where(np.isfinite(given) & (given > 0), given, tsec)
    tri = conn[:, 2] == conn[:, 3]
    return np.where(tri, tn[:, :3].mean(axis=1), tn.mean(axis=1))


def part_contact(model: Model) -> dict[int, dict[str, float]]:
    """Part ID -> the *PART_CONTACT fields (FS FD DC VC OPTT SFT SSF, SSF 0
    read as 1) of the parts that have them."""
    out = {}
    for pid, part in model.parts.items():
        if "CONTACT" in getattr(part, "options", ()):
            out[int(pid)] = {f: _num(part, f) for f in ("fs", "fd", "dc", "vc", "optt", "sft")}
            out[int(pid)]["ssf"] = _num(part, "ssf", 1.0) or 1.0
    return out


def _per_part(pc: dict, pids: np.ndarray, fld: str, default: float) -> np.ndarray:
    """(k,) the *PART_CONTACT field of each entry's part (``default`` for parts without one)."""
    return np.array([pc[int(p)][fld] if int(p) in pc else default for p in pids], float).reshape(len(pids))


def _contact_thickness(model: Model, sel, conn, problems: list, rec, sst: float, sfst: float):
    """(contact thickness (k,), given (k,)) of the shells ``sel``: the shell
    thickness scaled by the part's SFT (else SFST), replaced by SST > 0 and
    over both by the part's OPTT > 0 (``given``: SST or OPTT set it)."""
    pc = part_contact(model)
    pids = model.shells.pid[sel]
    optt, sft = _per_part(pc, pids, "optt", 0.0), _per_part(pc, pids, "sft", 0.0)
    base = np.where(sft > 0, sft, sfst) * _shell_thickness(model, sel, conn, problems, rec)
    t = np.where(optt > 0, optt, sst if sst > 0 else base)
    return t, (optt > 0) | (sst > 0)


def _bulk(model: Model, pid: int, problems: list, rec) -> float:
    part = model.parts.get(int(pid))
    mat = model.materials.get(part.get("mid")) if part is not None else None
    e, nu = _num(mat, "e"), _num(mat, "pr")
    if mat is None or e <= 0 or not -1.0 < nu < 0.5:
        problems.append(
            _problem(
                rec,
                None,
                f"part {int(pid)} of the contact surface needs a material with "
                "E > 0 and -1 < PR < 0.5 (the penalty uses its bulk modulus)",
            )
        )
        return 0.0
    return e / (3.0 * (1.0 - 2.0 * nu))


def _solid_conn(model: Model, sel: np.ndarray) -> np.ndarray:
    """(k, 8) solid connectivity with 4-node input and LS-DYNA tetrahedra
    made n1 n2 n3 n3 n4 n4 n4 n4 (as solids.build_solids does)."""
    conn = model.solids.nodes[sel].astype(np.int64)
    blank = conn[:, 4:] < 0
    conn[:, 4:] = np.where(blank, conn[:, 3:4], conn[:, 4:])
    tet = np.all(conn[:, 4:] == conn[:, 3:4], axis=1) & (conn[:, 2] != conn[:, 3])
    conn[tet] = conn[tet][:, [0, 1, 2, 2, 3, 3, 3, 3]]
    return conn


def _node_shell_thickness(
    model: Model, nodes: np.ndarray, problems: list, rec, sst: float = 0.0, sfst: float = 1.0
) -> np.ndarray:
    """(k,) the largest contact thickness of the shells holding each node (0: none)."""
    sh = model.shells
    sel = np.isin(sh.nodes, nodes).any(axis=1) if len(sh) else np.zeros(0, bool)
    t = np.zeros(len(model.nodes))
    if sel.any():
        conn = sh.nodes[sel].astype(np.int64)
        conn[:, 3] = np.where(conn[:, 3] < 0, conn[:, 2], conn[:, 3])
        te, _ = _contact_thickness(model, sel, conn, problems, rec, sst, sfst)
        for a in range(4):
            np.maximum.at(t, conn[:, a], te)
    return t[nodes]


def _solid_faces(conn: np.ndarray, inner: bool = False):
    """(faces (k, 4) with triangles n1 n2 n3 n3, owning element (k,), the
    element across (k,), -1 for none) of the faces used by one element of
    ``conn`` (degenerate faces dropped); ``inner``: also every face two
    elements share, once for each, outward of its owner (they become
    surface when the element across is deleted)."""
    faces = conn[:, _HEX_FACES].reshape(-1, 4)
    owner = np.repeat(np.arange(len(conn)), 6)
    keep = np.ones(len(faces), bool)
    for i in np.flatnonzero((faces == np.roll(faces, -1, axis=1)).any(axis=1)):  # degenerate shapes
        f = faces[i]
        d = list(dict.fromkeys(int(f[j]) for j in range(4) if f[j] != f[(j + 1) % 4]))  # cyclic, no repeats
        keep[i] = len(d) >= 3
        faces[i] = d + [d[-1]] * (4 - len(d)) if keep[i] else -1
    faces, owner = faces[keep], owner[keep]
    if not len(faces):
        return faces, owner, np.zeros(0, np.int64)
    key = faces.copy()
    key[faces[:, 2] == faces[:, 3], 3] = -1  # a triangle's key: its three nodes
    key = np.sort(key, axis=1)
    _, inv, cnt = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    inv = inv.ravel()
    once = cnt[inv] == 1
    partner = np.full(len(faces), -1, np.int64)
    if not inner:
        return faces[once], owner[once], partner[once]
    twice = np.flatnonzero(cnt[inv] == 2)
    order = twice[np.argsort(inv[twice], kind="stable")]  # the two copies of each shared face side by side
    a, b = order[0::2], order[1::2]
    partner[a], partner[b] = owner[b], owner[a]
    use = once | (partner >= 0)
    return faces[use], owner[use], partner[use]


def _erodes(model: Model) -> bool:
    """Whether solids may be deleted in the run: *CONTROL_TIMESTEP ERODE = 1
    or a solid material with a failure strain (FAIL; TSEF, SSEF of
    MAT_026)."""
    ts = model.find("CONTROL_TIMESTEP")
    if ts and int(_num(ts[0], "erode", 0) or 0) == 1:
        return True
    for pid in np.unique(model.solids.pid):
        part = model.parts.get(int(pid))
        mat = model.materials.get(part.get("mid")) if part is not None else None
        if mat is not None and any(0.0 < _num(mat, f, 0.0) < 1e20 for f in ("fail", "tsef", "ssef")):
            return True
    return False


def _areas(x, seg):
    tri = seg[:, 2] == seg[:, 3]
    u = np.where(tri[:, None], x[seg[:, 1]] - x[seg[:, 0]], x[seg[:, 2]] - x[seg[:, 0]])
    w = np.where(tri[:, None], x[seg[:, 2]] - x[seg[:, 0]], x[seg[:, 3]] - x[seg[:, 1]])
    return 0.5 * np.linalg.norm(np.cross(u, w), axis=1)


def build_surface(
    model: Model,
    pids: ArrayLike,
    slsfac: float,
    sf: float,
    thick: float,
    thick_scale: float,
    problems: list,
    rec: Record | None,
    slave: bool = False,
    limit: bool = False,
) -> Surface:
    """Segments of the parts ``pids``: shells and exterior solid faces, with
    their contact thickness (``thick`` > 0 replaces the shells'; else
    scaled by ``thick_scale``; the parts' SFT and OPTT: see the module;
    ``limit``: the single-surface 40 % rule) and SOFT = 0 penalty stiffness
    scaled by slsfac·sf (``slave``: also by the parts' SSF)."""
    x = model.nodes.xyz
    pids = np.asarray(pids, np.int64)
    pc = part_contact(model) if slave else {}
    out = []
    sh = model.shells
    sel = np.isin(sh.pid, pids)
    if sel.any():
        conn = sh.nodes[sel].astype(np.int64)
        conn[:, 3] = np.where(conn[:, 3] < 0, conn[:, 2], conn[:, 3])
        t, given = _contact_thickness(model, sel, conn, problems, rec, thick, thick_scale)
        if limit:
            t = np.where(given, t, np.minimum(t, 0.4 * _shortest_edge(x, conn)))
        pids_sel = sh.pid[sel]
        upids = np.unique(pids_sel)
        bulk = np.array([_bulk(model, p, problems, rec) for p in upids])[np.searchsorted(upids, pids_sel)]
        area = _areas(x, conn)
        tri = conn[:, 2] == conn[:, 3]
        edges = np.stack([np.linalg.norm(x[conn[:, (j + 1) % 3]] - x[conn[:, j]], axis=1) for j in range(3)], 1)
        diag = np.where(
            tri,
            edges.max(axis=1),
            np.minimum(
                np.linalg.norm(x[conn[:, 2]] - x[conn[:, 0]], axis=1),
                np.linalg.norm(x[conn[:, 3]] - x[conn[:, 1]], axis=1),
            ),
        )
        k = slsfac * sf * _per_part(pc, pids_sel, "ssf", 1.0) * bulk * area / np.where(diag > 0, diag, 1.0)
        out.append(
            Surface(
                conn,
                t,
                k,
                np.zeros(len(conn), np.int8),
                np.zeros(len(conn)),
                np.sqrt(area),
                np.flatnonzero(sel),
                np.zeros(len(conn), np.int8),
                np.full(len(conn), -1, np.int64),
            )
        )
    so = model.solids
    sel = np.isin(so.pid, pids)
    if sel.any():
        conn = _solid_conn(model, sel)
        vol = np.empty(len(conn))
        solid_volumes(x, conn, np.zeros((N_CHUNKS, N_WORK)), vol)
        faces, owner, partner = _solid_faces(conn, inner=_erodes(model))
        bulk = {int(p): _bulk(model, p, problems, rec) for p in np.unique(so.pid[sel])}
        kb = np.array([bulk[int(p)] for p in so.pid[sel][owner]]) if len(owner) else np.zeros(0)
        area = _areas(x, faces)
        v = np.maximum(vol[owner], 1e-300)
        out.append(
            Surface(
                faces,
                np.zeros(len(faces)),
                slsfac * sf * _per_part(pc, so.pid[sel][owner], "ssf", 1.0) * kb * area**2 / v,
                np.ones(len(faces), np.int8),
                0.5 * v / np.maximum(area, 1e-300),
                np.sqrt(area),
                np.flatnonzero(sel)[owner],
                np.ones(len(faces), np.int8),
                np.where(partner >= 0, np.flatnonzero(sel)[np.maximum(partner, 0)], -1),
            )
        )
    return concat(*out) if out else Surface.empty()


def _part_ids(model: Model, rec, id_fld: str, typ_fld: str, allowed: tuple, problems: list):
    """('parts', pids) or ('nodes', node indices) of a contact side, or None."""
    sid, typ = int(_num(rec, id_fld)), int(_num(rec, typ_fld))
    names = {
        0: "segment sets",
        1: "shell element sets",
        2: "part sets",
        3: "parts",
        4: "node sets",
        5: "all parts",
        6: "part sets to exclude",
    }
    if typ == 0 and sid == 0 and 0 in allowed:  # single surface: SSID 0 means every part
        typ = 5
    if typ not in allowed:
        problems.append(
            _problem(
                rec,
                typ_fld,
                f"{typ_fld.upper()} {typ} ({names.get(typ, 'unknown type')}) is not "
                "supported here (supported: " + ", ".join(f"{a} {names[a]}" for a in allowed if a) + ")",
            )
        )
        return None
    if typ == 0:
        problems.append(
            _problem(
                rec,
                typ_fld,
                f"{typ_fld.upper()} 0 (segment sets) is not supported yet; give the parts (2 part set, 3 part)",
            )
        )
        return None
    if typ == 5:
        return "parts", np.array(sorted(model.parts), np.int64)
    if sid <= 0:
        problems.append(_problem(rec, id_fld, f"{id_fld.upper()} is needed with {typ_fld.upper()} {typ}"))
        return None
    try:
        if typ == 2:
            pids = model.set_members("PART", sid)
        elif typ == 4:
            nodes = model.node_index(model.set_members("NODE", sid))
            if np.any(nodes < 0):
                problems.append(_problem(rec, id_fld, f"*SET_NODE {sid} names nodes that are not defined"))
                return None
            return "nodes", nodes.astype(np.int64)
        else:
            pids = np.array([sid], np.int64)
    except (KeyError, ValueError) as e:
        problems.append(_problem(rec, id_fld, str(e).strip("'\"")))
        return None
    missing = [int(p) for p in pids if int(p) not in model.parts]
    if missing:
        problems.append(_problem(rec, id_fld, f"part {missing[0]} is not defined"))
        return None
    return "parts", np.asarray(pids, np.int64)


def _element_nodes(model: Model, pids) -> np.ndarray:
    out = [np.zeros(0, np.int64)]
    for t in (model.shells, model.solids):
        if len(t):
            out.append(t.nodes[np.isin(t.pid, pids)].ravel().astype(np.int64))
    nodes = np.unique(np.concatenate(out))
    return nodes[nodes >= 0]


def _options(rec, problems: list) -> dict | None:
    ok = True
    for fld, (accepted, what) in _FIXED.items():
        val = rec.get(fld)
        if val is not None and float(val) not in accepted:
            problems.append(_problem(rec, fld, f"{what} ({fld.upper()} = {val}) is not supported"))
            ok = False
    soft = int(_num(rec, "soft"))
    if soft not in (0, 1):
        problems.append(_problem(rec, "soft", f"SOFT {soft} is not supported (0 penalty, 1 soft constraint)"))
        ok = False
    if _num(rec, "fs") < 0 and _num(rec, "fs") != -1:
        problems.append(
            _problem(
                rec, "fs", f"FS = {_num(rec, 'fs'):g} is not supported (FS = -1: the parts' *PART_CONTACT friction)"
            )
        )
        ok = False
    for fld in ("fd", "dc", "vdc", "sst", "mst"):
        if _num(rec, fld) < 0:
            problems.append(
                _problem(rec, fld, f"{fld.upper()} < 0 (friction or thickness from other cards) is not supported")
            )
            ok = False
    if _num(rec, "bt") < 0:
        problems.append(_problem(rec, "bt", "BT < 0 (birth during dynamic relaxation) is not supported"))
        ok = False
    if not ok:
        return None

    def pos(fld, default):
        return _num(rec, fld, default) or default

    return dict(
        fs=_num(rec, "fs"),
        fd=_num(rec, "fd"),
        dc=_num(rec, "dc"),
        vdc=_num(rec, "vdc"),
        fsf=pos("fsf", 1.0),
        soft=soft,
        sofscl=pos("sofscl", 0.1),
        birth=_num(rec, "bt"),
        death=pos("dt", 1e20),
        bsort=int(pos("bsort", BSORT_DEFAULT)),
        sfs=pos("sfs", 1.0),
        sfm=pos("sfm", 1.0),
        sst=_num(rec, "sst"),
        mst=_num(rec, "mst"),
        sfst=pos("sfst", 1.0),
        sfmt=pos("sfmt", 1.0),
        dtstif=_num(rec, "dtstif"),
        ignore=_ignore(rec, problems),
    )


def _shortest_edge(x: np.ndarray, seg: np.ndarray) -> np.ndarray:
    """(k,) the shortest edge of each segment (LS-DYNA's single-surface rule,
    *CONTROL_CONTACT SSTHK = 0: a shell's contact thickness is at most 40 %
    of it unless SST or OPTT give the thickness)."""
    edge = np.stack([np.linalg.norm(x[seg[:, (j + 1) % 4]] - x[seg[:, j]], axis=1) for j in range(4)], axis=1)
    return np.where(edge > 0, edge, np.inf).min(axis=1)  # a triangle's n3 = n4 edge is no edge


def _part_friction(model: Model, rec, o: dict, slave, master, problems: list) -> bool:
    """FS = −1: FS FD DC of the interface's parts (*PART_CONTACT; 0 for a
    part without it) into ``o``, where every part gives the same (which
    part's values LS-DYNA takes for a pair is then moot); False with a
    Problem where they differ or a part's VC (viscous friction) is set."""
    pids = set()
    for side in (slave, master):
        if side is None:
            continue
        if side[0] == "parts":
            pids.update(int(p) for p in side[1])
        else:  # a node set: the parts of the elements holding its nodes
            for t in (model.shells, model.solids):
                if len(t):
                    pids.update(int(p) for p in np.unique(t.pid[np.isin(t.nodes, side[1]).any(axis=1)]))
    pc = part_contact(model)
    zero = dict.fromkeys(("fs", "fd", "dc", "vc"), 0.0)
    values = {p: tuple(pc.get(p, zero)[f] for f in ("fs", "fd", "dc", "vc")) for p in sorted(pids)}
    if len(set(values.values())) > 1:
        first = min(values)
        other = next(p for p in values if values[p] != values[first])
        problems.append(
            _problem(
                rec,
                "fs",
                "FS = -1 with part-based friction that differs between the parts of the interface is not "
                f"supported: FS FD DC VC of part {first} {values[first]}, of part {other} {values[other]} "
                "(*PART_CONTACT)",
            )
        )
        return False
    fs, fd, dc, vc = next(iter(values.values()), (0.0, 0.0, 0.0, 0.0))
    if vc != 0:
        problems.append(
            _problem(rec, "fs", f"viscous friction limit VC = {vc:g} of the parts' *PART_CONTACT is not supported")
        )
        return False
    o.update(fs=fs, fd=fd, dc=dc)
    return True


def _interface(
    model: Model, rec, number: int, slsfac: float, problems: list, ssthk: int = 0, ignore: int = 0
) -> Interface | None:
    """One interface, numbered ``number`` (its rcforc interface number,
    ``model.contacts``); ``ssthk``, ``ignore``: *CONTROL_CONTACT's (the
    contact's own IGNORE wins where it is not 0)."""
    kind = rec.keyword
    n = len(model.nodes)
    o = _options(rec, problems)
    cid = int(number)
    slave = _part_ids(
        model,
        rec,
        "ssid",
        "sstyp",
        {KINDS[0]: (0, 2, 3, 5), KINDS[1]: (2, 3, 4, 5), KINDS[2]: (2, 3, 5)}[kind],
        problems,
    )
    master = None
    if kind != KINDS[0]:
        master = _part_ids(model, rec, "msid", "mstyp", (2, 3), problems)
        if master is None:
            return None
    if slave is None or o is None:
        return None
    before = len(problems)
    if o["fs"] == -1 and not _part_friction(model, rec, o, slave, master, problems):
        return None
    s_surf = (
        build_surface(
            model,
            slave[1],
            slsfac,
            o["sfs"],
            o["sst"],
            o["sfst"],
            problems,
            rec,
            slave=True,
            limit=kind == KINDS[0] and not ssthk,
        )
        if slave[0] == "parts"
        else Surface.empty()
    )
    if kind == KINDS[0]:
        nodes = s_surf.nodes()
        t, k = s_surf.node_values(nodes, n)
        side = np.full(len(nodes), -1, np.int64)
        seg, mside = s_surf, np.zeros(len(s_surf.seg), np.int64)
        node_side = np.ones(len(nodes), np.int64)
    else:
        m_surf = build_surface(model, master[1], slsfac, o["sfm"], o["mst"], o["sfmt"], problems, rec)
        if kind == KINDS[1]:
            if slave[0] == "nodes":  # thickness of the shells on the nodes; stiffness from the master
                nodes = slave[1]
                t = _node_shell_thickness(model, nodes, problems, rec, o["sst"], o["sfst"])
                if o["sst"] > 0:  # SST also for nodes without shells (OPTT still first where a part gives it)
                    t = np.where(t > 0, t, o["sst"])
                k = np.full(len(nodes), np.inf)
            else:
                nodes = _element_nodes(model, slave[1])
                t, k = s_surf.node_values(nodes, n)
            side = np.zeros(len(nodes), np.int64)
            seg, mside = m_surf, np.ones(len(m_surf.seg), np.int64)
            node_side = np.ones(len(nodes), np.int64)
        else:  # both passes: slave nodes on master segments, master nodes on slave segments
            sn, mn = s_surf.nodes(), m_surf.nodes()
            ts, ks = s_surf.node_values(sn, n)
            tm, km = m_surf.node_values(mn, n)
            nodes, t, k = np.concatenate([sn, mn]), np.concatenate([ts, tm]), np.concatenate([ks, km])
            side = np.concatenate([np.zeros(len(sn), np.int64), np.ones(len(mn), np.int64)])
            node_side = 1 - side
            seg = concat(s_surf, m_surf)
            mside = np.concatenate([np.zeros(len(s_surf.seg), np.int64), np.ones(len(m_surf.seg), np.int64)])
    if len(problems) > before:
        return None
    if not len(seg.seg):
        problems.append(
            _problem(
                rec, "msid" if kind != KINDS[0] else "ssid", "the contact surface has no segments (shells or solids)"
            )
        )
        return None
    return Interface(
        cid,
        rec.name,
        nodes.astype(np.int64),
        side,
        np.asarray(t, float),
        np.asarray(k, float),
        node_side,
        seg.seg,
        mside,
        seg.thick,
        seg.k,
        seg.onesided,
        seg.depth,
        seg.size,
        seg.owner,
        seg.solid,
        seg.partner,
        fs=o["fs"],
        fd=o["fd"],
        dc=o["dc"],
        vdc=o["vdc"],
        fsf=o["fsf"],
        soft=o["soft"],
        sofscl=o["sofscl"],
        dt0=o["dtstif"] if o["dtstif"] > 0 else np.inf,
        birth=o["birth"],
        death=o["death"],
        bsort=o["bsort"],
        ignore=o["ignore"] or ignore,
    )


def _initial_dt(model: Model, groups) -> float:
    """TSSFAC × the smallest initial element step of the groups (inf: none)."""
    ts = model.find("CONTROL_TIMESTEP")
    tssfac = _num(ts[0], "tssfac", 0.9) or 0.9 if ts else 0.9
    st = SimpleNamespace(x=model.nodes.xyz)
    dts = [g.critical_dt(st) for g in groups if hasattr(g, "critical_dt")]
    return tssfac * min(dts, default=np.inf)


def build_contacts(model: Model, groups: Sequence[ElementGroup], problems: list) -> list[ContactGroup]:
    """One ContactGroup per *CONTACT_AUTOMATIC_{SINGLE_SURFACE,
    NODES_TO_SURFACE, SURFACE_TO_SURFACE} card, in deck order; ``groups``:
    the element groups (their initial step sizes SOFT = 1). Cards with
    options the reader does not type are refused with every unread card
    (support.unsupported_cards)."""
    out: list[ContactGroup] = []
    recs = [r for r in model.keywords if getattr(r, "keyword", "") in KINDS and hasattr(r, "get")]
    if not recs:
        return out
    slsfac, ignore, ssthk = _control(model, problems)
    numbers = interface_numbers(model)
    dt0 = None
    for rec in recs:
        c = _interface(model, rec, numbers[id(rec)], slsfac, problems, ssthk, ignore)
        if c is None:
            continue
        if c.soft == 1 and not np.isfinite(c.dt0):
            dt0 = _initial_dt(model, groups) if dt0 is None else dt0
            c.dt0 = dt0
        out.append(ContactGroup(c, len(model.nodes), _links(model, c, groups)))
    return out


def _links(model: Model, c: Interface, groups) -> list:
    """(segment rows, alive array, element rows, across) tying segments to
    the deformable shell and solid elements they come from (rigid parts
    never erode): across False, the segment lives while its element does;
    True, an inner face is surface only once the solid across it is gone."""
    out = []
    for g in groups:
        kind = getattr(g, "kind", "")
        alive = getattr(getattr(g, "st", None), "alive", None)
        if kind not in ("shell", "solid") or alive is None or not len(g.ids):
            continue
        is_solid = int(kind == "solid")
        rows = np.flatnonzero(c.solid == is_solid)
        order = np.argsort(g.ids)
        all_ids = model.solids.ids if is_solid else model.shells.ids
        for across, elems in ((False, c.owner), (True, c.partner)):
            sub = rows[elems[rows] >= 0]
            ids = all_ids[elems[sub]]
            j = np.minimum(np.searchsorted(g.ids[order], ids), len(order) - 1)
            hit = g.ids[order][j] == ids
            if hit.any():
                out.append((sub[hit], alive, order[j[hit]], across))
    return out
