"""Rigid parts (*MAT_RIGID) as rigid bodies: their shells, solids and beams
only give the body its mass, centre of gravity and inertia (or
*PART_INERTIA does), *CONSTRAINED_EXTRA_NODES add nodes to it,
*CONSTRAINED_RIGID_BODIES merges parts into their lead part, and CMO = 1
with CON1/CON2 holds its translations/rotations in the global system."""

from __future__ import annotations

import numpy as np

from ..keyword.errors import Problem
from ..model.mass import MassProperties
from ..model.model import Model
from .rigid import RigidBody, build_body

# translational constraint codes (CON1) -> held global directions
_CON = {0: (0, 0, 0), 1: (1, 0, 0), 2: (0, 1, 0), 3: (0, 0, 1), 4: (1, 1, 0), 5: (0, 1, 1), 6: (1, 0, 1), 7: (1, 1, 1)}


def rigid_part_ids(model: Model) -> set[int]:
    out = set()
    for pid, part in model.parts.items():
        mat = model.materials.get(part.get("mid"))
        if mat is not None and mat.keyword == "MAT_RIGID":
            out.add(pid)
    return out


def _elements_nodes(model: Model, pids) -> np.ndarray:
    out = [np.zeros(0, np.int64)]
    for t in (model.shells, model.solids, model.beams, model.discretes):
        if len(t):
            out.append(t.nodes[np.isin(t.pid, pids)].ravel())
    nodes = np.unique(np.concatenate(out))
    return nodes[nodes >= 0]


def part_bodies(model: Model, x: np.ndarray, v: np.ndarray, mass: np.ndarray, problems: list) -> list[RigidBody]:
    rigid = rigid_part_ids(model)
    if not rigid:
        return []
    lead = {pid: pid for pid in rigid}
    extra: dict[int, list] = {}
    for rec in model.keywords:
        kw = getattr(rec, "keyword", "")
        if kw == "CONSTRAINED_RIGID_BODIES":
            for pl, pc in zip(rec.rows["pidl"], rec.rows["pidc"]):
                if int(pl) not in rigid or int(pc) not in rigid:
                    problems.append(
                        Problem(*rec.where(None), rec.name, "PIDL", f"parts {int(pl)} and {int(pc)} must both be rigid")
                    )
                    continue
                lead[int(pc)] = int(pl)
        elif kw == "CONSTRAINED_EXTRA_NODES":
            ids = rec.rows["nid"] if "nid" in rec.rows else rec.rows["nsid"]
            for pid, i in zip(rec.rows["pid"], ids):
                nodes = (
                    model.node_index([i]) if "nid" in rec.rows else model.node_index(model.set_members("NODE", int(i)))
                )
                extra.setdefault(int(pid), []).append(nodes)
    bodies = []
    for pid_lead in sorted(set(lead.values())):
        members = [p for p, ld in lead.items() if ld == pid_lead]
        nodes = _elements_nodes(model, members)
        for p in members:
            for e in extra.get(p, []):
                nodes = np.union1d(nodes, e)
        if not len(nodes):
            continue
        props = model.mass_properties(members)
        point = mass[nodes]  # lumped masses on the body's nodes join it
        if point.sum() > 0:
            r = x[nodes]
            c = (point[:, None] * r).sum(0) / point.sum()
            d = r - c
            inertia = np.einsum(
                "k,kij->ij", point, (d * d).sum(1)[:, None, None] * np.eye(3) - d[:, :, None] * d[:, None, :]
            )
            props = props + MassProperties(float(point.sum()), c, inertia)
        if props.mass <= 0:
            problems.append(Problem(model.source or "", 0, "MAT_RIGID", "RO", f"rigid part {pid_lead} has no mass"))
            continue
        lead_part = model.parts[pid_lead]
        mat = model.materials[lead_part["mid"]]
        given = {"tm": props.mass, "cog": props.cog, "inertia": props.inertia}
        if "INERTIA" in lead_part.options:  # the given initial velocities
            if int(lead_part.get("ircs", 0) or 0):  # the tensor would be taken in the wrong axes
                problems.append(
                    Problem(
                        *lead_part.where("ircs"),
                        lead_part.keyword,
                        "IRCS",
                        f"part {pid_lead}: an inertia tensor in a local system (IRCS = 1) is not supported yet",
                    )
                )
            given["v"] = [lead_part.get(k, 0.0) for k in ("vtx", "vty", "vtz")]
            given["w"] = [lead_part.get(k, 0.0) for k in ("vrx", "vry", "vrz")]
        body = build_body(pid_lead, nodes, x, v, mass, given)
        cmo = int(mat.get("cmo", 0) or 0)
        con1, con2 = int(mat.get("con1", 0) or 0), int(mat.get("con2", 0) or 0)
        if cmo == 1:
            if con1 not in _CON or con2 not in _CON:
                problems.append(
                    Problem(
                        *mat.where("con1"),
                        mat.name,
                        "CON1",
                        f"constraint codes CON1 = {con1}, CON2 = {con2}: 0 to 7 expected",
                    )
                )
            body.held_v = np.diag(np.array(_CON.get(con1, (0, 0, 0)), float))
            body.held_w = np.diag(np.array(_CON.get(con2, (0, 0, 0)), float))
        elif cmo == -1:  # CON1: local system, CON2: SPC code "xyzXYZ" as digits (100000: x held)
            from .frames import axes

            try:
                r = axes(model, con1) if con1 else np.eye(3)
            except (KeyError, ValueError) as e:
                problems.append(Problem(*mat.where("con1"), mat.name, "CON1", str(e)))
                continue
            digits = [int(c) for c in f"{con2:06d}"[-6:]]
            body.held_v = np.array(digits[:3], float)[:, None] * r
            body.held_w = np.array(digits[3:], float)[:, None] * r
        elif cmo != 0:
            problems.append(Problem(*mat.where("cmo"), mat.name, "CMO", f"CMO = {cmo}: -1, 0 or 1 expected"))
        body.constrain()
        bodies.append(body)
    return bodies
