"""Mass-property kernels against closed-form (hand) integrals.

Each body's mass, CoG and inertia about the CoG come from textbook formulas
(box, polygon, triangle, tetrahedron, parallelepiped, segment), never from
the kernels themselves; the quadrature is exact for all of them, hence the
tight 1e-9 relative tolerance.
"""

import warnings

import numpy as np
import pytest

from crashlite.model.mass import (
    MassProperties,
    Moments,
    beam_moments,
    combine,
    point_moments,
    shell_moments,
    solid_moments,
)

RTOL = 1e-9
RHO = 7.85e-9  # steel, t/mm³


def close(actual, expected):
    """Relative tolerance on the array's scale (zeros off the diagonal)."""
    expected = np.asarray(expected, float)
    np.testing.assert_allclose(actual, expected, rtol=RTOL, atol=RTOL * max(np.abs(expected).max(), 1e-300))


def rotation(axis, angle):
    """Rodrigues: rotation by ``angle`` about ``axis``."""
    k = np.asarray(axis, float) / np.linalg.norm(axis)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * kx + (1 - np.cos(angle)) * kx @ kx


R = rotation([1.0, -2.0, 0.7], 0.83)
SHIFT = np.array([120.0, -45.0, 80.0])


def inertia_from_second(m, c, second):
    """Inertia about the CoG from ∫r⊗r about the origin (hand formula)."""
    s = second - m * np.outer(c, c)
    return np.trace(s) * np.eye(3) - s


def check(props, m, c, inertia):
    close(props.mass, m)
    close(props.cog, c)
    close(props.inertia, inertia)


def grid_quads(xs, ys):
    """Nodes (z = 0) and quads of a structured grid, counter-clockwise."""
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    xyz = np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)], axis=1)
    idx = np.arange(X.size).reshape(X.shape)
    conn = np.stack([idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]], axis=-1).reshape(-1, 4)
    return xyz, conn


def grid_hexes(xs, ys, zs):
    X, Y, Z = np.meshgrid(xs, ys, zs, indexing="ij")
    xyz = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)
    i = np.arange(X.size).reshape(X.shape)
    conn = np.stack(
        [
            i[:-1, :-1, :-1],
            i[1:, :-1, :-1],
            i[1:, 1:, :-1],
            i[:-1, 1:, :-1],
            i[:-1, :-1, 1:],
            i[1:, :-1, 1:],
            i[1:, 1:, 1:],
            i[:-1, 1:, 1:],
        ],
        axis=-1,
    )
    return xyz, conn.reshape(-1, 8)


def tet_moments(p):
    """Volume, ∫r dV and ∫r⊗r dV of a tetrahedron (4, 3):
    V, V s/4 and V/20 (Σ pᵢ⊗pᵢ + s⊗s) with s = Σ pᵢ."""
    v = abs(np.linalg.det(p[1:] - p[0])) / 6
    s = p.sum(0)
    return v, v * s / 4, v / 20 * (p.T @ p + np.outer(s, s))


def expected_from_tets(p, tets):
    """Mass, CoG and inertia of a solid made of tetrahedra (node index lists)."""
    v, f, s = (sum(x) for x in zip(*(tet_moments(p[list(t)]) for t in tets)))
    m, c = RHO * v, f / v
    return m, c, inertia_from_second(m, c, RHO * s)


# -- shells ------------------------------------------------------------------


def test_rectangular_plate_meshed_and_rotated():
    """Plate a × b × t from 3 × 2 uneven quads: box formulas; rotated and
    shifted, the CoG moves with the body and I becomes R I Rᵀ."""
    a, b, t = 300.0, 120.0, 2.5
    xyz, conn = grid_quads([0.0, 70.0, 210.0, a], [0.0, 50.0, b])
    m = RHO * a * b * t
    c = np.array([a / 2, b / 2, 0.0])
    inertia = np.diag([b * b + t * t, a * a + t * t, a * a + b * b]) * m / 12
    check(combine(shell_moments(xyz, conn, np.full(len(conn), t), np.full(len(conn), RHO))), m, c, inertia)
    moved = xyz @ R.T + SHIFT
    props = combine(shell_moments(moved, conn, t, RHO))
    check(props, m, R @ c + SHIFT, R @ inertia @ R.T)


