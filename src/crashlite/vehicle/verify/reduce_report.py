"""The page of a vehicle reduction: the four steps as the paper shows them
(figures 10–12, tables 2 and 3, the springs of figure 15)."""

from __future__ import annotations

from typing import Protocol

from ...report.html import Raw, esc, image, num, page, table
from ..connection.connection import DIRECTIONS
from ..steps import loadpaths as lp


class ReductionView(Protocol):
    """What the page reads of a ``reduce.Reduction`` (the Reduction writes
    its page, so this module names it without importing it)."""

    deck: str
    load_paths: list  # steps.loadpaths.LoadPaths, one per load case

    def summary(self) -> dict: ...


def reduction_page(r: ReductionView) -> str:
    """Self-contained HTML of a ``reduce.Reduction``."""
    s = r.summary()
    body = [
        f"<p>Full deck <code>{esc(r.deck or 'model')}</code>; interface at "
        f"{esc([round(v, 2) for v in s['interface']['point']])} normal to {esc(s['interface']['axis'])}, "
        f"{s['interface']['nodes']} interface nodes.</p>"
    ]
    size = s["model_size"]
    body.append(
        table(
            ["", "full", "simplified"],
            [
                ["elements", size["full_elements"], size["simplified_elements"]],
                ["parts", size["full_parts"], size["simplified_parts"]],
                ["element reduction", "", f"{num(size['element_reduction_percent'], 3)} %"],
                ["mass replaced", "", f"{num(size['removed_mass_percent'], 3)} %"],
            ],
        )
    )
    body.append("<h2>Step 1: load paths through the interface</h2>")
    for p in r.load_paths:
        body.append(f"<h3>{esc(p.load_case)}</h3>")
        body.append(
            '<div class="grid">'
            + image(lp.plot_forces(p), "section forces")
            + image(lp.plot_impulses(p), "impulses")
            + "</div>"
        )
        body.append(
            table(
                ["assembly", "section", "peak force", "max impulse", "share [%]"],
                [
                    [
                        a["assembly"],
                        a["section"],
                        num(a["max_force"]),
                        num(a["max_impulse"]),
                        num(a["share_percent"], 3),
                    ]
                    for a in p.table()
                ],
            )
        )
    body.append(image(lp.plot_shares(r.load_paths), "load-path shares"))
    used = s["shares_used"]
    body.append(
        f"<p>Shares used: <b>{esc(used['basis'])}</b>; largest deviation of each load case from them "
        "(percentage points): "
        + ", ".join(f"{esc(k)} {v:.2f}" for k, v in used["max_deviation_percent_points"].items())
        + "</p>"
    )
    body.append("<h2>Step 2: mass and centre of gravity of the replaced structure</h2>")
    t2 = s["step2_mass"]
    rows = [
        [k, num(v["x"], 6), num(v["y"], 6), num(v["z"], 6), num(v["mass"], 6)]
        for k, v in t2.items()
        if isinstance(v, dict) and "x" in v
    ]
    body.append(table(["", f"CoG x [{t2['units']['length']}]", "y", "z", f"mass [{t2['units']['mass']}]"], rows))
    body.append("<h2>Step 3: stiffness of the replaced structure</h2>")
    t3 = s["step3_stiffness"]
    tr = t3["transverse"]
    body.append(
        table(
            ["force", "displacement", "longitudinal stiffness", "lateral", "vertical", "roll"],
            [
                [
                    num(t3["force"]),
                    num(t3["displacement"]),
                    num(t3["stiffness"], 6),
                    num(tr["lateral"]),
                    num(tr["vertical"]),
                    num(tr["roll"]),
                ]
            ],
        )
    )
    body.append(f'<p class="note">Linear static model: {esc(t3["static_model"])}, {t3["dofs"]} DOFs.</p>')
    ir = t3.get("inertia_relief")
    if ir:
        body.append(
            f"<p>Under inertia relief (the structure held by its own mass, as in the crash): "
            f"displacement {num(ir['displacement'])} against its mean motion, longitudinal stiffness "
            f"{num(ir['stiffness'], 6)}"
            + ("".join(f", {k} {num(v)}" for k, v in ir.get("transverse", {}).items() if k != "shear"))
            + f". The springs share the {'inertia-relief' if t3['springs_from'] == 'relief' else 'axle-borne'} "
            "K; the anti-rotation beam takes the same kind's shear and roll stiffness.</p>"
        )
    body.append("<h2>Step 4: the surrogate</h2>")
    sur = s["step4_surrogate"]
    conn = s.get("connection_against_structure")
    lead = ""
    if sur.get("connection") == "craig-bampton":
        c = sur["condensation"]
        f = c["mode_frequencies"]
        body.append(
            f"<p>The replaced structure is one linear superelement with its stiffness and mass "
            f"(*ELEMENT_DIRECT_MATRIX_INPUT, Craig–Bampton): the translations of its {c['cut_nodes']} cut "
            f"nodes and {c['boundary_nodes'] - c['cut_nodes']} nodes kept behind the cut, and its "
            f"{c['modes']} lowest modes with them held"
            + (f" ({num(f[0])} to {num(f[-1])} per time unit)" if f else "")
            + f": {c['dofs']} DOFs in all. Its mass ({num(c['mass'])}) and inertia are the structure's; "
            "no rear rigid body. The load-path shares of step 1 are reported, not needed.</p>"
        )
    elif sur.get("connection") == "condensed":
        c = sur["condensation"]
        body.append(
            f"<p>The cut is joined to the rear body by the replaced structure condensed onto its "
            f"{c['nodes']} nodes ({c['dofs']} translations; {c['left_out']} left free): the structure's "
            "flexibility at every cut DOF relative to its own mean rigid motion, held by its inertia as in "
            "the crash, inverted into one linear superelement (*ELEMENT_DIRECT_MATRIX_INPUT) between the "
            "cut nodes and the rear body, so the cut bends as the elastic structure behind it would. "
            f"Stiffness eigenvalues {num(c['stiffness_eigenvalues'][0])} to "
            f"{num(c['stiffness_eigenvalues'][1])}. The load-path shares of step 1 are reported, not "
            "needed: the condensed matrix distributes the load.</p>"
        )
        lead = (
            "Held rigid, the condensed cut is one 6×6 stiffness at the interface; against the rigid "
            "interface of step 3 under inertia relief, per direction (the cut's shell rotations stay free "
            "in the condensed one, so it comes out a little softer across):"
        )
    else:
        body.append(
            table(
                ["assembly", "share [%]", "stiffness", "damping", "direction", "interface nodes"],
                [
                    [
                        sp["assembly"],
                        num(sp["share_percent"], 3),
                        num(sp["stiffness"], 6),
                        num(sp["damping"]),
                        Raw(esc([round(v, 3) for v in sp["direction"]])),
                        sp["interface_nodes"],
                    ]
                    for sp in sur["springs"]
                ],
            )
        )
        b = sur["beam"]
        body.append(
            f"<p>Anti-rotation beam: length {num(b['length'])}, axial stiffness {num(b['axial_stiffness'])}, "
            f"EI {num(b['EI'])}, GJ {num(b['GJ'])}; interface: {esc(sur['interface'])} rigid body.</p>"
        )
        lead = (
            "The springs and the beam join the interface body to the rear body: the front structure "
            "feels them as one 6×6 stiffness at the interface. Against the replaced structure's own, held "
            "by its inertia (step 3 under inertia relief), per direction:"
        )
    if conn:
        body.append(
            f"<p>{lead} the compliance under that load alone (the rest free) and the stiffness with the "
            "rest held, surrogate over structure.</p>"
        )
        body.append(
            table(
                [
                    "direction",
                    "structure compliance",
                    "surrogate compliance",
                    "compliance ratio",
                    "stiffness ratio (rest held)",
                ],
                [
                    [
                        name,
                        num(d["structure_compliance"]),
                        num(d["surrogate_compliance"]),
                        num(d["compliance_ratio"], 3),
                        num(d["stiffness_ratio_held"], 3),
                    ]
                    for name, d in conn["directions"].items()
                ],
            )
        )
    both = s.get("replaced_structure_modes") or {}
    if both.get("held"):
        body.append(
            "<p>Modes of the replaced structure held at the interface (a rear joined to the front there "
            "rings in these): each one's effective mass along and inertia about the vehicle axes through "
            "the interface centre, in % of the structure's; where the modes below the crash's "
            "frequencies (a 70 ms pulse: below about 30 Hz) hold little, a rigid rear is right.</p>"
        )
        body.append(_modes_table(both["held"], both["held"]["effective_mass_percent"]))
    if both.get("free"):
        body.append(
            "<p>Free modes of the replaced structure (its interface one rigid body): a rigid rear leaves "
            "them out. Each mode's share of the interface's compliance under inertia relief, and the parts "
            "holding most of its kinetic energy; a slow mode (a period longer than the crash) deflects "
            "little in the crash however much of the static compliance it carries.</p>"
        )
        body.append(_modes_table(both["free"], both["free"].get("compliance_share_percent") or {}))
    body.append(
        "<p>Run time of the steps: " + ", ".join(f"{esc(k)} {v:.1f} s" for k, v in s["seconds"].items()) + "</p>"
    )
    notes = s["notes"] + sur["notes"]
    if notes:
        body.append("<h2>Notes</h2><ul>" + "".join(f"<li>{esc(n)}</li>" for n in notes) + "</ul>")
    return page("crashlite simplified vehicle: the four steps", body)


def _modes_table(modes: dict, percent: dict) -> str:
    """One row per mode: frequency, ``percent`` per direction (blank where
    absent) and the parts it lives in."""
    return table(
        ["mode", "frequency"] + [f"{d} %" for d in DIRECTIONS] + ["where"],
        [
            [j + 1, num(f, 3)]
            + [num(percent[d][j], 3) if d in percent else "" for d in DIRECTIONS]
            + [", ".join(f"{k} {v:.0f} %" for k, v in modes["kinetic_energy_share_percent"][j].items())]
            for j, f in enumerate(modes["frequencies"])
        ],
    )
