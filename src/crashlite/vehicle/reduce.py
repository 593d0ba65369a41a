"""The four steps of the simplified vehicle, from a full deck and its runs.

``reduce_vehicle`` takes any vehicle deck whose interface cross sections
name the assemblies (*DATABASE_CROSS_SECTION_PLANE with a title and a part
set per assembly, as the generic car has; or ``assemblies`` given) and the
results of one or more full runs (crashlite results folders, LS-DYNA
binout or ASCII folders), and runs:

1. load paths per load case (``loadpaths``) and the shares the surrogate
   uses: those of one load case, or their mean over the load cases
   (``combined_shares``), with each load case's deviation from it;
2. mass, CoG and inertia of the replaced structure, the rear-axle point
   (``massprops``);
3. the longitudinal stiffness K and the transverse and roll stiffness of
   the replaced structure on one factorisation (``stiffness``), and K under
   inertia relief (``relief``), which the springs share by default
   (``springs="axle"``: the paper's K, borne at the rear axle);
4. the surrogate deck: by default the cut joined to the rear body by the
   replaced structure condensed onto the cut nodes under inertia relief
   (``condense``, ``condensed``: the cut bends as the elastic structure
   behind it would); ``connection="springs"`` is the paper's form, a rigid
   interface and one spring per load path (``surrogate``).

``Reduction.write`` writes the simplified deck, ``reduction.json`` with
every figure and a page ``reduction.html`` with the paper's tables 2–3
and figures 10–12.
"""

from __future__ import annotations

import json
import time
from collections.abc import Collection, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from ..model.model import Model
from .connection.cb_surrogate import build_cb_surrogate
from .connection.condense import relieved_condensation
from .connection.condensed import build_condensed_surrogate
from .connection.connection import compare_connection, connection_stiffness
from .connection.modes import free_modes, held_modes
from .steps import loadpaths as lp
from .steps.cut import Cut, cut_behind
from .steps.massprops import NodeSelection, ReplacedMass, replaced_mass
from .steps.relief import relieved_stiffness
from .steps.stiffness import StiffnessResult, longitudinal_stiffness
from .steps.surrogate import Surrogate, build_surrogate

CONNECTIONS = ("condensed", "craig-bampton", "springs")

if TYPE_CHECKING:
    from ..results.history import History


@dataclass
class Reduction:
    """Steps 1–4 and what they found."""

    deck: str
    load_paths: list  # LoadPaths, one per load case
    shares: dict  # assembly -> share used (fraction)
    share_basis: str  # the load case the shares come from, or "combined"
    share_deviation: dict  # load case -> max |share − used share|
    cut: Cut
    mass: ReplacedMass
    stiffness: StiffnessResult  # with its transverse and roll stiffness
    surrogate: Surrogate
    seconds: dict = field(default_factory=dict)  # step -> wall time [s]
    notes: list = field(default_factory=list)
    relief: StiffnessResult | None = None  # K under inertia relief
    springs: str = "relief"  # the K the springs share: "relief" or "axle" (the paper's step 3)
    connection: dict | None = None  # the surrogate's 6×6 connection against the structure's (connection.py)
    modes: dict | None = None  # the replaced structure's modes, "free" and "held" at the interface (modes.py)
    connection_kind: str = "springs"  # "condensed" (the structure condensed on the cut) or "springs" (the paper)
    condensation: dict | None = None  # condense.Condensation.summary() of the condensed connection

    @property
    def spring_stiffness(self) -> float:
        """The K the springs share (``springs``)."""
        return (self.relief if self.springs == "relief" else self.stiffness).stiffness

    def summary(self) -> dict:
        full = self.cut.model
        sur = self.surrogate.model
        n_full = sum(len(getattr(full, t)) for t in ("shells", "solids", "beams", "discretes"))
        n_sur = sum(len(getattr(sur, t)) for t in ("shells", "solids", "beams", "discretes"))
        return {
            "deck": self.deck,
            "interface": {
                "point": self.cut.point.tolist(),
                "axis": self.cut.axis.tolist(),
                "nodes": int(len(self.cut.interface_nodes)),
            },
            "step1_load_paths": [p.to_dict() for p in self.load_paths],
            "shares_used": {
                "basis": self.share_basis,
                "shares_percent": {k: 100 * v for k, v in self.shares.items()},
                "max_deviation_percent_points": {k: 100 * v for k, v in self.share_deviation.items()},
            },
            "step2_mass": {**self.mass.table(), "inertia": self.mass.structure.inertia.tolist()},
            "step3_stiffness": {
                **self.stiffness.table(),
                "transverse": dict(self.stiffness.transverse),
                "static_model": dict(self.stiffness.elements),
                "dofs": self.stiffness.n_dofs,
                "inertia_relief": None
                if self.relief is None
                else {**self.relief.table(), "transverse": dict(self.relief.transverse or {})},
                "springs_from": self.springs,
            },
            "step4_surrogate": {
                "connection": self.connection_kind,
                **self.surrogate.summary(),
                **({"condensation": self.condensation} if self.condensation else {}),
            },
            "connection_against_structure": self.connection,
            "replaced_structure_modes": self.modes,
            "model_size": {
                "full_elements": n_full,
                "simplified_elements": n_sur,
                "element_reduction_percent": 100.0 * (1 - n_sur / n_full) if n_full else None,
                "full_parts": len(full.parts),
                "simplified_parts": len(sur.parts),
                "removed_mass_percent": 100.0 * self.mass.structure.mass / full.mass_properties().mass,
            },
            "seconds": dict(self.seconds),
            "notes": list(self.notes),
        }

    def write(self, deck_path: Path | str, report_dir: Path | str | None = None, fmt: str = "fixed") -> dict:
        """The simplified deck at ``deck_path``; reduction.json and
        reduction.html in ``report_dir`` (default: beside the deck)."""
        from ..report.build import jsonable

        deck_path = Path(deck_path)
        out = Path(report_dir) if report_dir is not None else deck_path.parent
        out.mkdir(parents=True, exist_ok=True)
        written = {"deck": self.surrogate.write(deck_path, fmt=fmt)}
        (out / "reduction.json").write_text(json.dumps(jsonable(self.summary()), indent=1, allow_nan=False) + "\n")
        written["summary"] = out / "reduction.json"
        from .verify.reduce_report import reduction_page

        (out / "reduction.html").write_text(reduction_page(self))
        written["html"] = out / "reduction.html"
        return written


