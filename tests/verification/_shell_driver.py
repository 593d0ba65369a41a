"""Decks with shells through the solver's set-up and time loop.

``run_deck`` builds and integrates a deck and returns the Results together
with the shell group (final element state). Deck helpers write flat
rectangular meshes of shells.
"""

from __future__ import annotations

import numpy as np

from crashlite import read_deck
from crashlite.solver import setup
from crashlite.solver.loop import integrate
from crashlite.solver.shells import ShellGroup


def run_deck(path, output_dt=None):
    """(Results, ShellGroup, Setup) of a deck run to its end time."""
    model = read_deck(path)
    s = setup.build(model)
    (g,) = [g for g in s.groups if isinstance(g, ShellGroup)]
    res = integrate(s, output_dt)
    return res, g, s, model


def grid(nx, ny, lx, ly, x0=0.0, y0=0.0):
    """Node coordinates (ny+1)*(nx+1) in the z = 0 plane, row by row, and
    quad connectivity (1-based deck IDs), counter-clockwise."""
    xs, ys = np.linspace(x0, x0 + lx, nx + 1), np.linspace(y0, y0 + ly, ny + 1)
    xyz = np.array([[x, y, 0.0] for y in ys for x in xs])
    nid = lambda i, j: j * (nx + 1) + i + 1  # noqa: E731
    quads = np.array(
        [[nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)] for j in range(ny) for i in range(nx)]
    )
    return xyz, quads


def deck_text(xyz, quads, section, material, extra="", hourglass="1,4,0.1", pid=1):
    """A keyword deck: nodes, shells of part ``pid``, section and material
    card text (IDs 1), *HOURGLASS 1 and ``extra`` cards."""
    nodes = "\n".join(f"{i + 1},{float(x)!r},{float(y)!r},{float(z)!r}" for i, (x, y, z) in enumerate(xyz))
    elems = "\n".join(f"{k + 1},{pid}," + ",".join(str(int(n)) for n in q) for k, q in enumerate(quads))
    return f"""*KEYWORD
*NODE
{nodes}
*ELEMENT_SHELL
{elems}
*PART
shells
{pid},1,1,0,1
*SECTION_SHELL
{section}
{material}
*HOURGLASS
{hourglass}
{extra}*END
"""
