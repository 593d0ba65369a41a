"""Belytschko–Lin–Tsay shell (LS-DYNA ELFORM 2) and the C0 triangle.

One in-plane integration point, a corotational frame per element and the
stresses kept in that frame (the frame turns with the element, so rigid
rotations leave them unchanged):
  e3 along the cross product of the diagonals (quad) or sides (triangle),
  e1 along side 1-2 projected on the plane, e2 = e3 × e1 (LS-DYNA's
  default). Fibres are along e3; nodal rotations enter through the angular
  velocities only (rate form), no drilling stiffness.
Strain rates at the mid-step configuration x(n+½) = x(n+1) − ½Δt·v(n+½):
  membrane ε̇ = B v̂, curvature κ̇x = B1·θ̂y, κ̇y = −B2·θ̂x,
  2κ̇xy = B2·θ̂y − B1·θ̂x, transverse shear 2ε̇xz = B1·v̂z + N·Σθ̂y,
  2ε̇yz = B2·v̂z − N·Σθ̂x (N = ¼ quad, ⅓ triangle), and at height z the
  in-plane rate ε̇ + z κ̇. B is the one-point (centroid) gradient: exact
  for linear fields on any quadrilateral (patch test); the triangle is the
  constant-strain triangle with linear rotations (Belytschko–Stolarski–
  Carpenter C0 element, n3 = n4 in the deck).
Through the thickness NIP Gauss (or Lobatto) points carry plane-stress
J2 stresses (kernels.plane_stress); the resultants N = ∫σ dz,
M = ∫zσ dz, Q = SHRF·∫τ dz give the nodal forces and moments at
x(n+1) as the exact transpose of the strain-rate operator (internal power
A·(N·ε̇ + M·κ̇ + Q·γ̇)). Optional thickness change from the integrated
normal strain (ISTUPD). Belytschko–Wong–Chiang warping correction
(BWC = 1): curvature rates from the in-plane velocities of a warped
element, B^c = 2 z_γ/A² [x13, x42, x31, x24] (and y), with the element's
rigid spin about its normal projected out so rigid rotations stay strain
free.

Hourglass control (quads, Belytschko–Tsay modes with γ = h − (h·x̂)B1 −
(h·ŷ)B2, h = (1, −1, 1, −1), orthogonal to linear fields): membrane
q̇ = γ·v̂x − ¼(γ·ẑ)Σθ̂y, γ·v̂y + ¼(γ·ẑ)Σθ̂x (rigid rotations of warped
elements excluded), out-of-plane γ·v̂z, bending γ·θ̂x, γ·θ̂y.
Stiffness (IHQ 4, 5): Q̇ = r k q̇ with k = E t A B·B/8 (membrane),
SHRF G t³ B·B/12 (out-of-plane), E t³ A B·B/192 (bending), as in the
BT element; r = QM, QW, QB; on Flanagan–Belytschko's γ/4 (see FB). Viscous (IHQ 1–3): Q = r c q̇ with c the
critical damping 2·sqrt(k·m/|γ|²) of the mode at the element's lumped
mass (rotary inertia m·A/8), so QM is the fraction of critical damping.

Forces and moments ON the nodes go per element corner into fe, me
(n, 4, 3); the fourth corner of a triangle stays zero. Nodes gather them
in a fixed order (kernels.solid.gather_corners): results do not depend on
the number of threads. Elements run in N_CHUNKS fixed chunks,
each with its thread's scratch rows, and within a chunk in blocks of BLOCK
elements: the strain increments of all the block's points first, then
their stresses in one pass that LLVM vectorises where the block is one
material and one section
(plane_stress.update_block; the kernel's single most expensive part was
the return mapping, point by point), then the elements' forces.

Arrays (n elements; units of the model, e.g. mm, t, s, N, MPa):
  x (n_nodes, 3) float64 coordinates at t(n+1) [length]
  v (n_nodes, 3) float64 velocities at t(n+½) [length/time]
  w (n_nodes, 3) float64 angular velocities at t(n+½) [1/time]
  conn (n, 4) int64 node indices (triangles n1 n2 n3 n3); tri (n,) int8 1: triangle
  mat_of (n,) int64 material row; mtype, props, mcurve: see kernels.plane_stress
  curve_start, curve_stop (n_curves,) int64; curve_x, curve_y (m,) float64 curve store
  nip (n,) int64 points through the thickness (1–10); rule (n,) int64 0 Gauss, 1 Lobatto
  shrf (n,) float64 shear correction factor
  hg_kind (n,) int64 0 none, 1 viscous, 2 stiffness; hg_qm, hg_qb, hg_qw (n,) float64 coefficients
  rho (n,) float64 density incl. non-structural mass [mass/length³] (viscous hourglass)
  istupd: 1 thickness change; bwc: 1 warping correction; isdo: *CONTROL_TIMESTEP ISDO (0, 1, 2)
  state, updated in place:
  sig, back (n, nip_max, 5) float64 stress and back stress σx σy τxy τyz τzx in the element frame [stress]
  epsp (n, nip_max) float64 effective plastic strain; ipfail (n, nip_max) int8 1: failed point
  thick (n,) float64 thickness [length]
  alive (n,) int8 1 active, 0 eroded (all points failed), -1 collapsed (area ≤ 0)
  hgq (n, 5) float64 hourglass generalized stresses (2 membrane [force], out-of-plane [force],
      2 bending [force·length])
  energy (n,) float64 internal energy [energy]; hg_energy (n,) float64 hourglass energy [energy]
  points, geometry, kk: scratch (see ``scratch``)
  fe, me (n, 4, 3) float64 output corner forces [force] and moments [force·length]
  step (n,) float64 output: each element's critical step at x(n+1) as shell_timestep's (+inf: inactive) [time]
"""

