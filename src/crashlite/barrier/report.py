"""Pages of the barrier workflow: the characterisation plot (the paper's
figures 1–2) and the verification index (figures 6 and 8, table 1)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from ..report.html import Raw, esc, image, num, page, table
from ..report.plots import CMP_STYLE, REF_STYLE, _pyplot, png

if TYPE_CHECKING:
    from .characterise import Characteristic


def characterisation_plot(chars: dict[str, Characteristic]) -> bytes:
    """Force–crush of each block's compression test (raw and CFC 600) with
    the reduced simplified curve, one panel per block."""
    plt = _pyplot()
    fig, axes = plt.subplots(1, len(chars), figsize=(5.4 * len(chars), 3.4), squeeze=False)
    for ax, c in zip(axes[0], chars.values()):
        ax.plot(c.crush, c.force_raw / 1e3, color="#bbb", lw=0.6, label="detailed, unfiltered")
        ax.plot(c.crush, c.force / 1e3, label="detailed, CFC 600", **REF_STYLE)
        x, f = c.curve.points(c.depth)
        ax.plot(x, f / 1e3, label="simplified curve", **CMP_STYLE)
        top = max(3.0 * c.curve.plateau, 1.3 * c.curve.peak) / 1e3
        ax.set(xlabel="crush [mm]", ylabel="force [kN]", title=c.block, xlim=(0, c.depth), ylim=(0, top))
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    return png(fig)


def _force_plot(d, s, t_c: float, overlap: float) -> bytes:
    from .cases import rated_force

    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6.0, 3.4))
    peak = 0.0
    for c, style in ((d, REF_STYLE), (s, CMP_STYLE)):
        t, f = rated_force(c)
        ax.plot(t * 1e3, f / 1e3, color=style.get("color"), lw=0.6, alpha=0.35)
        t, f = rated_force(c, t_c)
        ax.plot(t * 1e3, f / 1e3, label=f"{c.barrier} (rated)", **style)
        peak = max(peak, f.max())
    ax.axvline(t_c * 1e3, color="#888", lw=0.8, ls=":")
    ax.set(
        xlabel="time [ms]",
        ylabel="impactor force, CFC 60 [kN]",
        ylim=(min(0.0, ax.get_ylim()[0]), 1.6 * peak / 1e3),
        title=f"{round(100 * overlap)} % overlap (dotted: first barrier crushed solid;\n"
        "faint: the whole event filtered in one)",
    )
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return png(fig)


def write_index(out: Path, summary: dict, cases: dict) -> Path:
    """index.html of a barrier verification folder."""
    body = [
        f"<p>Rigid impactor {num(summary['impactor']['mass_kg'])} kg at "
        f"{num(summary['impactor']['speed_km_h'])} km/h against the detailed barrier (solid honeycomb, "
        f"{num(summary['element_size_mm'])} mm elements) and the simplified barrier (non-linear discrete "
        "beams). Every figure is in <code>summary.json</code>.</p>",
        f"<p>Curves of the simplified barrier: {esc(summary['simplified_curves_source'])}.</p>",
    ]
    cal = summary.get("calibration")
    if cal:
        body.append(
            table(
                ["calibration (multiplier on the characterised curve)", "value"],
                [[k, f"{v:.3f}"] for k, v in cal["multipliers"].items()]
                + [
                    ["misfit before / after", f"{cal['misfit_start']:.3f} / {cal['misfit']:.3f}"],
                    ["simplified runs", str(cal["runs"])],
                ],
            )
        )
    body.append("<h2>Model size and run time (table 1)</h2>")
    keys = [
        ("nodes", "nodes"),
        ("solids", "solids"),
        ("shells", "shells"),
        ("beams", "discrete beams"),
        ("elements", "elements"),
        ("time_step_ms", "time step [ms]"),
        ("cycles", "cycles"),
        ("run_time_s", "run time [s]"),
        ("energy_ratio", "energy ratio at end"),
        ("barrier_energy_kJ", "barrier energy [kJ]"),
        ("peak_force_kN_cfc60", "peak force CFC 60 [kN]"),
        ("deleted_elements", "elements deleted by the end"),
    ]
    cs = summary["cases"]
    body.append(
        table(
            ["", *[f"{c['barrier']} {num(c['overlap_percent'])} %" for c in cs]],
            [[label, *[num(c.get(k)) for c in cs]] for k, label in keys]
            + [
                [
                    "hourglass / internal energy at end [%]",
                    *[num((c.get("hourglass_percent") or {}).get("end_percent")) for c in cs],
                ]
            ],
        )
    )
    body.append("<h2>Impactor force, simplified against detailed</h2>")
    rows, classes = [], []
    for e in summary["overlaps"]:
        rc, rw = e["rating_crush_phase"], e["rating_whole_event"]
        link = Raw(f'<a href="{esc(Path(e["report"]).relative_to(out))}">report</a>') if "report" in e else "–"
        rows.append(
            [
                f"{num(e['overlap_percent'])} %",
                f"{rc['overall']:.3f} ({rc['grade']})",
                num(rc["until_ms"]),
                f"{rw['overall']:.3f} ({rw['grade']})",
                num(e["elements_percent"]),
                num(e["run_time_ratio"]),
                link,
            ]
        )
        classes.append(rc["grade"])
    body.append(
        table(
            [
                "overlap",
                "ISO/TS 18571, crush phase",
                "crush phase ends [ms]",
                "ISO/TS 18571, whole event",
                "elements simplified / detailed [%]",
                "run time detailed / simplified",
                "comparison",
            ],
            rows,
            classes=classes,
        )
    )
    pics = []
    for e in summary["overlaps"]:
        ov = e["overlap_percent"] / 100.0
        d, s = cases["detailed", ov], cases["simplified", ov]
        t_c = e["rating_crush_phase"]["until_ms"] / 1e3
        pics.append(image(_force_plot(d, s, t_c, ov), f"force {e['overlap_percent']} %"))
    body.append('<div class="grid">' + "".join(pics) + "</div>")
    path = out / "index.html"
    path.write_text(page("Simplified against detailed offset deformable barrier", body))
    return path


def write_characterisation_page(out: Path, chars: dict[str, Characteristic]) -> Path:
    """index.html of a characterisation folder: plot and reduced curves."""
    rows = []
    for c in chars.values():
        k = c.curve
        rows.append(
            [
                c.block,
                num(k.peak / 1e3),
                num(k.rise),
                num(k.plateau / 1e3),
                num(100 * k.compaction),
                num(100 * k.full),
                num(c.solids),
                num(c.cycles),
                num(c.wall_time),
            ]
        )
    body = [
        "<p>Each block of the detailed barrier compressed alone by a rigid block impactor; the simplified "
        "curve is reduced automatically (<code>curves.json</code>).</p>",
        image(characterisation_plot(chars), "characterisation"),
        table(
            [
                "block",
                "peak [kN]",
                "at [mm]",
                "plateau [kN]",
                "compaction onset [% depth]",
                "full compaction [% depth]",
                "solids",
                "cycles",
                "run time [s]",
            ],
            rows,
        ),
    ]
    path = Path(out) / "index.html"
    path.write_text(page("Barrier characterisation", body))
    return path
