"""The paper's simplified-vehicle workflow on the generic car, end to end.

``us_ncap_study`` generates the car, runs its US NCAP load case, proposes
an interface from that run (``interface.propose_interface``, reported
beside the one used), reduces it at the interface (steps 1–4), runs the
simplified car in the same load case and verifies it against the full
one, writing every deck, results folder and report under one folder:

    out/car.k, out/usncap.k, out/full/          the full model and its run
    out/interface.json                          the interface proposal
    out/simplified.k, out/reduction.{json,html} steps 1–4
    out/usncap_simplified.k, out/simplified/    the simplified run
    out/verify/index.html, summary.json         the verification
    out/twin.k, out/usncap_twin.k, out/twin/    with ``twin``: the elastic twin and its run

With ``twin`` the full model's elastic twin (``vehicle.connection.twin``: the
structure behind the interface elastic) runs in the same load case, and
the verification splits its deviations into the elastic premise's and the
surrogate's (``elastic_twin`` in summary.json).
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path


@dataclass
class Study:
    out: Path
    reduction: object  # reduce.Reduction
    verification: object  # verification.VehicleVerification
    seconds: dict  # stage -> wall time [s]
    proposal: object = None  # interface.InterfaceProposal from the full run


def us_ncap_study(
    out: Path | str,
    mesh_size: float = 38.0,
    end_time: float = 0.08,
    interface_x: float = -600.0,
    speed_kmh: float = 56.0,
    quiet: bool = True,
    say: Callable[[str], None] = print,
    twin: bool = False,
    **reduce_options,
) -> Study:
    """Full run, reduction, simplified run and verification (module docstring)."""
    from ..report.build import jsonable
    from ..solver import run
    from .car.generic import generic_vehicle
    from .car.loadcases import usncap_deck
    from .connection.interface import propose_interface
    from .reduce import reduce_vehicle
    from .verify.verification import verify_vehicle

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    seconds = {}
    t0 = time.perf_counter()
    v = generic_vehicle(mesh_size, interface_x=interface_x)
    car = v.write(out / "car.k")
    full_deck = usncap_deck(car, out / "usncap.k", speed_kmh=speed_kmh, end_time=end_time)
    seconds["generate"] = time.perf_counter() - t0
    say(f"  generic car: {v.shells} shells, {v.mass:.0f} kg; US NCAP {speed_kmh:g} km/h, {end_time * 1e3:g} ms")
    t0 = time.perf_counter()
    full = run(full_deck, out=out / "full", quiet=quiet)
    seconds["full run"] = time.perf_counter() - t0
    say(f"  full run: {full.cycles} cycles in {full.wall_time:.1f} s")
    t0 = time.perf_counter()
    prop = propose_interface(v.model, out / "full", also=(v.interface_x,))
    (out / "interface.json").write_text(json.dumps(jsonable(prop.summary()), indent=1) + "\n")
    seconds["interface proposal"] = time.perf_counter() - t0
    at = next(c for c in prop.candidates if c["x"] == v.interface_x)
    said = next((c for c in prop.candidates if c["x"] == prop.x), None)
    say(
        "  interface proposal: "
        + (
            f"x = {prop.x:.0f} mm ({said['energy_behind_percent']:.2f} % of the absorbed "
            f"energy and {said['strained_area_percent_behind']:.2f} % of the area strained "
            f"beyond {100 * prop.strain:g} % behind it, {said['replaced_elements_percent']:.0f} % "
            "of the elements replaced)"
            if said
            else "none (" + prop.notes[-1] + ")"
        )
        + f"; at the interface used, x = {at['x']:.0f}: {at['energy_behind_percent']:.2f} % and "
        f"{at['strained_area_percent_behind']:.2f} %"
        + (
            f", the cut bends up to {at['interface_warping_max']:.1f} mm out of a rigid motion (rms "
            f"{at['interface_warping_rms']:.1f})"
            if "interface_warping_max" in at
            else ""
        )
    )
    t0 = time.perf_counter()
    red = reduce_vehicle(
        car, [out / "full"], load_cases=["US NCAP"], interface=v.interface_x, axle_parts=["rear axle"], **reduce_options
    )
    red.write(out / "simplified.k", out)
    seconds["reduction"] = time.perf_counter() - t0
    s = red.summary()
    worst = (red.connection or {}).get("largest_compliance_misfit")
    c = red.condensation or {}
    if red.connection_kind == "springs":
        joined = f"{len(red.surrogate.springs)} springs"
    elif red.connection_kind == "craig-bampton":
        joined = (
            f"the structure a Craig-Bampton superelement on {c['cut_nodes']} cut nodes with {c['modes']} held modes"
        )
    else:
        joined = f"the structure condensed on {c['nodes']} cut nodes"
    say(
        f"  steps 1-4: K = {red.stiffness.stiffness:.5g} N/mm borne at the axle, {red.relief.stiffness:.5g} under "
        f"inertia relief, replaced {red.mass.structure.mass * 1e3:.1f} kg, "
        f"{joined}; {s['model_size']['simplified_elements']} of "
        f"{s['model_size']['full_elements']} elements kept"
        + (
            f"; held rigid, the connection against the structure misfits most in {worst['direction']} (compliance "
            f"x{worst['ratio']:.2g})"
            if worst
            else ""
        )
    )
    sim_deck = usncap_deck(out / "simplified.k", out / "usncap_simplified.k", speed_kmh=speed_kmh, end_time=end_time)
    t0 = time.perf_counter()
    sim = run(sim_deck, out=out / "simplified", quiet=quiet)
    seconds["simplified run"] = time.perf_counter() - t0
    say(f"  simplified run: {sim.cycles} cycles in {sim.wall_time:.1f} s")
    twin_run = (
        _twin_run(
            red.cut,
            out / "twin.k",
            out / "twin",
            lambda car_deck: usncap_deck(car_deck, out / "usncap_twin.k", speed_kmh=speed_kmh, end_time=end_time),
            quiet,
            say,
        )
        if twin
        else {}
    )
    t0 = time.perf_counter()
    ver = verify_vehicle(out / "full", out / "simplified", full_deck, sim_deck, **twin_run)
    ver.write(out / "verify")
    seconds["verification"] = time.perf_counter() - t0
    return Study(out, red, ver, seconds, prop)


def _twin_run(cut, car_path: Path, results: Path, load_case, quiet: bool, say) -> dict:
    """Write the elastic twin of ``cut`` to ``car_path``, its load-case deck
    (``load_case(car deck) -> deck``) and run it into ``results``: the
    ``twin``, ``twin_deck`` arguments of ``verify_vehicle``."""
    from ..keyword.writer import write_deck
    from ..solver import run
    from .connection.twin import elastic_twin

    tw = elastic_twin(cut)
    deck = load_case(write_deck(tw.model, car_path)[0])
    r = run(deck, out=results, quiet=quiet)
    s = tw.summary()
    say(
        f"  elastic twin: {s['elements_made_elastic']} elements behind the interface elastic; {r.cycles} cycles "
        f"in {r.wall_time:.1f} s"
    )
    return {"twin": results, "twin_deck": deck}


@dataclass
class PaperStudy:
    """Both load cases of the paper, one surrogate (``paper_study``)."""

    out: Path
    reduction: object  # reduce.Reduction
    verifications: dict  # "US NCAP", "Euro NCAP ODB" -> verification.VehicleVerification
    runs: dict  # run name -> {"deck", "results", "loop_time", "cycles", "elements"}
    summary: dict  # time reductions and the verification figures (summary.json)


ODB_RUNS = {  # run name -> (vehicle, barrier)
    "odb full car, detailed barrier": ("full", "detailed"),
    "odb full car, simplified barrier": ("full", "simplified"),
    "odb simplified car, detailed barrier": ("simplified", "detailed"),
    "odb simplified car, simplified barrier": ("simplified", "simplified"),
}


def _slug(name: str) -> str:
    return name.replace(",", "").replace(" ", "_")


def paper_study(
    out: Path | str,
    mesh_size: float = 38.0,
    barrier_size: float = 50.0,
    barrier_options: dict | None = None,
    beams: dict | None = None,
    usncap_end: float = 0.08,
    odb_end: float = 0.1,
    interface_x: float = -600.0,
    shares: str = "combined",
    variants: bool = True,
    quiet: bool = True,
    say: Callable[[str], None] = print,
    twin: bool = False,
    front: str = "generic",
    **reduce_options,
) -> PaperStudy:
    """The paper's whole verification on the generic car, in one folder:

    1. full runs: US NCAP (56 km/h, rigid wall) and Euro NCAP ODB (64 km/h,
       40 %) against the detailed barrier (honeycomb solids of
       ``barrier_size`` mm; ``barrier_options``: the rest of
       ``detailed_barrier``'s, e.g. finer rows and columns; ``beams``:
       ``simplified_barrier``'s options, e.g. its grid);
    2. one reduction at ``interface_x`` from both runs (``shares``:
       "combined", the mean of the load cases' shares, or one load case's
       name), its deviation from each load case's own shares reported;
    3. simplified runs: US NCAP, and ODB against the simplified barrier;
       with ``variants`` also the two ODB runs with one simplification
       each (full car + simplified barrier, simplified car + detailed
       barrier), which tell the time each simplification saves (the
       paper's figures 25–27);
    4. verification of each load case (full against simplified, full car
       + detailed barrier against simplified car + simplified barrier;
       with ``variants`` also each simplification on its own in ODB), and
       the time reductions, in ``summary.json`` and ``index.html``;
    5. with ``twin``, the full car's elastic twin in US NCAP, which splits
       that verification's deviations into the elastic premise's and the
       surrogate's (``us_ncap_study``).

    ``front``: the generic car's bumper beam ("stiff": the second front a
    barrier is checked under, ``car.body.FRONTS``).
    """
    from ..solver import run
    from ..verify.hourglass import results_share
    from ..verify.timing import reduction as time_reduction
    from .car.generic import generic_vehicle
    from .car.loadcases import odb_deck, usncap_deck
    from .reduce import reduce_vehicle
    from .verify.verification import verify_vehicle

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    v = generic_vehicle(mesh_size, interface_x=interface_x, front=front)
    car = v.write(out / "car.k")
    say(
        f"  generic car: {v.shells} shells, {v.mass:.0f} kg at {mesh_size:g} mm; detailed barrier "
        f"{barrier_size:g} mm; US NCAP {usncap_end * 1e3:g} ms, ODB {odb_end * 1e3:g} ms"
    )
    runs: dict = {}

    def go(name: str, deck: Path) -> Path:
        folder = out / "runs" / _slug(name)
        r = run(deck, out=folder, quiet=quiet)
        runs[name] = {
            "deck": deck,
            "results": folder,
            "loop_time": r.loop_time,
            "cycles": r.cycles,
            "elements": int(sum((r.info.get("elements") or {}).values())),
            "hourglass": results_share(r),
            # shells and solids deleted by the end (a torn honeycomb element is deleted, its crush with it)
            "deleted": r.deleted(),
        }
        hg = runs[name]["hourglass"]
        share = f", hourglass {hg['end_percent']:.1f} % of the internal energy" if hg.get("end_percent") else ""
        say(f"  {name}: {r.cycles} cycles, time loop {r.loop_time:.1f} s{share}")
        return folder

    def odb(vehicle_deck: Path, barrier: str, name: str) -> Path:
        return odb_deck(
            vehicle_deck,
            out / f"{_slug(name)}.k",
            barrier=barrier,
            end_time=odb_end,
            element_size=barrier_size,
            honeycomb=barrier_options,
            beams=beams,
        )

    decks = {"usncap full": usncap_deck(car, out / "usncap_full.k", end_time=usncap_end)}
    go("usncap full", decks["usncap full"])
    first = "odb full car, detailed barrier"
    decks[first] = odb(car, "detailed", first)
    go(first, decks[first])
    red = reduce_vehicle(
        car,
        [runs["usncap full"]["results"], runs[first]["results"]],
        load_cases=["US NCAP", "Euro NCAP ODB"],
        interface=v.interface_x,
        axle_parts=["rear axle"],
        shares=shares,
        **reduce_options,
    )
    simplified = out / "simplified.k"
    red.write(simplified, out)
    s = red.summary()
    say(
        f"  steps 1-4 ({s['shares_used']['basis']} shares): K = {red.stiffness.stiffness:.5g} N/mm borne at the "
        f"axle, {red.relief.stiffness:.5g} under inertia relief (springs: {red.springs}), "
        f"{s['model_size']['simplified_elements']} of {s['model_size']['full_elements']} elements kept"
    )
    decks["usncap simplified"] = usncap_deck(simplified, out / "usncap_simplified.k", end_time=usncap_end)
    go("usncap simplified", decks["usncap simplified"])
    for name, (vehicle, barrier) in ODB_RUNS.items():
        if name == first or (not variants and vehicle != barrier):
            continue
        decks[name] = odb(car if vehicle == "full" else simplified, barrier, name)
        go(name, decks[name])
    twin_run = (
        _twin_run(
            red.cut,
            out / "twin.k",
            out / "runs" / "usncap_twin",
            lambda car_deck: usncap_deck(car_deck, out / "usncap_twin.k", end_time=usncap_end),
            quiet,
            say,
        )
        if twin
        else {}
    )
    ver = {
        "US NCAP": verify_vehicle(
            runs["usncap full"]["results"],
            runs["usncap simplified"]["results"],
            decks["usncap full"],
            decks["usncap simplified"],
            load_case="US NCAP",
            **twin_run,
        )
    }
    last = "odb simplified car, simplified barrier"
    ver["Euro NCAP ODB"] = verify_vehicle(
        runs[first]["results"],
        runs[last]["results"],
        decks[first],
        decks[last],
        load_case="Euro NCAP ODB",
        names=("full + detailed barrier", "simplified + simplified barrier"),
    )
    if variants:  # each simplification on its own: the car on the same detailed barrier, the barrier under the full car
        mixed = {
            "Euro NCAP ODB, vehicle only": ("odb simplified car, detailed barrier", ("full car", "simplified car")),
            "Euro NCAP ODB, barrier only": (
                "odb full car, simplified barrier",
                ("detailed barrier", "simplified barrier"),
            ),
        }
        for case, (other, names) in mixed.items():
            ver[case] = verify_vehicle(
                runs[first]["results"], runs[other]["results"], decks[first], decks[other], load_case=case, names=names
            )
    for name, vv in ver.items():
        vv.write(out / "verify" / _slug(name.lower()))
    loop = {k: r["loop_time"] for k, r in runs.items()}  # the time compared (verify.timing: the time loop)
    times = {
        "us_ncap": {
            "full_s": loop["usncap full"],
            "simplified_s": loop["usncap simplified"],
            "vehicle_reduction_percent": time_reduction(loop["usncap full"], loop["usncap simplified"]),
        },
        "odb": {
            "full_car_detailed_barrier_s": loop[first],
            "simplified_car_simplified_barrier_s": loop[last],
            "combined_reduction_percent": time_reduction(loop[first], loop[last]),
        },
    }
    if variants:
        times["odb"].update(
            {
                "full_car_simplified_barrier_s": loop["odb full car, simplified barrier"],
                "simplified_car_detailed_barrier_s": loop["odb simplified car, detailed barrier"],
                "barrier_reduction_percent": time_reduction(loop[first], loop["odb full car, simplified barrier"]),
                "vehicle_reduction_percent": time_reduction(loop[first], loop["odb simplified car, detailed barrier"]),
            }
        )
    summary = {
        "mesh_size": mesh_size,
        "front": front,
        "barrier_element_size": barrier_size,
        "barrier_options": dict(barrier_options or {}),
        "simplified_barrier_options": dict(beams or {}),
        "interface_x": v.interface_x,
        "shares": s["shares_used"],
        "time": times,
        "runs": {
            k: {
                "loop_time_s": r["loop_time"],
                "cycles": r["cycles"],
                "elements": r["elements"],
                "hourglass_percent": r["hourglass"],
                "deleted_elements": r["deleted"],
            }
            for k, r in runs.items()
        },
        "verification": {k: vv.figures for k, vv in ver.items()},
    }
    from ..report.build import jsonable

    (out / "summary.json").write_text(json.dumps(jsonable(summary), indent=1, allow_nan=False) + "\n")
    from .verify.study_report import study_page

    links = {
        "reduction (steps 1-4)": "reduction.html",
        **{f"verification {k}": f"verify/{_slug(k.lower())}/index.html" for k in ver},
    }
    (out / "index.html").write_text(study_page(jsonable(summary), links))
    return PaperStudy(out, red, ver, runs, summary)
