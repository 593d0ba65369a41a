"""Nodal loads (*LOAD_NODE_POINT, *LOAD_NODE_SET): forces and moments
along the global axes from load curves, and the work they do."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..model.model import Model
from .records import _curve, _problem


@dataclass
class NodalLoads:
    """k load entries: node (k,) indices, comp (k,) 0-2 force x y z, 3-5
    moment x y z; scale (k,); curves: (time, value) arrays, curve (k,) the
    entry's curve."""

    node: np.ndarray
    comp: np.ndarray
    scale: np.ndarray
    curve: np.ndarray
    curves: list

    def values(self, t: float) -> np.ndarray:
        """(k,) load of each entry at time t [force or moment]."""
        at = np.array([np.interp(t, c[0], c[1]) for c in self.curves])
        return self.scale * at[self.curve]

    def apply(self, t: float, f: np.ndarray, moment: np.ndarray | None) -> None:
        """Add the loads at t to f (n, 3) and moment (n, 3)."""
        val = self.values(t)
        force = self.comp < 3
        np.add.at(f, (self.node[force], self.comp[force]), val[force])
        if moment is not None and (~force).any():
            np.add.at(moment, (self.node[~force], self.comp[~force] - 3), val[~force])

    def work(self, t_mid: float, v: np.ndarray, w: np.ndarray | None, dt: float) -> float:
        """Work over a step of length dt whose mid time is t_mid, with the
        half-step velocities v and angular velocities w."""
        val = self.values(t_mid)
        force = self.comp < 3
        out = float(np.dot(val[force], v[self.node[force], self.comp[force]]))
        if w is not None and (~force).any():
            out += float(np.dot(val[~force], w[self.node[~force], self.comp[~force] - 3]))
        return out * dt


def build_nodal_loads(model: Model, rot_nodes: np.ndarray, problems: list) -> NodalLoads | None:
    """The nodal loads of a deck (None without any). ``rot_nodes`` (n,)
    bool: nodes with rotational degrees of freedom (moments need them)."""
    node, comp, scale, curve, curves, slot = [], [], [], [], [], {}
    for rec in model.find("LOAD_NODE"):
        point = rec.name == "LOAD_NODE_POINT"
        rows = rec.rows
        for i in range(len(rows["dof"])):
            dof, lcid = int(rows["dof"][i]), int(rows["lcid"][i])
            if dof in (4, 8) or dof not in (1, 2, 3, 5, 6, 7):
                problems.append(
                    _problem(rec, "dof", f"DOF {dof}: only global forces (1-3) and moments (5-7) are supported")
                )
                continue
            if int(rows["cid"][i]):
                problems.append(_problem(rec, "cid", "loads in a local system are not supported yet"))
                continue
            if lcid not in model.curves:
                problems.append(_problem(rec, "lcid", f"curve {lcid} is not defined"))
                continue
            try:
                idx = (
                    model.node_index(np.array([rows["nid"][i]]))
                    if point
                    else model.node_index(model.set_members("node", int(rows["nsid"][i])))
                )
            except KeyError as e:
                problems.append(_problem(rec, "nid" if point else "nsid", str(e).strip("'\"")))
                continue
            c = dof - 1 if dof <= 3 else dof - 2
            if c >= 3 and not rot_nodes[idx].all():
                problems.append(
                    _problem(
                        rec,
                        "dof",
                        "a moment on a node without rotational degrees of freedom (no shell or beam attached)",
                    )
                )
                continue
            if lcid not in slot:
                slot[lcid] = len(curves)
                curves.append(_curve(model, lcid))
            node.append(idx)
            comp.append(np.full(len(idx), c))
            scale.append(np.full(len(idx), float(rows["sf"][i])))
            curve.append(np.full(len(idx), slot[lcid]))
    if not node:
        return None
    return NodalLoads(
        np.concatenate(node).astype(np.int64),
        np.concatenate(comp).astype(np.int64),
        np.concatenate(scale),
        np.concatenate(curve).astype(np.int64),
        curves,
    )