def test_trapezoid_plate():
    """One non-parallelogram quad and the same trapezoid as 2 quads: polygon
    area-moment formulas (Green's theorem) plus the thickness term t²/12."""
    v = np.array([[0.0, 0.0], [60.0, 0.0], [45.0, 30.0], [10.0, 30.0]])
    t = 1.5
    x0, y0 = v.T
    x1, y1 = np.roll(v, -1, axis=0).T
    cr = x0 * y1 - x1 * y0
    area = cr.sum() / 2
    assert area == pytest.approx((60 + 35) * 30 / 2)
    sx, sy = ((x0 + x1) * cr).sum() / 6, ((y0 + y1) * cr).sum() / 6
    sxx = ((x0**2 + x0 * x1 + x1**2) * cr).sum() / 12
    syy = ((y0**2 + y0 * y1 + y1**2) * cr).sum() / 12
    sxy = ((x0 * y1 + 2 * x0 * y0 + 2 * x1 * y1 + x1 * y0) * cr).sum() / 24
    m = RHO * t * area
    second = RHO * t * np.array([[sxx, sxy, 0], [sxy, syy, 0], [0, 0, area * t * t / 12]])
    c = np.array([sx, sy, 0.0]) / area
    expected = (m, c, inertia_from_second(m, c, second))

    xyz = np.c_[v, np.zeros(4)]
    check(combine(shell_moments(xyz, [[0, 1, 2, 3]], t, RHO)), *expected)
    split = np.vstack([xyz, [[35.0, 0, 0], [27.5, 30.0, 0]]])  # bottom and top midpoints
    check(combine(shell_moments(split, [[0, 4, 5, 3], [4, 1, 2, 5]], t, RHO)), *expected)


def test_plate_with_linear_nodal_thickness():
    """t = t0 + k x on a rectangle: m = ρ b ∫t dx, ∫x² etc. by hand; the
    through-thickness term ∫ρ t³/12 dA is exact too (degree 3)."""
    a, b, t0, t1 = 80.0, 40.0, 1.0, 3.0
    k = (t1 - t0) / a
    xyz, conn = grid_quads([0.0, 30.0, a], [0.0, b])
    tn = t0 + k * xyz[conn, 0]  # (n, 4) nodal thicknesses
    iu = lambda p: ((t0 + k * a) ** (p + 1) - t0 ** (p + 1)) / (k * (p + 1))  # ∫ t^p dx  # noqa: E731
    ix = t0 * a**2 / 2 + k * a**3 / 3  # ∫ t x dx
    ixx = t0 * a**3 / 3 + k * a**4 / 4  # ∫ t x² dx
    m = RHO * b * iu(1)
    first = RHO * np.array([b * ix, iu(1) * b**2 / 2, 0.0])
    second = RHO * np.array([[b * ixx, ix * b**2 / 2, 0], [ix * b**2 / 2, iu(1) * b**3 / 3, 0], [0, 0, b * iu(3) / 12]])
    c = first / m
    check(combine(shell_moments(xyz, conn, tn, RHO)), m, c, inertia_from_second(m, c, second))


def test_triangle_as_degenerate_quad():
    """Triangle in space (node 3 repeated): ∫r⊗r dA = A/12 (Σ pᵢ⊗pᵢ + s⊗s)
    plus A t²/12 n⊗n through the thickness; a 4th thickness is ignored."""
    p = np.array([[10.0, -5.0, 3.0], [70.0, 12.0, -8.0], [25.0, 48.0, 30.0]])
    t = 2.0
    nrm = np.cross(p[1] - p[0], p[2] - p[0])
    area = np.linalg.norm(nrm) / 2
    n = nrm / (2 * area)
    s = p.sum(0)
    m = RHO * t * area
    second = RHO * t * (area / 12 * (p.T @ p + np.outer(s, s)) + area * t * t / 12 * np.outer(n, n))
    c = s / 3
    props = combine(shell_moments(p, [[0, 1, 2, 2]], [[t, t, t, 99.0]], [RHO]))
    check(props, m, c, inertia_from_second(m, c, second))


