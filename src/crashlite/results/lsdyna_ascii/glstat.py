"""glstat: global energies and time step, one block per state.

Layout (LSTC's binout-to-ASCII translator l2a.c, ``translate_glstat``,
which reproduces LS-DYNA's own file)::

     <title>
                             ls-dyna ...     date ...


     dt of cycle       0 is controlled by shell      element    1234

     time...........................   0.00000E+00
     kinetic energy.................   2.50000E+06
     ...
     total energy / initial energy..   1.00000E+00

Each value line is a label padded with dots to 31 characters, then
``%14.5E`` (6 significant digits). Scripts key on the labels, so crashlite
writes LS-DYNA's labels in LS-DYNA's order; quantities crashlite does not
have are not written.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ._text import LABEL_LINE, header, known_cycles, to_float

# (label as LS-DYNA prints it, lasso-python Binout name), in LS-DYNA's order
LABELS = [
    ("time", "time"),
    ("time step", "time_step"),
    ("kinetic energy", "kinetic_energy"),
    ("internal energy", "internal_energy"),
    ("stonewall energy", "stonewall_energy"),
    ("rigid body stopper energy", "rb_stopper_energy"),
    ("spring and damper energy", "spring_and_damper_energy"),
    ("hourglass energy ", "hourglass_energy"),
    ("system damping energy", "system_damping_energy"),
    ("sliding interface energy", "sliding_interface_energy"),
    ("external work", "external_work"),
    ("total energy", "total_energy"),
    ("total energy / initial energy", "energy_ratio"),
    ("global x velocity", "global_x_velocity"),
    ("global y velocity", "global_y_velocity"),
    ("global z velocity", "global_z_velocity"),
    ("time per zone cycle.(nanosec)", "nzc"),
    ("added mass", "added_mass"),
    ("percentage increase", "percent_increase"),
]
# labels of newer LS-DYNA versions whose Binout names are not the label's words
_READ_ONLY = {
    "reached the minimum time step": "num_bad_shells",
    "energy ratio w/o eroded energy": "energy_ratio_wo_eroded",
}
_NAMES = {" ".join(label.split()): name for label, name in LABELS} | _READ_ONLY
_CYCLE = re.compile(r"dt of cycle\s*(\d+)")


def write(path: Path, data: dict, title: str = "") -> Path:
    """``data``: Binout name -> (n_states,) array (``time`` required;
    ``cycle`` optional, int). Names not in ``LABELS`` are not written."""
    t = np.asarray(data["time"], float)
    cycle = np.asarray(data.get("cycle", np.zeros(len(t))), np.int64)
    present = [(label, np.asarray(data[name], float)) for label, name in LABELS if name in data]
    out = [header(title)]
    for i in range(len(t)):
        out.append(f"\n\n dt of cycle{int(cycle[i]):8d} is controlled by crashlite\n\n")
        for label, values in present:
            if label == "added mass":
                out.append("\n\n")
            out.append(f" {label}{'.' * (31 - len(label))}{values[i]:14.5E}\n")
    Path(path).write_text("".join(out))
    return Path(path)


def read(path: Path) -> dict:
    """Quantities of a glstat file (crashlite's or LS-DYNA's) as
    (n_states,) arrays; a state starts at each ``time`` line. Per-wall
    stonewall energies are summed."""
    states: list[dict] = []
    cycle = None
    for line in Path(path).read_text(errors="replace").splitlines():
        m = _CYCLE.search(line)
        if m:
            cycle = int(m.group(1))
            continue
        m = LABEL_LINE.match(line)
        if not m:
            continue
        label = " ".join(m.group(1).split()).rstrip(".").strip()
        name = _NAMES.get(label) or re.sub(r"\W+", "_", label.lower()).strip("_")
        try:
            value = to_float(m.group(2))
        except ValueError:
            continue
        if name == "time":
            states.append({"time": value} | ({"cycle": float(cycle)} if cycle is not None else {}))
            cycle = None
            continue
        if not states:
            continue
        if name == "stonewall_energy":
            value += states[-1].get(name, 0.0)
        states[-1][name] = value
    size = [len(s) - ("cycle" in s) for s in states]
    if len(states) > 1 and size[-1] < size[-2]:  # cut while being written
        states = states[:-1]
    if not states:
        return {}
    names = [k for k in states[0] if all(k in s for s in states)]
    out = {k: np.array([s[k] for s in states]) for k in names}
    if "cycle" in out:
        c = known_cycles(out.pop("cycle").astype(np.int64).tolist())
        if c is not None:
            out["cycle"] = c
    return out
