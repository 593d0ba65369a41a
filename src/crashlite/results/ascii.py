"""LS-DYNA-style ASCII history files: glstat written by crashlite runs and
read from crashlite or LS-DYNA output folders.

glstat is a sequence of blocks, one per state, each a list of
``label........  value`` lines; scripts that read LS-DYNA's glstat key on
these labels, so crashlite writes the same ones.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

# label in the file -> quantity name (lasso-python Binout naming)
GLSTAT = [
    ("time", "time"),
    ("time step", "time_step"),
    ("kinetic energy", "kinetic_energy"),
    ("internal energy", "internal_energy"),
    ("spring and damper energy", "spring_and_damper_energy"),
    ("hourglass energy", "hourglass_energy"),
    ("system damping energy", "system_damping_energy"),
    ("sliding interface energy", "sliding_interface_energy"),
    ("external work", "external_work"),
    ("total energy", "total_energy"),
    ("total energy / initial energy", "energy_ratio"),
    ("added mass", "added_mass"),
    ("percentage increase", "percentage_increase"),
]
_LINE = re.compile(r"^\s*([A-Za-z][\w /().-]*?)\s*\.{2,}\s*([-+0-9.EeDd]+)\s*$")


def write_glstat(path: Path, history: dict, title: str = "") -> Path:
    """``history``: quantity name -> (n_states,) array (missing ones: 0)."""
    n = len(history["time"])
    lines = [f" crashlite glstat  {title}".rstrip(), ""]
    for i in range(n):
        lines += ["", f" dt of cycle {int(history.get('cycle', np.zeros(n))[i]):9d} is controlled by discrete", ""]
        for label, name in GLSTAT:
            value = float(np.asarray(history.get(name, np.zeros(n)))[i])
            lines.append(f" {label}{'.' * max(2, 31 - len(label))} {value:14.5E}")
    path.write_text("\n".join(lines) + "\n")
    return path


def read_glstat(path: Path) -> dict:
    """Quantities of a glstat file (crashlite's or LS-DYNA's) as arrays."""
    names = {label: name for label, name in GLSTAT}
    out: dict[str, list] = {}
    for line in Path(path).read_text(errors="replace").splitlines():
        m = _LINE.match(line)
        if not m:
            continue
        label = m.group(1).strip().rstrip(".").strip()
        name = names.get(label, re.sub(r"\W+", "_", label.lower()).strip("_"))
        try:
            out.setdefault(name, []).append(float(m.group(2).replace("D", "E").replace("d", "e")))
        except ValueError:
            continue
    n = len(out.get("time", []))
    return {k: np.array(v) for k, v in out.items() if len(v) == n}