import math

import numba
import numpy as np
from numba import njit, prange

from .plane_stress import (
    N_ROWS,
    P_E,
    P_G,
    P_RO,
    P_WAVE,
    R_D,
    R_DEZ,
    R_FAILED,
    R_OK,
    R_WK,
    W,
    update_block,
    update_point,
    work_density,
)
from .shell_block import (
    BW,
    G_AREA,
    G_AREA1,
    G_DT,
    G_F,
    G_HG,
    G_HGS,
    G_LIVE,
    G_RATE,
    G_RES,
    N_G,
    block_forces,
    block_rates,
    char_length,
    gather_nodes,
)


def _rules():
    """ZETA, WEIGHT (2, 11, 10): rule (0 Gauss, 1 Lobatto), NIP, point:
    positions in [−1, 1] from bottom to top and weights summing to 1."""
    zeta = np.zeros((2, 11, 10))
    weight = np.zeros((2, 11, 10))
    for n in range(1, 11):
        g, gw = np.polynomial.legendre.leggauss(n)
        zeta[0, n, :n], weight[0, n, :n] = g, gw / 2.0
        if n >= 3:  # Lobatto: ends and the roots of P'_{n-1}, w = 2/(n(n-1)P_{n-1}²)
            p = np.polynomial.legendre.Legendre.basis(n - 1)
            inner = np.sort(p.deriv().roots().real)
            pts = np.concatenate([[-1.0], inner, [1.0]])
            zeta[1, n, :n], weight[1, n, :n] = pts, 2.0 / (n * (n - 1) * p(pts) ** 2) / 2.0
        else:
            zeta[1, n, :n], weight[1, n, :n] = g, gw / 2.0
    return zeta, weight


ZETA, WEIGHT = _rules()

N_CHUNKS = 64  # fixed number of element chunks: thread-count independent results
BLOCK = BW  # elements whose rates, and whose points (up to 10 each), are computed in one vectorised pass
assert BLOCK * 10 <= W


def scratch(nip_max: int) -> tuple[np.ndarray, ...]:
    """Scratch of shell_forces, one row per thread of Numba's pool (a chunk
    writes every slot it reads, so which row it gets cannot change a
    result; a row per chunk put megabytes through the caches every cycle):
    points (threads, plane_stress.N_ROWS·W) float64, geometry (threads,
    shell_block.N_G·BW) float64; and the point number k of each block
    column (W,) int64 for elements of nip_max points."""
    rows = numba.config.NUMBA_NUM_THREADS
    return (np.zeros((rows, N_ROWS * W)), np.zeros((rows, N_G * BW)), np.arange(W, dtype=np.int64) % nip_max)


@njit(cache=True, inline="always")
def _kill(e, fe, me):
    for a in range(4):
        for i in range(3):
            fe[e, a, i] = 0.0
            me[e, a, i] = 0.0


@njit(cache=True, inline="always")
def _no_strain(P, l, nipm):
    """Zero increments for the points of block slot l (an element skipped
    this step: the vectorised pass then leaves its state as it is)."""
    for p in range(l * nipm, (l + 1) * nipm):
        for i in range(5):
            P[(R_D + i) * W + p] = 0.0


