"""The geometry of a block of Belytschko–Lin–Tsay shells, as loops that
LLVM vectorises across the block's elements: strain rates at the
mid-step shape, nodal forces at x(n+1).

kernels.shell's docstring has the formulas: the corotational frame, the
one-point gradient B, the membrane, curvature and transverse-shear rates
with the Belytschko–Wong–Chiang warping correction, the hourglass mode
rates; the forces and moments as the exact transpose of those rates,
with the hourglass resistance.
A triangle (n3 = n4) runs as a quadrilateral with its third node twice:
its normal, area and the summed B of the doubled node are those of the
C0 triangle, and only the shear's nodal mean (⅓ instead of ¼) and the
quadrilateral-only terms (warping, hourglass) tell the two apart.

The block's scratch G is flat with a constant width BW (row r of element
slot l at r·BW + l): a first loop copies the nodes' positions (at
mid-step and at x(n+1)), velocities and angular velocities into it
(indirect loads, not vectorised), the others compute from G alone (and
the caller copies the forces out), so that LLVM sees no aliasing and
keeps the whole element in SIMD registers, BW elements at a time.
"""

import math

from numba import njit

BW = 16  # elements of a block (kernels.shell.BLOCK)
# input rows: node a's mid-step position relative to node 1, velocity, angular velocity; 1 quad / 0 triangle
G_Q = 0  # 12 rows: 3a + i
G_V = 12  # 12 rows
G_W = 24  # 12 rows
G_QUAD = 36
# output rows
G_AREA = 37  # area (≤ 0 or NaN: degenerate)
G_RATE = 38  # 8 rows: ε̇x, ε̇y, γ̇xy, κ̇x, κ̇y, 2κ̇xy, γ̇yz, γ̇xz
G_HG = 46  # 7 rows: hourglass rates (membrane x, y, out-of-plane, bending x, y), Σ(B1² + B2²), Σγ²
# forces at x(n+1): input rows (and the positions G_Q1)
G_RES = 53  # 8 rows: resultants Nx, Ny, Nxy, Mx, My, Mxy, Qx, Qy per unit length
G_HGS = 61  # 5 rows: hourglass generalized stresses
# output rows
G_F = 66  # 24 rows: force and moment ON corner a, component i at 6a + i and 6a + 3 + i (a triangle's
# fourth corner zero)
G_AREA1 = 90  # area at x(n+1) (≤ 0 or NaN: degenerate)
G_LIVE = 91  # kernels.shell's: the mid-step area of an element that gets forces this step (0: none)
G_DT = 92  # at x(n+1): the critical step times the wave speed, char_length
G_Q1 = 93  # 12 rows, input: node a's position at x(n+1) relative to node 1
N_G = 105


@njit(cache=True)
def gather_nodes(first, nb, x, v, w_ang, dt, conn, tri, G):
    """Copy the nodes of elements first .. first + nb - 1 into G: positions
    relative to the first node at mid-step and at x(n+1), velocities,
    angular velocities (slots past nb repeat the last element). One
    gather for both passes: the loads are indirect, the costly part."""
    h = 0.5 * dt
    for l in range(BW):
        e = first + min(l, nb - 1)
        n0 = conn[e, 0]
        for a in range(4):
            nd = conn[e, a]
            for i in range(3):
                xa, va, x0, v0 = x[nd, i], v[nd, i], x[n0, i], v[n0, i]
                G[(G_Q + 3 * a + i) * BW + l] = (xa - h * va) - (x0 - h * v0)
                G[(G_Q1 + 3 * a + i) * BW + l] = xa - x0
                G[(G_V + 3 * a + i) * BW + l] = va
                G[(G_W + 3 * a + i) * BW + l] = w_ang[nd, i]
        G[G_QUAD * BW + l] = 0.0 if tri[e] == 1 else 1.0


