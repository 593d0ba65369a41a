"""The page of a simplified-vehicle verification (the paper's figures 20–22, 26)."""

from __future__ import annotations

from typing import Protocol

from ...report.html import esc, image, num, page, table
from ...report.plots import _pyplot, pair_plot, png


class VerificationView(Protocol):
    """What the page reads of a ``verification.VehicleVerification`` (it
    writes its page, so this module names it without importing it)."""

    names: tuple  # (full, simplified)
    figures: dict
    pairs: list  # verify.curves.CurvePair
    intrusion: dict | None
    notes: list


def intrusion_plot(intr: dict, names: tuple) -> bytes:
    """Firewall intrusion of both runs and their difference over the firewall (y, z)."""
    plt = _pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(12.0, 3.4), sharey=True)
    lo = float(min(intr["full"].min(), intr["simplified"].min()))
    hi = float(max(intr["full"].max(), intr["simplified"].max()))
    scale = float(intr["full"].max())
    for ax, (title, values, kw) in zip(
        axes,
        (
            (f"{names[0]}: intrusion", intr["full"], {"vmin": lo, "vmax": hi, "cmap": "viridis"}),
            (f"{names[1]}: intrusion", intr["simplified"], {"vmin": lo, "vmax": hi, "cmap": "viridis"}),
            (
                "|difference| / max intrusion [%]",
                100.0 * intr["difference"] / scale,
                {"vmin": 0.0, "vmax": 10.0, "cmap": "magma_r"},
            ),
        ),
    ):
        sc = ax.scatter(intr["y"], intr["z"], c=values, s=9, **kw)
        fig.colorbar(sc, ax=ax, shrink=0.85)
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("y", fontsize=8)
        ax.set_aspect("equal")
        ax.tick_params(labelsize=7)
    axes[0].set_ylabel("z", fontsize=8)
    return png(fig)


