"""8-node hexahedron, fully integrated and selectively reduced (LS-DYNA ELFORM 2).

2×2×2 Gauss points (weights 1) at ξ = ±1/√3. At each point the velocity
gradient L_p = Σ_I v_I ⊗ ∂N_I/∂x comes from the shape-function derivatives
on the mid-step geometry x(n+½) = x(n+1) − ½Δt·v(n+½), as the one-point
kernel does (kernels.solid); its volumetric part is replaced by the
element's mean, tr D̄ = Σ_p J_p tr L_p / Σ_p J_p (B-bar, selective
reduction: a nearly incompressible material does not lock), so the strain
rate of point p is D̃_p = sym L_p + ⅓(tr D̄ − tr L_p) I.

Per point: the stress is rotated by the Hughes–Winget (Cayley) rotation of
the point's spin (honeycomb: its stress keeps its components in the
material axes, which convect with L_p, ``kernels.solid._convect_axes``);
then the material update (``solid_materials.update_stress``) with
Δε = D̃_p·Δt, the honeycomb's and foam's relative volume being the point's
det J over its initial det J. Bulk viscosity as in ELFORM 1, at the element
level (from tr D̄, the element's density, wave speed and V^⅓); material
damping (P_DAMP) as the viscous stress μ·D̃_p, μ = P_DAMP·ρ·c·L from the
element's values, L = V / A_max the time step's characteristic length (a
fraction P_DAMP of critical damping of the element's highest mode: on V^⅓ an
element crushed flat is many times overdamped and the explicit viscous force,
which the step does not cover, diverges).

Nodal forces at x(n+1): f_I = −Σ_p J_p (s_p + p̄ I)·∂N_I/∂x (p), s_p the
deviator of the point's total stress and p̄ = Σ_p J_p ⅓tr σ_p / V the
element's mean pressure: the transpose of the B-bar operator, so the force
power equals the stress power of D̃. No hourglass modes, no hourglass forces.
Internal energy: trapezoid work of each point's total stress over the step
at its mid-step det J, summed over the points.

The element's outputs that the rest of the solver reads are written to the
one-point kernel's element arrays: stress, viscous stress and plastic strain
as the mean of the points, the energy summed, the exact volume Σ_p J_p, the
volumetric rate tr D̄, the wave modulus the largest of the points'.
An element is inverted (alive −1) when det J ≤ 0 at a point, eroded
(alive 0) when a point fails (MAT_024 FAIL, MAT_026 TSEF/SSEF).

Arrays (n = elements of the set, nf = fully integrated ones; units as in
kernels.solid):
  idx (nf,) int64 rows of the fully integrated elements
  detj0 (nf, 8) float64 det J at the Gauss points at t = 0 [length³]
  state per point, updated in place: psig, psv (nf, 8, 6) material and
  viscous stress [stress]; pepsp (nf, 8); phist (nf, 8, N_HIST);
  paxes (nf, 8, 3, 3) material axes
  element arrays (n, ...) of kernels.solid: alive, vol, rate, cmod, energy,
  sig, sv, epsp (written for the rows idx), work (n_chunks, N_WORK_FULL)
  scratch, fe (n, 8, 3) corner forces ON the nodes [force].
The elements are processed in ``work.shape[0]`` fixed chunks; each writes
only its own rows, so results do not depend on the number of threads.
"""

import math

import numpy as np
from numba import njit, prange

from .solid import _DE, _M, _R, _V, _X, FACES, N_WORK, XI, _convect_axes, _load_coords, _rotate6
from .solid_materials import HONEYCOMB, _to_global, _to_local, update_stress


def _gauss_derivatives():
    """(8 points, 8 nodes, 3) ∂N_a/∂ξ_k at the Gauss points ξ_p = XI[p]/√3
    (point p lies next to node p)."""
    pts = XI / math.sqrt(3.0)
    dn = np.empty((8, 8, 3))
    for p in range(8):
        for a in range(8):
            for k in range(3):
                o1, o2 = [m for m in range(3) if m != k]
                dn[p, a, k] = XI[a, k] * (1.0 + XI[a, o1] * pts[p, o1]) * (1.0 + XI[a, o2] * pts[p, o2]) / 8.0
    return dn


