"""The crashlite demo: what the toolkit does today, on bundled decks.

Run with ``./demo.sh``. It reads the example deck (parameters, expressions,
an include file), prints what ``crashlite info`` shows, writes the model back
as an LS-DYNA deck in fixed and long format, reads those again and checks
that every value survived.
"""

from __future__ import annotations

import sys
import time
from importlib import resources
from pathlib import Path

from . import read_deck, write_deck
from .keyword.equality import model_differences
from .model.summary import format_summary, summary


def example_deck(name: str = "tube") -> Path:
    return Path(str(resources.files("crashlite") / "examples" / name / f"{name}.k"))


def main(argv: list[str] | None = None) -> int:
    """``[OUT] [--skip-vehicle]``: the stages in order; the last (the
    simplified vehicle on the generic car) takes a few minutes."""
    args = list(argv or [])
    skip_vehicle = "--skip-vehicle" in args
    args = [a for a in args if a != "--skip-vehicle"]
    out = Path(args[0]) if args else Path("out/demo")
    rc = decks(out)
    if rc == 0 and not skip_vehicle:
        rc = vehicle(out)
    return rc


def decks(out: Path) -> int:
    """Stages 1–6: decks in and out, the solver on closed-form cases, the barrier."""
    deck = example_deck()
    print(f"== 1. Read an LS-DYNA keyword deck: {deck.name}\n")
    print(
        "(the very first run compiles crashlite's Numba kernels: about a minute; "
        "they are cached for every later run)\n",
        flush=True,
    )
    t0 = time.perf_counter()
    model = read_deck(deck)
    t_read = time.perf_counter() - t0
    print(format_summary(summary(model)))
    print(f"\n(read in {t_read * 1e3:.1f} ms)")
    print(f"\n== 2. Write it back and read it again ({out}/)\n")
    for fmt in ("fixed", "long", "free"):
        path = out / f"tube_{fmt}.k"
        write_deck(model, path, fmt=fmt)
        again = read_deck(path)
        diff = model_differences(model, again)
        status = "identical" if not diff else "DIFFERS: " + "; ".join(diff)
        print(f"  {fmt:<6} {path}  {path.stat().st_size / 1024:8.1f} KiB  re-read: {status}")
        if diff:
            return 1
    mp = model.mass_properties()
    print("\n== 3. Mass properties of the whole model\n")
    print(f"  mass    {mp.mass:.6g} t")
    print(f"  CoG     ({', '.join(f'{c:.3f}' for c in mp.cog)}) mm")
    print("  inertia about CoG [t·mm²]")
    for row in mp.inertia:
        print("          " + "  ".join(f"{v:12.5g}" for v in row))
    return crash_pulse(out)


def _compare(rows) -> float:
    """Print (quantity, crashlite, analytic) rows; return the worst deviation."""
    print(f"  {'':<26}{'crashlite':>12}{'analytic':>12}{'deviation':>11}")
    worst = 0.0
    for name, got, exact in rows:
        dev = (got - exact) / exact
        worst = max(worst, abs(dev))
        print(f"  {name:<26}{got:12.4g}{exact:12.4g}{dev:10.2%}")
    return worst


def crash_pulse(out: Path) -> int:
    """Run the single-mass crash pulse example and check it against the
    closed-form answer (C = v0·sqrt(m/k), t_m = π/2·sqrt(m/k))."""
    import math

    import numpy as np

    from .solver import run

    deck = example_deck("pulse")
    print(f"\n== 4. Run a deck with the explicit solver: {deck.name} (1263 kg at 56 km/h on a spring)\n")
    model = read_deck(deck)
    res = run(model, out=out / "pulse")
    params = {p.name: p.value for p in model.parameters}
    m, v0, k = params["m"], params["v0"], params["k"]
    u = -res.node_displacement[:, 0, 0]
    a = np.abs(np.gradient(res.node_velocity[:, 0, 0], res.time)) / 9810.0
    rows = [
        ("dynamic crush [mm]", u.max(), v0 * math.sqrt(m / k)),
        ("time of max crush [ms]", 1e3 * res.time[np.argmax(u)], 1e3 * math.pi / 2 * math.sqrt(m / k)),
        ("peak deceleration [g]", a.max(), v0 * math.sqrt(k / m) / 9810.0),
    ]
    worst = _compare(rows)
    ratio = res.energy_ratio
    print(
        f"\n  {res.cycles} cycles of {res.dt * 1e3:.3g} ms in {res.wall_time:.2f} s; energy ratio "
        f"{ratio.min():.5f}..{ratio.max():.5f}; results in {out / 'pulse'}/results.npz"
    )
    if worst >= 0.02:
        return 1
    return impactor(out)