@njit(cache=True, error_model="numpy", inline="always")
def _point(e, k, p, dt, mat_of, mtype, props, mcurve, cs, ce, cx, cy, shrf, sig, back, epsp, P):
    """update_point of point k of element e with the increments of column p
    of P; its Δε_zz, work, done and failed flags into P."""
    m = mat_of[e]
    d0, d1, d2 = P[R_D * W + p], P[(R_D + 1) * W + p], P[(R_D + 2) * W + p]
    d3, d4 = P[(R_D + 3) * W + p], P[(R_D + 4) * W + p]
    o0, o1, o2, o3, o4 = sig[e, k, 0], sig[e, k, 1], sig[e, k, 2], sig[e, k, 3], sig[e, k, 4]
    ep, dez, failed = update_point(
        mtype[m], props, m, mcurve, cs, ce, cx, cy, sig, back, e, k, epsp[e, k], d0, d1, d2, d3, d4, dt
    )
    epsp[e, k] = ep
    s0, s1, s2, s3, s4 = sig[e, k, 0], sig[e, k, 1], sig[e, k, 2], sig[e, k, 3], sig[e, k, 4]
    P[R_DEZ * W + p] = dez
    P[R_WK * W + p] = work_density(o0, o1, o2, o3, o4, s0, s1, s2, s3, s4, d0, d1, d2, d3, d4, shrf[e])
    P[R_OK * W + p] = 1.0
    P[R_FAILED * W + p] = 1.0 if failed else 0.0


