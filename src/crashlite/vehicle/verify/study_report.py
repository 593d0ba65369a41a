"""The page of the paper study (``workflow.paper_study``): computational
time of every run and the reduction of each simplification (the paper's
figures 25–27), the figures of both load-case verifications, links to
their pages and to the reduction page."""

from __future__ import annotations

from ...report.html import esc, image, num, page, table
from ...report.plots import _pyplot, png
from .verification import split_text


def time_plot(runs: dict) -> bytes:
    """Horizontal bars: the time loop of every run [s]."""
    plt = _pyplot()
    names = list(runs)
    secs = [runs[n]["loop_time_s"] for n in names]
    fig, ax = plt.subplots(figsize=(8.0, 0.45 * len(names) + 1.0))
    bars = ax.barh(
        range(len(names)),
        secs,
        color=["#4c72b0" if "full" in n and "simplified" not in n else "#55a868" for n in names],
    )
    ax.set_yticks(range(len(names)), names, fontsize=8)
    ax.invert_yaxis()
    ax.set_xlabel("time loop [s]", fontsize=8)
    ax.bar_label(bars, [f"{s:.1f} s" for s in secs], fontsize=7, padding=2)
    ax.tick_params(labelsize=7)
    return png(fig)


HOURGLASS_LIMIT = 10.0  # percent of the internal energy


def hourglass_rows(runs: dict) -> list[list[str]]:
    """One row per run: hourglass share at the end and at its largest, with
    the part holding most (its own share), over the limit marked; and the
    elements the run deleted."""
    rows = []
    for name, r in runs.items():
        hg = r.get("hourglass_percent") or {}
        gone = num(r.get("deleted_elements"))
        if not hg:
            rows.append([name, "–", "–", "", "", gone])
            continue
        over = " (over)" if (hg.get("max_percent") or 0.0) > HOURGLASS_LIMIT else ""
        part = hg.get("part") or {}
        rows.append(
            [
                name,
                _pct(hg.get("end_percent")),
                _pct(hg.get("max_percent")) + over,
                num(1e3 * hg["max_time"], 3),
                f"{part['id']} ({_pct(part.get('percent_of_its_internal'))})" if part else "",
                gone,
            ]
        )
    return rows


def _pct(value) -> str:
    return "–" if value is None else f"{value:.1f} %"


def study_page(summary: dict, links: dict) -> str:
    t = summary["time"]
    body = [
        f"<p>Generic car at {num(summary['mesh_size'])} mm, detailed barrier at "
        f"{num(summary['barrier_element_size'])} mm, interface at x = {num(summary['interface_x'])}; one "
        f"surrogate for both load cases ({esc(summary['shares']['basis'])} load-path shares).</p>"
    ]
    rows = [["US NCAP: simplified vehicle", _pct(t["us_ncap"]["vehicle_reduction_percent"]), "65 %"]]
    odb = t["odb"]
    if "vehicle_reduction_percent" in odb:
        rows += [
            ["ODB: simplified barrier (full car)", _pct(odb["barrier_reduction_percent"]), ""],
            ["ODB: simplified vehicle (detailed barrier)", _pct(odb["vehicle_reduction_percent"]), ""],
        ]
    rows.append(["ODB: both simplified", _pct(odb["combined_reduction_percent"]), "92 %"])
    body += [
        "<h2>Computational time</h2>",
        table(["simplification", "time-loop reduction", "paper"], rows),
        image(time_plot(summary["runs"]), "time loop of every run"),
        "<h2>Hourglass energy</h2>",
        f"<p>Hourglass energy as a share of the internal energy (the usual limit {HOURGLASS_LIMIT:g} %), at the "
        "end and at its largest once the internal energy has reached a tenth of its own largest; and the shells and "
        "solids each run deleted (eroded, failed or collapsed): a torn honeycomb element takes its crush with it.</p>",
        table(
            ["run", "at the end", "largest", "at [ms]", "part with most", "elements deleted"],
            hourglass_rows(summary["runs"]),
        ),
    ]
    rows = []
    for case, f in summary["verification"].items():
        fw = f.get("firewall_intrusion") or {}
        eng = f.get("engine_top_acceleration") or {}
        rows.append(
            [
                case,
                num(f.get("energy_rating_min"), 3),
                num(f["crash_box_internal_energy_deviation_percent"], 3),
                num(fw.get("max_deviation_percent"), 3),
                num(fw.get("mean_deviation_percent"), 3),
                num(eng.get("rating"), 3),
            ]
        )
    body += [
        "<h2>Verification</h2>",
        table(
            [
                "load case",
                "energy rating (min)",
                "crash-box energy [%]",
                "firewall max |Δ| [%]",
                "firewall mean |Δ| [%]",
                "engine top rating",
            ],
            rows,
        ),
    ]
    dev = summary["shares"].get("max_deviation_percent_points") or {}
    if dev:
        body.append(
            table(
                ["load case", "largest share deviation from the surrogate's [points]"],
                [[k, num(v, 3)] for k, v in dev.items()],
            )
        )
    body.append(
        "<h2>Pages</h2><ul>"
        + "".join(f'<li><a href="{esc(href)}">{esc(label)}</a></li>' for label, href in links.items())
        + "</ul>"
    )
    return page("crashlite simplified vehicle: US NCAP and Euro NCAP ODB", body)


def verification_lines(summary: dict) -> list[str]:
    """One text line per load case of the study's verification figures."""
    out = []
    for case, f in summary["verification"].items():
        fw = f.get("firewall_intrusion") or {}
        rating = f.get("energy_rating_min")
        out.append(
            f"{case}: energy rating min {'–' if rating is None else f'{rating:.3f}'}, crash-box energy "
            f"{_pct(f['crash_box_internal_energy_deviation_percent'])}, firewall intrusion max "
            f"{_pct(fw.get('max_deviation_percent'))} mean {_pct(fw.get('mean_deviation_percent'))}"
            f"{split_text(fw)}{twin_text(f.get('elastic_twin'))}"
        )
    return out


def twin_text(tw: dict | None) -> str:
    """ "; elastic premise: intrusion max a % ..., surrogate: ..." for a
    verification with an elastic twin's run, else ""."""
    if not tw:
        return ""
    return "; " + ", ".join(
        f"{label}: crash-box energy {_pct(tw[k]['crash_box_internal_energy_deviation_percent'])}, intrusion max "
        f"{_pct(tw[k].get('firewall_intrusion_max_deviation_percent'))} mean "
        f"{_pct(tw[k].get('firewall_intrusion_mean_deviation_percent'))}"
        for k, label in (("premise", "elastic premise (full vs twin)"), ("surrogate", "surrogate (twin vs simplified)"))
    )