# -- solids ------------------------------------------------------------------


def test_brick_from_hexes_with_moved_inner_node():
    """Brick a × b × c as 2 × 2 × 2 hexes: exact box values, also after the
    shared centre node moves (8 general trilinear elements that still tile
    the brick) and after rotating the whole mesh."""
    a, b, c = 60.0, 40.0, 30.0
    xyz, conn = grid_hexes([0, 25.0, a], [0, 20.0, b], [0, 12.0, c])
    m = RHO * a * b * c
    cog = np.array([a, b, c]) / 2
    inertia = np.diag([b * b + c * c, a * a + c * c, a * a + b * b]) * m / 12
    check(combine(solid_moments(xyz, conn, RHO)), m, cog, inertia)
    centre = 13  # node (1, 1, 1) of the 3 × 3 × 3 grid
    xyz[centre] += [7.0, -4.0, 5.0]
    check(combine(solid_moments(xyz, conn, np.full(len(conn), RHO))), m, cog, inertia)
    props = combine(solid_moments(xyz @ R.T + SHIFT, conn, RHO))
    check(props, m, R @ cog + SHIFT, R @ inertia @ R.T)


def test_parallelepiped_from_affine_hexes():
    """A sheared brick r = o + A ξ, ξ ∈ [0,1]³, meshed with 2 × 2 × 1
    parallelepipeds (affine but distorted, left-handed A): ∫r⊗r dV =
    |det A| (o⊗o + o⊗(A h) + (A h)⊗o + A M Aᵀ), h = ½(1,1,1), M = ∫ξ⊗ξ
    (1/3 on, 1/4 off the diagonal)."""
    o = np.array([5.0, -3.0, 2.0])
    A = np.array([[40.0, 12.0, 5.0], [3.0, 30.0, -6.0], [4.0, 7.0, -25.0]])
    assert np.linalg.det(A) < 0
    ref, conn = grid_hexes([0, 0.4, 1], [0, 0.5, 1], [0, 1])
    xyz = o + ref @ A.T
    vol = abs(np.linalg.det(A))
    h = np.full(3, 0.5)
    M = np.full((3, 3), 0.25) + np.eye(3) / 12
    m = RHO * vol
    second = RHO * vol * (np.outer(o, o) + np.outer(o, A @ h) + np.outer(A @ h, o) + A @ M @ A.T)
    c = o + A @ h
    check(combine(solid_moments(xyz, conn, RHO)), m, c, inertia_from_second(m, c, second))


@pytest.mark.parametrize(
    "order",
    [[0, 1, 2, 2, 3, 3, 3, 3], [0, 1, 2, 3, 3, 3, 3, 3], [3, 2, 1, 0, 0, 0, 0, 0]],
    ids=["n3-n4-repeated", "ls-dyna-n4-repeated", "reversed"],
)
def test_tetrahedron_as_degenerate_hex(order):
    p = np.array([[1.0, 2.0, 0.5], [41.0, 5.0, -3.0], [8.0, 33.0, 4.0], [6.0, 9.0, 27.0]])
    check(combine(solid_moments(p, [order], RHO)), *expected_from_tets(p, [[0, 1, 2, 3]]))