@njit(cache=True, error_model="numpy", inline="always")
def _shape(G, q, l):
    """Frame (x̂, ŷ, ẑ), local coordinates of the four corners about the
    centroid and area of slot l from its positions in G rows q .. q + 11
    (NaN or area ≤ 0: degenerate)."""
    q1x, q1y, q1z = G[(q + 3) * BW + l], G[(q + 4) * BW + l], G[(q + 5) * BW + l]
    q2x, q2y, q2z = G[(q + 6) * BW + l], G[(q + 7) * BW + l], G[(q + 8) * BW + l]
    q3x, q3y, q3z = G[(q + 9) * BW + l], G[(q + 10) * BW + l], G[(q + 11) * BW + l]
    # normal along the diagonals' cross product (a triangle's: its sides')
    sx, sy, sz = q3x - q1x, q3y - q1y, q3z - q1z
    nx = q2y * sz - q2z * sy
    ny = q2z * sx - q2x * sz
    nz = q2x * sy - q2y * sx
    inl = 1.0 / math.sqrt(nx * nx + ny * ny + nz * nz)
    nx, ny, nz = nx * inl, ny * inl, nz * inl
    d = q1x * nx + q1y * ny + q1z * nz
    tx, ty, tz = q1x - d * nx, q1y - d * ny, q1z - d * nz
    itl = 1.0 / math.sqrt(tx * tx + ty * ty + tz * tz)
    tx, ty, tz = tx * itl, ty * itl, tz * itl
    bx, by, bz = ny * tz - nz * ty, nz * tx - nx * tz, nx * ty - ny * tx
    cx = 0.25 * (q1x + q2x + q3x)
    cy = 0.25 * (q1y + q2y + q3y)
    cz = 0.25 * (q1z + q2z + q3z)
    # local coordinates about the centroid
    X0, Y0, Z0 = -(cx * tx + cy * ty + cz * tz), -(cx * bx + cy * by + cz * bz), -(cx * nx + cy * ny + cz * nz)
    X1 = (q1x - cx) * tx + (q1y - cy) * ty + (q1z - cz) * tz
    Y1 = (q1x - cx) * bx + (q1y - cy) * by + (q1z - cz) * bz
    Z1 = (q1x - cx) * nx + (q1y - cy) * ny + (q1z - cz) * nz
    X2 = (q2x - cx) * tx + (q2y - cy) * ty + (q2z - cz) * tz
    Y2 = (q2x - cx) * bx + (q2y - cy) * by + (q2z - cz) * bz
    Z2 = (q2x - cx) * nx + (q2y - cy) * ny + (q2z - cz) * nz
    X3 = (q3x - cx) * tx + (q3y - cy) * ty + (q3z - cz) * tz
    Y3 = (q3x - cx) * bx + (q3y - cy) * by + (q3z - cz) * bz
    Z3 = (q3x - cx) * nx + (q3y - cy) * ny + (q3z - cz) * nz
    area = 0.5 * ((X2 - X0) * (Y3 - Y1) + (X1 - X3) * (Y2 - Y0))
    return tx, ty, tz, bx, by, bz, nx, ny, nz, X0, Y0, Z0, X1, Y1, Z1, X2, Y2, Z2, X3, Y3, Z3, area


@njit(cache=True, error_model="numpy", inline="always")
def _gradient(X0, Y0, X1, Y1, X2, Y2, X3, Y3, area):
    """One-point gradient B1, B2 and hourglass vector γ = h − (h·x̂)B1 −
    (h·ŷ)B2 of the four corners."""
    f = 0.5 / area
    a0, a1, a2, a3 = f * (Y1 - Y3), f * (Y2 - Y0), f * (Y3 - Y1), f * (Y0 - Y2)
    c0, c1, c2, c3 = f * (X3 - X1), f * (X0 - X2), f * (X1 - X3), f * (X2 - X0)
    hx = X0 - X1 + X2 - X3
    hy = Y0 - Y1 + Y2 - Y3
    return (
        a0,
        a1,
        a2,
        a3,
        c0,
        c1,
        c2,
        c3,
        1.0 - hx * a0 - hy * c0,
        -1.0 - hx * a1 - hy * c1,
        1.0 - hx * a2 - hy * c2,
        -1.0 - hx * a3 - hy * c3,
    )


