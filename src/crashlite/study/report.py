"""The study report: figures, summary.json and the best design's deck.

Figures (PNG): parallel coordinates of every complete design (variables
and responses, coloured by the first objective, infeasible ones grey),
objective/constraint scatter plots, each response against each variable
(with the metamodel's main effect), the Pareto front (two or more
objectives) or the optimisation history (one), sensitivity indices and the
metamodels' leave-one-out check. summary.json holds every figure's data
in numbers: designs, best design, Pareto set, metamodel quality, indices.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from .config import StudyConfig
from .runner import best_design, pareto
from .storage import Design, StudyStore


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _finite(v):
    if isinstance(v, float) and not math.isfinite(v):
        return None
    if isinstance(v, dict):
        return {k: _finite(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_finite(x) for x in v]
    if isinstance(v, np.generic):
        return _finite(v.item())
    return v


def build_report(cfg: StudyConfig, out=None) -> dict:
    """Write the report of a study into ``out`` (default
    <study folder>/report); returns the summary (also summary.json)."""
    out = Path(out) if out is not None else cfg.directory / "report"
    out.mkdir(parents=True, exist_ok=True)
    store = StudyStore(cfg, readonly=True)
    designs = store.designs()
    latest: dict[str, Design] = {}
    for d in designs:  # the last trial of each design key (reruns)
        latest[d.key] = d
    designs = list(latest.values())
    ok = [d for d in designs if d.status == "complete"]
    best, _ = best_design(cfg, ok)
    front = pareto(cfg, [d for d in ok if d.feasible is not False]) if cfg.objectives else []
    summary = {
        "study": cfg.name,
        "study_file": str(cfg.path),
        "deck": str(cfg.deck),
        "storage": cfg.storage,
        "variables": [v.describe() | {"baseline": v.baseline} for v in cfg.variables],
        "responses": {k: r.describe() for k, r in cfg.responses.items()},
        "objectives": [{"response": o.response, "goal": o.goal} for o in cfg.objectives],
        "constraints": [{"response": c.response, "lower": c.lower, "upper": c.upper} for c in cfg.constraints],
        "counts": _counts(designs),
        "designs": [_design_row(d) for d in sorted(designs, key=lambda d: d.key)],
        "best": _design_row(best) if best else None,
        "pareto": [d.key for d in front],
        "figures": [],
        "metamodels": {},
        "sensitivity": {},
        "notes": [],
    }
    figures = summary["figures"]
    models = {}
    if len(ok) >= len(cfg.variables) + 2:
        from .optimize import fit_responses

        for name in cfg.responses:
            try:
                models[name] = fit_responses(cfg, ok, [name])[name]
                summary["metamodels"][name] = models[name].describe()
            except (ValueError, np.linalg.LinAlgError) as e:
                summary["notes"].append(f"metamodel of {name}: {e}")
    else:
        summary["notes"].append(f"{len(ok)} complete designs: metamodels need at least {len(cfg.variables) + 2}")
    summary["sensitivity"] = _sensitivity(cfg, designs, models, summary["notes"])
    if ok:
        figures.append(_parallel(cfg, ok, out / "parallel_coordinates.png"))
        figures.append(_vs_variables(cfg, ok, models, out / "responses_vs_variables.png"))
        f = _scatter(cfg, ok, best, out / "scatter.png")
        if f:
            figures.append(f)
        if len(cfg.objectives) >= 2:
            figures.append(_pareto(cfg, ok, front, out / "pareto_front.png"))
        if cfg.objectives:
            figures.append(_history(cfg, designs, out / "history.png"))
    if models:
        figures.append(_loo(cfg, ok, models, out / "metamodels.png"))
    if summary["sensitivity"]:
        figures.append(_sens_figure(cfg, summary["sensitivity"], out / "sensitivity.png"))
    if best is not None:
        summary["best_deck"] = _best_deck(cfg, best, out, summary["notes"])
    (out / "summary.json").write_text(json.dumps(_finite(summary), indent=2))
    return summary


def _counts(designs) -> dict:
    c = {"designs": len(designs)}
    for s in ("complete", "failed", "running", "interrupted", "waiting"):
        c[s] = sum(d.status == s for d in designs)
    c["feasible"] = sum(d.status == "complete" and d.feasible is not False for d in designs)
    by_phase = {}
    for d in designs:
        p = by_phase.setdefault(d.phase, {"complete": 0, "failed": 0, "other": 0})
        p[d.status if d.status in ("complete", "failed") else "other"] += 1
    c["phases"] = by_phase
    return c


def _design_row(d: Design) -> dict:
    return {
        "key": d.key,
        "trial": d.number,
        "phase": d.phase,
        "status": d.status,
        "values": d.values,
        "responses": d.responses,
        "feasible": d.feasible,
        "message": d.message,
        "wall_time": d.info.get("wall_time"),
        "attempt": d.info.get("attempt"),
        "directory": d.info.get("directory"),
        "deck": d.info.get("deck"),
    }


# --- sensitivity -------------------------------------------------------------------


def _sensitivity(cfg, designs, models, notes) -> dict:
    from .sampling import to_bounds  # noqa: F401 - keep import light
    from .sensitivity import morris_indices, morris_points, saltelli_points, sobol_from_values, sobol_indices

    out = {}
    s = cfg.sensitivity
    by_key = {d.key: d for d in designs}
    if s and s.method == "morris":
        x = morris_points(cfg.variables, s.trajectories, s.levels, s.seed)
        keys = [f"morris-{i:04d}" for i in range(len(x))]
        if all(k in by_key and by_key[k].done for k in keys):
            res = {}
            for name in cfg.responses:
                y = np.array(
                    [by_key[k].responses.get(name, np.nan) if by_key[k].status == "complete" else np.nan for k in keys]
                )
                try:
                    res[name] = morris_indices(cfg.variables, x, y, s.levels, s.seed)
                except ValueError as e:
                    notes.append(f"Morris indices of {name}: {e}")
            out["morris"] = res
        else:
            notes.append("Morris screening not finished: no Morris indices yet")
    if s and s.method == "sobol" and s.runs:
        x = saltelli_points(cfg.variables, s.samples, s.seed)
        keys = [f"sobol-{i:05d}" for i in range(len(x))]
        if all(k in by_key and by_key[k].status == "complete" for k in keys):
            out["sobol_runs"] = {
                name: sobol_from_values(cfg.variables, [by_key[k].responses[name] for k in keys], s.seed)
                for name in cfg.responses
            }
        else:
            notes.append("Sobol runs not all complete: no Sobol indices from runs")
    if models:
        n = s.samples if s else 1024
        seed = s.seed if s else 0
        res = {}
        for name, m in models.items():
            try:
                res[name] = sobol_indices(cfg.variables, m.predict, n=n, seed=seed) | {
                    "metamodel": m.kind,
                    "loo_r2": m.loo_r2,
                }
            except ValueError as e:
                notes.append(f"Sobol indices of {name} on its metamodel: {e}")
        out["sobol_metamodel"] = res
    return out


# --- figures -----------------------------------------------------------------------


def _fig(path: Path, caption: str, fig, plt) -> dict:
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return {"file": path.name, "caption": caption}


def _colour_values(cfg, ok):
    if cfg.objectives:
        o = cfg.objectives[0].response
        return np.array([d.responses[o] for d in ok]), o
    first = next(iter(cfg.responses))
    return np.array([d.responses.get(first, np.nan) for d in ok]), first


def _parallel(cfg, ok, path) -> dict:
    plt = _plt()
    cols = [v.name for v in cfg.variables] + list(cfg.responses)
    data = np.array(
        [[d.values[v.name] for v in cfg.variables] + [d.responses.get(r, np.nan) for r in cfg.responses] for d in ok],
        float,
    )
    lo, hi = np.nanmin(data, axis=0), np.nanmax(data, axis=0)
    for j, v in enumerate(cfg.variables):
        lo[j], hi[j] = v.lower, v.upper
    norm = (data - lo) / np.where(hi > lo, hi - lo, 1.0)
    c, cname = _colour_values(cfg, ok)
    fig, ax = plt.subplots(figsize=(max(6, 1.3 * len(cols)), 4.5))
    cmap = plt.get_cmap("viridis")
    cn = (c - np.nanmin(c)) / (np.ptp(c) if np.ptp(c) > 0 else 1.0)
    for i, d in enumerate(ok):
        feas = d.feasible is not False
        ax.plot(
            range(len(cols)),
            norm[i],
            color=cmap(cn[i]) if feas else "0.75",
            lw=1.2 if feas else 0.8,
            alpha=0.9 if feas else 0.6,
            zorder=2 if feas else 1,
        )
    ax.set_xticks(range(len(cols)), [f"{n}\n[{lo[j]:.3g}, {hi[j]:.3g}]" for j, n in enumerate(cols)], fontsize=8)
    ax.set_yticks([0, 1], ["min", "max"])
    for j in range(len(cols)):
        ax.axvline(j, color="0.3", lw=0.6)
    sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(np.nanmin(c), np.nanmax(c)))
    fig.colorbar(sm, ax=ax, label=cname)
    ax.set_title(f"{cfg.name}: {len(ok)} designs (grey: infeasible)")
    return _fig(
        path,
        "Parallel coordinates of every complete design: variables then responses, each scaled "
        f"to its range; colour: {cname}; grey: infeasible",
        fig,
        plt,
    )


def _vs_variables(cfg, ok, models, path) -> dict:
    plt = _plt()
    names = list(cfg.responses)
    nv = len(cfg.variables)
    fig, axes = plt.subplots(len(names), nv, figsize=(2.8 * nv + 0.5, 2.3 * len(names) + 0.5), squeeze=False)
    x = np.array([[d.values[v.name] for v in cfg.variables] for d in ok])
    centre = np.array([0.5 * (v.lower + v.upper) for v in cfg.variables])
    for i, r in enumerate(names):
        y = np.array([d.responses.get(r, np.nan) for d in ok])
        feas = np.array([d.feasible is not False for d in ok])
        for j, v in enumerate(cfg.variables):
            ax = axes[i, j]
            ax.scatter(x[feas, j], y[feas], s=12, color="C0", label="feasible")
            ax.scatter(x[~feas, j], y[~feas], s=12, color="0.6", marker="x", label="infeasible")
            if r in models:
                g = np.linspace(v.lower, v.upper, 50)
                pts = np.tile(centre, (50, 1))
                pts[:, j] = g
                ax.plot(g, models[r].predict(pts), color="C3", lw=1.2, label="metamodel (others at centre)")
            for c in cfg.constraints:
                if c.response == r:
                    for b in (c.lower, c.upper):
                        if b is not None:
                            ax.axhline(b, color="C1", ls="--", lw=1)
            if i == len(names) - 1:
                ax.set_xlabel(v.name)
            if j == 0:
                ax.set_ylabel(cfg.responses[r].label, fontsize=8)
            ax.tick_params(labelsize=7)
    axes[0, 0].legend(fontsize=6)
    return _fig(
        path,
        "Each response against each variable; line: the metamodel's main effect with the other "
        "variables at the centre of their bounds; dashed: constraint bounds",
        fig,
        plt,
    )


def _scatter(cfg, ok, best, path):
    plt = _plt()
    pairs = []
    objs = [o.response for o in cfg.objectives]
    others = [c.response for c in cfg.constraints if c.response not in objs]
    if len(objs) >= 2:
        pairs += [(objs[0], objs[1])]
    if objs:
        pairs += [(objs[0], r) for r in others]
    if not pairs:
        names = list(cfg.responses)
        pairs = [(names[0], names[1])] if len(names) >= 2 else []
    if not pairs:
        return None
    fig, axes = plt.subplots(1, len(pairs), figsize=(4.2 * len(pairs), 3.8), squeeze=False)
    for ax, (a, b) in zip(axes[0], pairs):
        feas = np.array([d.feasible is not False for d in ok])
        xa = np.array([d.responses[a] for d in ok])
        yb = np.array([d.responses[b] for d in ok])
        ax.scatter(xa[feas], yb[feas], s=16, color="C0", label="feasible")
        ax.scatter(xa[~feas], yb[~feas], s=16, color="0.6", marker="x", label="infeasible")
        if best is not None:
            ax.scatter(
                [best.responses[a]],
                [best.responses[b]],
                s=80,
                facecolors="none",
                edgecolors="C3",
                lw=2,
                label=f"best ({best.key})",
            )
        for c in cfg.constraints:
            for bound in (c.lower, c.upper):
                if bound is None:
                    continue
                if c.response == b:
                    ax.axhline(bound, color="C1", ls="--", lw=1)
                if c.response == a:
                    ax.axvline(bound, color="C1", ls="--", lw=1)
        ax.set_xlabel(cfg.responses[a].label)
        ax.set_ylabel(cfg.responses[b].label)
        ax.legend(fontsize=7)
    return _fig(path, "Objective against constraint responses (dashed: limits), best feasible design circled", fig, plt)


def _pareto(cfg, ok, front, path) -> dict:
    plt = _plt()
    a, b = cfg.objectives[0].response, cfg.objectives[1].response
    fig, ax = plt.subplots(figsize=(5, 4))
    feas = np.array([d.feasible is not False for d in ok])
    xa = np.array([d.responses[a] for d in ok])
    yb = np.array([d.responses[b] for d in ok])
    ax.scatter(xa[feas], yb[feas], s=14, color="C0", label="feasible")
    ax.scatter(xa[~feas], yb[~feas], s=14, color="0.6", marker="x", label="infeasible")
    if front:
        f = sorted(front, key=lambda d: d.responses[a])
        ax.plot([d.responses[a] for d in f], [d.responses[b] for d in f], "o-", color="C3", label="Pareto front")
    ax.set_xlabel(f"{cfg.responses[a].label} ({cfg.objectives[0].goal})")
    ax.set_ylabel(f"{cfg.responses[b].label} ({cfg.objectives[1].goal})")
    ax.legend(fontsize=7)
    return _fig(path, f"Pareto front of {a} and {b} among the feasible designs", fig, plt)


def _history(cfg, designs, path) -> dict:
    plt = _plt()
    o = cfg.objectives[0]
    seq = sorted([d for d in designs if d.status == "complete"], key=lambda d: d.number)
    sign = 1.0 if o.goal == "minimize" else -1.0
    fig, ax = plt.subplots(figsize=(6, 3.6))
    xs = np.arange(len(seq))
    ys = np.array([d.responses[o.response] for d in seq])
    feas = np.array([d.feasible is not False for d in seq])
    phases = sorted({d.phase for d in seq})
    for k, p in enumerate(phases):
        m = np.array([d.phase == p for d in seq])
        ax.scatter(xs[m & feas], ys[m & feas], s=14, color=f"C{k}", label=p)
        ax.scatter(xs[m & ~feas], ys[m & ~feas], s=14, color=f"C{k}", marker="x", alpha=0.5)
    best = []
    cur = math.inf
    for y, f in zip(ys, feas):
        if f and sign * y < cur:
            cur = sign * y
        best.append(sign * cur if math.isfinite(cur) else np.nan)
    ax.step(xs, best, where="post", color="k", lw=1.2, label="best feasible so far")
    ax.set_xlabel("design (order run)")
    ax.set_ylabel(cfg.responses[o.response].label)
    ax.legend(fontsize=7)
    return _fig(
        path, f"{o.response} of every design in the order run (x: infeasible) and the best feasible so far", fig, plt
    )


def _loo(cfg, ok, models, path) -> dict:
    plt = _plt()
    names = list(models)
    fig, axes = plt.subplots(1, len(names), figsize=(3.2 * len(names), 3.2), squeeze=False)
    for ax, name in zip(axes[0], names):
        m = models[name]
        y = np.array([d.responses.get(name, np.nan) for d in ok])
        y = y[np.isfinite(y)]
        ax.scatter(y, m.loo_predictions, s=12)
        lo, hi = float(np.min(y)), float(np.max(y))
        ax.plot([lo, hi], [lo, hi], "k--", lw=0.8)
        ax.set_title(f"{name}: {m.kind}, R²(LOO) {m.loo_r2:.3f}", fontsize=8)
        ax.set_xlabel("run", fontsize=8)
        ax.set_ylabel("metamodel, left out", fontsize=8)
        ax.tick_params(labelsize=7)
    return _fig(
        path,
        "Leave-one-out check of each response's metamodel: run value against the prediction of "
        "the metamodel fitted without that design",
        fig,
        plt,
    )


def _sens_figure(cfg, sens, path) -> dict:
    plt = _plt()
    blocks = []
    for kind, key in (("sobol_runs", "ST"), ("sobol_metamodel", "ST"), ("morris", "mu_star")):
        if sens.get(kind):
            blocks.append((kind, key))
    names = list(cfg.responses)
    fig, axes = plt.subplots(
        len(blocks), 1, figsize=(max(6, 1.2 * len(names) * len(cfg.variables) / 2), 3.2 * len(blocks)), squeeze=False
    )
    w = 0.8 / len(cfg.variables)
    for ax, (kind, key) in zip(axes[:, 0], blocks):
        data = sens[kind]
        for j, v in enumerate(cfg.variables):
            vals = []
            for r in names:
                e = data.get(r, {}).get(v.name, {})
                val = e.get(key, np.nan)
                if kind == "morris":  # mu* relative to the largest of the response
                    tot = max((data.get(r, {}).get(u.name, {}).get(key, 0.0) for u in cfg.variables), default=0.0)
                    val = val / tot if tot else np.nan
                vals.append(val)
            ax.bar(np.arange(len(names)) + j * w, vals, w, label=v.name)
            if kind != "morris":
                s1 = [data.get(r, {}).get(v.name, {}).get("S1", np.nan) for r in names]
                ax.scatter(np.arange(len(names)) + j * w, s1, color="k", s=10, zorder=3)
        ax.set_xticks(np.arange(len(names)) + 0.4 - w / 2, names, fontsize=8)
        ax.set_ylabel({"ST": "Sobol ST (dots: S1)", "mu_star": "Morris μ* / max"}[key], fontsize=8)
        ax.set_title(
            {
                "sobol_runs": "Sobol indices from runs",
                "sobol_metamodel": "Sobol indices on the metamodels",
                "morris": "Morris screening",
            }[kind],
            fontsize=9,
        )
        ax.legend(fontsize=7)
    return _fig(path, "Sensitivity of each response to each variable", fig, plt)


def _best_deck(cfg, best: Design, out: Path, notes) -> str | None:
    deck = best.info.get("deck")
    if not deck:
        notes.append(f"best design {best.key}: its deck is not recorded")
        return None
    src = cfg.directory / deck
    if not src.is_file():
        notes.append(f"best design {best.key}: deck {src} is gone")
        return None
    from .. import read_deck, write_deck

    target = out / "best_design.k"
    if target.exists():
        target.unlink()
    write_deck(read_deck(src), target)
    return target.name
