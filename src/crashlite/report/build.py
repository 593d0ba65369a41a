"""The comparison report: REPORT_DIR/index.html (self-contained) and
REPORT_DIR/summary.json (every figure of the comparison)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from . import pictures, plots
from .html import Raw, esc, image, num, page, pct, table

GROUP_TITLES = {
    "energy": "Global energies",
    "part": "Internal energy per part",
    "section": "Section forces",
    "wall": "Rigid-wall forces",
    "node_displacement": "History-node displacements",
    "node_acceleration": "History-node accelerations",
}
TIME_UNITS = {1.0: "s", 1e-3: "ms", 1e-6: "µs"}


def jsonable(value):
    """Plain JSON types; a non-finite number is an error (figures that
    cannot be computed are None, never NaN)."""
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return jsonable(value.tolist())
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (np.floating, float)):
        v = float(value)
        if not math.isfinite(v):
            raise ValueError(f"summary: a figure is {v} (not a number)")
        return v
    if isinstance(value, (np.bool_,)):
        return bool(value)
    if value is None or isinstance(value, (str, int, bool)):
        return value
    return str(value)


def write_report(
    c, directory, pictures_view: str = "iso", picture_times: list[float] | None = None, with_plots: bool = True
) -> dict[str, Path]:
    """Write index.html and summary.json of a Comparison ``c`` into
    ``directory``; pictures of the deformed structures at ``picture_times``
    (default the times of the field comparisons) when both runs have field
    states. Returns the paths written."""
    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    summary = c.summary()
    unit = TIME_UNITS.get(c.options.time_scale, "time unit")
    times = list(picture_times) if picture_times is not None else [f.time for f in c.fields]
    pics = []
    if c.ref.states is not None and c.cmp.states is not None and times:
        for t in times:
            pics.append(
                (
                    t,
                    pictures.side_by_side(
                        [(c.ref.name, c.ref.states), (c.cmp.name, c.cmp.states)], float(t), pictures_view
                    ),
                )
            )
    summary["report"] = {"pictures": [float(t) for t, _ in pics], "view": pictures_view, "time_unit": unit}
    text = json.dumps(jsonable(summary), indent=1, allow_nan=False)
    (out / "summary.json").write_text(text + "\n")
    body = _body(c, summary, pics, unit, with_plots)
    (out / "index.html").write_text(page(f"crashlite comparison: {c.cmp.name} against {c.ref.name}", body))
    return {"html": out / "index.html", "summary": out / "summary.json"}


def _body(c, s: dict, pics, unit: str, with_plots: bool) -> list[str]:
    names = (c.ref.name, c.cmp.name)
    ov = s["overall"]
    body = [
        f"<p>Reference <b>{esc(names[0])}</b> (<code>{esc(c.ref.path)}</code>), comparison "
        f"<b>{esc(names[1])}</b> (<code>{esc(c.cmp.path)}</code>); common time range "
        f"{num(c.t0)} – {num(c.t1)} {unit}. {ov['pairs']} curve pairs, {ov['rated']} rated; "
        f"mean ISO/TS 18571 rating {num(ov['mean_rating'], 3)}, lowest {num(ov['min_rating'], 3)}"
        + (f" ({esc(ov['worst'])})" if ov["worst"] else "")
        + ".</p>"
    ]
    body += _overview(c)
    body += _settings(s, names)
    body += _timing(s)
    body += _pulse(c, s, unit, with_plots)
    for group, title in GROUP_TITLES.items():
        pairs = c.group(group)
        if pairs:
            body += _pairs(title, pairs, names, unit, with_plots)
    body += _fields(c, names, pics, unit, with_plots)
    body += _mismatches(c, s)
    notes = s["notes"]
    if notes:
        body.append("<h2>Notes</h2><ul>" + "".join(f'<li class="note">{esc(n)}</li>' for n in notes) + "</ul>")
    body.append(
        '<p class="note">All figures are in summary.json next to this page. Deviations are '
        "100·(comparison − reference)/|reference|; ratings by ISO/TS 18571 "
        "(objective-rating-metrics) on the common range at 10 kHz.</p>"
    )
    return body


def _overview(c) -> list[str]:
    rows = []
    for group, title in GROUP_TITLES.items():
        rated = [p.rating.overall for p in c.group(group) if p.rating is not None]
        if c.group(group):
            rows.append(
                [
                    title,
                    len(c.group(group)),
                    len(rated),
                    num(float(np.mean(rated)) if rated else None, 3),
                    num(float(np.min(rated)) if rated else None, 3),
                ]
            )
    if not rows:
        return []
    return ["<h2>Overview</h2>", table(["quantity", "pairs", "rated", "mean rating", "lowest rating"], rows)]


def _settings(s: dict, names) -> list[str]:
    ref, cmp = s["reference"], s["comparison"]
    keys = [
        ("path", "results"),
        ("deck", "deck"),
        ("title", "title"),
        ("history", "history reader"),
        ("states", "history states"),
        ("end_time", "end time"),
        ("time_step_min", "smallest time step"),
        ("time_step_last", "last time step"),
        ("nodes", "nodes (deck)"),
        ("parts", "parts (deck)"),
    ]
    rows = [[label, num(ref.get(k)), num(cmp.get(k))] for k, label in keys if k in ref or k in cmp]
    for name in sorted(set(ref.get("controls", {})) | set(cmp.get("controls", {}))):
        a, b = ref.get("controls", {}).get(name, {}), cmp.get("controls", {}).get(name, {})
        for f in sorted(set(a) | set(b)):
            rows.append([f"*{name} {f}", num(a.get(f)), num(b.get(f))])
    opts = ", ".join(f"{k} = {v}" for k, v in s["options"].items() if v is not None)
    return [
        "<h2>Runs and settings</h2>",
        table(["", names[0], names[1]], rows),
        f'<p class="note">Comparison options: {esc(opts)}</p>',
    ]


def _timing(s: dict) -> list[str]:
    if not s["timing"]:
        return []
    from ..verify.timing import format_duration

    rows = [
        [
            r["name"],
            r["elements"],
            ", ".join(f"{k} {v}" for k, v in r["elements_by_type"].items()),
            num(r["element_share_percent"], 3),
            num(r["time_step"]),
            num(r["cycles"]),
            num(r["end_time"]),
            format_duration(r["cpu_time"]),
            format_duration(r["wall_time"]),
            pct(r["cpu_reduction_percent"]),
            pct(r["wall_reduction_percent"]),
            num(r["speedup"], 3),
            format_duration(r.get("setup_time")),
            format_duration(r.get("compile_time")),
        ]
        for r in s["timing"]
    ]
    return [
        "<h2>Time accounting</h2>",
        table(
            [
                "run",
                "elements",
                "by type",
                "% of reference",
                "time step",
                "cycles",
                "end time",
                "CPU time",
                "wall time",
                "CPU reduction",
                "wall reduction",
                "speed-up",
                "start-up",
                "of it compilation",
            ],
            rows,
            left=3,
        ),
        '<p class="note">CPU and wall time of crashlite runs are those of the time loop; the start-up '
        "(building the arrays, first forces, Numba compilation) is listed apart and not compared. "
        "LS-DYNA times are the d3hsp totals.</p>",
    ]


def _pulse(c, s: dict, unit: str, with_plots: bool) -> list[str]:
    p = s["pulse"]
    if not p or (p.get("reference") is None and p.get("comparison") is None):
        return []
    keys = [
        ("v0", "initial speed"),
        ("peak_deceleration", "peak deceleration"),
        ("peak_deceleration_g", "peak deceleration [g]"),
        ("time_of_peak", f"time of peak [{unit}]"),
        ("mean_deceleration", "mean deceleration"),
        ("mean_deceleration_g", "mean deceleration [g]"),
        ("dynamic_crush", "dynamic crush"),
        ("time_of_crush", f"time of crush [{unit}]"),
        ("time_to_zero_velocity", f"time to zero velocity [{unit}]"),
        ("olc", "OLC"),
        ("olc_g", "OLC [g]"),
    ]
    dev = p.get("deviation_percent", {})
    rows = []
    for k, label in keys:
        a = (p.get("reference") or {}).get(k)
        b = (p.get("comparison") or {}).get(k)
        base = k[:-2] if k.endswith("_g") else k
        rows.append([label, num(a), num(b), pct(dev.get(base)) if base in dev and not k.endswith("_g") else ""])
    out = [
        f"<h2>Crash pulse (node {p['node']}, along {p['axis']}"
        + (f", CFC {p['cfc']:g}" if p.get("cfc") else "")
        + ")</h2>",
        table(["", c.ref.name, c.cmp.name, "deviation"], rows),
    ]
    if with_plots and c.pulse_curves:
        out.append(image(plots.pulse_plot(c.pulse_curves, p["axis"], p["node"], unit), "crash pulse"))
    return out


def _pairs(title: str, pairs, names, unit: str, with_plots: bool) -> list[str]:
    rows, classes = [], []
    for p in pairs:
        d, r = p.deviation, p.rating
        rows.append(
            [
                p.name,
                num(d["peak_ref"]),
                num(d["peak_cmp"]),
                pct(d["peak_deviation_percent"]),
                num(d["at_time"]),
                num(d["value_ref"]),
                num(d["value_cmp"]),
                pct(d["value_deviation_percent"]),
                num(d["integral_ref"]),
                num(d["integral_cmp"]),
                pct(d["integral_deviation_percent"]),
                num(d["max_abs_difference"]),
                *(
                    [
                        num(r.corridor, 3),
                        num(r.phase, 3),
                        num(r.magnitude, 3),
                        num(r.slope, 3),
                        num(r.overall, 3),
                        r.grade,
                    ]
                    if r is not None
                    else ["–"] * 5 + [p.note or "not rated"]
                ),
            ]
        )
        classes.append(r.grade if r is not None else "")
    out = [
        f"<h2>{esc(title)}</h2>",
        table(
            [
                "",
                "peak ref",
                "peak cmp",
                "peak dev.",
                f"at [{unit}]",
                "value ref",
                "value cmp",
                "value dev.",
                "integral ref",
                "integral cmp",
                "integral dev.",
                "max |diff|",
                "corridor",
                "phase",
                "magnitude",
                "slope",
                "ISO rating",
                "grade",
            ],
            rows,
            classes=classes,
        ),
    ]
    if with_plots:
        out.append(
            '<div class="grid">' + "".join(image(plots.pair_plot(p, names, unit), p.name) for p in pairs) + "</div>"
        )
    return out


def _fields(c, names, pics, unit: str, with_plots: bool) -> list[str]:
    if not c.fields and not pics:
        return []
    out = ["<h2>Node fields and deformed structures</h2>"]
    if c.fields:
        rows = []
        for f in c.fields:
            g = f.figures
            rows.append(
                [
                    num(f.time),
                    f.component,
                    len(f.ids),
                    num(g["max_displacement_ref"]),
                    num(g["max_displacement_cmp"]),
                    pct(g["max_displacement_deviation_percent"]),
                    num(g["max_difference"]),
                    g["node_of_max_difference"],
                    num(g["mean_difference"]),
                    pct(g["max_relative_deviation_percent"]).lstrip("+"),
                    pct(g["mean_relative_deviation_percent"]).lstrip("+"),
                ]
            )
        out.append(
            table(
                [
                    f"time [{unit}]",
                    "component",
                    "common nodes",
                    "max disp. ref",
                    "max disp. cmp",
                    "max disp. dev.",
                    "max difference",
                    "at node",
                    "mean difference",
                    "max rel. dev.",
                    "mean rel. dev.",
                ],
                rows,
                left=0,
            )
        )
        out.append(
            '<p class="note">Relative deviations divide by the largest reference displacement of the '
            "compared nodes.</p>"
        )
        if with_plots:
            out.append(
                '<div class="grid">'
                + "".join(image(plots.field_plot(f, names), f"field at {f.time:.4g}") for f in c.fields)
                + "</div>"
            )
    for t, png in pics:
        out.append(f"<h3>Deformed structures at t = {num(t)} {unit}</h3>" + image(png, f"deformed at {t:.4g}"))
    return out


def _mismatches(c, s: dict) -> list[str]:
    m = s["mismatches"]
    if not m:
        return []
    rows = []
    for what, d in m.items():
        for key, who in (
            ("only_ref", f"only in {c.ref.name}"),
            ("only_cmp", f"only in {c.cmp.name}"),
            ("in_neither", "requested, in neither"),
        ):
            e = d.get(key)
            if e and e["count"]:
                more = f" … ({e['count']} in all)" if e["count"] > len(e["ids"]) else ""
                rows.append([what, who, e["count"], Raw(esc(", ".join(map(str, e["ids"]))) + more)])
    if not rows:
        return []
    return [
        "<h2>Entities not matched</h2>",
        '<p class="note">IDs and names one run lacks are listed here and left out of the comparison; '
        "nothing is matched by position or guessed.</p>",
        table(["entity", "where", "count", "IDs"], rows, left=4),
    ]
