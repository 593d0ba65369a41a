"""Where a study stands, from its database alone (also while another
session runs it): designs per phase and status, what is running, the best
design so far."""

from __future__ import annotations

import time

from .config import StudyConfig
from .runner import best_design, pareto
from .storage import StudyStore


def study_status(cfg: StudyConfig) -> dict:
    store = StudyStore(cfg, readonly=True)
    latest = {}
    for d in store.designs():
        latest[d.key] = d
    designs = list(latest.values())
    phases: dict = {}
    for d in designs:
        p = phases.setdefault(d.phase, {})
        p[d.status] = p.get(d.status, 0) + 1
    best, n_pareto = best_design(cfg, designs)
    driver = store.attr("driver")
    now = time.time()
    return {
        "study": cfg.name,
        "storage": cfg.storage,
        "designs": len(designs),
        "phases": phases,
        "complete": sum(d.status == "complete" for d in designs),
        "failed": [{"key": d.key, "message": d.message} for d in designs if d.status == "failed"],
        "running": [
            {"key": d.key, "since_s": None if d.started is None else now - d.started}
            for d in designs
            if d.status == "running"
        ],
        "best": None if best is None else {"key": best.key, "values": best.values, "responses": best.responses},
        "pareto": [
            d.key for d in pareto(cfg, [d for d in designs if d.status == "complete" and d.feasible is not False])
        ]
        if len(cfg.objectives) > 1
        else [],
        "session": None if not driver else {**driver, "heartbeat_age_s": now - float(driver.get("beat", now))},
    }


def format_status(s: dict) -> str:
    lines = [
        f"study {s['study']!r} ({s['storage']}): {s['designs']} designs, {s['complete']} complete, "
        f"{len(s['failed'])} failed, {len(s['running'])} running"
    ]
    for phase, counts in s["phases"].items():
        lines.append(f"  {phase}: " + ", ".join(f"{n} {k}" for k, n in sorted(counts.items())))
    if s["session"]:
        d = s["session"]
        lines.append(f"  run by process {d.get('pid')} on {d.get('host')} (heartbeat {d['heartbeat_age_s']:.0f} s ago)")
    for r in s["running"][:10]:
        since = "" if r["since_s"] is None else f" for {r['since_s']:.0f} s"
        lines.append(f"  running: {r['key']}{since}")
    for f in s["failed"][:10]:
        lines.append(f"  failed: {f['key']}: {f['message'][:200]}")
    if s["best"]:
        b = s["best"]
        vals = ", ".join(f"{k} = {v:.6g}" for k, v in b["values"].items())
        resp = ", ".join(f"{k} = {v:.6g}" for k, v in b["responses"].items())
        lines.append(f"  best: {b['key']}: {vals} -> {resp}")
    if s["pareto"]:
        lines.append(f"  Pareto-optimal: {', '.join(s['pareto'])}")
    return "\n".join(lines)