GP_DN = _gauss_derivatives()

# scratch after the one-point kernel's layout (its _X, _V, _R, _DE, _M are shared)
_L = N_WORK  # velocity gradient L_p at mid-step, row major (8 × 9)
_JM = _L + 72  # det J_p at mid-step (8)
_GN = _JM + 8  # det J_p · ∂N_I/∂x at t(n+1) (8 points × 24)
_JN = _GN + 192  # det J_p at t(n+1) (8)
_OLD = _JN + 8  # total stress at the start of the step, rotated (8 × 6)
_T = _OLD + 48  # total stress at t(n+1) (8 × 6)
N_WORK_FULL = _T + 48


@njit(cache=True)
def _cofactors(w, p):
    """Cofactors C_ij of the Jacobian J_ij = ∂x_i/∂ξ_j at Gauss point p of
    the coordinates w[_X:_X+24], and det J. ∂N/∂x_i = Σ_j C_ij ∂N/∂ξ_j / det J."""
    j00 = j01 = j02 = j10 = j11 = j12 = j20 = j21 = j22 = 0.0
    for a in range(8):
        x0, x1, x2 = w[_X + 3 * a], w[_X + 3 * a + 1], w[_X + 3 * a + 2]
        g0, g1, g2 = GP_DN[p, a, 0], GP_DN[p, a, 1], GP_DN[p, a, 2]
        j00 += x0 * g0
        j01 += x0 * g1
        j02 += x0 * g2
        j10 += x1 * g0
        j11 += x1 * g1
        j12 += x1 * g2
        j20 += x2 * g0
        j21 += x2 * g1
        j22 += x2 * g2
    c00 = j11 * j22 - j12 * j21
    c01 = j12 * j20 - j10 * j22
    c02 = j10 * j21 - j11 * j20
    c10 = j02 * j21 - j01 * j22
    c11 = j00 * j22 - j02 * j20
    c12 = j01 * j20 - j00 * j21
    c20 = j01 * j12 - j02 * j11
    c21 = j02 * j10 - j00 * j12
    c22 = j00 * j11 - j01 * j10
    det = j00 * c00 + j01 * c01 + j02 * c02
    return c00, c01, c02, c10, c11, c12, c20, c21, c22, det


@njit(cache=True)
def _mid_gradients(w):
    """L_p into w[_L:], det J_p into w[_JM:] from the mid-step coordinates
    and the velocities w[_V:]. False if a det J ≤ 0."""
    for p in range(8):
        c00, c01, c02, c10, c11, c12, c20, c21, c22, det = _cofactors(w, p)
        w[_JM + p] = det
        if det <= 0.0:
            return False
        inv = 1.0 / det
        l00 = l01 = l02 = l10 = l11 = l12 = l20 = l21 = l22 = 0.0
        for a in range(8):
            g0, g1, g2 = GP_DN[p, a, 0], GP_DN[p, a, 1], GP_DN[p, a, 2]
            b0 = (c00 * g0 + c01 * g1 + c02 * g2) * inv
            b1 = (c10 * g0 + c11 * g1 + c12 * g2) * inv
            b2 = (c20 * g0 + c21 * g1 + c22 * g2) * inv
            va0, va1, va2 = w[_V + 3 * a], w[_V + 3 * a + 1], w[_V + 3 * a + 2]
            l00 += va0 * b0
            l01 += va0 * b1
            l02 += va0 * b2
            l10 += va1 * b0
            l11 += va1 * b1
            l12 += va1 * b2
            l20 += va2 * b0
            l21 += va2 * b1
            l22 += va2 * b2
        o = _L + 9 * p
        w[o], w[o + 1], w[o + 2] = l00, l01, l02
        w[o + 3], w[o + 4], w[o + 5] = l10, l11, l12
        w[o + 6], w[o + 7], w[o + 8] = l20, l21, l22
    return True


