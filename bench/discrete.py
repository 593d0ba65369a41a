"""Discrete-element throughput of the explicit solver.

A chain of N springs with lumped masses (grounded at one end, moving end
pulled by an initial velocity), run for a fixed number of cycles on 1 and on
2 threads in the same process. Prints cycles per second, ns per
spring-cycle for the whole cycle (forces, assembly, update, energy) and the
2-thread speed-up. The set-up of a run (incidence, part accounting) is
measured apart: a run of cycles/10 cycles is subtracted. Usage::

    python bench/discrete.py [--springs 100000] [--cycles 200]
"""

from __future__ import annotations

import argparse
import time

import numba
import numpy as np

from crashlite.solver import integrate
from crashlite.solver.discretes import Discrete
from crashlite.solver.kernels.discrete import LINEAR
from crashlite.solver.setup import Setup


def chain(n: int, cycles: int) -> Setup:
    nodes = n + 1
    x0 = np.zeros((nodes, 3))
    x0[:, 0] = np.arange(nodes) * 10.0
    v0 = np.zeros((nodes, 3))
    v0[-1, 0] = 1000.0
    mass = np.full(nodes, 1e-3)
    fixed = np.zeros((nodes, 3), bool)
    fixed[0] = True
    z = np.zeros(n)
    d = Discrete(
        np.arange(1, n + 1),
        np.arange(n, dtype=np.int64),
        np.arange(1, n + 1, dtype=np.int64),
        np.full(n, LINEAR, np.int64),
        np.full(n, 100.0),
        np.ones(n),
        z.copy(),
        np.full(n, 10.0),
        np.zeros((n, 3)),
        x0[:-1].copy(),
        np.zeros(n, np.int64),
        np.zeros(n, np.int64),
        np.zeros(0),
        np.zeros(0),
        np.zeros(n, np.int64),
    )
    s = Setup(x0, v0, mass, fixed, d)
    s.end_cycle = cycles
    s.end_time = 1.0
    return s


def _run(n: int, cycles: int) -> float:
    s = chain(n, cycles)
    t = time.perf_counter()
    res = integrate(s, output_dt=1.0)
    elapsed = time.perf_counter() - t
    assert res.cycles == cycles
    return elapsed


def timed(n: int, cycles: int, threads: int) -> tuple[float, float]:
    """(seconds per cycle, set-up seconds) on ``threads`` threads."""
    numba.set_num_threads(threads)
    integrate(chain(1000, 5))  # compile / warm up
    short = max(cycles // 10, 1)
    t_short, t_long = _run(n, short), _run(n, cycles)
    per_cycle = (t_long - t_short) / (cycles - short)
    return per_cycle, t_long - per_cycle * cycles


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--springs", type=int, default=100_000)
    ap.add_argument("--cycles", type=int, default=200)
    args = ap.parse_args()
    n, c = args.springs, args.cycles
    results = {}
    for threads in sorted({1, min(2, numba.config.NUMBA_NUM_THREADS)}):
        e, setup = timed(n, c, threads)
        results[threads] = e
        print(
            f"{threads} thread(s): {1 / e:8.1f} cycles/s  {e / n * 1e9:7.1f} ns per spring-cycle "
            f"({n:,} springs, {c} cycles; set-up {setup:.3f} s)"
        )
    if 2 in results:
        print(
            f"2-thread speed-up: {results[1] / results[2]:.2f}x  (targets: <= 20 ns per spring-cycle, speed-up >= 1.6)"
        )


if __name__ == "__main__":
    main()