@njit(cache=True, error_model="numpy")
def _elements(
    e0,
    e1,
    x,
    v,
    w_ang,
    dt,
    conn,
    tri,
    mat_of,
    mtype,
    props,
    mcurve,
    cs,
    ce,
    cx,
    cy,
    nip,
    rule,
    shrf,
    hg_kind,
    hg_qm,
    hg_qb,
    hg_qw,
    rho,
    istupd,
    bwc,
    isdo,
    sig,
    back,
    epsp,
    ipfail,
    thick,
    alive,
    hgq,
    energy,
    hg_energy,
    P,
    kk,
    G,
    fe,
    me,
    step,
):
    """Elements e0 .. e1 - 1 (one chunk; scratch rows ``P``, ``G``, point
    numbers ``kk``) in blocks of BLOCK: the strain rates at the mid-step
    shape (kernels.shell_block, vectorised), the increments of the block's
    points, their stresses (in one vectorised pass,
    plane_stress.update_block, where the block is one material and one
    section; update_point otherwise and where the pass declines), then
    each element's resultants and forces at x(n+1). One
    call per chunk: a Numba call reference-counts each array argument,
    which per element would cost more than a third of the element itself."""
    nipm = sig.shape[1]
    sigf = sig.reshape(-1)
    backf = back.reshape(-1)
    epf = epsp.reshape(-1)
    ipf = ipfail.reshape(-1)
    for first in range(e0, e1, BLOCK):
        last = min(first + BLOCK, e1)
        gather_nodes(first, last - first, x, v, w_ang, dt, conn, tri, G)
        block_rates(bwc, G)
        for e in range(first, last):  # strain increments at x(n+½), points into P
            l = e - first
            G[G_LIVE * BW + l] = 0.0
            if alive[e] != 1:
                _kill(e, fe, me)
                _no_strain(P, l, nipm)
                continue
            area = G[G_AREA * BW + l]
            if not area > 0.0:  # also NaN: a degenerate frame
                alive[e] = -1
                _kill(e, fe, me)
                _no_strain(P, l, nipm)
                continue
            G[G_LIVE * BW + l] = area
            dx, dy, gxy = G[G_RATE * BW + l], G[(G_RATE + 1) * BW + l], G[(G_RATE + 2) * BW + l]
            kx, ky, kxy = G[(G_RATE + 3) * BW + l], G[(G_RATE + 4) * BW + l], G[(G_RATE + 5) * BW + l]
            gyz, gxz = G[(G_RATE + 6) * BW + l], G[(G_RATE + 7) * BW + l]
            t = thick[e]
            nk = nip[e]
            r = rule[e]
            for k in range(nk):
                p = l * nipm + k
                z = 0.5 * ZETA[r, nk, k] * t
                P[R_D * W + p] = (dx + z * kx) * dt
                P[(R_D + 1) * W + p] = (dy + z * ky) * dt
                P[(R_D + 2) * W + p] = (gxy + z * kxy) * dt
                P[(R_D + 3) * W + p] = gyz * dt
                P[(R_D + 4) * W + p] = gxz * dt
        # the points' stresses
        m = mat_of[first]
        one = True
        for e in range(first + 1, last):
            one = one and mat_of[e] == m and nip[e] == nip[first] and shrf[e] == shrf[first]
        if one:
            update_block(
                (last - first) * nipm,
                P,
                kk,
                nip[first],
                sigf,
                backf,
                epf,
                ipf,
                first * nipm,
                mtype,
                props,
                m,
                mcurve,
                cs,
                ce,
                cx,
                cy,
                shrf[first],
                dt,
            )
        else:
            for e in range(first, last):
                l = e - first
                if G[G_LIVE * BW + l] > 0.0:
                    for k in range(nip[e]):
                        if ipfail[e, k] == 0:
                            _point(
                                e,
                                k,
                                l * nipm + k,
                                dt,
                                mat_of,
                                mtype,
                                props,
                                mcurve,
                                cs,
                                ce,
                                cx,
                                cy,
                                shrf,
                                sig,
                                back,
                                epsp,
                                P,
                            )
        for e in range(first, last):  # state, resultants, forces at x(n+1)
            l = e - first
            if G[G_LIVE * BW + l] <= 0.0:
                continue
            nn = 3 if tri[e] == 1 else 4
            quad = nn == 4
            t = thick[e]
            m = mat_of[e]
            ks = shrf[e]
            nk = nip[e]
            r = rule[e]
            n0 = n1 = n2 = m0 = m1 = m2 = q0 = q1 = 0.0
            work = 0.0
            dezs = 0.0
            nfail = 0
            for k in range(nk):
                if ipfail[e, k] != 0:
                    nfail += 1
                    continue
                p = l * nipm + k
                if P[R_OK * W + p] == 0.0:  # declined by the vectorised pass
                    _point(e, k, p, dt, mat_of, mtype, props, mcurve, cs, ce, cx, cy, shrf, sig, back, epsp, P)
                zeta = ZETA[r, nk, k]
                wt = WEIGHT[r, nk, k]
                s0, s1, s2, s3, s4 = sig[e, k, 0], sig[e, k, 1], sig[e, k, 2], sig[e, k, 3], sig[e, k, 4]
                work += wt * P[R_WK * W + p]
                if P[R_FAILED * W + p] == 1.0:
                    ipfail[e, k] = 1
                    nfail += 1
                dezs += wt * P[R_DEZ * W + p]
                n0 += wt * s0
                n1 += wt * s1
                n2 += wt * s2
                m0 += wt * zeta * s0
                m1 += wt * zeta * s1
                m2 += wt * zeta * s2
                q0 += wt * s4  # τzx
                q1 += wt * s3  # τyz
            area = G[G_LIVE * BW + l]  # mid-step
            energy[e] += area * t * work
            if nfail == nk:
                alive[e] = 0
                G[G_LIVE * BW + l] = 0.0  # no forces
                for k in range(nk):
                    for i in range(5):
                        sig[e, k, i] = 0.0
                _kill(e, fe, me)
                continue
            if istupd == 1:
                t = t * (1.0 + dezs)
                thick[e] = t
            # resultants per unit length: N = t Σwσ, M = t²/2 Σwζσ, Q = SHRF t Σwτ
            n0, n1, n2 = t * n0, t * n1, t * n2
            hm = 0.5 * t * t
            m0, m1, m2 = hm * m0, hm * m1, hm * m2
            qx, qy = ks * t * q0, ks * t * q1
            # hourglass resistance at the mid-step geometry
            h0 = h1 = h2 = h3 = h4 = 0.0
            if quad and hg_kind[e] > 0:
                h0, h1, h2, h3, h4 = _hourglass(
                    e,
                    l,
                    G,
                    area,
                    t,
                    dt,
                    props[m, P_E],
                    props[m, P_G],
                    ks,
                    rho[e],
                    hg_kind[e],
                    hg_qm[e],
                    hg_qb[e],
                    hg_qw[e],
                    hgq,
                    hg_energy,
                )
            for i, val in enumerate((n0, n1, n2, m0, m1, m2, qx, qy)):
                G[(G_RES + i) * BW + l] = val
            for i, val in enumerate((h0, h1, h2, h3, h4)):
                G[(G_HGS + i) * BW + l] = val
        # forces at x(n+1)
        block_forces(bwc, isdo, G)
        for e in range(first, last):
            l = e - first
            if G[G_LIVE * BW + l] <= 0.0:
                step[e] = np.inf
                continue
            if not G[G_AREA1 * BW + l] > 0.0:
                alive[e] = -1
                _kill(e, fe, me)
                step[e] = np.inf
                continue
            step[e] = G[G_DT * BW + l] / math.sqrt(wave_speed2(isdo, props, mat_of[e]))
            for a in range(4):
                for i in range(3):
                    fe[e, a, i] = G[(G_F + 6 * a + i) * BW + l]
                    me[e, a, i] = G[(G_F + 6 * a + 3 + i) * BW + l]