@njit(cache=True)
def _end_gradients(w):
    """det J_p · ∂N_I/∂x into w[_GN:], det J_p into w[_JN:] from the
    coordinates at t(n+1). Returns the volume Σ_p det J_p, or a value ≤ 0
    if a det J ≤ 0."""
    vol = 0.0
    for p in range(8):
        c00, c01, c02, c10, c11, c12, c20, c21, c22, det = _cofactors(w, p)
        w[_JN + p] = det
        if det <= 0.0:
            return det
        vol += det
        for a in range(8):
            g0, g1, g2 = GP_DN[p, a, 0], GP_DN[p, a, 1], GP_DN[p, a, 2]
            o = _GN + 24 * p + 3 * a
            w[o] = c00 * g0 + c01 * g1 + c02 * g2
            w[o + 1] = c10 * g0 + c11 * g1 + c12 * g2
            w[o + 2] = c20 * g0 + c21 * g1 + c22 * g2
    return vol


@njit(cache=True)
def _largest_face(w):
    """Largest face area of the coordinates w[_X:_X+24], each face ½|d1 × d2|
    from its diagonals (as kernels.solid.solid_timestep)."""
    amax = 0.0
    for fc in range(6):
        a0, a1, a2, a3 = _X + 3 * FACES[fc, 0], _X + 3 * FACES[fc, 1], _X + 3 * FACES[fc, 2], _X + 3 * FACES[fc, 3]
        d10, d11, d12 = w[a2] - w[a0], w[a2 + 1] - w[a0 + 1], w[a2 + 2] - w[a0 + 2]
        d20, d21, d22 = w[a3] - w[a1], w[a3 + 1] - w[a1 + 1], w[a3 + 2] - w[a1 + 2]
        c0 = d11 * d22 - d12 * d21
        c1 = d12 * d20 - d10 * d22
        c2 = d10 * d21 - d11 * d20
        amax = max(amax, 0.5 * math.sqrt(c0 * c0 + c1 * c1 + c2 * c2))
    return amax


@njit(cache=True)
def _strain_rate(w, p, th):
    """D̃_p (xx, yy, zz, xy, yz, zx) of point p: sym L_p with its trace
    replaced by the element's mean th."""
    o = _L + 9 * p
    dv = (th - (w[o] + w[o + 4] + w[o + 8])) / 3.0
    return (
        w[o] + dv,
        w[o + 4] + dv,
        w[o + 8] + dv,
        0.5 * (w[o + 1] + w[o + 3]),
        0.5 * (w[o + 5] + w[o + 7]),
        0.5 * (w[o + 6] + w[o + 2]),
    )


@njit(cache=True)
def _spin_rotation(w, p, dt):
    """Cayley rotation of ½Δt·W_p into w[_R:_R+9] (exact for a rigid rotation)."""
    o = _L + 9 * p
    ax = 0.25 * dt * (w[o + 7] - w[o + 5])
    ay = 0.25 * dt * (w[o + 2] - w[o + 6])
    az = 0.25 * dt * (w[o + 3] - w[o + 1])
    aa = ax * ax + ay * ay + az * az
    f = 2.0 / (1.0 + aa)
    w[_R + 0] = 1.0 + f * (ax * ax - aa)
    w[_R + 1] = f * (-az + ax * ay)
    w[_R + 2] = f * (ay + ax * az)
    w[_R + 3] = f * (az + ay * ax)
    w[_R + 4] = 1.0 + f * (ay * ay - aa)
    w[_R + 5] = f * (-ax + ay * az)
    w[_R + 6] = f * (-ay + az * ax)
    w[_R + 7] = f * (ax + az * ay)
    w[_R + 8] = 1.0 + f * (az * az - aa)


@njit(cache=True)
def _kill(k, e, fe, sig, sv, psig, psv):
    for a in range(8):
        for i in range(3):
            fe[e, a, i] = 0.0
    for t in range(6):
        sig[e, t] = 0.0
        sv[e, t] = 0.0
        for p in range(8):
            psig[k, p, t] = 0.0
            psv[k, p, t] = 0.0


