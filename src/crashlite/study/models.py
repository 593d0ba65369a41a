"""Small front-structure decks for studies, tests and benchmarks.

A straight square steel tube drives at ``speed`` into a fixed rigid wall:
a *crash box* at the front (part "crash box"), a *rail* behind it (part
"rail"), then the rest of the vehicle. The rest is either

* ``"full"``: an elastic rear frame of shells (part "rear frame", the
  structure the paper's simplified vehicle replaces) ending in a nodal
  rigid body that carries the vehicle mass, or
* ``"surrogate"``: the paper's step 4 in one dimension: the rail's end ring
  is a nodal rigid body (the interface), tied by one linear spring of the
  rear frame's axial stiffness K = E·A/L (part "rear spring") to the mass.

Both decks have the same crash box and rail (their thicknesses are the
design variables, addressed by part name), history node 900001 (the mass,
so deceleration and crush are read from it) and rigid wall 1 (the barrier
force). Units mm–t–s–N–MPa. The decks are written in free format and run
in LS-DYNA unchanged.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

MASS_NODE = 900001  # history node: the vehicle mass
INTERFACE_NODE = 900002  # surrogate: centre of the interface rigid body

DEFAULTS = dict(
    side=50.0,
    box_length=100.0,
    rail_length=150.0,
    rear_length=300.0,
    t_box=1.2,
    t_rail=2.0,
    t_rear=3.0,
    sigy_box=300.0,
    sigy_rail=300.0,
    mass=0.012,
    speed=15000.0,
    end_time=0.008,
    element_size=10.0,
    contact=False,
)


def _ring(c: float, n_side: int) -> np.ndarray:
    """(4·n_side, 2) y, z of a square ring of side c, counter-clockwise."""
    a = np.arange(n_side) * (c / n_side) - c / 2
    half = np.full(n_side, c / 2)
    return np.concatenate([np.stack(p, 1) for p in ((a, -half), (half, a), (-a, half), (-half, -a))])


def front_structure(path, variant: str = "full", **options) -> Path:
    """Write the deck of one variant ("full" or "surrogate") to ``path``.

    Options (defaults in ``DEFAULTS``): side [mm] of the square section,
    box_length, rail_length, rear_length [mm], t_box, t_rail, t_rear [mm]
    wall thicknesses, sigy_box, sigy_rail [MPa] yield stresses (MAT_024,
    nearly perfectly plastic), mass [t] of the vehicle, speed [mm/s],
    end_time [s], element_size [mm], contact (single-surface contact
    between the folds). Returns the path written.
    """
    unknown = set(options) - set(DEFAULTS)
    if unknown:
        raise ValueError(f"front_structure: unknown option(s) {', '.join(sorted(unknown))}")
    if variant not in ("full", "surrogate"):
        raise ValueError(f"front_structure: variant must be 'full' or 'surrogate', got {variant!r}")
    o = {**DEFAULTS, **options}
    c, h = o["side"], o["element_size"]
    n_side = max(1, int(round(c / h)))
    ring = _ring(c, n_side)
    nr = len(ring)
    lengths = [o["box_length"], o["rail_length"]] + ([o["rear_length"]] if variant == "full" else [])
    rows = [max(1, int(round(L / h))) for L in lengths]
    xs = [0.0]
    for L, n in zip(lengths, rows):
        xs += list(xs[-1] + np.linspace(0.0, L, n + 1)[1:])
    xs = np.array(xs)
    # imperfection of the symmetric folding mode over the first half fold
    # (faces y = ±c/2 out, z = ±c/2 in): folding starts at the wall
    t0 = o["t_box"]
    trig = 2 * 0.983 * c ** (2 / 3) * t0 ** (1 / 3)
    amp = 0.3 * t0
    nodes = []
    for _j, x in enumerate(xs):
        f = amp * math.sin(math.pi * (trig - x) / trig) if x < trig else 0.0
        for y, z in ring:
            dy = dz = 0.0
            if abs(abs(y) - c / 2) < 1e-9 and abs(z) < c / 2:
                dy = math.copysign(f * math.cos(math.pi * z / c), y)
            elif abs(abs(z) - c / 2) < 1e-9 and abs(y) < c / 2:
                dz = -math.copysign(f * math.cos(math.pi * y / c), z)
            nodes.append((0, x, y + dy, z + dz))
    nodes = [(j + 1, float(x), float(y), float(z)) for j, (_, x, y, z) in enumerate(nodes)]
    shells = []
    row0 = 0
    for pid, n in enumerate(rows, start=1):
        for j in range(row0, row0 + n):
            for i in range(nr):
                a, b = j * nr + i + 1, j * nr + (i + 1) % nr + 1
                shells.append((len(shells) + 1, pid, a, b, b + nr, a + nr))
        row0 += n
    end_ring = range((len(xs) - 1) * nr + 1, len(xs) * nr + 1)
    x_end = float(xs[-1])
    out = []
    w = out.append
    w("*KEYWORD")
    w("*TITLE")
    w(f"Front structure ({variant}): crash box and rail into a rigid wall (crashlite study example)")
    w("$ Units: mm, tonne, s, N, MPa.")
    w("*PARAMETER")
    w(f"R mass,{o['mass']!r}")
    w(f"R speed,{o['speed']!r}")
    w("*CONTROL_TERMINATION")
    w(f"{o['end_time']!r},")
    w("*CONTROL_TIMESTEP")
    w("0.0,0.9")
    w("*CONTROL_ENERGY")
    w("2,2,2,2")
    w("*CONTROL_HOURGLASS")
    w("4,0.03")
    w("*DATABASE_GLSTAT")
    w("1.0e-5,1")
    w("*DATABASE_MATSUM")
    w("1.0e-5,1")
    w("*DATABASE_NODOUT")
    w("1.0e-5,1")
    w("*DATABASE_RWFORC")
    w("1.0e-5,1")
    w("*DATABASE_HISTORY_NODE")
    w(f"{MASS_NODE}")
    names = ["crash box", "rail", "rear frame"]
    thick = [o["t_box"], o["t_rail"], o["t_rear"]]
    for pid in range(1, len(rows) + 1):
        w("*PART")
        w(names[pid - 1])
        w(f"{pid},{pid},{pid},0,0")
        w("*SECTION_SHELL_TITLE")
        w(f"{names[pid - 1]} section")
        w(f"{pid},2,0.8333,5")
        t = thick[pid - 1]
        w(f"{t!r},{t!r},{t!r},{t!r}")
    w("*MAT_PIECEWISE_LINEAR_PLASTICITY_TITLE")
    w("crash box steel")
    w(f"1,7.85e-9,210000.0,0.3,{o['sigy_box']!r},1.0")
    w("0,0,0,0")
    w("*MAT_PIECEWISE_LINEAR_PLASTICITY_TITLE")
    w("rail steel")
    w(f"2,7.85e-9,210000.0,0.3,{o['sigy_rail']!r},1.0")
    w("0,0,0,0")
    area = 4 * c * o["t_rear"]
    stiffness = 210000.0 * area / o["rear_length"]  # axial stiffness of the rear frame [N/mm]
    if variant == "full":
        w("*MAT_ELASTIC_TITLE")
        w("rear frame steel")
        w("3,7.85e-9,210000.0,0.3")
    else:
        w("*PART")
        w("rear spring")
        w("3,3,3,0,0")
        w("*SECTION_DISCRETE")
        w("3,0")
        w("*MAT_SPRING_ELASTIC_TITLE")
        w(f"rear frame stiffness K = E*A/L = {stiffness:.1f} N/mm")
        w(f"3,{stiffness!r}")
    w("*NODE")
    out += [f"{n},{x!r},{y!r},{z!r}" for n, x, y, z in nodes]
    if variant == "full":
        w(f"{MASS_NODE},{x_end!r},0.0,0.0")
    else:
        w(f"{INTERFACE_NODE},{x_end!r},0.0,0.0")
        w(f"{MASS_NODE},{x_end + 100.0!r},0.0,0.0")
    w("*ELEMENT_SHELL")
    out += [",".join(map(str, s)) for s in shells]
    w("*ELEMENT_MASS")
    w(f"900001,{MASS_NODE},&mass")
    if variant == "surrogate":  # step 2: the replaced structure's mass at its CoG (here: on the axis)
        rear_mass = 7.85e-9 * 4 * c * o["t_rear"] * o["rear_length"]
        w(f"900002,{MASS_NODE},{rear_mass!r}")
    rb = list(end_ring) + [MASS_NODE if variant == "full" else INTERFACE_NODE]
    w("*SET_NODE_LIST")
    w("1")
    out += [",".join(map(str, rb[i : i + 8])) for i in range(0, len(rb), 8)]
    w("*CONSTRAINED_NODAL_RIGID_BODY")
    w("101,0,1")
    if variant == "surrogate":
        w("*ELEMENT_DISCRETE")
        w(f"900001,3,{INTERFACE_NODE},{MASS_NODE},0,1.0")
        w("*BOUNDARY_SPC_NODE")
        w(f"{MASS_NODE},0,0,1,1,1,1,1")
    w("*INITIAL_VELOCITY")
    w("0")
    w("-&speed,0.0,0.0")
    w("*RIGIDWALL_PLANAR_ID")
    w("1,barrier")
    w("0,0,0")
    w("-0.5,0.0,0.0,1.0,0.0,0.0,1.0")
    if o["contact"]:
        w("*CONTACT_AUTOMATIC_SINGLE_SURFACE")
        w("0,0,0")
        w("")
        w("")
    w("*END")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(out) + "\n")
    return path