def section_assemblies(model: Model, names: Collection[str] | None = None) -> tuple[dict, dict, np.ndarray | None]:
    """Assemblies of the deck's cross sections: (name -> part IDs of the
    section's part set, name -> section ID, the common plane point or None).
    ``names``: the section titles to use (default every titled plane section
    with a part set)."""
    asm, ids, points = {}, {}, []
    for rec in model.find("DATABASE_CROSS_SECTION_PLANE"):
        title = str(rec.get("title", "") or "").strip()
        psid = int(rec.get("psid", 0) or 0)
        if not title or psid <= 0 or (names is not None and title not in names):
            continue
        asm[title] = [int(p) for p in model.set_members("PART", psid)]
        ids[title] = int(rec.get("csid", 0) or 0)
        points.append([float(rec.get(a, 0.0) or 0.0) for a in ("xct", "yct", "zct")])
    if names is not None:
        missing = sorted(set(names) - set(asm))
        if missing:
            raise KeyError(f"no titled *DATABASE_CROSS_SECTION_PLANE with a part set for {missing}")
    point = None
    if points:
        p = np.array(points)
        if np.allclose(p, p[0], atol=1e-6):
            point = p[0]
    return asm, ids, point


def _support(model: Model, support):
    if isinstance(support, str) and support.strip().isdigit():
        return ("set", int(support))
    if support is not None:
        return support
    for (kind, sid), rec in model.sets.items():
        if kind == "NODE" and "axle" in str(rec.title or "").lower():
            return ("set", sid)
    raise ValueError(
        "no support given and no node set titled '... axle ...': name the rear-axle attachment "
        "points (a *SET_NODE title or ID)"
    )