@njit(cache=True)
def _rotate_point(w, kind, s, vs, q, h, dt, p):
    """Stress, viscous stress and material axes of point p to t(n+1)'s frame
    (a honeycomb's history h carries its initial axes as material lines)."""
    if kind == HONEYCOMB:  # the stress keeps its components in the convected material axes
        o = _L + 9 * p
        _to_local(q, s, 0, w, _M)
        _convect_axes(
            q,
            h,
            w[o] * dt,
            w[o + 1] * dt,
            w[o + 2] * dt,
            w[o + 3] * dt,
            w[o + 4] * dt,
            w[o + 5] * dt,
            w[o + 6] * dt,
            w[o + 7] * dt,
            w[o + 8] * dt,
        )
        _to_global(q, w, _M, s)
    else:
        _rotate6(w, s)
        for j in range(3):  # material axes turn with the point
            c0, c1, c2 = q[0, j], q[1, j], q[2, j]
            for i in range(3):
                q[i, j] = w[_R + 3 * i] * c0 + w[_R + 3 * i + 1] * c1 + w[_R + 3 * i + 2] * c2
    _rotate6(w, vs)


@njit(cache=True)
def _element(
    k,
    e,
    x,
    v,
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
    rho0,
    vol0,
    q1,
    q2,
    detj0,
    psig,
    psv,
    pepsp,
    phist,
    paxes,
    alive,
    vol,
    rate,
    cmod,
    energy,
    sig,
    sv,
    epsp,
    w,
    fe,
):
    if alive[e] != 1:
        _kill(k, e, fe, sig, sv, psig, psv)
        rate[e] = 0.0
        return
    for a in range(8):
        n = conn[e, a]
        for i in range(3):
            w[_V + 3 * a + i] = v[n, i]
    _load_coords(x, v, conn, e, 0.5 * dt, w)
    if not _mid_gradients(w):
        alive[e] = -1
        _kill(k, e, fe, sig, sv, psig, psv)
        return
    vm = 0.0
    th = 0.0
    for p in range(8):
        o = _L + 9 * p
        vm += w[_JM + p]
        th += w[_JM + p] * (w[o] + w[o + 4] + w[o + 8])
    th /= vm  # the element's mean volumetric strain rate tr D̄
    _load_coords(x, v, conn, e, 0.0, w)
    vn = _end_gradients(w)
    if vn <= 0.0:
        alive[e] = -1
        _kill(k, e, fe, sig, sv, psig, psv)
        return
    vol[e] = vn
    lt = vn / _largest_face(w)  # the step's characteristic length V / A_max (solid_timestep)
    m = mat_of[e]
    kind = mtype[m]
    pr = props[m]
    wave = 0.0
    failed = False
    for p in range(8):
        s = psig[k, p]
        vs = psv[k, p]
        _spin_rotation(w, p, dt)
        _rotate_point(w, kind, s, vs, paxes[k, p], phist[k, p], dt, p)
        for t in range(6):
            w[_OLD + 6 * p + t] = s[t] + vs[t]
        d00, d11, d22, d01, d12, d20 = _strain_rate(w, p, th)
        w[_DE], w[_DE + 1], w[_DE + 2] = d00 * dt, d11 * dt, d22 * dt
        w[_DE + 3], w[_DE + 4], w[_DE + 5] = d01 * dt, d12 * dt, d20 * dt
        wp, fp = update_stress(
            kind,
            pr,
            mcurve[m],
            cs,
            ce,
            cx,
            cy,
            s,
            w,
            _DE,
            _M,
            pepsp[k],
            p,
            phist[k, p],
            paxes[k, p],
            w[_JN + p] / detj0[k, p],
            dt,
        )
        wave = max(wave, wp)
        failed = failed or fp
    if failed:
        alive[e] = 0
        _kill(k, e, fe, sig, sv, psig, psv)
        return
    cmod[e] = wave
    rate[e] = th
    rho = rho0[e] * vol0[e] / vn
    le = vn ** (1.0 / 3.0)
    c = math.sqrt(wave / rho)
    qb = 0.0
    if th < 0.0 and pr[7] != 0.0:  # P_BULKQ
        qb = rho * le * (q1[e] * le * th * th - q2[e] * c * th)
    # P_DAMP: viscous stress factor, on the step's length V / A_max (not V^⅓ as the bulk viscosity):
    # a fraction P_DAMP of critical damping of the element's highest mode, whatever its shape; on V^⅓
    # an element crushed flat (V^⅓ / L ~ 100) is overdamped ~5x and the explicit viscous force diverges
    mu = pr[6] * rho * c * lt
    de = 0.0
    pbar = 0.0
    for t in range(6):
        sig[e, t] = 0.0
        sv[e, t] = 0.0
    ep = 0.0
    for p in range(8):
        d00, d11, d22, d01, d12, d20 = _strain_rate(w, p, th)
        vs = psv[k, p]
        vs[0] = mu * d00 - qb
        vs[1] = mu * d11 - qb
        vs[2] = mu * d22 - qb
        vs[3] = mu * d01
        vs[4] = mu * d12
        vs[5] = mu * d20
        s = psig[k, p]
        o = _T + 6 * p
        for t in range(6):
            w[o + t] = s[t] + vs[t]
            sig[e, t] += 0.125 * s[t]
            sv[e, t] += 0.125 * vs[t]
        ep += 0.125 * pepsp[k, p]
        b = _OLD + 6 * p
        de += (
            0.5
            * w[_JM + p]
            * dt
            * (
                (w[b] + w[o]) * d00
                + (w[b + 1] + w[o + 1]) * d11
                + (w[b + 2] + w[o + 2]) * d22
                + 2.0 * ((w[b + 3] + w[o + 3]) * d01 + (w[b + 4] + w[o + 4]) * d12 + (w[b + 5] + w[o + 5]) * d20)
            )
        )
        pbar += w[_JN + p] * (w[o] + w[o + 1] + w[o + 2])
    energy[e] += de
    epsp[e] = ep
    pbar /= 3.0 * vn  # the element's mean pressure (of the total stress, tension positive)
    for a in range(8):
        for i in range(3):
            fe[e, a, i] = 0.0
    for p in range(8):
        o = _T + 6 * p
        sh = pbar - (w[o] + w[o + 1] + w[o + 2]) / 3.0  # deviator of the point plus the mean pressure
        t0, t1, t2 = w[o] + sh, w[o + 1] + sh, w[o + 2] + sh
        t3, t4, t5 = w[o + 3], w[o + 4], w[o + 5]
        for a in range(8):
            g = _GN + 24 * p + 3 * a
            b0, b1, b2 = w[g], w[g + 1], w[g + 2]
            fe[e, a, 0] -= t0 * b0 + t3 * b1 + t5 * b2
            fe[e, a, 1] -= t3 * b0 + t1 * b1 + t4 * b2
            fe[e, a, 2] -= t5 * b0 + t4 * b1 + t2 * b2


