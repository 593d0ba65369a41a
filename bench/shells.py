"""Shell throughput of the explicit solver, with self-contact.

An array of square steel tubes (Belytschko–Lin–Tsay shells, MAT_024,
NIP 5 (``--nip``), IHQ 4) standing side by side a few millimetres apart, struck by a
moving rigid wall, all parts in one *CONTACT_AUTOMATIC_SINGLE_SURFACE: by
default 8 x 8 tubes of 1600 shells, 102 400 shells. The deck is written and
read once; each run builds a fresh Setup and integrates a fixed number of
cycles on 1 and on 2 threads in the same process (Numba compiled before
any timing). The set-up of a run (incidence, first search) is measured
apart: a run of cycles/10 cycles is subtracted. Prints µs per
element-cycle for the whole cycle, per group (shells, contact, rest of the
loop), the contact share and the 2-thread speed-up. Usage::

    python bench/shells.py [--tubes 8] [--cycles 300] [--nip 5]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numba
import numpy as np

from crashlite import read_deck
from crashlite.solver import integrate, setup

C, T, H_EL, LENGTH, GAP = 50.0, 1.5, 5.0, 200.0, 2.0  # tube side, thickness, element size, length, gap [mm]
V0 = 10000.0  # wall speed [mm/s]


def tube_array(n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Nodes (k, 3), shells (m, 4) 0-based and part of each shell (m,) of
    n x n tubes along z (z = 0 to LENGTH)."""
    ns, nz = int(round(C / H_EL)), int(round(LENGTH / H_EL))
    a = np.arange(ns) * (C / ns) - C / 2
    half = np.full(ns, C / 2)
    ring = np.concatenate([np.stack(p, 1) for p in ((a, -half), (half, a), (-a, half), (-half, -a))])
    nr = len(ring)
    z = np.linspace(0.0, LENGTH, nz + 1)
    one = np.concatenate([np.column_stack([ring, np.full(nr, zk)]) for zk in z])
    j, i = np.divmod(np.arange(nz * nr), nr)
    quad = np.stack([j * nr + i, j * nr + (i + 1) % nr, (j + 1) * nr + (i + 1) % nr, (j + 1) * nr + i], 1)
    xyz, conn, pid = [], [], []
    for k in range(n * n):
        cx, cy = divmod(k, n)
        xyz.append(one + [cx * (C + GAP), cy * (C + GAP), 0.0])
        conn.append(quad + k * len(one))
        pid.append(np.full(len(quad), k + 1))
    return np.concatenate(xyz), np.concatenate(conn), np.concatenate(pid)


def write_deck(path: Path, n: int, cycles: int, nip: int = 5) -> int:
    """The deck of n x n tubes run for ``cycles`` cycles (``nip`` points
    through the thickness); its shell count."""
    xyz, conn, pid = tube_array(n)
    nodes = np.arange(1, len(xyz) + 1)
    bottom = nodes[np.abs(xyz[:, 2]) < 1e-9]
    with open(path, "w") as f:
        f.write("*KEYWORD\n*NODE\n")
        f.write("\n".join(f"{i},{x:.6f},{y:.6f},{z:.6f}" for i, (x, y, z) in zip(nodes, xyz)))
        f.write("\n*ELEMENT_SHELL\n")
        rows = np.column_stack([np.arange(1, len(conn) + 1), pid, conn + 1])
        f.write("\n".join(",".join(map(str, r)) for r in rows.tolist()))
        f.write("\n")
        for p in range(1, n * n + 1):
            f.write(f"*PART\ntube {p}\n{p},1,1,0,1\n")
        f.write(
            f"*SECTION_SHELL\n1,2,0.8333,{nip}\n{T},{T},{T},{T}\n"
            "*MAT_PIECEWISE_LINEAR_PLASTICITY\n1,7.85e-9,210000.0,0.3,250.0,1.0\n0,0,0,0\n"
            "*HOURGLASS\n1,4,0.05\n"
            "*SET_NODE_LIST\n1\n"
            + "\n".join(",".join(map(str, bottom[k : k + 8])) for k in range(0, len(bottom), 8))
            + "\n"
            "*BOUNDARY_SPC_SET\n1,0,1,1,1,1,1,1\n"
            f"*RIGIDWALL_PLANAR_MOVING\n0\n0,0,{LENGTH + 0.01},0,0,{LENGTH - 1.0}\n1.0,{V0}\n"
            "*CONTACT_AUTOMATIC_SINGLE_SURFACE\n0,0,0\n\n\n"
            f"*CONTROL_TERMINATION\n1.0,{cycles}\n*END\n"
        )
    return len(conn)


