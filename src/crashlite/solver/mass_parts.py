"""*ELEMENT_MASS_PART(_SET): translational mass added to parts.

ADDMASS, or FINMASS minus the part's (part set's) mass when FINMASS > 0, is
spread over the nodes in proportion to the mass the part's own elements put
on each, so the part's centre of mass stays where it was and a node shared
with another part only takes its share. A deformable part's nodes carry it
in the lumped masses (kinetic energy, momentum and matsum's part mass count
it); a rigid part's body takes its mass from ``model.properties`` (element
mass and inertia scaled alike: ``mass_part_rows``), the same rows read the
same way. A time-varying mass (LCID), a FINMASS below the part's mass, a
negative ADDMASS and parts without element mass are refused.
"""

from __future__ import annotations

import numpy as np
from scipy import sparse

from ..model.model import Model
from ..model.properties import element_mass, mass_part_factors, mass_part_rows
from .records import _problem


def part_node_masses(groups: list, beams, beam_pid: np.ndarray, n: int) -> tuple[np.ndarray, sparse.csr_matrix]:
    """(part IDs (k,), (k, n) sparse masses each part's shells, solids and
    beams lump on the nodes), as the groups lump them: an element's mass in
    equal shares on its distinct nodes."""
    pid, node, share = [], [], []
    for g in groups:
        if g.kind == "shell":
            s = g.s
            nn = np.where(s.tri == 1, 3, 4)
            m = s.rho * s.thick0 * s.area0 / nn
            for a in range(4):
                sel = (a < 3) | (s.tri == 0)
                pid.append(s.pid[sel]), node.append(s.conn[sel, a]), share.append(m[sel])
        elif g.kind == "solid":
            s = g.s
            srt = np.sort(s.conn, axis=1)
            first = np.ones(srt.shape, bool)
            first[:, 1:] = srt[:, 1:] != srt[:, :-1]
            count = first.sum(axis=1)
            pid.append(np.repeat(s.pid, count)), node.append(srt[first])
            share.append(np.repeat(s.rho0 * s.vol0 / count, count))
    if beams is not None and len(beam_pid) == len(beams.mass):
        for end in (beams.n1, beams.n2):
            pid.append(beam_pid), node.append(end), share.append(0.5 * beams.mass)
    if not pid:
        return np.zeros(0, np.int64), sparse.csr_matrix((0, n))
    pid_all = np.concatenate(pid).astype(np.int64)
    ids = np.unique(pid_all)
    rows = np.searchsorted(ids, pid_all)
    mat = sparse.csr_matrix((np.concatenate(share), (rows, np.concatenate(node))), shape=(len(ids), n))
    return ids, mat


def add_part_masses(
    model: Model, groups: list, beams, beam_pid: np.ndarray, rigid: np.ndarray, mass: np.ndarray, problems: list
) -> None:
    """Add every *ELEMENT_MASS_PART row's mass to the nodes of its deformable
    parts in ``mass`` (n,), in place (rigid parts' bodies take theirs
    through ``model.mass_properties``)."""
    if not model.find("ELEMENT_MASS_PART"):
        return
    ids, per_node = part_node_masses(groups, beams, beam_pid, len(mass))
    rigid_set = {int(p) for p in rigid}

    def own(p: int) -> float:
        if p in rigid_set:
            return element_mass(model, p)
        k = np.searchsorted(ids, p)
        return float(per_node[k].sum()) if k < len(ids) and ids[k] == p else 0.0

    before = len(problems)
    for r in mass_part_rows(model, own):
        rows, k = r.rec.rows, r.row
        ident, fm, am = int(rows["pid"][k]), float(rows["finmass"][k]), float(rows["addmass"][k])
        what = f"part set {ident}" if "SET" in r.rec.options else f"part {ident}"
        if int(rows["lcid"][k]):
            problems.append(_problem(r.rec, "lcid", f"{what}: a mass varying in time (LCID) is not supported yet"))
        elif not r.pids:
            problems.append(
                _problem(r.rec, "pid", f"{what} is not defined, or its parts take their mass from *PART_INERTIA")
            )
        elif r.current <= 0:
            problems.append(_problem(r.rec, "pid", f"{what} has no element mass to spread the added mass over"))
        elif fm > 0 and r.added < 0:
            problems.append(
                _problem(
                    r.rec, "finmass", f"{what}: FINMASS {fm:g} is below its mass {r.current:g}; mass can only be added"
                )
            )
        elif fm <= 0 and am < 0:
            problems.append(_problem(r.rec, "addmass", f"{what}: ADDMASS {am:g} < 0; mass can only be added"))
    if len(problems) > before:  # the set-up fails: nothing to add
        return
    # rows that scale a part by 1 + r_i in turn scale it by their product: its nodes take (product - 1) of
    # the mass its elements lumped there
    for p, f in mass_part_factors(model, own).items():
        if p not in rigid_set and own(p) > 0:
            mass += (f - 1.0) * per_node[np.searchsorted(ids, p)].toarray().ravel()
