"""Decks of several flat shell plates (each its own part and node range)
for the tied-contact, spot-weld and section tests."""

from __future__ import annotations

import numpy as np

E, RHO = 210000.0, 7.85e-9  # MPa, t/mm³


class Plates:
    """Collects plates and extra cards into one keyword deck."""

    def __init__(self, t: float = 1.0, nu: float = 0.0, hourglass: str = "1,4,0.1"):
        self.t, self.nu, self.hourglass = t, nu, hourglass
        self.nodes: list[tuple[int, float, float, float]] = []
        self.elems: list[tuple[int, int, list[int]]] = []
        self.grids: dict[int, np.ndarray] = {}  # pid -> (ny+1, nx+1) node IDs
        self.extra: list[str] = []

    def plate(self, pid: int, x0: float, x1: float, nx: int, y0: float, y1: float, ny: int, z: float = 0.0):
        """A plate of part ``pid`` (node IDs from 1000·pid + 1); returns the
        (ny+1, nx+1) array of its node IDs (row j: y, column i: x)."""
        ids = np.zeros((ny + 1, nx + 1), np.int64)
        for j, y in enumerate(np.linspace(y0, y1, ny + 1)):
            for i, x in enumerate(np.linspace(x0, x1, nx + 1)):
                ids[j, i] = 1000 * pid + j * (nx + 1) + i + 1
                self.nodes.append((int(ids[j, i]), float(x), float(y), float(z)))
        for j in range(ny):
            for i in range(nx):
                self.elems.append(
                    (1000 * pid + j * nx + i + 1, pid, [ids[j, i], ids[j, i + 1], ids[j + 1, i + 1], ids[j + 1, i]])
                )
        self.grids[pid] = ids
        return ids

    def add(self, text: str) -> None:
        self.extra.append(text.strip() + "\n")

    def node_set(self, sid: int, ids) -> None:
        ids = [int(i) for i in np.ravel(ids)]
        rows = [",".join(str(i) for i in ids[k : k + 8]) for k in range(0, len(ids), 8)]
        self.add("*SET_NODE_LIST\n" + f"{sid}\n" + "\n".join(rows))

    def spc(self, ids, dofs: str = "1,1,1,1,1,1") -> None:
        self.add("*BOUNDARY_SPC_NODE\n" + "\n".join(f"{int(i)},0,{dofs}" for i in np.ravel(ids)))

    def history(self, ids) -> None:
        ids = [int(i) for i in np.ravel(ids)]
        self.add(
            "*DATABASE_HISTORY_NODE\n"
            + "\n".join(",".join(str(i) for i in ids[k : k + 8]) for k in range(0, len(ids), 8))
        )

    def text(self, end_time: float) -> str:
        pids = sorted({e[1] for e in self.elems})
        out = ["*KEYWORD", "*NODE"] + [f"{i},{x!r},{y!r},{z!r}" for i, x, y, z in self.nodes]
        out.append("*ELEMENT_SHELL")
        out += [f"{e},{p}," + ",".join(str(int(n)) for n in q) for e, p, q in self.elems]
        for p in pids:
            out += ["*PART", f"plate {p}", f"{p},1,1,0,1"]
        out += [
            "*SECTION_SHELL",
            "1,2,0.8333,2",
            f"{self.t},{self.t},{self.t},{self.t}",
            "*MAT_ELASTIC",
            f"1,{RHO},{E},{self.nu}",
            "*HOURGLASS",
            self.hourglass,
        ]
        out += [x.rstrip("\n") for x in self.extra]
        out += ["*CONTROL_TERMINATION", f"{end_time!r},", "*END"]
        return "\n".join(out) + "\n"

    def write(self, path, end_time: float):
        path.write_text(self.text(end_time))
        return path


def ramp_curve(lcid: int, amplitude: float, t_ramp: float, t_end: float, n: int = 41) -> str:
    """*DEFINE_CURVE: a (1 − cos) ramp from 0 to ``amplitude`` over
    ``t_ramp``, then held to ``t_end``."""
    s = np.linspace(0.0, 1.0, n)
    rows = [f"{float(a * t_ramp)!r},{float(amplitude * 0.5 * (1 - np.cos(np.pi * a)))!r}" for a in s]
    rows.append(f"{float(max(t_end, 1.01 * t_ramp))!r},{float(amplitude)!r}")
    return f"*DEFINE_CURVE\n{lcid}\n" + "\n".join(rows)