@njit(cache=True, parallel=True)
def solid_full_forces(
    x,
    v,
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
    rho0,
    vol0,
    q1,
    q2,
    detj0,
    psig,
    psv,
    pepsp,
    phist,
    paxes,
    alive,
    vol,
    rate,
    cmod,
    energy,
    sig,
    sv,
    epsp,
    work,
    fe,
):
    """One step of the fully integrated elements ``idx`` (see the module
    docstring): point and element state to t(n+1), corner forces ``fe``."""
    nf = idx.shape[0]
    nc = work.shape[0]
    for ch in prange(nc):
        w = work[ch]
        for k in range(ch * nf // nc, (ch + 1) * nf // nc):
            _element(
                k,
                idx[k],
                x,
                v,
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
                rho0,
                vol0,
                q1,
                q2,
                detj0,
                psig,
                psv,
                pepsp,
                phist,
                paxes,
                alive,
                vol,
                rate,
                cmod,
                energy,
                sig,
                sv,
                epsp,
                w,
                fe,
            )


@njit(cache=True)
def point_jacobians(x, idx, conn, work, out):
    """out (nf, 8) det J at the Gauss points of the elements ``idx`` at the
    coordinates x [length³] (work (k, N_WORK_FULL) scratch, its first row used)."""
    w = work[0]
    for k in range(idx.shape[0]):
        _load_coords(x, x, conn, idx[k], 0.0, w)
        for p in range(8):
            out[k, p] = _cofactors(w, p)[9]