class _Clock:
    """Wall time spent in the forces of each group kind."""

    def __init__(self, s):
        self.spent: dict[str, float] = {}
        for g in s.groups:
            g.forces = self._wrap(g.forces, g.kind)

    def _wrap(self, fn, kind):
        def timed(st):
            t0 = time.perf_counter()
            fn(st)
            self.spent[kind] = self.spent.get(kind, 0.0) + time.perf_counter() - t0

        return timed


def _run(model, cycles: int) -> tuple[float, float, dict]:
    """(wall seconds, CPU seconds of the process, wall seconds by group kind)
    of ``cycles`` cycles of a fresh Setup."""
    s = setup.build(model)
    s.end_cycle = cycles
    clock = _Clock(s)
    t, c = time.perf_counter(), time.process_time()
    res = integrate(s, output_dt=1.0)
    elapsed, cpu = time.perf_counter() - t, time.process_time() - c
    assert res.cycles == cycles and not res.info["stopped"], res.info["stopped"]
    return elapsed, cpu, clock.spent


def timed(model, cycles: int, threads: int) -> dict:
    """Seconds per cycle (wall, CPU of all threads, by group kind) and the
    set-up seconds of a run, on ``threads`` threads."""
    numba.set_num_threads(threads)
    short = max(cycles // 10, 1)
    t_short, c_short, g_short = _run(model, short)
    t_long, c_long, g_long = _run(model, cycles)
    per_cycle = (t_long - t_short) / (cycles - short)
    return dict(
        wall=per_cycle,
        cpu=(c_long - c_short) / (cycles - short),
        set_up=t_long - per_cycle * cycles,
        groups={k: (g_long[k] - g_short.get(k, 0.0)) / (cycles - short) for k in g_long},
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tubes", type=int, default=8, help="tubes per row (n x n tubes of 1600 shells)")
    ap.add_argument("--cycles", type=int, default=300)
    ap.add_argument("--nip", type=int, default=5, help="integration points through the thickness (car decks: 2-3)")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        write_deck(Path(tmp) / "warm.k", 1, 20)
        _run(read_deck(Path(tmp) / "warm.k"), 20)  # compile before any timing
        path = Path(tmp) / "tubes.k"
        t0 = time.perf_counter()
        n = write_deck(path, args.tubes, args.cycles, args.nip)
        model = read_deck(path)
        print(
            f"{args.tubes}x{args.tubes} tubes: {n:,} shells (NIP {args.nip}), {len(model.nodes):,} nodes "
            f"(deck written and read in {time.perf_counter() - t0:.1f} s)"
        )
    results = {}
    for threads in sorted({1, min(2, numba.config.NUMBA_NUM_THREADS)}):
        r = timed(model, args.cycles, threads)
        results[threads] = r["wall"]
        us = r["wall"] / n * 1e6
        rest = r["wall"] - sum(r["groups"].values())
        parts = "  ".join(f"{k} {v / n * 1e6:.3f}" for k, v in r["groups"].items())
        print(
            f"{threads} thread(s): {us:.3f} µs per element-cycle, {us * threads:.3f} per element-cycle-core "
            f"(CPU {r['cpu'] / n * 1e6:.3f}; by group: {parts}  rest {rest / n * 1e6:.3f}); contact share "
            f"{r['groups'].get('contact', 0.0) / r['wall']:.1%}; {args.cycles} cycles, set-up {r['set_up']:.1f} s"
        )
    if 2 in results:
        print(
            f"2-thread speed-up: {results[1] / results[2]:.2f}x  (targets: <= 0.5 µs per element-cycle-core, "
            "contact share <= 30 %, speed-up >= 1.7)"
        )
    print(
        "wall-clock figures; the CPU time counts every thread (waiting ones too). On a machine shared with "
        "other jobs the wall figures grow and the speed-up shrinks."
    )


if __name__ == "__main__":
    main()