@pytest.mark.parametrize(
    "order", [[0, 1, 2, 2, 3, 4, 5, 5], [0, 1, 4, 3, 2, 2, 5, 5]], ids=["n3-n6-repeated", "ls-dyna-n5-n6-repeated"]
)
def test_wedge_as_degenerate_hex(order):
    """Oblique triangular prism (triangles 0 1 2 and 3 4 5) = 3 tetrahedra."""
    tri = np.array([[0.0, 0.0, 0.0], [30.0, 2.0, 1.0], [5.0, 25.0, -2.0]])
    p = np.vstack([tri, tri + [4.0, -3.0, 20.0]])
    expected = expected_from_tets(p, [[0, 1, 2, 3], [1, 2, 3, 4], [2, 3, 4, 5]])
    check(combine(solid_moments(p, [order], RHO)), *expected)


def test_pyramid_as_degenerate_hex():
    """Planar convex quad base, apex repeated 4 times = 2 tetrahedra."""
    p = np.array([[0.0, 0.0, 0.0], [40.0, -5.0, 0.0], [45.0, 30.0, 0.0], [-3.0, 35.0, 0.0], [12.0, 8.0, 33.0]])
    expected = expected_from_tets(p, [[0, 1, 2, 4], [0, 2, 3, 4]])
    check(
        combine(solid_moments(p @ R.T, [[0, 1, 2, 3, 4, 4, 4, 4]], RHO)),
        expected[0],
        R @ expected[1],
        R @ expected[2] @ R.T,
    )


# -- beams and points -------------------------------------------------------


def test_beam_segment():
    """Uniform rod: m = ρAL, CoG at mid-length, I = m L²/12 (1 − e⊗e)."""
    a, b = np.array([10.0, 20.0, -5.0]), np.array([110.0, -30.0, 45.0])
    area = 80.0
    L = np.linalg.norm(b - a)
    e = (b - a) / L
    m = RHO * area * L
    props = combine(beam_moments(np.array([a, b]), [[0, 1]], [area], [RHO]))
    check(props, m, (a + b) / 2, m * L * L / 12 * (np.eye(3) - np.outer(e, e)))
    # split in two at an uneven point: same body
    mid = a + 0.3 * (b - a)
    check(
        combine(beam_moments(np.array([a, mid, b]), [[0, 1], [1, 2]], area, RHO)),
        m,
        (a + b) / 2,
        m * L * L / 12 * (np.eye(3) - np.outer(e, e)),
    )


def test_point_masses_with_inertia():
    """Two point bodies: I = Σ Iₖ + mₖ(|dₖ|²·1 − dₖ⊗dₖ), dₖ from the CoG."""
    p = np.array([[0.0, 0.0, 0.0], [100.0, 50.0, -20.0]])
    m = np.array([0.2, 0.6])
    i0 = np.array([[5.0, 0.3, -0.2], [0.3, 4.0, 0.1], [-0.2, 0.1, 6.0]])
    i1 = np.diag([1.0, 2.0, 2.5])
    c = (m[:, None] * p).sum(0) / m.sum()
    expected = i0 + i1
    for mk, pk in zip(m, p):
        d = pk - c
        expected = expected + mk * (d @ d * np.eye(3) - np.outer(d, d))
    check(combine(point_moments(p, m, np.stack([i0, i1]))), m.sum(), c, expected)
    # a single body's own tensor survives unchanged about its point
    check(combine(point_moments(p[1:], m[1:], i0[None])), m[1], p[1], i0)


# -- combining ---------------------------------------------------------------


def _bodies():
    xyz, conn = grid_quads([0.0, 50.0, 120.0], [0.0, 40.0])
    plate = shell_moments(xyz + [0, 0, 300.0], conn, 2.0, RHO)
    bxyz, bconn = grid_hexes([0, 20.0, 50.0], [0, 30.0], [0, 10.0, 25.0])
    brick = solid_moments(bxyz @ R.T + [200.0, 10.0, 0.0], bconn, RHO)
    beam = beam_moments(np.array([[0.0, -50.0, 0.0], [0.0, -50.0, 400.0]]), [[0, 1]], 50.0, RHO)
    point = point_moments([[80.0, 80.0, 80.0]], [1e-4], np.diag([2.0, 3.0, 4.0])[None])
    return plate, brick, beam, point