# The stiffness form acts on Flanagan and Belytschko's hourglass vector
# γ_FB = ¼(h − (h·x̂)B1 − (h·ŷ)B2) (their quadrilateral, eq. 72; so too the
# one-point shells of Belytschko's group), a quarter of the γ above: rates and
# forces each carry ¼, the stiffness 1/16. LS-DYNA's IHQ 4 is this: the
# parity car (tests/parity) lands on LS-DYNA's energies with it, and 16 times
# too stiff without it (docs/parity.md).
FB = 1.0 / 16.0


@njit(cache=True, error_model="numpy", inline="always")
def _hourglass(e, l, G, area, t, dt, young, shear, ks, rho, kind, qm, qb, qw, hgq, hg_energy):
    """Hourglass generalized stresses of the step from the mid-step rates of
    slot l of G (see the module docstring); returns them (membrane x, y,
    out-of-plane, bending x, y)."""
    r0, r1, r2 = G[G_HG * BW + l], G[(G_HG + 1) * BW + l], G[(G_HG + 2) * BW + l]
    r3, r4 = G[(G_HG + 3) * BW + l], G[(G_HG + 4) * BW + l]
    bb, gg = G[(G_HG + 5) * BW + l], G[(G_HG + 6) * BW + l]
    km = young * t * area * bb / 8.0
    kw = ks * shear * t * t * t * bb / 12.0
    kb = young * t * t * t * area * bb / 192.0
    if kind == 2:  # stiffness: incremental, on Flanagan–Belytschko's γ/4 (hence k/16)
        c0, c2, c3 = qm * km * dt * FB, qw * kw * dt * FB, qb * kb * dt * FB
        n0, n1, n2 = hgq[e, 0] + c0 * r0, hgq[e, 1] + c0 * r1, hgq[e, 2] + c2 * r2
        n3, n4 = hgq[e, 3] + c3 * r3, hgq[e, 4] + c3 * r4
    else:  # viscous: QM × critical damping of the mode at the lumped mass
        mass = 0.25 * rho * t * area
        c0 = 2.0 * qm * math.sqrt(km * mass / gg)
        c2 = 2.0 * qw * math.sqrt(kw * mass / gg)
        c3 = 2.0 * qb * math.sqrt(kb * mass * area / 8.0 / gg)
        n0, n1, n2, n3, n4 = c0 * r0, c0 * r1, c2 * r2, c3 * r3, c3 * r4
    hg_energy[e] += (
        0.5
        * dt
        * (
            (hgq[e, 0] + n0) * r0
            + (hgq[e, 1] + n1) * r1
            + (hgq[e, 2] + n2) * r2
            + (hgq[e, 3] + n3) * r3
            + (hgq[e, 4] + n4) * r4
        )
    )
    hgq[e, 0], hgq[e, 1], hgq[e, 2], hgq[e, 3], hgq[e, 4] = n0, n1, n2, n3, n4
    return n0, n1, n2, n3, n4


