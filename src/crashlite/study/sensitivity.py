"""Global sensitivity: Morris elementary effects and Sobol indices (SALib).

Morris screening and Saltelli-sampled Sobol indices can run on the deck
itself (their designs are ordinary study designs); Sobol indices of
every response can also be computed on a metamodel fitted to the designs
already run, at no extra run.
"""

from __future__ import annotations

import numpy as np

from .sampling import problem


def morris_points(variables, trajectories: int, levels: int, seed: int) -> np.ndarray:
    """(r·(d+1), d) Morris trajectories in the variables' bounds."""
    from SALib.sample import morris

    return morris.sample(problem(variables), trajectories, num_levels=levels, seed=seed)


def morris_indices(variables, x: np.ndarray, y: np.ndarray, levels: int, seed: int = 0) -> dict:
    """{variable: {mu, mu_star, sigma, mu_star_conf}} of one response.

    x (r·(d+1), d), y (r·(d+1),) with NaN where a run failed: trajectories
    holding a failed run are left out (``trajectories_used`` tells)."""
    from SALib.analyze import morris

    d = len(variables)
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    r = len(y) // (d + 1)
    keep = np.isfinite(y[: r * (d + 1)].reshape(r, d + 1)).all(axis=1)
    if keep.sum() < 2:
        raise ValueError(f"Morris: {int(keep.sum())} complete trajectories; at least 2 are needed")
    rows = np.repeat(keep, d + 1)
    res = morris.analyze(
        problem(variables),
        x[: r * (d + 1)][rows],
        y[: r * (d + 1)][rows],
        num_levels=levels,
        seed=seed,
        print_to_console=False,
    )
    out = {}
    for j, v in enumerate(variables):
        out[v.name] = {k: float(res[k][j]) for k in ("mu", "mu_star", "sigma", "mu_star_conf")}
    out["trajectories_used"] = int(keep.sum())
    return out


def saltelli_points(variables, n: int, seed: int) -> np.ndarray:
    """(n·(d+2), d) Saltelli points for first-order and total indices."""
    from SALib.sample import sobol

    return sobol.sample(problem(variables), n, calc_second_order=False, seed=seed)


def sobol_from_values(variables, y: np.ndarray, seed: int = 0) -> dict:
    """{variable: {S1, S1_conf, ST, ST_conf}} from Saltelli-point values."""
    from SALib.analyze import sobol

    y = np.asarray(y, float)
    if not np.all(np.isfinite(y)):
        raise ValueError(
            f"Sobol: {int((~np.isfinite(y)).sum())} of {len(y)} values are missing (failed runs); "
            f"Saltelli estimates need every point"
        )
    if np.ptp(y) == 0:
        return {v.name: {"S1": 0.0, "S1_conf": 0.0, "ST": 0.0, "ST_conf": 0.0} for v in variables}
    res = sobol.analyze(problem(variables), y, calc_second_order=False, seed=seed, print_to_console=False)
    return {v.name: {k: float(res[k][j]) for k in ("S1", "S1_conf", "ST", "ST_conf")} for j, v in enumerate(variables)}


def sobol_indices(variables, f, n: int = 4096, seed: int = 0) -> dict:
    """Sobol indices of a vectorised function f(x (m, d)) -> (m,) over the
    variables' bounds (a metamodel, or an analytic test function)."""
    x = saltelli_points(variables, n, seed)
    return sobol_from_values(variables, np.asarray(f(x), float), seed)
