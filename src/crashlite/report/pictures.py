"""Pictures of deformed structures, two runs side by side at one time
(matplotlib 3D collections, off-screen; no VTK needed), coloured by the
displacement magnitude on one shared scale so the colours compare."""

from __future__ import annotations

import numpy as np

from .plots import _pyplot, png

# faces of an 8-node brick (VTK / LS-DYNA node order)
_HEX_FACES = ((0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))
MAX_FACETS = 40_000  # beyond this matplotlib is too slow: the nodes are drawn instead
MAX_POINTS = 20_000
VIEWS = {"iso": (25.0, -60.0), "side": (0.0, -90.0), "top": (90.0, -90.0), "front": (0.0, 0.0)}


def split_cells(cells) -> tuple[np.ndarray, list[np.ndarray]]:
    """(lines (n, 2), polygons [rows of 3 or 4]) of connectivity rows:
    2 nodes a line, 3 or 4 a facet, 8 a brick (its six faces)."""
    lines, polys = [], []
    for row in cells:
        row = np.asarray(row, np.int64)
        if len(row) == 2:
            lines.append(row)
        elif len(row) in (3, 4):
            polys.append(row)
        elif len(row) == 8:
            polys += [row[list(f)] for f in _HEX_FACES]
    return (np.array(lines, np.int64).reshape(-1, 2), polys)


def _draw(ax, x: np.ndarray, u: np.ndarray, lines, polys, norm, cmap) -> None:
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    if len(polys) + len(lines) > MAX_FACETS:  # a large model: every k-th node, same k in both runs
        k = max(1, len(x) // MAX_POINTS)
        ax.scatter(x[::k, 0], x[::k, 1], x[::k, 2], c=cmap(norm(u[::k])), s=1, depthshade=False)
        return
    if len(polys):
        col = Poly3DCollection(
            [x[p] for p in polys],
            facecolors=cmap(norm([u[p].mean() for p in polys])),
            edgecolors="0.25",
            linewidths=0.2,
        )
        ax.add_collection3d(col)
    if len(lines):
        col = Line3DCollection(x[lines], colors=cmap(norm(u[lines].mean(axis=1))), linewidths=1.5)
        ax.add_collection3d(col)
    if not len(polys):  # line models and bare points: the nodes themselves
        ax.scatter(x[:, 0], x[:, 1], x[:, 2], c=cmap(norm(u)), s=6, depthshade=False)


def side_by_side(runs, time: float, view: str = "iso") -> bytes:
    """PNG of the deformed structures of ``runs`` ([(name, FieldStates)],
    usually two) at ``time``: same axes limits, same colour scale."""
    from matplotlib.colors import Normalize

    plt = _pyplot()
    cmap = plt.get_cmap("viridis")
    shapes = []
    for name, s in runs:
        x = s.at(time)
        shapes.append((name, x, np.linalg.norm(x - s.x[0], axis=1), *split_cells(s.cells)))
    allx = np.concatenate([sh[1] for sh in shapes])
    lo, hi = allx.min(axis=0), allx.max(axis=0)
    span = np.maximum(hi - lo, 1e-9 * max(float(np.max(hi - lo)), 1.0))
    umax = max(float(sh[2].max()) for sh in shapes)
    norm = Normalize(0.0, umax if umax > 0 else 1.0)
    elev, azim = VIEWS.get(view, VIEWS["iso"])
    fig = plt.figure(figsize=(4.2 * len(shapes) + 0.8, 4.0))
    for k, (name, x, u, lines, polys) in enumerate(shapes):
        ax = fig.add_subplot(1, len(shapes), k + 1, projection="3d")
        _draw(ax, x, u, lines, polys, norm, cmap)
        ax.set_xlim(lo[0], lo[0] + span[0])
        ax.set_ylim(lo[1], lo[1] + span[1])
        ax.set_zlim(lo[2], lo[2] + span[2])
        ax.set_box_aspect(tuple(np.maximum(span, 0.02 * span.max())))
        ax.view_init(elev=elev, azim=azim)
        ax.set_title(f"{name}\nt = {time:.4g}", fontsize=9)
        ax.tick_params(labelsize=6)
        ax.set_xlabel("x", fontsize=7)
        ax.set_ylabel("y", fontsize=7)
        ax.set_zlabel("z", fontsize=7)
    sm = plt.cm.ScalarMappable(norm=norm, cmap=cmap)
    fig.colorbar(sm, ax=fig.axes, shrink=0.7, label="displacement magnitude")
    return png(fig)
