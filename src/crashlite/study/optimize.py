"""Optimisation on metamodels: the constrained optimum of the fitted
responses, and the sequential (shrinking-region) plan that verifies it
with runs, as LS-OPT's sequential response-surface method does."""

from __future__ import annotations

import numpy as np

from .config import StudyConfig
from .metamodel import fit
from .sampling import to_bounds, unit_points
from .storage import Design


def fit_responses(cfg: StudyConfig, designs, names=None) -> dict:
    """name -> Metamodel of each response over the complete designs."""
    ok = [d for d in designs if d.status == "complete"]
    x = np.array([[d.values[v.name] for v in cfg.variables] for d in ok], float)
    lo = np.array([v.lower for v in cfg.variables])
    hi = np.array([v.upper for v in cfg.variables])
    out = {}
    for name in names or cfg.responses:
        y = np.array([d.responses.get(name, np.nan) for d in ok], float)
        out[name] = fit(x, y, lo, hi, cfg.metamodel)
    return out


def metamodel_optimum(cfg: StudyConfig, models: dict, lower=None, upper=None, seed: int = 0):
    """(x (d,), predicted objective, predicted feasible) of the first
    objective on the metamodels, within [lower, upper] (default the
    bounds), subject to the constraints (penalised where no point meets
    them)."""
    from scipy.optimize import differential_evolution

    lo = np.array([v.lower for v in cfg.variables]) if lower is None else np.asarray(lower, float)
    hi = np.array([v.upper for v in cfg.variables]) if upper is None else np.asarray(upper, float)
    obj = cfg.objectives[0]
    sign = 1.0 if obj.goal == "minimize" else -1.0
    scale = max(abs(float(np.mean(models[obj.response].predict(0.5 * (lo + hi))))), 1e-12)

    def violation(x):
        v = 0.0
        for c in cfg.constraints:
            y = float(models[c.response].predict(x)[0])
            v += sum(max(0.0, e) for e in c.violations(y))
        return v

    def f(x):
        return sign * float(models[obj.response].predict(x)[0]) / scale + 1e3 * violation(x)

    res = differential_evolution(f, list(zip(lo, hi)), seed=seed, tol=1e-8, maxiter=300, polish=True)
    x = np.clip(res.x, lo, hi)
    return x, float(models[obj.response].predict(x)[0]), violation(x) <= 1e-9


def metamodel_step(cfg: StudyConfig, designs, k: int, points: int) -> list:
    """Plan of iteration k: [(key, values)] — the metamodel optimum and
    points-1 Latin hypercube designs in a region around the best design so
    far, shrunk by ``shrink``**k (at the start, the whole space)."""
    opt = cfg.optimization
    names = [v.name for v in cfg.variables]
    lo = np.array([v.lower for v in cfg.variables])
    hi = np.array([v.upper for v in cfg.variables])
    d = len(names)
    ok = [x for x in designs if x.status == "complete"]
    need = d + 2
    plan = []
    if len(ok) < need:  # too few designs for a metamodel: a space-filling start
        pts = to_bounds(unit_points("lhs", max(points, need - len(ok)), d, opt.seed + 1000 + k), cfg.variables)
        return [(f"mm-{k:02d}-{j:02d}", dict(zip(names, map(float, p)))) for j, p in enumerate(pts)]
    models = fit_responses(cfg, ok, [cfg.objectives[0].response] + [c.response for c in cfg.constraints])
    best, _ = best_design(cfg, ok)
    centre = np.array([best.values[n] for n in names]) if best is not None else 0.5 * (lo + hi)
    half = 0.5 * (hi - lo) * opt.shrink**k
    rlo = np.clip(centre - half, lo, hi)
    rhi = np.clip(centre + half, lo, hi)
    x, _, _ = metamodel_optimum(cfg, models, rlo, rhi, seed=opt.seed + k)
    plan.append((f"mm-{k:02d}-00", dict(zip(names, map(float, x)))))
    if points > 1:
        u = unit_points("lhs", points - 1, d, opt.seed + 1000 + k)
        pts = rlo + u * (rhi - rlo)
        for j, p in enumerate(pts, start=1):
            plan.append((f"mm-{k:02d}-{j:02d}", dict(zip(names, map(float, p)))))
    return plan


def best_design(cfg: StudyConfig, designs: list[Design]):
    """(best feasible design of the first objective, number of feasible
    Pareto-optimal designs)."""
    ok = [d for d in designs if d.status == "complete" and d.feasible is not False]
    if not cfg.objectives or not ok:
        return None, 0
    o = cfg.objectives[0]
    sign = 1.0 if o.goal == "minimize" else -1.0
    best = min(ok, key=lambda d: sign * d.responses[o.response])
    return best, len(pareto(cfg, ok))


def pareto(cfg: StudyConfig, designs: list[Design]) -> list[Design]:
    """The non-dominated designs among ``designs`` (objectives only)."""
    if not cfg.objectives:
        return []
    signs = np.array([1.0 if o.goal == "minimize" else -1.0 for o in cfg.objectives])
    f = np.array([[d.responses[o.response] for o in cfg.objectives] for d in designs]) * signs
    keep = []
    for i in range(len(designs)):
        dominated = np.any(np.all(f <= f[i], axis=1) & np.any(f < f[i], axis=1))
        if not dominated:
            keep.append(designs[i])
    return keep