@njit(cache=True, inline="always")
def _local(G, a, l, tx, ty, tz, bx, by, bz, nx, ny, nz):
    """Node a's velocity (x̂, ŷ, ẑ) and angular velocity (x̂, ŷ) in the frame."""
    ux, uy, uz = G[(G_V + 3 * a) * BW + l], G[(G_V + 3 * a + 1) * BW + l], G[(G_V + 3 * a + 2) * BW + l]
    wx, wy, wz = G[(G_W + 3 * a) * BW + l], G[(G_W + 3 * a + 1) * BW + l], G[(G_W + 3 * a + 2) * BW + l]
    return (
        tx * ux + ty * uy + tz * uz,
        bx * ux + by * uy + bz * uz,
        nx * ux + ny * uy + nz * uz,
        tx * wx + ty * wy + tz * wz,
        bx * wx + by * wy + bz * wz,
    )


@njit(cache=True, error_model="numpy")
def block_rates(bwc, G):
    """The rates of the BW elements in G (see the module docstring)."""
    for l in range(BW):
        tx, ty, tz, bx, by, bz, nx, ny, nz, X0, Y0, Z0, X1, Y1, Z1, X2, Y2, Z2, X3, Y3, Z3, area = _shape(G, G_Q, l)
        quad = G[G_QUAD * BW + l]
        a0, a1, a2, a3, c0, c1, c2, c3, g0, g1, g2, g3 = _gradient(X0, Y0, X1, Y1, X2, Y2, X3, Y3, area)
        # local velocities and angular velocities
        vx0, vy0, vz0, ox0, oy0 = _local(G, 0, l, tx, ty, tz, bx, by, bz, nx, ny, nz)
        vx1, vy1, vz1, ox1, oy1 = _local(G, 1, l, tx, ty, tz, bx, by, bz, nx, ny, nz)
        vx2, vy2, vz2, ox2, oy2 = _local(G, 2, l, tx, ty, tz, bx, by, bz, nx, ny, nz)
        vx3, vy3, vz3, ox3, oy3 = _local(G, 3, l, tx, ty, tz, bx, by, bz, nx, ny, nz)
        dx = a0 * vx0 + a1 * vx1 + a2 * vx2 + a3 * vx3
        dy = c0 * vy0 + c1 * vy1 + c2 * vy2 + c3 * vy3
        bvx = c0 * vx0 + c1 * vx1 + c2 * vx2 + c3 * vx3
        gxy = bvx + a0 * vy0 + a1 * vy1 + a2 * vy2 + a3 * vy3
        kx = a0 * oy0 + a1 * oy1 + a2 * oy2 + a3 * oy3
        ky = -(c0 * ox0 + c1 * ox1 + c2 * ox2 + c3 * ox3)
        kxy = c0 * oy0 + c1 * oy1 + c2 * oy2 + c3 * oy3 - (a0 * ox0 + a1 * ox1 + a2 * ox2 + a3 * ox3)
        wvx = a0 * vz0 + a1 * vz1 + a2 * vz2 + a3 * vz3
        wvy = c0 * vz0 + c1 * vz1 + c2 * vz2 + c3 * vz3
        sox = ox0 + ox1 + ox2 + quad * ox3  # Σ over the distinct nodes
        soy = oy0 + oy1 + oy2 + quad * oy3
        inv = 0.25 if quad == 1.0 else 1.0 / 3.0
        gxz = wvx + soy * inv
        gyz = wvy - sox * inv
        zg = g0 * Z0 + g1 * Z1 + g2 * Z2 + g3 * Z3
        if bwc == 1:  # warping correction (quadrilaterals)
            cw = quad * 0.5 * zg / (area * area)
            om = 0.5 * (gxy - 2.0 * bvx)  # in-plane spin
            e0x, e0y = cw * (X0 - X2), cw * (Y0 - Y2)  # B^c of nodes 1 and 3, 2 and 4: ±c·x13, ±c·x42
            e1x, e1y = cw * (X3 - X1), cw * (Y3 - Y1)
            u0x, u0y = vx0 + om * Y0, vy0 - om * X0
            u1x, u1y = vx1 + om * Y1, vy1 - om * X1
            u2x, u2y = vx2 + om * Y2, vy2 - om * X2
            u3x, u3y = vx3 + om * Y3, vy3 - om * X3
            kx += e0x * (u0x - u2x) + e1x * (u1x - u3x)
            ky += e0y * (u0y - u2y) + e1y * (u1y - u3y)
            kxy += e0y * (u0x - u2x) + e1y * (u1x - u3x) + e0x * (u0y - u2y) + e1x * (u1y - u3y)
        G[G_AREA * BW + l] = area
        G[G_RATE * BW + l], G[(G_RATE + 1) * BW + l], G[(G_RATE + 2) * BW + l] = dx, dy, gxy
        G[(G_RATE + 3) * BW + l], G[(G_RATE + 4) * BW + l], G[(G_RATE + 5) * BW + l] = kx, ky, kxy
        G[(G_RATE + 6) * BW + l], G[(G_RATE + 7) * BW + l] = gyz, gxz
        G[G_HG * BW + l] = g0 * vx0 + g1 * vx1 + g2 * vx2 + g3 * vx3 - 0.25 * zg * soy
        G[(G_HG + 1) * BW + l] = g0 * vy0 + g1 * vy1 + g2 * vy2 + g3 * vy3 + 0.25 * zg * sox
        G[(G_HG + 2) * BW + l] = g0 * vz0 + g1 * vz1 + g2 * vz2 + g3 * vz3
        G[(G_HG + 3) * BW + l] = g0 * ox0 + g1 * ox1 + g2 * ox2 + g3 * ox3
        G[(G_HG + 4) * BW + l] = g0 * oy0 + g1 * oy1 + g2 * oy2 + g3 * oy3
        G[(G_HG + 5) * BW + l] = a0 * a0 + a1 * a1 + a2 * a2 + a3 * a3 + c0 * c0 + c1 * c1 + c2 * c2 + c3 * c3
        G[(G_HG + 6) * BW + l] = g0 * g0 + g1 * g1 + g2 * g2 + g3 * g3


