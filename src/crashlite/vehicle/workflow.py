"""The paper's simplified-vehicle workflow on the generic car, end to end.

``us_ncap_study`` generates the car, runs its US NCAP load case, reduces
it at the interface (steps 1–4), runs the simplified car in the same load
case and verifies it against the full one, writing every deck, results
folder and report under one folder:

    out/car.k, out/usncap.k, out/full/          the full model and its run
    out/simplified.k, out/reduction.{json,html} steps 1–4
    out/usncap_simplified.k, out/simplified/    the simplified run
    out/verify/index.html, summary.json         the verification
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path


@dataclass
class Study:
    out: Path
    reduction: object  # reduce.Reduction
    verification: object  # verification.VehicleVerification
    seconds: dict  # stage -> wall time [s]


def us_ncap_study(out, mesh_size: float = 38.0, end_time: float = 0.08, interface_x: float = -600.0,
                  speed_kmh: float = 56.0, quiet: bool = True, say=print, **reduce_options) -> Study:
    """Full run, reduction, simplified run and verification (module docstring)."""
    from ..solver import run
    from .generic import generic_vehicle
    from .loadcases import usncap_deck
    from .reduce import reduce_vehicle
    from .verification import verify_vehicle

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
    red = reduce_vehicle(car, [out / "full"], load_cases=["US NCAP"], interface=interface_x,
                         axle_parts=["rear axle"], **reduce_options)
    red.write(out / "simplified.k", out)
    seconds["reduction"] = time.perf_counter() - t0
    s = red.summary()
    say(f"  steps 1-4: K = {red.stiffness.stiffness:.5g} N/mm, replaced {red.mass.structure.mass * 1e3:.1f} kg, "
        f"{len(red.surrogate.springs)} springs; {s['model_size']['simplified_elements']} of "
        f"{s['model_size']['full_elements']} elements kept")
    sim_deck = usncap_deck(out / "simplified.k", out / "usncap_simplified.k", speed_kmh=speed_kmh, end_time=end_time)
    t0 = time.perf_counter()
    sim = run(sim_deck, out=out / "simplified", quiet=quiet)
    seconds["simplified run"] = time.perf_counter() - t0
    say(f"  simplified run: {sim.cycles} cycles in {sim.wall_time:.1f} s")
    t0 = time.perf_counter()
    ver = verify_vehicle(out / "full", out / "simplified", full_deck, sim_deck)
    ver.write(out / "verify")
    seconds["verification"] = time.perf_counter() - t0
    return Study(out, red, ver, seconds)
