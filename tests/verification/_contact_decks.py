"""Small contact decks written by the tests: shell plates, solid bars and
lumped masses, with a *CONTACT_AUTOMATIC_... card; and a runner that
returns the Results with the contact groups."""

from __future__ import annotations

import numpy as np

from crashlite import read_deck
from crashlite.solver import setup
from crashlite.solver.loop import integrate

STEEL = (7.85e-9, 210000.0, 0.3)  # ρ [t/mm³], E [MPa], ν


class Deck:
    """Builds a keyword deck node by node and part by part (deck IDs from 1)."""

    def __init__(self):
        self.xyz: list = []
        self.lines: list[str] = []
        self.elem = 0
        self.extra: list[str] = []

    def nodes(self, xyz) -> np.ndarray:
        """Add nodes; their deck IDs."""
        first = len(self.xyz) + 1
        self.xyz += [tuple(float(c) for c in p) for p in np.asarray(xyz, float).reshape(-1, 3)]
        return np.arange(first, len(self.xyz) + 1)

    def plate(self, pid, nx, ny, lx, ly, z=0.0, x0=0.0, y0=0.0, thick=1.0, mat=STEEL, rigid=False) -> np.ndarray:
        """A flat quad shell plate of part ``pid`` at height z (a free
        *MAT_RIGID part when ``rigid``); its node IDs."""
        xs, ys = np.linspace(x0, x0 + lx, nx + 1), np.linspace(y0, y0 + ly, ny + 1)
        ids = self.nodes([[x, y, z] for y in ys for x in xs]).reshape(ny + 1, nx + 1)
        rows = []
        for j in range(ny):
            for i in range(nx):
                self.elem += 1
                rows.append(f"{self.elem},{pid},{ids[j, i]},{ids[j, i + 1]},{ids[j + 1, i + 1]},{ids[j + 1, i]}")
        self.lines += [
            "*ELEMENT_SHELL",
            *rows,
            "*PART",
            f"plate {pid}",
            f"{pid},{pid},{pid}",
            "*SECTION_SHELL",
            f"{pid},2,1.0,2",
            f"{thick},{thick},{thick},{thick}",
            "*MAT_RIGID" if rigid else "*MAT_ELASTIC",
            f"{pid},{mat[0]},{mat[1]},{mat[2]}",
        ]
        return ids.ravel()

    def bar(self, pid, n, length, side, x0=0.0, mat=STEEL) -> np.ndarray:
        """A bar of n hexahedra along x from x0, square section side × side;
        its node IDs (4 per station, station by station)."""
        st = [
            [x, y, z]
            for x in np.linspace(x0, x0 + length, n + 1)
            for (y, z) in ((0, 0), (side, 0), (side, side), (0, side))
        ]
        ids = self.nodes(st).reshape(n + 1, 4)
        rows = []
        for i in range(n):
            self.elem += 1
            a, b = ids[i], ids[i + 1]
            # LS-DYNA order: n1-n4 one face, n5-n8 the opposite one, right-handed
            rows.append(f"{self.elem},{pid},{a[0]},{a[1]},{a[2]},{a[3]},{b[0]},{b[1]},{b[2]},{b[3]}")
        self.lines += [
            "*ELEMENT_SOLID",
            *rows,
            "*PART",
            f"bar {pid}",
            f"{pid},{pid},{pid}",
            "*SECTION_SOLID",
            f"{pid},1",
            "*MAT_ELASTIC",
            f"{pid},{mat[0]},{mat[1]},{mat[2]}",
        ]
        return ids.ravel()

    def mass(self, nid, m) -> None:
        self.elem += 1
        self.lines += ["*ELEMENT_MASS", f"{self.elem},{nid},{m}"]

    def node_set(self, sid, ids) -> None:
        ids = [int(i) for i in ids]
        self.lines += ["*SET_NODE_LIST", f"{sid}"] + [",".join(map(str, ids[k : k + 8])) for k in range(0, len(ids), 8)]

    def fix(self, ids) -> None:
        self.lines += ["*BOUNDARY_SPC_NODE"] + [f"{int(i)},0,1,1,1,1,1,1" for i in ids]

    def velocity(self, ids, v) -> None:
        self.lines += ["*INITIAL_VELOCITY_NODE"] + [f"{int(i)},{v[0]},{v[1]},{v[2]}" for i in ids]

    def contact(self, kind, c1, c2="", c3="", card_a=None, cid=None) -> None:
        head = [f"*CONTACT_AUTOMATIC_{kind}" + ("_ID" if cid else "")] + ([f"{cid}"] if cid else [])
        self.lines += head + [c1, c2, c3] + ([card_a] if card_a is not None else [])

    def text(self, end_time) -> str:
        nodes = [f"{i + 1},{x!r},{y!r},{z!r}" for i, (x, y, z) in enumerate(self.xyz)]
        return (
            "\n".join(
                [
                    "*KEYWORD",
                    "*NODE",
                    *nodes,
                    *self.lines,
                    *self.extra,
                    "*CONTROL_TERMINATION",
                    f"{end_time:.8g},",
                    "*END",
                ]
            )
            + "\n"
        )

    def write(self, path, end_time):
        path.write_text(self.text(end_time))
        return path


def run(path, output_dt=None):
    """(Results, contact groups, Setup) of a deck run to its end time."""
    s = setup.build(read_deck(path))
    contacts = [g for g in s.groups if g.kind == "contact"]
    return integrate(s, output_dt), contacts, s


def momentum(s, v) -> np.ndarray:
    """(3,) total momentum Σ m v [mass·length/time]."""
    return (s.mass[:, None] * v).sum(axis=0)