@njit(cache=True, error_model="numpy", inline="always")
def _corner(b1, b2, g, k1, k2, wq, fr, tx, ty, tz, bx, by, bz, nx, ny, nz):
    """Force and moment ON a corner (global components) from its B1, B2,
    hourglass γ, warping B^c (k1, k2) and share wq of the shear's moment;
    fr the element's resultants, hourglass stresses, ¼z_γ, the warping
    sum and the area."""
    n0, n1, n2, m0, m1, m2, qx, qy, h0, h1, h2, h3, h4, zg4, sbwc, area = fr
    fx = area * (b1 * n0 + b2 * n2) + g * h0 + area * (m0 * k1 + m2 * k2) - 0.5 * sbwc * b2
    fy = area * (b2 * n1 + b1 * n2) + g * h1 + area * (m1 * k2 + m2 * k1) + 0.5 * sbwc * b1
    fz = area * (b1 * qx + b2 * qy) + g * h2
    mx = area * (-b2 * m1 - b1 * m2 - wq * qy) + g * h3 + zg4 * h1
    my = area * (b1 * m0 + b2 * m2 + wq * qx) + g * h4 - zg4 * h0
    return (
        -(fx * tx + fy * bx + fz * nx),
        -(fx * ty + fy * by + fz * ny),
        -(fx * tz + fy * bz + fz * nz),
        -(mx * tx + my * bx),
        -(mx * ty + my * by),
        -(mx * tz + my * bz),
    )


@njit(cache=True, inline="always")
def char_length(isdo, quad, area, s01, s12, s23, s30, d02, d13):
    """LS-DYNA's characteristic length of a shell (*CONTROL_TIMESTEP ISDO)
    from its area and squared sides s01..s30 and diagonals d02, d13; a
    triangle (quad 0) is the quadrilateral with nodes 3 and 4 the same, β = 1:
    0: (1 + β)·A / longest side; 1: (1 + β)·A / longest diagonal;
    2: the larger of ISDO 0's and the shortest side (with the bar wave
    speed, kernels.shell.wave_speed2)."""
    f = 2.0 - quad  # 1 + β
    if isdo == 1:
        return f * area / math.sqrt(max(d02, d13))
    length = f * area / math.sqrt(max(max(s01, s12), max(s23, s30)))
    if isdo == 2:
        shortest = min(min(s01, s12), min(s23 + (1.0 - quad) * 1e300, s30))
        length = max(length, math.sqrt(shortest))
    return length