def test_add_is_parallel_axis_theorem():
    """Adding bodies' MassProperties equals combining their raw moments."""
    bodies = _bodies()
    together = combine(*bodies)
    summed = combine(bodies[0])
    for b in bodies[1:]:
        summed = summed + combine(b)
    check(summed, together.mass, together.cog, together.inertia)
    empty = MassProperties(0.0, np.zeros(3), np.zeros((3, 3)))
    for props in (empty + summed, summed + empty):
        check(props, together.mass, together.cog, together.inertia)


def test_weights_mask_selects_and_scales():
    plate, brick, beam, point = _bodies()
    sel = np.zeros(len(brick.mass), bool)
    sel[[0, 2]] = True
    sub = Moments(brick.mass[sel], brick.first[sel], brick.second[sel])
    expected = combine(plate, sub)
    props = combine(plate, brick, beam, weights_mask=[None, sel, np.zeros(1)])
    check(props, expected.mass, expected.cog, expected.inertia)
    doubled = combine(plate, weights_mask=[np.full(len(plate.mass), 2.0)])
    single = combine(plate)
    check(doubled, 2 * single.mass, single.cog, 2 * single.inertia)
    with pytest.raises(ValueError):
        combine(plate, brick, weights_mask=[None])


def test_principal_axes_of_rotated_brick():
    """Brick with distinct edges, rotated: principal moments are the box
    values in ascending order, axes the rotated edge directions."""
    a, b, c = 20.0, 50.0, 35.0  # Ixx > Izz > Iyy
    xyz, conn = grid_hexes([0, a], [0, b], [0, c])
    props = combine(solid_moments(xyz @ R.T + SHIFT, conn, RHO))
    m = RHO * a * b * c
    moments, axes = props.principal
    close(moments, np.array([a * a + c * c, a * a + b * b, b * b + c * c]) * m / 12)
    expected_axes = R[:, [1, 2, 0]]  # edges y, z, x
    close(np.abs(np.sum(axes * expected_axes, axis=0)), np.ones(3))
    close(axes.T @ axes, np.eye(3))
    assert np.linalg.det(axes) == pytest.approx(1.0)
    close(axes @ np.diag(moments) @ axes.T, props.inertia)


def test_zero_mass_and_empty_inputs_do_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with np.errstate(all="raise"):
            for props in (
                combine(),
                combine(shell_moments(np.zeros((0, 3)), np.zeros((0, 4), int), [], [])),
                combine(solid_moments(np.ones((1, 3)), np.zeros((1, 8), int), 1.0)),
                combine(shell_moments(np.ones((1, 3)), np.zeros((1, 4), int), 1.0, 1.0)),
                combine(beam_moments(np.eye(3), [[0, 1]], 10.0, 0.0)),
            ):
                assert props.mass == 0.0
                assert np.array_equal(props.cog, np.zeros(3))
                assert np.array_equal(props.inertia, np.zeros((3, 3)))
            assert shell_moments(np.zeros((0, 3)), np.zeros((0, 4), int), [], []).second.shape == (0, 3, 3)


def test_blocks_match_single_pass(monkeypatch):
    """Block processing of large meshes gives the same per-element rows."""
    import crashlite.model.mass as mass

    xyz, conn = grid_hexes(np.linspace(0, 50, 6), [0, 10.0], [0, 10.0, 30.0])
    sxyz, sconn = grid_quads(np.linspace(0, 90, 8), [0, 5.0, 20.0])
    ref_solid, ref_shell = solid_moments(xyz, conn, RHO), shell_moments(sxyz, sconn, 1.2, RHO)
    monkeypatch.setattr(mass, "_BLOCK_SOLIDS", 3)
    monkeypatch.setattr(mass, "_BLOCK_SHELLS", 4)
    for got, ref in ((solid_moments(xyz, conn, RHO), ref_solid), (shell_moments(sxyz, sconn, 1.2, RHO), ref_shell)):
        for g, r in zip(got, ref):
            np.testing.assert_array_equal(g, r)
