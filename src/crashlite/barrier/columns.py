"""Honeycomb columns on nodes of their own, joined by links that tear.

A block of MAT_026 solids that shares its nodes can only tear where an
element fails, and LS-DYNA then deletes the element (SSEF): with it the
crush capacity of a band one element wide along every tear, which real
honeycomb keeps. Here every column of elements (one element across the
face, the block's whole depth) gets its own copy of each node, and the
copies of neighbouring columns are joined at every node of their shared
wall by springs (*ELEMENT_DISCRETE, zero length, fixed orientation):

- along the depth (the crush axis), the cell walls' shear: τ·A up to a
  slip, then torn (``simplified.shear_link_springs``), A the node's share
  of the wall;
- across it, the honeycomb's weak in-plane stiffness (elastic, never
  torn), which keeps the columns together sideways.

A column beside a car's imprint is then dragged along until its walls
tear, and crushes fully where it is pushed, as the cells do.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass, field


@dataclass
class Column:
    """One element of a column-split block: its grid position and faces."""

    element: tuple  # (eid, part, n1..n8) as written for the shared mesh
    block: str
    layer: int  # index along the depth within its block
    col: tuple[int, int]  # (row along z, column along y), in the barrier's grid
    plus_y: tuple  # original node IDs of the face towards the next column along y
    plus_z: tuple  # ... towards the next row along z
    dy: float
    dz: float
    ds: float


@dataclass
class Split:
    """The elements on their columns' copies and the links between them."""

    elements: list = field(default_factory=list)  # (eid, part, n1..n8)
    new_nodes: list = field(default_factory=list)  # (id, original id)
    copies: dict = field(default_factory=dict)  # original id -> [ids]
    links: dict = field(default_factory=lambda: defaultdict(list))  # block -> [(copy 1, copy 2, h, wall area)]


def split_columns(elems: list[Column], next_id: int) -> Split:
    """Each column its own node copies (the first column to use a node
    keeps its ID), and at every node of a wall two columns share, the pair
    of copies with the columns' spacing h and the node's share of the wall
    (a quarter of each element face it bounds)."""
    out = Split()
    copy: dict = {}
    taken: set = set()

    def node(n, col):
        key = (n, col)
        if key not in copy:
            if n in taken:
                copy[key] = next_id + len(out.new_nodes)
                out.new_nodes.append((copy[key], n))
            else:
                copy[key] = n
                taken.add(n)
            out.copies.setdefault(n, []).append(copy[key])
        return copy[key]

    for e in elems:
        out.elements.append((*e.element[:2], *[node(n, e.col) for n in e.element[2:]]))
    present = {(e.block, e.layer, e.col) for e in elems}
    spacing_y = {e.col[1]: e.dy for e in elems}
    spacing_z = {e.col[0]: e.dz for e in elems}
    share: dict = defaultdict(float)
    for e in elems:
        k, j = e.col
        for nxt, face, area, h in (
            ((k, j + 1), e.plus_y, e.dz * e.ds, 0.5 * (e.dy + spacing_y.get(j + 1, 0.0))),
            ((k + 1, j), e.plus_z, e.dy * e.ds, 0.5 * (e.dz + spacing_z.get(k + 1, 0.0))),
        ):
            if (e.block, e.layer, nxt) not in present:  # a free face: nothing beside it in this block
                continue
            for n in face:
                share[(e.block, round(h, 6), copy[(n, e.col)], copy[(n, nxt)])] += 0.25 * area
    for (block, h, a, b), area in share.items():
        out.links[block].append((a, b, h, area))
    return out