@njit(cache=True, error_model="numpy")
def block_forces(bwc, isdo, G):
    """Corner forces and moments ON the nodes of the BW elements in G from
    their resultants and hourglass stresses (see the module docstring); the
    area and the length of the critical step at x(n+1)."""
    for l in range(BW):
        tx, ty, tz, bx, by, bz, nx, ny, nz, X0, Y0, Z0, X1, Y1, Z1, X2, Y2, Z2, X3, Y3, Z3, area = _shape(G, G_Q1, l)
        quad = G[G_QUAD * BW + l]
        a0, a1, a2, a3, c0, c1, c2, c3, g0, g1, g2, g3 = _gradient(X0, Y0, X1, Y1, X2, Y2, X3, Y3, area)
        zg = g0 * Z0 + g1 * Z1 + g2 * Z2 + g3 * Z3
        n0, n1, n2 = G[G_RES * BW + l], G[(G_RES + 1) * BW + l], G[(G_RES + 2) * BW + l]
        m0, m1, m2 = G[(G_RES + 3) * BW + l], G[(G_RES + 4) * BW + l], G[(G_RES + 5) * BW + l]
        qx, qy = G[(G_RES + 6) * BW + l], G[(G_RES + 7) * BW + l]
        h0, h1, h2 = G[G_HGS * BW + l], G[(G_HGS + 1) * BW + l], G[(G_HGS + 2) * BW + l]
        h3, h4 = G[(G_HGS + 3) * BW + l], G[(G_HGS + 4) * BW + l]
        zg4 = 0.25 * zg * quad
        inv = 0.25 if quad == 1.0 else 1.0 / 3.0
        # warping correction: B^c of nodes 1..4 = c·(x13, x42, x31, x24) (and y)
        cw = quad * 0.5 * zg / (area * area) if bwc == 1 else 0.0
        e0x, e0y = cw * (X0 - X2), cw * (Y0 - Y2)
        e1x, e1y = cw * (X3 - X1), cw * (Y3 - Y1)
        sbwc = area * (
            (m0 * e0x + m2 * e0y) * (Y0 - Y2)
            - (m1 * e0y + m2 * e0x) * (X0 - X2)
            + (m0 * e1x + m2 * e1y) * (Y1 - Y3)
            - (m1 * e1y + m2 * e1x) * (X1 - X3)
        )
        fr = (n0, n1, n2, m0, m1, m2, qx, qy, h0, h1, h2, h3, h4, zg4, sbwc, area)
        f0 = _corner(a0, c0, g0, e0x, e0y, inv, fr, tx, ty, tz, bx, by, bz, nx, ny, nz)
        f1 = _corner(a1, c1, g1, e1x, e1y, inv, fr, tx, ty, tz, bx, by, bz, nx, ny, nz)
        f2 = _corner(a2, c2, g2, -e0x, -e0y, inv, fr, tx, ty, tz, bx, by, bz, nx, ny, nz)
        f3 = _corner(a3, c3, g3, -e1x, -e1y, inv * quad, fr, tx, ty, tz, bx, by, bz, nx, ny, nz)
        tri = 1.0 - quad  # a triangle: its fourth corner is its third node
        for i in range(6):
            G[(G_F + i) * BW + l] = f0[i]
            G[(G_F + 6 + i) * BW + l] = f1[i]
            G[(G_F + 12 + i) * BW + l] = f2[i] + tri * f3[i]
            G[(G_F + 18 + i) * BW + l] = quad * f3[i]
        G[G_AREA1 * BW + l] = area
        # the element's step (kernels.shell.shell_timestep's, here where the shape is at hand)
        s01 = (X1 - X0) ** 2 + (Y1 - Y0) ** 2 + (Z1 - Z0) ** 2
        s12 = (X2 - X1) ** 2 + (Y2 - Y1) ** 2 + (Z2 - Z1) ** 2
        s23 = (X3 - X2) ** 2 + (Y3 - Y2) ** 2 + (Z3 - Z2) ** 2
        s30 = (X0 - X3) ** 2 + (Y0 - Y3) ** 2 + (Z0 - Z3) ** 2
        d02 = (X2 - X0) ** 2 + (Y2 - Y0) ** 2 + (Z2 - Z0) ** 2
        d13 = (X3 - X1) ** 2 + (Y3 - Y1) ** 2 + (Z3 - Z1) ** 2
        G[G_DT * BW + l] = char_length(isdo, quad, area, s01, s12, s23, s30, d02, d13)
