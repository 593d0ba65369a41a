"""Fully integrated shell (LS-DYNA ELFORM 16, Engelmann–Whirley–Goudreau
1989): a bilinear four-node quadrilateral integrated at 2 × 2 in-plane
Gauss points in a corotational element frame, Mindlin plate kinematics
with Bathe–Dvorkin assumed natural transverse shear strains; no
hourglass modes, so no hourglass control.

Frame (kernels.shell's, so that stresses are kept and written in the same
axes): e3 along the cross product of the diagonals, e1 along side 1-2
projected on the plane, e2 = e3 × e1; nodes at local (X_a, Y_a) about the
centroid (the projection on the plane: no warping terms; a warped
element runs as its projection). Nodal degrees of freedom in the frame:
velocities v̂x, v̂y, v̂z and angular velocities θ̂x, θ̂y (no drilling
stiffness, as the Belytschko–Lin–Tsay element).

At the natural point (ξ, η) of the bilinear map, N_a = ¼(1 + ξ_a ξ)(1 + η_a η),
J = ∂(X, Y)/∂(ξ, η) and ∂N_a/∂(x, y) = J⁻¹ ∂N_a/∂(ξ, η); the strain rates
(the rows of the operator B, 8 × 20):
  membrane ε̇x = Σ N_a,x v̂x_a, ε̇y = Σ N_a,y v̂y_a, γ̇xy = Σ (N_a,y v̂x_a + N_a,x v̂y_a),
  curvature κ̇x = Σ N_a,x θ̂y_a, κ̇y = −Σ N_a,y θ̂x_a, 2κ̇xy = Σ (N_a,y θ̂y_a − N_a,x θ̂x_a),
  and at height z the in-plane rate ε̇ + z κ̇ (kernels.shell's conventions);
  transverse shear (assumed natural strain, MITC4): the covariant shears
  γ_ξ = v̂z,ξ + X,ξ θ̂y − Y,ξ θ̂x sampled at the edge midpoints A (0, −1)
  and C (0, 1), γ_η = v̂z,η + X,η θ̂y − Y,η θ̂x at D (−1, 0) and B (1, 0),
  interpolated γ_ξ(η) = ½(1 − η)γ_ξ^A + ½(1 + η)γ_ξ^C, γ_η(ξ) = ½(1 − ξ)γ_η^D
  + ½(1 + ξ)γ_η^B at each Gauss point, and (γ̇xz, γ̇yz) solved from
  J (γ̇xz, γ̇yz) = (γ_ξ, γ_η).
  Constant curvature fields carry no shear on any straight-sided element
  (no shear locking).
Through the thickness the NIP points of kernels.shell (Gauss or Lobatto)
at each of the four Gauss points carry plane-stress J2 stresses
(kernels.plane_stress.update_point); the resultants N = ∫σ dz, M = ∫zσ dz,
Q = SHRF·∫τ dz of each Gauss point give the nodal forces and moments at
x(n+1) as Σ_g det J_g B_gᵀ (N, M, Q)_g, the exact transpose of the rates
(the internal power Σ_g det J_g (N·ε̇ + M·κ̇ + Q·γ̇)). Rates at the
mid-step shape x(n+½) = x(n+1) − ½Δt·v(n+½), forces at x(n+1), as the
one-point element. Thickness change (ISTUPD) from the normal strain of the
four Gauss points' mean. Time step: the one-point element's
characteristic length (kernels.shell_block.char_length), as LS-DYNA.

State (nf elements of this formulation, row j of element idx[j]):
  sig4, back4 (nf, 4·nip_max, 5) float64 stress and back stress at Gauss
  point g, through-thickness point k in row g·nip_max + k [stress];
  epsp4 (nf, 4·nip_max) float64; ipfail4 (nf, 4·nip_max) int8.
The element-averaged layers (the mean of the four Gauss points, as
LS-DYNA writes shell results) go to the shell set's sig, epsp (n, nip_max)
and ipfail (1 where all four points failed) for output; the other arrays
(thick, alive, energy, fe, me, step) are the shell set's (kernels.shell).
Elements are independent (each writes its own rows): results do not depend
on the number of threads.
"""

import math

import numpy as np
from numba import njit, prange

from .plane_stress import update_point, work_density
from .shell import WEIGHT, ZETA, wave_speed2
from .shell_block import char_length

XI_A = np.array([-1.0, 1.0, 1.0, -1.0])  # natural coordinates of the nodes
ETA_A = np.array([-1.0, -1.0, 1.0, 1.0])
_G = 1.0 / math.sqrt(3.0)
XI_G = np.array([-_G, _G, _G, -_G])  # the 2 × 2 Gauss points (weights 1)
ETA_G = np.array([-_G, -_G, _G, _G])
N_CHUNKS = 64  # fixed element chunks, each with its own scratch