def reduce_vehicle(
    deck: Model | Path | str,
    results: History | Path | str | Sequence[History | Path | str],
    load_cases: Sequence[str] | None = None,
    interface: float | None = None,
    axis: ArrayLike = (1.0, 0.0, 0.0),
    assemblies: dict[str, int | str | Iterable[int | str]] | None = None,
    support: NodeSelection | None = None,
    axle_parts: int | str | Iterable[int | str] | None = None,
    shares: str = "combined",
    t_end: float | None = None,
    interface_mode: str = "rigid",
    spring_length: float = 100.0,
    damping_ratio: float = 0.0,
    mass_split: str = "axle",
    springs: str = "relief",
    modes: int = 0,
    connection: str = "condensed",
    condensed_modes: int = 0,
    cut_dashpots: bool = True,
    shells: str = "static",
    quiet: bool = True,
) -> Reduction:
    """Steps 1–4 (module docstring).

    deck        the full vehicle deck (path or Model)
    results     one results path (or History) per load case
    load_cases  their names (default "load case 1", ...)
    interface   x of the interface along ``axis`` [length] (default: the plane of the sections)
    assemblies  name -> part IDs or titles (default: the titled cross sections and their part sets)
    support     rear-axle attachment points: a *SET_NODE title, ("set", SID) or node indices
                (default: the node set whose title names the axle)
    axle_parts  parts of the rear axle (table 2's rear-axle mass)
    shares      "combined" (mean over the load cases) or the name of one load case
    t_end       ignore section forces after this time (e.g. the rebound)
    mass_split  "axle" or "cog" (``surrogate.build_surrogate``)
    springs     the K the springs share: "relief" (default), the replaced structure held by its own
                inertia as in the crash (``relief``), or "axle", the paper's step 3 (borne at the rear axle)
    modes       also the replaced structure's lowest modes, free and held at the interface
                (``modes.free_modes``, ``modes.held_modes``; 0: none)
    connection  "condensed" (default): the cut joined to the rear body by the replaced structure
                condensed onto it (``condensed``; shares, springs and the interface options then
                only report); "craig-bampton": the replaced structure as a superelement with its
                mass and held modes (``craig_bampton``, ``cb_surrogate``: no rear rigid body);
                "springs": the paper's rigid interface and load-path springs
    condensed_modes  with the condensed connection, the replaced structure's lowest free modes that
                move on their own (residual flexibility, ``condense``; 0: quasi-static); with
                "craig-bampton" its modes held at the boundary
    cut_dashpots  with the condensed connection, dashpots of the replaced structure's wave impedance
                between the cut nodes and the rear body (``impedance``)
    shells      the replaced shells' stiffness in the condensed and Craig-Bampton connections: "static"
                (QM6 membrane, MITC4 plate) or "kernel" (the time loop's own shells linearised:
                ``kernel_stiffness``, the stiffness the full run integrates)
    """
    from ..keyword.reader import read_deck

    if springs not in ("axle", "relief"):
        raise ValueError(f"springs={springs!r}: 'axle' or 'relief'")
    if connection not in CONNECTIONS:
        raise ValueError(f"connection={connection!r}: one of {CONNECTIONS}")
    say = (lambda *a: None) if quiet else (lambda *a: print(*a, flush=True))
    model = deck if isinstance(deck, Model) else read_deck(deck)
    results = list(results) if isinstance(results, (list, tuple)) else [results]
    names = list(load_cases) if load_cases is not None else [f"load case {k + 1}" for k in range(len(results))]
    if len(names) != len(results):
        raise ValueError(f"{len(names)} load-case names for {len(results)} results")
    notes: list = []
    seconds = {}
    t0 = time.perf_counter()
    sec_asm, sec_ids, plane = section_assemblies(model)
    if assemblies is None:
        if not sec_asm:
            raise ValueError(
                "the deck has no titled *DATABASE_CROSS_SECTION_PLANE with a part set: give the "
                "assemblies (name -> parts)"
            )
        assemblies = sec_asm
    else:
        assemblies = {n: [int(p) for p in model.part_ids_of(ps)] for n, ps in assemblies.items()}
    missing = sorted(set(assemblies) - set(sec_ids))
    if missing:
        raise KeyError(f"no cross section for the assemblies {missing}: step 1 needs the section force of each")
    # step 1
    paths = []
    for name, res in zip(names, results):
        paths.append(lp.from_run(res, model, {n: sec_ids[n] for n in assemblies}, axis, name, t_end))
        say(f"step 1 ({name}): " + ", ".join(f"{k} {100 * v:.1f} %" for k, v in paths[-1].shares().items()))
    if shares == "combined":
        comb = lp.combined_shares(paths)
        used, deviation, basis = comb["shares"], comb["deviation"], "combined" if len(paths) > 1 else names[0]
    else:
        if shares not in names:
            raise KeyError(f"shares {shares!r}: not a load case ({names}) nor 'combined'")
        used = paths[names.index(shares)].shares()
        basis = shares
        deviation = {p.load_case: float(max(abs(p.shares().get(k, 0.0) - v) for k, v in used.items())) for p in paths}
    seconds["step 1 load paths"] = time.perf_counter() - t0
    # cut at the interface
    a = np.asarray(axis, float)
    a = a / np.linalg.norm(a)
    if interface is not None:
        point = float(interface) * a
    elif plane is not None:
        point = plane
    else:
        raise ValueError("the interface sections lie in different planes: give the interface position")
    cut = cut_behind(model, point=point, axis=a)
    # step 2
    t0 = time.perf_counter()
    sup = _support(model, support)
    mass = replaced_mass(cut, axle_nodes=sup, axle_parts=axle_parts)
    seconds["step 2 mass"] = time.perf_counter() - t0
    say(f"step 2: replaced mass {mass.structure.mass:.6g} at {np.round(mass.structure.cog, 1).tolist()}")
    # step 3
    t0 = time.perf_counter()
    k = longitudinal_stiffness(cut, sup, transverse=(1000.0, 1.0e6))
    rel = relieved_stiffness(cut, transverse=(1000.0, 1.0e6))
    trans = rel.transverse if springs == "relief" else k.transverse  # the beam as the springs: one way of bearing
    seconds["step 3 stiffness"] = time.perf_counter() - t0
    say(
        f"step 3: K = {k.stiffness:.6g} (F {k.force:g}, u {k.displacement:.4g}); shear {trans['shear']:.4g}, "
        f"roll {trans['roll']:.4g}; under inertia relief K = {rel.stiffness:.6g}"
    )
    # step 4
    t0 = time.perf_counter()
    k_springs = rel.stiffness if springs == "relief" else k.stiffness
    cond = None
    if connection == "craig-bampton":
        sur = build_cb_surrogate(cut, mass, modes=condensed_modes, stiffness=rel.stiffness, shells=shells)
        say(
            f"step 4: the replaced structure as a Craig-Bampton superelement on {sur.craig_bampton.cut_nodes} "
            f"cut nodes, {len(sur.model.shells)} of {len(model.shells)} shells kept"
        )
    elif connection == "condensed":
        cond = relieved_condensation(cut, modes=condensed_modes, shells=shells)
        sur = build_condensed_surrogate(cut, cond, mass, dashpots=cut_dashpots)
        say(
            f"step 4: the replaced structure condensed on {len(cond.nodes)} cut nodes, "
            f"{len(sur.model.shells)} of {len(model.shells)} shells kept"
        )
    else:
        sur = build_surrogate(
            cut,
            assemblies,
            used,
            k_springs,
            mass,
            trans,
            interface=interface_mode,
            spring_length=spring_length,
            damping_ratio=damping_ratio,
            mass_split=mass_split,
        )
        say(f"step 4: {len(sur.springs)} springs, {len(sur.model.shells)} of {len(model.shells)} shells kept")
    seconds["step 4 surrogate"] = time.perf_counter() - t0
    conn = None
    if cond is not None and rel.flexibility is not None:  # the condensed cut held rigid against the structure
        conn = compare_connection(cond.rigid_stiffness(rel.load_point), rel.flexibility, cut.axis)
    elif connection == "springs" and interface_mode == "rigid" and rel.flexibility is not None:
        conn = compare_connection(connection_stiffness(sur, rel.load_point), rel.flexibility, cut.axis)
        worst = conn["largest_compliance_misfit"]
        say(
            f"  the springs and beam against the replaced structure: {worst['direction']} compliance "
            f"x{worst['ratio']:.3g} (the largest misfit)"
        )
    free = None
    if modes > 0:
        t0 = time.perf_counter()
        fm = free_modes(cut, count=modes)
        hm = held_modes(cut, count=modes)
        free = {"free": fm.summary(rel.flexibility, cut.axis), "held": hm.summary()}
        seconds["modes"] = time.perf_counter() - t0
        eff = free["held"]["effective_mass_percent"]
        say(
            f"  modes of the replaced structure held at the interface up to {hm.frequencies[-1]:.3g} (time unit⁻¹) "
            "hold "
            + ", ".join(f"{sum(v):.1f} % of its {d}" for d, v in eff.items() if d in ("axial", "vertical", "pitch"))
        )
    notes += mass.notes + k.notes + [n for n in rel.notes if n not in k.notes]
    return Reduction(
        str(getattr(model, "source", "") or ""),
        paths,
        used,
        basis,
        deviation,
        cut,
        mass,
        k,
        sur,
        seconds,
        notes,
        rel,
        springs,
        conn,
        free,
        connection,
        (cond or sur.craig_bampton).summary() if connection != "springs" else None,
    )
