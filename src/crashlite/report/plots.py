"""Curve plots of a comparison (matplotlib, off-screen) as PNG bytes."""

from __future__ import annotations

import io

import numpy as np

REF_STYLE = {"color": "#1f4e9c", "lw": 1.6}
CMP_STYLE = {"color": "#d2691e", "lw": 1.4, "ls": "--"}


def _pyplot():
    import matplotlib

    matplotlib.use("Agg", force=False)  # no display needed
    import matplotlib.pyplot as plt

    return plt


def png(fig) -> bytes:
    """The figure as PNG bytes; the figure is closed."""
    plt = _pyplot()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90, bbox_inches="tight")
    plt.close(fig)
    return buf.getvalue()


def pair_plot(pair, names: tuple[str, str], time_unit: str = "s") -> bytes:
    """Reference and comparison curve of one CurvePair, with the common range
    shaded off where it ends and the rating in the title."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(5.6, 3.0))
    ax.plot(pair.t_ref, pair.y_ref, label=names[0], **REF_STYLE)
    ax.plot(pair.t_cmp, pair.y_cmp, label=names[1], **CMP_STYLE)
    d = pair.deviation
    t_end = max(pair.t_ref[-1], pair.t_cmp[-1])
    if d.get("t1") is not None and d["t1"] < t_end:
        ax.axvspan(d["t1"], t_end, color="0.9", zorder=0)
    title = pair.name
    if pair.rating is not None:
        title += f"   ISO {pair.rating.overall:.3f} ({pair.rating.grade})"
    ax.set_title(title, fontsize=9)
    ax.set_xlabel(f"time [{time_unit}]", fontsize=8)
    ax.set_ylabel(pair.unit, fontsize=8)
    ax.tick_params(labelsize=7)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=7)
    return png(fig)


def pulse_plot(curves: dict, axis: str, node: int, time_unit: str = "s") -> bytes:
    """Forward velocity of the crash pulse node of each run."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(5.6, 3.0))
    for (name, (t, v)), style in zip(curves.items(), (REF_STYLE, CMP_STYLE)):
        ax.plot(t, v, label=name, **style)
    ax.axhline(0.0, color="0.5", lw=0.5)
    ax.set_title(f"crash pulse: node {node} velocity along {axis}", fontsize=9)
    ax.set_xlabel(f"time [{time_unit}]", fontsize=8)
    ax.set_ylabel("forward velocity", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=7)
    return png(fig)


def field_plot(fc, names: tuple[str, str]) -> bytes:
    """Displacement of every common node in both runs, nodes sorted by the
    reference displacement, and their difference."""
    plt = _pyplot()
    mag = (lambda u: np.abs(u)) if np.ndim(fc.u_ref) == 1 else (lambda u: np.linalg.norm(u, axis=1))
    ur, uc = mag(fc.u_ref), mag(fc.u_cmp)
    order = np.argsort(ur, kind="stable")
    fig, ax = plt.subplots(figsize=(5.6, 3.0))
    k = np.arange(len(order))
    ax.plot(k, ur[order], label=names[0], **REF_STYLE)
    ax.plot(k, uc[order], label=names[1], **CMP_STYLE)
    ax.plot(k, fc.difference[order], label="difference", color="0.3", lw=0.8)
    ax.set_title(f"displacement ({fc.component}) at t = {fc.time:.4g} on {len(k)} common nodes", fontsize=9)
    ax.set_xlabel("nodes, by reference displacement", fontsize=8)
    ax.set_ylabel("length", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=7)
    return png(fig)
