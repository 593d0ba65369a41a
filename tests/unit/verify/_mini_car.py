"""A small crash model for comparison tests: a 1 t body (nodal rigid body
of four rear nodes of 0.25 t) runs at 56 km/h into a fixed rigid wall on four linear
crush springs, two per rail (parts 1 "crash box L" and 2 "crash box R");
a cross section cuts the springs, the body and a front node are history
nodes, field states every 5 ms.

Elastic springs of total stiffness K = 4k give the closed form: peak
force v0·√(m·K), time of peak (π/2)·√(m/K), crush v0·√(m/K). ``extra``
adds a third part (a bumper spring, part 3) and history node 9, so the
two runs differ in their entities.
"""

from __future__ import annotations

from pathlib import Path

MASS = 1.0  # t
V0 = 15555.6  # mm/s
END = 0.08  # s


def deck_text(k: float = 672.0, extra: bool = False, end: float = END) -> str:
    nodes, springs = [], []
    # front nodes 1-4 at x = 0, rear nodes 5-8 at x = 500, y = ±300, z = 0 / 200
    corners = [(300.0, 0.0), (300.0, 200.0), (-300.0, 0.0), (-300.0, 200.0)]
    for i, (y, z) in enumerate(corners):
        nodes.append(f"{i + 1},0.0,{y},{z}")
        nodes.append(f"{i + 5},500.0,{y},{z}")
        springs.append(f"{i + 1},{1 if y > 0 else 2},{i + 1},{i + 5}")
    if extra:
        nodes += ["9,0.0,0.0,100.0", "10,500.0,0.0,100.0"]  # node 10 rides on the body
        springs.append("5,3,9,10")
    front = [1, 2, 3, 4] + ([9] if extra else [])
    rear = [5, 6, 7, 8] + ([10] if extra else [])
    everything = front + rear
    cards = [
        "*KEYWORD",
        "*TITLE",
        f"mini car k={k:g}{' with bumper' if extra else ''}",
        "*NODE",
        *nodes,
        "*ELEMENT_DISCRETE",
        *springs,
        "*ELEMENT_MASS",
        *[f"{100 + n},{n},{MASS / 4!r}" for n in (5, 6, 7, 8)],
        *[f"{100 + n},{n},1e-5" for n in front],
        "*PART",
        "crash box L",
        "1,1,1",
        "*PART",
        "crash box R",
        "2,1,1",
        *(["*PART", "bumper", "3,1,1"] if extra else []),
        "*SECTION_DISCRETE",
        "1,0",
        "*MAT_SPRING_ELASTIC",
        f"1,{k!r}",
        "*SET_NODE_LIST",
        "1",
        *_rows(rear),
        "*SET_NODE_LIST",
        "2",
        *_rows(front),
        "*SET_NODE_LIST",
        "3",
        *_rows(everything),
        "*SET_PART_LIST",
        "7",
        "1,2",
        "*CONSTRAINED_NODAL_RIGID_BODY",
        "50,0,1",
        "*INITIAL_VELOCITY",
        "3",
        f"{-V0!r},0,0",
        "*RIGIDWALL_PLANAR",
        "2",
        "0,0,0,1,0,0",
        "*DATABASE_CROSS_SECTION_PLANE_ID",
        "11,mid rail",
        "0,250,0,0,251,0,0",
        "*DATABASE_HISTORY_NODE",
        "5,1" + (",9" if extra else ""),
        "*DATABASE_BINARY_D3PLOT",
        "0.005",
        "*CONTROL_TERMINATION",
        repr(end),
        "*CONTROL_TIMESTEP",
        ",0.5",
        "*END",
    ]
    return "\n".join(cards) + "\n"


def _rows(ids) -> list[str]:
    """Set members, 8 to a card line."""
    return [",".join(map(str, ids[i : i + 8])) for i in range(0, len(ids), 8)]


def write_and_run(folder, k: float = 672.0, extra: bool = False, end: float = END) -> tuple[Path, Path]:
    """Write the deck to folder/deck.k and run it into folder/out:
    (deck path, results folder)."""
    from crashlite.solver import run

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    deck = folder / "deck.k"
    deck.write_text(deck_text(k, extra, end))
    run(deck, out=folder / "out")
    return deck, folder / "out"