@njit(cache=True, error_model="numpy")
def frame(q, R, XY):
    """Corotational frame R (rows e1, e2, e3) and local coordinates XY
    (4, 2) about the centroid of the corners q (4, 3); returns the area
    (≤ 0 or NaN: degenerate)."""
    d0, d1, d2 = q[2, 0] - q[0, 0], q[2, 1] - q[0, 1], q[2, 2] - q[0, 2]
    s0, s1, s2 = q[3, 0] - q[1, 0], q[3, 1] - q[1, 1], q[3, 2] - q[1, 2]
    n0, n1, n2 = d1 * s2 - d2 * s1, d2 * s0 - d0 * s2, d0 * s1 - d1 * s0
    inl = 1.0 / math.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
    n0, n1, n2 = n0 * inl, n1 * inl, n2 * inl
    t0, t1, t2 = q[1, 0] - q[0, 0], q[1, 1] - q[0, 1], q[1, 2] - q[0, 2]
    d = t0 * n0 + t1 * n1 + t2 * n2
    t0, t1, t2 = t0 - d * n0, t1 - d * n1, t2 - d * n2
    itl = 1.0 / math.sqrt(t0 * t0 + t1 * t1 + t2 * t2)
    t0, t1, t2 = t0 * itl, t1 * itl, t2 * itl
    R[0, 0], R[0, 1], R[0, 2] = t0, t1, t2
    R[1, 0], R[1, 1], R[1, 2] = n1 * t2 - n2 * t1, n2 * t0 - n0 * t2, n0 * t1 - n1 * t0
    R[2, 0], R[2, 1], R[2, 2] = n0, n1, n2
    c = np.zeros(3)
    for a in range(4):
        for i in range(3):
            c[i] += 0.25 * q[a, i]
    for a in range(4):
        for r in range(2):
            XY[a, r] = (q[a, 0] - c[0]) * R[r, 0] + (q[a, 1] - c[1]) * R[r, 1] + (q[a, 2] - c[2]) * R[r, 2]
    return 0.5 * ((XY[2, 0] - XY[0, 0]) * (XY[3, 1] - XY[1, 1]) + (XY[1, 0] - XY[3, 0]) * (XY[2, 1] - XY[0, 1]))


@njit(cache=True, error_model="numpy", inline="always")
def _jacobian(XY, xi, eta):
    """J11 = X,ξ, J12 = Y,ξ, J21 = X,η, J22 = Y,η at (ξ, η)."""
    j11 = j12 = j21 = j22 = 0.0
    for a in range(4):
        nx = 0.25 * XI_A[a] * (1.0 + ETA_A[a] * eta)
        ne = 0.25 * ETA_A[a] * (1.0 + XI_A[a] * xi)
        j11 += nx * XY[a, 0]
        j12 += nx * XY[a, 1]
        j21 += ne * XY[a, 0]
        j22 += ne * XY[a, 1]
    return j11, j12, j21, j22


@njit(cache=True, error_model="numpy")
def _covariant(XY, xi, eta, along_xi, row):
    """Row (20,) of the covariant transverse shear γ_ξ (along_xi) or γ_η at (ξ, η)."""
    j11, j12, j21, j22 = _jacobian(XY, xi, eta)
    xs, ys = (j11, j12) if along_xi else (j21, j22)
    for a in range(4):
        na = 0.25 * (1.0 + XI_A[a] * xi) * (1.0 + ETA_A[a] * eta)
        if along_xi:
            dn = 0.25 * XI_A[a] * (1.0 + ETA_A[a] * eta)
        else:
            dn = 0.25 * ETA_A[a] * (1.0 + XI_A[a] * xi)
        row[5 * a + 0] = 0.0
        row[5 * a + 1] = 0.0
        row[5 * a + 2] = dn
        row[5 * a + 3] = -ys * na
        row[5 * a + 4] = xs * na


