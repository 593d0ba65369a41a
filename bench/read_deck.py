"""Deck reading speed: crashlite.read_deck vs lsdyna-mesh-reader.

Generates a deck of N shells (default 1.5 M) split over a main file (with
*PARAMETER, *PARAMETER_EXPRESSION, parts, sections, materials) and a mesh
include file, then reads it in fresh processes:

* crashlite reads the main deck (includes, parameters, references, model);
* lsdyna-mesh-reader reads the mesh include (nodes and shells: all it can).

Prints wall time (first call in a fresh process, and a second call), peak
resident memory, and the ratios. Usage::

    python bench/read_deck.py [--shells 1500000] [--dir /tmp/crashlite-bench]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

N_PARTS = 50


def generate(directory: Path, n_shells: int) -> tuple[Path, Path]:
    """A flat grid of quads, nodes and shells in fixed format."""
    directory.mkdir(parents=True, exist_ok=True)
    side = int(np.ceil(np.sqrt(n_shells)))
    nx, ny = side, int(np.ceil(n_shells / side))
    n_nodes = (nx + 1) * (ny + 1)
    mesh = directory / "mesh.k"
    main = directory / "main.k"
    t0 = time.perf_counter()
    with open(mesh, "w") as f:
        f.write("*KEYWORD\n*NODE\n$#   nid               x               y               z      tc      rc\n")
        ids = np.arange(1, n_nodes + 1)
        j, i = np.divmod(ids - 1, nx + 1)
        x = i * 5.0 + 0.125 * (j % 3)
        y = j * 5.0
        z = np.sin(i * 0.01) * 3.0
        rows = np.char.add(np.char.rjust(ids.astype(str), 8), np.char.rjust(np.round(x, 6).astype(str), 16))
        rows = np.char.add(rows, np.char.rjust(np.round(y, 6).astype(str), 16))
        rows = np.char.add(rows, np.char.rjust(np.round(z, 6).astype(str), 16))
        f.write("\n".join(rows.tolist()))
        f.write("\n*ELEMENT_SHELL\n$#   eid     pid      n1      n2      n3      n4\n")
        e = np.arange(n_shells)
        b, a = np.divmod(e, nx)
        n1 = b * (nx + 1) + a + 1
        conn = np.stack([e + 1, e % N_PARTS + 1, n1, n1 + 1, n1 + nx + 2, n1 + nx + 1], axis=1)
        txt = np.char.rjust(conn.astype(str), 8)
        rows = txt[:, 0]
        for k in range(1, 6):
            rows = np.char.add(rows, txt[:, k])
        f.write("\n".join(rows.tolist()))
        f.write("\n*END\n")
    with open(main, "w") as f:
        f.write(
            "*KEYWORD\n*TITLE\nread_deck benchmark\n*PARAMETER\nR t0      1.2\nR ro      7.85e-9\n"
            "*PARAMETER_EXPRESSION\nR sigy    235.0*1.1\n"
        )
        for p in range(1, N_PARTS + 1):
            f.write(f"*PART\npart {p}\n{p:10d}{p:10d}{p:10d}\n")
            f.write(f"*SECTION_SHELL\n{p:10d}{2:10d}\n{'&t0':>10}\n")
            f.write(
                f"*MAT_PIECEWISE_LINEAR_PLASTICITY\n{p:10d}{'&ro':>10}{210000.0:10}{0.3:10}{'&sigy':>10}"
                f"{500.0:10}\n\n\n\n"
            )
        f.write("*INCLUDE\nmesh.k\n*END\n")
    print(
        f"generated {n_shells:,} shells, {n_nodes:,} nodes in {time.perf_counter() - t0:.1f} s "
        f"({mesh.stat().st_size / 2**20:.0f} MiB mesh include)"
    )
    return main, mesh


_PROBE = r"""
import json, statistics, sys, time
t0 = time.perf_counter()
{imports}
{warmup}
t_import = time.perf_counter() - t0
times = []
for _ in range(4):
    t = time.perf_counter()
    obj = {call}
    times.append(time.perf_counter() - t)
    if len(times) < 4:
        del obj
{check}
# VmHWM: peak resident memory of this process (ru_maxrss would include the
# parent's peak, which Linux carries across exec)
hwm = [l for l in open("/proc/self/status") if l.startswith("VmHWM")][0].split()[1]
print(json.dumps({{"import": t_import, "first": times[0], "median": statistics.median(times[1:]),
                  "peak_mib": int(hwm) / 1024, "counts": counts}}))
"""


def probe(imports: str, call: str, check: str, warmup: str = "") -> dict:
    code = _PROBE.format(imports=imports, call=call, check=check, warmup=warmup)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(out.stderr[-2000:])
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--shells", type=int, default=1_500_000)
    ap.add_argument("--dir", type=Path, default=Path("/tmp/crashlite-bench"))
    args = ap.parse_args()
    main_deck, mesh = generate(args.dir, args.shells)
    tiny = args.dir / "tiny.k"
    tiny.write_text("*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n*END\n")
    cl = probe(
        "import crashlite",
        f"crashlite.read_deck({str(main_deck)!r})",
        "counts = [len(obj.nodes), len(obj.shells), len(obj.parts)]",
        warmup=f"crashlite.read_deck({str(tiny)!r})  # loads the compiled kernels",
    )
    print(
        f"crashlite.read_deck      import+kernels {cl['import']:5.2f} s  first {cl['first']:6.2f} s  "
        f"median {cl['median']:6.2f} s  peak {cl['peak_mib']:6.0f} MiB  "
        f"(nodes, shells, parts) = {cl['counts']}"
    )
    try:
        lm = probe(
            "import lsdyna_mesh_reader",
            f"lsdyna_mesh_reader.Deck({str(mesh)!r})",
            "counts = [sum(len(s.nid) for s in obj.node_sections), "
            "sum(len(s.eid) for s in obj.element_shell_sections)]",
        )
    except RuntimeError as e:
        print(f"lsdyna-mesh-reader not available ({str(e).strip().splitlines()[-1]}); install the 'bench' extra")
        return
    print(
        f"lsdyna-mesh-reader       import         {lm['import']:5.2f} s  first {lm['first']:6.2f} s  "
        f"median {lm['median']:6.2f} s  peak {lm['peak_mib']:6.0f} MiB  (nodes, shells) = {lm['counts']}"
    )
    print(
        f"ratio crashlite / lsdyna-mesh-reader: first read {cl['first'] / lm['first']:.2f}x, "
        f"median of 3 more {cl['median'] / lm['median']:.2f}x  (target: within 2x; peak under 3 GB)"
    )
    print(
        "each reader runs in a fresh process; crashlite loads its compiled Numba kernels "
        "(cached on disk after the very first run) before the timed reads"
    )


if __name__ == "__main__":
    main()
