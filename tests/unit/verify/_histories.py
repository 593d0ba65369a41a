"""Synthetic run histories for comparison tests: every quantity a scaled
half sine, so deviations and ratings are known."""

import math

import numpy as np

from crashlite.results import History

T = np.linspace(0.0, 0.1, 401)
V0 = 15555.6


def history(scale=1.0, shift=0.0, parts=(1, 2), nodes=(5,), sections=(11,), walls=(1,), t=T):
    """Histories of a run: energies, part energies, forces and node curves,
    all ``scale`` times a half sine; times shifted by ``shift``."""
    t = t + shift
    y = scale * np.sin(math.pi * (t - shift) / 0.1)
    n = len(t)
    ke = 0.5 * V0**2 * (1 - y / 2)
    ie = 0.5 * V0**2 * y / 2
    data = {
        "glstat": {
            "time": t,
            "kinetic_energy": ke,
            "internal_energy": ie,
            "total_energy": ke + ie,
            "hourglass_energy": np.zeros(n),
        },
        "matsum": {"time": t, "ids": np.array(parts), "internal_energy": np.outer(ie, np.arange(1, len(parts) + 1))},
        "secforc": {
            "time": t,
            "ids": np.array(sections),
            "x_force": np.outer(1e5 * y, np.ones(len(sections))),
            "y_force": np.zeros((n, len(sections))),
            "z_force": np.zeros((n, len(sections))),
        },
        "rwforc": {
            ("forces", "time"): t,
            ("forces", "ids"): np.array(walls),
            ("forces", "normal_force"): np.outer(2e5 * y, np.ones(len(walls))),
        },
        "nodout": {"time": t, "ids": np.array(nodes)},
    }
    v = -V0 * np.cos(math.pi * (t - shift) / 0.1)  # the body slows and rebounds (same in every run)
    for a in "xyz":
        on = a == "x"
        data["nodout"][f"{a}_displacement"] = np.outer(-300.0 * scale * y if on else 0 * y, np.ones(len(nodes)))
        data["nodout"][f"{a}_velocity"] = np.outer(v if on else 0 * y, np.ones(len(nodes)))
        data["nodout"][f"{a}_acceleration"] = np.outer(np.gradient(v, t) * scale if on else 0 * y, np.ones(len(nodes)))
    return History(data, "synthetic")