@njit(cache=True, error_model="numpy")
def operators(XY, B, det, T):
    """Strain-rate operators B (4, 8, 20) at the four Gauss points, rows
    ε̇x, ε̇y, γ̇xy, κ̇x, κ̇y, 2κ̇xy, γ̇yz, γ̇xz, columns 5a + (v̂x, v̂y, v̂z,
    θ̂x, θ̂y); det (4,) det J. T (4, 20) scratch: the tying points' rows."""
    _covariant(XY, 0.0, -1.0, True, T[0])  # A
    _covariant(XY, 0.0, 1.0, True, T[1])  # C
    _covariant(XY, -1.0, 0.0, False, T[2])  # D
    _covariant(XY, 1.0, 0.0, False, T[3])  # B
    for g in range(4):
        xi, eta = XI_G[g], ETA_G[g]
        j11, j12, j21, j22 = _jacobian(XY, xi, eta)
        dj = j11 * j22 - j12 * j21
        det[g] = dj
        inv = 1.0 / dj
        for i in range(8):
            for c in range(20):
                B[g, i, c] = 0.0
        for a in range(4):
            nxi = 0.25 * XI_A[a] * (1.0 + ETA_A[a] * eta)
            neta = 0.25 * ETA_A[a] * (1.0 + XI_A[a] * xi)
            nx = (j22 * nxi - j12 * neta) * inv
            ny = (j11 * neta - j21 * nxi) * inv
            c = 5 * a
            B[g, 0, c] = nx
            B[g, 1, c + 1] = ny
            B[g, 2, c] = ny
            B[g, 2, c + 1] = nx
            B[g, 3, c + 4] = nx
            B[g, 4, c + 3] = -ny
            B[g, 5, c + 4] = ny
            B[g, 5, c + 3] = -nx
        fa, fc = 0.5 * (1.0 - eta), 0.5 * (1.0 + eta)
        fd, fb = 0.5 * (1.0 - xi), 0.5 * (1.0 + xi)
        for c in range(20):
            gx = fa * T[0, c] + fc * T[1, c]  # γ_ξ
            ge = fd * T[2, c] + fb * T[3, c]  # γ_η
            B[g, 7, c] = (j22 * gx - j12 * ge) * inv  # γ̇xz
            B[g, 6, c] = (j11 * ge - j21 * gx) * inv  # γ̇yz


@njit(cache=True, inline="always")
def _kill(e, fe, me, step):
    for a in range(4):
        for i in range(3):
            fe[e, a, i] = 0.0
            me[e, a, i] = 0.0
    step[e] = np.inf


