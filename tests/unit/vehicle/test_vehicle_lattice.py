"""The lattice mesher of the generic car: grids, pieces, exact merging."""

import numpy as np
import pytest

from crashlite.vehicle.car import body
from crashlite.vehicle.car.lattice import Grid, Plate, Ruled, Tube, lattice_line, merge


def _grid(size, *extra):
    keys = [{0.0, 100.0}, {0.0, 40.0, 100.0}, {0.0, 100.0}]
    for ax, v in extra:
        keys[ax].add(v)
    return Grid(keys, size)


def test_grid_passes_through_every_keypoint_with_cells_near_the_size():
    g = _grid(30.0)
    y = g.coords[1]
    assert {0.0, 40.0, 100.0} <= set(y.tolist())
    assert np.all(np.diff(y) > 0)
    assert np.diff(y).max() <= 1.5 * 30.0 and np.diff(y).min() >= 40.0 / 2
    assert g.span(1, 100.0, 0.0).tolist() == y[::-1].tolist()
    with pytest.raises(ValueError, match="not a keypoint"):
        g.span(1, 0.0, 50.0)


def test_pieces_that_touch_share_nodes():
    """A plate and a tube whose wall contains the plate's edge: one mesh,
    the edge nodes merged (a T-joint), no duplicate nodes."""
    g = _grid(10.0)
    tube = Tube(0, 0.0, 100.0, ((0.0, 0.0), (40.0, 0.0), (40.0, 100.0), (0.0, 100.0)))
    plate = Plate(2, 100.0, (0.0, 40.0), (100.0, 100.0))  # z = 100, x 0..100, y 40..100: on the tube's top edge
    (pa, qa), (pb, _qb) = tube.mesh(g), plate.mesh(g)
    nodes, idx = merge(np.concatenate([pa, pb]))
    shared = len(pa) + len(pb) - len(nodes)
    assert shared == len(g.coords[0])  # the line y = 40, z = 100 along x
    assert len(np.unique(np.round(nodes, 9), axis=0)) == len(nodes)
    # the tube is closed: every edge is used by two quads except the two end rings
    edges = np.sort(np.stack([qa, np.roll(qa, -1, axis=1)], axis=2).reshape(-1, 2), axis=1)
    _, count = np.unique(edges, axis=0, return_counts=True)
    ring = len(tube.ring(g))
    assert (count == 1).sum() == 2 * ring


def test_merge_numbers_nodes_in_order_of_first_appearance():
    p = np.array([[1.0, 0, 0], [0, 0, 0], [1.0, 0, 0], [-0.0, 0, 0], [2.0, 0, 0]])
    nodes, idx = merge(p)
    assert nodes[:, 0].tolist() == [1.0, 0.0, 2.0]
    assert idx.tolist() == [0, 1, 0, 1, 2]


def test_ruled_piece_needs_matching_ends():
    g = _grid(10.0, (2, 50.0))
    ok = Ruled(((0.0, 0.0, 0.0), (0.0, 100.0, 0.0)), ((100.0, 0.0, 100.0), (100.0, 100.0, 100.0)), 141.0)
    xyz, q = ok.mesh(g)
    assert len(xyz) == 15 * len(g.span(1, 0.0, 100.0)) and q.max() < len(xyz)
    assert np.allclose(xyz[-len(g.span(1, 0.0, 100.0)) :, [0, 2]], 100.0)
    coarse = _grid(30.0, (2, 50.0))  # y: 0-40-100 in 3 cells, z: 0-50-100 in 4
    bad = Ruled(((0.0, 0.0, 0.0), (0.0, 100.0, 0.0)), ((0.0, 0.0, 0.0), (0.0, 0.0, 100.0)), 100.0)
    with pytest.raises(ValueError, match="must match"):
        bad.mesh(coarse)


def test_the_car_layout_is_meshable_at_every_size():
    """The sloped pieces (pillars, glass) join lattice lines with the same
    keypoint intervals, so their ends match at any element size."""
    keys = [set(), set(), set()]
    for p in body.parts():
        for piece in p.pieces:
            for ax, v in piece.keypoints():
                keys[ax].add(float(v))
    ruled = [pc for p in body.parts() for pc in p.pieces if isinstance(pc, Ruled)]
    assert len(ruled) == 6
    for size in np.arange(3.0, 60.0, 0.37):
        g = Grid(keys, size)
        for pc in ruled:
            assert len(lattice_line(g, pc.a)) == len(lattice_line(g, pc.b)), size
    gap, axis = Grid(keys, 10.0).smallest_gap()
    assert gap >= 40.0  # no sliver cells at coarse sizes