def impactor(out: Path) -> int:
    """A rigid 5 t impactor (moving rigid wall) on a bank of 100 inelastic
    crush springs with a 230 kN plateau, as in a barrier characterisation."""
    import math

    import numpy as np

    from .solver import run

    deck = example_deck("impactor")
    print(f"\n== 5. A rigid impactor on crush springs: {deck.name} (5000 kg at 15 km/h, 230 kN plateau)\n")
    model = read_deck(deck)
    res = run(model, out=out / "impactor")
    p = {q.name: q.value for q in model.parameters}
    m, v0, force, k_total = p["mass"], p["v0"], 100 * p["f"], 100 * p["ku"]
    v = res.wall_velocity[:, 0]
    stroke = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(res.time))])
    rows = [
        ("stroke [mm]", stroke.max(), m * v0**2 / (2 * force)),
        ("time to stop [ms]", 1e3 * res.time[np.argmax(stroke)], 1e3 * m * v0 / force),
        ("plateau force [kN]", np.abs(res.wall_force[:, 0, 0]).max() / 1e3, force / 1e3),
        ("rebound velocity [mm/s]", -v[-1], math.sqrt(force**2 / k_total / m)),
    ]
    worst = _compare(rows)
    print(f"\n  {res.cycles} cycles in {res.wall_time:.2f} s; results in {out / 'impactor'}/")
    return barrier(out) if worst < 0.02 else 1


def barrier(out: Path) -> int:
    """The paper's simplified offset deformable barrier (section 2.1):
    generated, written as an LS-DYNA include, and run under its rigid
    impactor at 40 % overlap."""
    import numpy as np

    from .barrier import Placement, simplified_barrier
    from .barrier.loadcases import Impactor, write_impactor_case
    from .solver import run
    from .verify.filters import filter_signal

    print("\n== 6. The simplified offset deformable barrier (paper section 2.1)\n")
    pl = Placement()
    b = simplified_barrier(placement=pl)
    folder = out / "barrier"
    main = write_impactor_case(folder, b, pl, Impactor(overlap=0.4), end_time=0.03)
    model = read_deck(main)
    print(
        f"  {folder / 'barrier.k'}: {len(model.discretes)} non-linear discrete beams "
        f"({int(np.sum(model.discretes.pid == 1))} main block, {int(np.sum(model.discretes.pid == 2))} bumper), "
        f"{b.shells} cladding shells, {len(model.nodes)} nodes, {b.mass * 1e3:.1f} kg"
    )
    res = run(model, out=folder / "out")
    t, f = filter_signal(res.time, -res.wall_force[:, 0, 0], 60.0)
    dx = res.final_x[:, 0] - model.nodes.xyz[:, 0]
    print(
        f"  rigid impactor 5000 kg at 64 km/h, 40 % overlap, 30 ms: CFC 60 force peak {f.max() / 1e3:.0f} kN, "
        f"deepest intrusion {dx.max():.0f} mm"
    )
    ratio = res.energy_ratio
    print(
        f"  {res.cycles} cycles of {res.dt * 1e3:.3g} ms in {res.wall_time:.2f} s; energy ratio "
        f"{ratio.min():.4f}..{ratio.max():.4f}; results in {folder / 'out'}/"
    )
    return 0 if np.all(np.abs(ratio - 1.0) < 0.02) else 1


def vehicle(out: Path, mesh_size: float = 60.0, end_time: float = 0.07) -> int:
    """The paper's four-step simplified vehicle (section 2.2) on the generic
    car in US NCAP, verified against the full car (section 4)."""
    from .vehicle.workflow import us_ncap_study

    print(f"\n== 7. The simplified vehicle (paper sections 2.2 and 4): generic car, {mesh_size:g} mm shells\n")
    st = us_ncap_study(out / "vehicle", mesh_size=mesh_size, end_time=end_time, twin=True)
    f = st.verification.figures
    fw = f.get("firewall_intrusion") or {}
    ratings = ", ".join(f"{k} {v:.3f}" for k, v in f["energy_ratings_deceleration_phase"].items() if v is not None)
    print(f"  energy ratings over the deceleration phase: {ratings}")
    print(
        f"  crash-box internal energy deviation {f['crash_box_internal_energy_deviation_percent']:+.2f} %; "
        f"firewall intrusion {fw.get('max_intrusion_full', float('nan')):.0f} mm, deviation max "
        f"{fw.get('max_deviation_percent', float('nan')):.1f} %, mean "
        f"{fw.get('mean_deviation_percent', float('nan')):.1f} %"
    )
    if f.get("elastic_twin"):
        from .vehicle.verify.study_report import twin_text

        print(
            "  split by the full car's elastic twin (its structure behind the interface elastic): "
            + twin_text(f["elastic_twin"]).lstrip("; ")
        )
    t = f["time"]
    print(
        f"  time loop {t['full']['wall_time']:.1f} s -> {t['simplified']['wall_time']:.1f} s "
        f"(reduction {t['reduction_percent']:.0f} %); reports: {st.out / 'reduction.html'}, "
        f"{st.out / 'verify' / 'index.html'}"
    )
    from .vehicle.verify.verdict import verdict, verdict_lines

    print("\n  the simplified vehicle against its bounds (US NCAP):")
    for line in verdict_lines(verdict(f)):
        print("    " + line)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