@njit(cache=True, error_model="numpy")
def _element(
    j,
    e,
    x,
    v,
    w_ang,
    dt,
    conn,
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
    istupd,
    isdo,
    sig4,
    back4,
    epsp4,
    ipfail4,
    thick,
    alive,
    energy,
    sig,
    epsp,
    ipfail,
    fe,
    me,
    step,
    q,
    R,
    XY,
    B,
    det,
    T,
    U,
    S,
    F,
):
    """One step of element e (state row j); scratch q .. F."""
    if alive[e] != 1:
        _kill(e, fe, me, step)
        return
    h = 0.5 * dt
    for a in range(4):
        nd = conn[e, a]
        for i in range(3):
            q[a, i] = x[nd, i] - h * v[nd, i]
    area = frame(q, R, XY)
    if not area > 0.0:
        alive[e] = -1
        _kill(e, fe, me, step)
        return
    for a in range(4):
        nd = conn[e, a]
        for r in range(3):
            U[5 * a + r] = R[r, 0] * v[nd, 0] + R[r, 1] * v[nd, 1] + R[r, 2] * v[nd, 2]
        for r in range(2):
            U[5 * a + 3 + r] = R[r, 0] * w_ang[nd, 0] + R[r, 1] * w_ang[nd, 1] + R[r, 2] * w_ang[nd, 2]
    operators(XY, B, det, T)
    m = mat_of[e]
    kind = mtype[m]
    t = thick[e]
    nk = nip[e]
    r = rule[e]
    ks = shrf[e]
    nipm = sig.shape[1]
    dez_mean = 0.0
    nfail = 0
    rt = np.zeros(8)
    for g in range(4):
        for i in range(8):
            s = 0.0
            for c in range(20):
                s += B[g, i, c] * U[c]
            rt[i] = s
        work = 0.0
        dezs = 0.0
        n0 = n1 = n2 = m0 = m1 = m2 = q0 = q1 = 0.0
        for k in range(nk):
            kk = g * nipm + k
            if ipfail4[j, kk] != 0:
                nfail += 1
                continue
            zeta = ZETA[r, nk, k]
            wt = WEIGHT[r, nk, k]
            z = 0.5 * zeta * t
            d0, d1, d2 = (rt[0] + z * rt[3]) * dt, (rt[1] + z * rt[4]) * dt, (rt[2] + z * rt[5]) * dt
            d3, d4 = rt[6] * dt, rt[7] * dt
            o0, o1, o2, o3, o4 = sig4[j, kk, 0], sig4[j, kk, 1], sig4[j, kk, 2], sig4[j, kk, 3], sig4[j, kk, 4]
            ep, dez, failed = update_point(
                kind, props, m, mcurve, cs, ce, cx, cy, sig4, back4, j, kk, epsp4[j, kk], d0, d1, d2, d3, d4, dt
            )
            epsp4[j, kk] = ep
            s0, s1, s2, s3, s4 = sig4[j, kk, 0], sig4[j, kk, 1], sig4[j, kk, 2], sig4[j, kk, 3], sig4[j, kk, 4]
            work += wt * work_density(o0, o1, o2, o3, o4, s0, s1, s2, s3, s4, d0, d1, d2, d3, d4, ks)
            dezs += wt * dez
            if failed:
                ipfail4[j, kk] = 1
                nfail += 1
            n0 += wt * s0
            n1 += wt * s1
            n2 += wt * s2
            m0 += wt * zeta * s0
            m1 += wt * zeta * s1
            m2 += wt * zeta * s2
            q0 += wt * s3  # τyz
            q1 += wt * s4  # τzx
        energy[e] += det[g] * t * work
        dez_mean += 0.25 * dezs
        S[g, 0], S[g, 1], S[g, 2] = n0, n1, n2
        S[g, 3], S[g, 4], S[g, 5] = m0, m1, m2
        S[g, 6], S[g, 7] = q0, q1
    # element-averaged layers for output
    for k in range(nipm):
        nf = 0
        for i in range(5):
            sig[e, k, i] = 0.0
        epsp[e, k] = 0.0
        for g in range(4):
            kk = g * nipm + k
            for i in range(5):
                sig[e, k, i] += 0.25 * sig4[j, kk, i]
            epsp[e, k] += 0.25 * epsp4[j, kk]
            nf += ipfail4[j, kk] != 0
        ipfail[e, k] = 1 if nf == 4 else 0
    if nfail == 4 * nk:
        alive[e] = 0
        for kk in range(sig4.shape[1]):
            for i in range(5):
                sig4[j, kk, i] = 0.0
        for k in range(nipm):
            for i in range(5):
                sig[e, k, i] = 0.0
        _kill(e, fe, me, step)
        return
    if istupd == 1:
        t = t * (1.0 + dez_mean)
        thick[e] = t
    # resultants per unit length: N = t Σwσ, M = t²/2 Σwζσ, Q = SHRF t Σwτ
    hm = 0.5 * t * t
    for g in range(4):
        for i in range(3):
            S[g, i] *= t
            S[g, 3 + i] *= hm
        S[g, 6] *= ks * t
        S[g, 7] *= ks * t
    # forces at x(n+1)
    for a in range(4):
        nd = conn[e, a]
        for i in range(3):
            q[a, i] = x[nd, i]
    area1 = frame(q, R, XY)
    if not area1 > 0.0:
        alive[e] = -1
        _kill(e, fe, me, step)
        return
    operators(XY, B, det, T)
    for c in range(20):
        s = 0.0
        for g in range(4):
            bs = 0.0
            for i in range(8):
                bs += B[g, i, c] * S[g, i]
            s += det[g] * bs
        F[c] = s
    for a in range(4):
        c = 5 * a
        for i in range(3):
            fe[e, a, i] = -(F[c] * R[0, i] + F[c + 1] * R[1, i] + F[c + 2] * R[2, i])
            me[e, a, i] = -(F[c + 3] * R[0, i] + F[c + 4] * R[1, i])
    sd = np.zeros(6)
    for p, (a, b) in enumerate(((0, 1), (1, 2), (2, 3), (3, 0), (0, 2), (1, 3))):
        sd[p] = (q[b, 0] - q[a, 0]) ** 2 + (q[b, 1] - q[a, 1]) ** 2 + (q[b, 2] - q[a, 2]) ** 2
    length = char_length(isdo, 1.0, area1, sd[0], sd[1], sd[2], sd[3], sd[4], sd[5])
    step[e] = length / math.sqrt(wave_speed2(isdo, props, m))


@njit(cache=True, parallel=True)
def full_forces(
    x,
    v,
    w_ang,
    dt,
    idx,
    conn,
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
    istupd,
    isdo,
    sig4,
    back4,
    epsp4,
    ipfail4,
    thick,
    alive,
    energy,
    sig,
    epsp,
    ipfail,
    fe,
    me,
    step,
):
    """One step of the fully integrated shells idx (nf,) (see the module
    docstring for their state; the other arrays as kernels.shell's):
    stresses, thickness, energies to t(n+1), corner forces fe and moments
    me ON the nodes, critical steps at x(n+1)."""
    nf = idx.shape[0]
    for ch in prange(N_CHUNKS):
        q = np.empty((4, 3))
        R = np.empty((3, 3))
        XY = np.empty((4, 2))
        B = np.empty((4, 8, 20))
        det = np.empty(4)
        T = np.empty((4, 20))
        U = np.empty(20)
        S = np.empty((4, 8))
        F = np.empty(20)
        for j in range(ch * nf // N_CHUNKS, (ch + 1) * nf // N_CHUNKS):
            _element(
                j,
                idx[j],
                x,
                v,
                w_ang,
                dt,
                conn,
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
                istupd,
                isdo,
                sig4,
                back4,
                epsp4,
                ipfail4,
                thick,
                alive,
                energy,
                sig,
                epsp,
                ipfail,
                fe,
                me,
                step,
                q,
                R,
                XY,
                B,
                det,
                T,
                U,
                S,
                F,
            )