def verification_page(v: VerificationView) -> str:
    f = v.figures
    names = v.names
    body = [
        f"<p>Load case <b>{esc(f['load_case'])}</b>: {esc(names[1])} against {esc(names[0])}; deceleration "
        f"phase 0 – {num(f['deceleration_phase_end'])} (the reference node {f['reference_node']} of the "
        f"{esc(names[0])} model stops moving forward).</p>"
    ]
    rows = []
    for k, e in f.get("energies", {}).items():
        rows.append([f"{k} energy", num(e["rating"], 3), num(e["deviation_at_end_percent"], 3)])
    for n, share in (f.get("hourglass_share_percent") or {}).items():
        rows.append([f"hourglass / internal energy at the end, {n} [%]", "", num(share, 3)])
    cb = f["crash_box_internal_energy"]
    rows.append(["crash boxes internal energy", num(cb["rating"], 3), num(cb["deviation_percent"], 3)])
    eng = f.get("engine_top_acceleration")
    if eng:
        rows.append(
            [
                f"engine top acceleration (CFC {num(eng['cfc'])}), peak",
                num(eng["rating"], 3),
                num(eng["peak_deviation_percent"], 3),
            ]
        )
    body.append("<h2>Figures</h2>")
    body.append(table(["quantity", "ISO/TS 18571 rating", "deviation [%]"], rows))
    fw = f.get("firewall_intrusion")
    if fw:
        body.append(
            table(
                ["firewall intrusion", names[0], names[1], "max |Δ| [%]", "mean |Δ| [%]"],
                [
                    [
                        f"at {num(fw['time'])}, {fw['nodes']} nodes",
                        num(fw["max_intrusion_full"]),
                        num(fw["max_intrusion_simplified"]),
                        num(fw["max_deviation_percent"], 3),
                        num(fw["mean_deviation_percent"], 3),
                    ]
                ],
            )
        )
        sp = fw.get("split")
        if sp:
            body.append(
                f"<p>The intrusion split at the interface ({sp['interface_nodes']} nodes in both runs): what "
                "the interface's own motion in the cell frame carries the firewall by (the replaced "
                "structure, or the surrogate's connection to it), and the kept structure's own deformation "
                "between interface and firewall; deviations relative to the largest intrusion of "
                f"{esc(names[0])}.</p>"
            )
            body.append(
                table(
                    [
                        "part of the intrusion",
                        f"{names[0]} max / mean",
                        f"{names[1]} max / mean",
                        "max |Δ| [%]",
                        "mean |Δ| [%]",
                    ],
                    [
                        [
                            label,
                            f"{num(c['max_full'])} / {num(c['mean_full'])}",
                            f"{num(c['max_simplified'])} / {num(c['mean_simplified'])}",
                            num(c["max_deviation_percent"], 3),
                            num(c["mean_deviation_percent"], 3),
                        ]
                        for label, c in (
                            ("carried by the interface", sp["carried_by_interface"]),
                            ("own deformation of the kept structure", sp["own_deformation"]),
                        )
                    ],
                )
            )
            warp = sp.get("interface_warping")
            if warp:
                body.append(
                    f"<p>The interface's own bending at that state, along the axis, away from the rigid "
                    f"motion that best fits its nodes: {esc(names[0])} max {num(warp['max_full'])}, rms "
                    f"{num(warp['rms_full'])} ({num(warp['max_full_percent'], 3)} % and "
                    f"{num(warp['rms_full_percent'], 3)} % of its largest intrusion); {esc(names[1])} max "
                    f"{num(warp['max_simplified'])}. A rigid interface holds the cut flat, and the kept "
                    "structure next to it cannot follow the full model closer than this; a cut joined by the "
                    "condensed structure (the default reduction) bends as the structure behind it.</p>"
                )
        if v.intrusion is not None:
            body.append(image(intrusion_plot(v.intrusion, names), "firewall intrusion"))
    tw = f.get("elastic_twin")
    if tw:
        body.append("<h2>The elastic premise and the surrogate</h2>")
        body.append(
            f"<p>A run of the elastic twin ({esc(names[0])} with the replaced structure elastic: same mesh, "
            "masses and connections, *MAT_ELASTIC of the same density and moduli) splits each deviation in "
            f"two: {esc(names[0])} against the twin is what the premise of an elastic structure behind the "
            "interface costs (no elastic surrogate at this interface comes closer); the twin against "
            f"{esc(names[1])} is the surrogate's own. Relative to the same figures of {esc(names[0])}.</p>"
        )
        rows = []
        for key, label in (
            ("premise", f"{names[0]} vs elastic twin (premise)"),
            ("surrogate", f"elastic twin vs {names[1]} (surrogate)"),
        ):
            d = tw[key]
            rows.append(
                [
                    label,
                    num(d["crash_box_internal_energy_deviation_percent"], 3),
                    num(d.get("firewall_intrusion_max_deviation_percent"), 3),
                    num(d.get("firewall_intrusion_mean_deviation_percent"), 3),
                ]
            )
        body.append(
            table(["comparison", "crash-box energy [%]", "intrusion max |Δ| [%]", "intrusion mean |Δ| [%]"], rows)
        )
    t = f["time"]
    body.append("<h2>Computational time</h2>")
    body.append(
        table(
            ["run", "elements", "cycles", "time step", "time loop [s]", "reduction"],
            [
                [
                    names[0],
                    t["elements_full"],
                    num(t["full"]["cycles"]),
                    num(t["full"]["time_step"]),
                    num(t["full"]["wall_time"]),
                    "",
                ],
                [
                    names[1],
                    t["elements_simplified"],
                    num(t["simplified"]["cycles"]),
                    num(t["simplified"]["time_step"]),
                    num(t["simplified"]["wall_time"]),
                    "–" if t["reduction_percent"] is None else f"{t['reduction_percent']:.1f} %",
                ],
            ],
        )
    )
    if f.get("verdict"):
        body.append(
            "<h2>Verdict</h2><p>Each figure against its bound (energy ratings ≥ 0.95, crash-box energy "
            "within 2 %, intrusion within 3 % on average and the elastic twin's largest deviation + 5 "
            "points at its worst node, time reduction ≥ 60 %).</p>"
        )
        body.append(
            table(
                ["figure", "measured", "bound", "verdict"],
                [
                    [
                        r["figure"],
                        num(r["value"], 3),
                        r["bound"],
                        "not measured" if r["passed"] is None else "pass" if r["passed"] else "FAIL",
                    ]
                    for r in f["verdict"]
                ],
            )
        )
    body.append(
        '<h2>Curves</h2><div class="grid">' + "".join(image(pair_plot(p, names), p.name) for p in v.pairs) + "</div>"
    )
    if v.notes:
        body.append("<h2>Notes</h2><ul>" + "".join(f"<li>{esc(n)}</li>" for n in v.notes) + "</ul>")
    return page(f"crashlite simplified vehicle verification: {f['load_case']}", body)