@njit(cache=True, parallel=True)
def shell_forces(
    x,
    v,
    w_ang,
    dt,
    conn,
    tri,
    mat_of,
    mtype,
    props,
    mcurve,
    curve_start,
    curve_stop,
    curve_x,
    curve_y,
    nip,
    rule,
    shrf,
    hg_kind,
    hg_qm,
    hg_qb,
    hg_qw,
    rho,
    istupd,
    bwc,
    isdo,
    sig,
    back,
    epsp,
    ipfail,
    thick,
    alive,
    hgq,
    energy,
    hg_energy,
    points,
    geometry,
    kk,
    fe,
    me,
    step,
):
    """One step of the shells (see the module docstring for the arrays):
    stresses, thickness, energies and state to t(n+1); corner forces fe
    and moments me ON the nodes; the elements' critical steps at x(n+1)
    (the loop needs them next: one pass over the elements less). Returns
    the smallest of the steps (NaN if one is)."""
    n = conn.shape[0]
    nc = N_CHUNKS
    for ch in prange(nc):
        tid = numba.get_thread_id()
        pts = points[tid]
        gc = geometry[tid]
        _elements(
            ch * n // nc,
            (ch + 1) * n // nc,
            x,
            v,
            w_ang,
            dt,
            conn,
            tri,
            mat_of,
            mtype,
            props,
            mcurve,
            curve_start,
            curve_stop,
            curve_x,
            curve_y,
            nip,
            rule,
            shrf,
            hg_kind,
            hg_qm,
            hg_qb,
            hg_qw,
            rho,
            istupd,
            bwc,
            isdo,
            sig,
            back,
            epsp,
            ipfail,
            thick,
            alive,
            hgq,
            energy,
            hg_energy,
            pts,
            kk,
            gc,
            fe,
            me,
            step,
        )
    smallest = np.inf  # what the time loop asks next: here rather than another pass from Python
    for e in range(n):
        if step[e] != step[e]:
            return np.nan  # a NaN step: the loop stops with a diagnosis
        smallest = min(smallest, step[e])
    return smallest


@njit(cache=True, inline="always")
def wave_speed2(isdo, props, m):
    """Squared wave speed of the shell step: the plate's E/(ρ(1 − ν²)), the
    bar's E/ρ with ISDO 2."""
    return props[m, P_E] / props[m, P_RO] if isdo == 2 else props[m, P_WAVE]


@njit(cache=True, inline="always")
def _d2(x, a, b):
    return (x[b, 0] - x[a, 0]) ** 2 + (x[b, 1] - x[a, 1]) ** 2 + (x[b, 2] - x[a, 2]) ** 2


@njit(cache=True, parallel=True)
def shell_timestep(x, conn, tri, alive, mat_of, props, isdo, dt_out):
    """LS-DYNA critical step of each shell (before TSSFAC): Δt = L/c with
    L the characteristic length of *CONTROL_TIMESTEP ISDO
    (kernels.shell_block.char_length) and c the plate wave speed
    sqrt(E/(ρ(1 − ν²))) (ISDO 2: the bar's, sqrt(E/ρ)), at the current
    positions. Inactive or degenerate elements: +inf. dt_out (n,) [time]."""
    for e in prange(conn.shape[0]):
        if alive[e] != 1:
            dt_out[e] = np.inf
            continue
        i0, i1, i2 = conn[e, 0], conn[e, 1], conn[e, 2]
        i3 = i2 if tri[e] == 1 else conn[e, 3]
        if tri[e] == 1:  # 2A = |x01 × x02|
            u0, u1, u2 = x[i1, 0] - x[i0, 0], x[i1, 1] - x[i0, 1], x[i1, 2] - x[i0, 2]
        else:  # 2A = |x02 × x13|
            u0, u1, u2 = x[i2, 0] - x[i0, 0], x[i2, 1] - x[i0, 1], x[i2, 2] - x[i0, 2]
        if tri[e] == 1:
            s0, s1, s2 = x[i2, 0] - x[i0, 0], x[i2, 1] - x[i0, 1], x[i2, 2] - x[i0, 2]
        else:
            s0, s1, s2 = x[i3, 0] - x[i1, 0], x[i3, 1] - x[i1, 1], x[i3, 2] - x[i1, 2]
        c0 = u1 * s2 - u2 * s1
        c1 = u2 * s0 - u0 * s2
        c2 = u0 * s1 - u1 * s0
        area = 0.5 * math.sqrt(c0 * c0 + c1 * c1 + c2 * c2)
        length = char_length(
            isdo,
            1.0 - tri[e],
            area,
            _d2(x, i0, i1),
            _d2(x, i1, i2),
            _d2(x, i2, i3),
            _d2(x, i3, i0),
            _d2(x, i0, i2),
            _d2(x, i1, i3),
        )
        if not area > 0.0 or not length > 0.0:
            dt_out[e] = np.inf
            continue
        dt_out[e] = length / math.sqrt(wave_speed2(isdo, props, mat_of[e]))
