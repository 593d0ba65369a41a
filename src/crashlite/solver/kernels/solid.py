"""8-node hexahedron with one-point integration (LS-DYNA ELFORM 1).

Flanagan–Belytschko uniform-strain element: the gradient operator is the
exact derivative of the element volume with respect to the nodal
coordinates, b_iI = ∂V/∂x_iI, so the mean strain rate is exact for any
trilinear shape (degenerate wedges and tetrahedra included) and a linear
velocity field gives a uniform strain rate (patch test).

Per step and element: velocity gradient at the mid-step configuration
x(n+½) = x(n+1) − ½Δt·v(n+½); the stress is first rotated by the
Hughes–Winget (Cayley) rotation of the spin, which is exactly the rotation
of a rigidly rotating element, so rigid rotations leave the stress
unchanged in its own frame (Jaumann rate); then the material update with
Δε = D·Δt; then artificial bulk viscosity and material damping as a
viscous stress; nodal forces −σ·b at x(n+1); then hourglass forces
(LS-DYNA IHQ 1–3 viscous, 4–5 Flanagan–Belytschko stiffness).

Forces exerted ON the nodes are written per element corner into
fe (n_elem, 8, 3); ``gather_corners`` sums them per node in a fixed order,
so results do not depend on the number of threads. The elements are
processed in ``work.shape[0]`` fixed chunks, each with its own scratch row.

Arrays (n = number of elements; units of the model, e.g. mm, t, s, N, MPa):
  x (n_nodes, 3) float64 coordinates at t(n+1) [length]
  v (n_nodes, 3) float64 velocities at t(n+½) [length/time]
  conn (n, 8) int64 node indices (LS-DYNA order; degenerate shapes repeat nodes)
  mat_of (n,) int64 row of the material tables
  mtype (n_mat,) int64 material kind (solid_materials.ELASTIC ...)
  props (n_mat, N_PROPS) float64, mcurve (n_mat, N_CURVES) int64: see solid_materials
  curve_start, curve_stop (n_curves,) int64; curve_x, curve_y (m,) float64 curve store
  rho0 (n,) float64 initial density [mass/length³]; vol0 (n,) initial volume [length³]
  hg_type (n,) int64 IHQ; hg_qm (n,) float64 QM; q1, q2 (n,) float64 bulk viscosity
  state, updated in place:
  sig (n, 6) float64 Cauchy stress (material part) [stress]
  sv (n, 6) float64 viscous stress of the last step (bulk viscosity, damping) [stress]
  epsp (n,) float64 effective plastic strain; hist (n, N_HIST) float64 history
  axes (n, 3, 3) float64 material axes a, b, c as columns (rotate with the element)
  hgq (n, 3, 4) float64 hourglass generalized forces [force]
  hg_kappa (n,) float64 hourglass stiffness of the last step (stiffness forms) [force/length]
  alive (n,) int8 1 active, 0 eroded (material failure), -1 inverted (V ≤ 0)
  vol (n,) float64 volume at t(n+1) [length³]
  rate (n,) float64 volumetric strain rate tr D [1/time]
  cmod (n,) float64 current wave modulus ρc² [stress]
  energy (n,) float64 internal energy (incl. viscous work) [energy]
  hg_energy (n,) float64 hourglass energy [energy]
  work (n_chunks, N_WORK) float64 scratch
  fe (n, 8, 3) float64 output corner forces [force]
"""

import math

import numpy as np
from numba import njit, prange

from .solid_materials import HONEYCOMB, N_SCRATCH, _to_global, _to_local, carry_lines, update_stress

# natural coordinates of the nodes, LS-DYNA order (1-4 bottom, 5-8 top)
XI = np.array(
    [[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1], [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], np.float64
)
# hourglass base vectors ηζ, ζξ, ξη, ξηζ at the nodes (4, 8)
HG_BASE = np.stack([XI[:, 1] * XI[:, 2], XI[:, 2] * XI[:, 0], XI[:, 0] * XI[:, 1], XI.prod(axis=1)])


def _volume_terms():
    """Nonzero terms of V = Σ D_IJK x_I y_J z_K for the trilinear hexahedron
    (D antisymmetric; kept for J < K), from 2x2x2 Gauss points (exact)."""
    eps = np.zeros((3, 3, 3))
    eps[0, 1, 2] = eps[1, 2, 0] = eps[2, 0, 1] = 1.0
    eps[0, 2, 1] = eps[2, 1, 0] = eps[1, 0, 2] = -1.0
    d = np.zeros((8, 8, 8))
    for p in XI / math.sqrt(3.0):
        dn = np.empty((8, 3))
        for a in range(3):
            o1, o2 = [b for b in range(3) if b != a]
            dn[:, a] = XI[:, a] * (1 + XI[:, o1] * p[o1]) * (1 + XI[:, o2] * p[o2]) / 8.0
        d += np.einsum("abc,ia,jb,kc->ijk", eps, dn, dn, dn)
    t = [
        (i, j, k, round(d[i, j, k] * 12.0) / 12.0)
        for i in range(8)
        for j in range(8)
        for k in range(j + 1, 8)
        if abs(d[i, j, k]) > 1e-12
    ]
    return (
        np.array([a[0] for a in t], np.int64),
        np.array([a[1] for a in t], np.int64),
        np.array([a[2] for a in t], np.int64),
        np.array([a[3] for a in t], np.float64),
    )


VT_I, VT_J, VT_K, VT_C = _volume_terms()

# scratch layout of one work row
_X, _B, _V, _G, _R, _DE, _M = 0, 24, 48, 72, 104, 113, 119
N_WORK = _M + N_SCRATCH
N_CHUNKS = 64  # fixed number of element chunks: thread-count independent results


@njit(cache=True)
def _grad(w):
    """b_iI = ∂V/∂x_iI into w[_B:_B+24] from coordinates w[_X:_X+24];
    returns V."""
    for k in range(24):
        w[_B + k] = 0.0
    for t in range(VT_C.shape[0]):
        i = 3 * VT_I[t]
        j = _X + 3 * VT_J[t]
        k = _X + 3 * VT_K[t]
        c = VT_C[t]
        w[_B + i] += c * (w[j + 1] * w[k + 2] - w[k + 1] * w[j + 2])
        w[_B + i + 1] += c * (w[j + 2] * w[k] - w[k + 2] * w[j])
        w[_B + i + 2] += c * (w[j] * w[k + 1] - w[k] * w[j + 1])
    vol = 0.0
    for a in range(8):
        vol += w[_X + 3 * a] * w[_B + 3 * a]
    return vol


@njit(cache=True)
def _load_coords(x, v, conn, e, shift, w):
    """Coordinates x − shift·v relative to the element's first node."""
    a0 = conn[e, 0]
    for a in range(8):
        n = conn[e, a]
        for i in range(3):
            w[_X + 3 * a + i] = (x[n, i] - shift * v[n, i]) - (x[a0, i] - shift * v[a0, i])


@njit(cache=True)
def _rotate6(w, s):
    """s ← R s Rᵀ (symmetric, Voigt) with R = w[_R:_R+9] row major."""
    m = (s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2])
    idx_i = (0, 1, 2, 0, 1, 2)
    idx_j = (0, 1, 2, 1, 2, 0)
    for t in range(6):
        i = idx_i[t]
        j = idx_j[t]
        acc = 0.0
        for k in range(3):
            rik = w[_R + 3 * i + k]
            acc += rik * (
                m[3 * k] * w[_R + 3 * j] + m[3 * k + 1] * w[_R + 3 * j + 1] + m[3 * k + 2] * w[_R + 3 * j + 2]
            )
        w[_M + t] = acc
    for t in range(6):
        s[t] = w[_M + t]


@njit(cache=True)
def _convect_axes(q, h, g00, g01, g02, g10, g11, g12, g20, g21, g22):
    """Material axes of a honeycomb (columns a, b, c) carried by the
    deformation: the cell axis a is a material line, a ← (I + L·Δt)·a
    (g = L·Δt), so a sheared cell keeps crushing along its walls; b is
    carried likewise and made orthogonal to a, c = a × b. (Turning them
    with the spin instead would swing a by half the shear angle, and a
    block sheared at the edge of an impactor would crush in its weak
    directions.) Its history h carries the initial axes as material lines
    by the same g first (``carry_lines``: on the first step it keeps q as
    it was before it moves)."""
    carry_lines(h, q, g00, g01, g02, g10, g11, g12, g20, g21, g22)
    a0, a1, a2 = q[0, 0], q[1, 0], q[2, 0]
    b0, b1, b2 = q[0, 1], q[1, 1], q[2, 1]
    n0 = a0 + g00 * a0 + g01 * a1 + g02 * a2
    n1 = a1 + g10 * a0 + g11 * a1 + g12 * a2
    n2 = a2 + g20 * a0 + g21 * a1 + g22 * a2
    r = 1.0 / math.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
    a0, a1, a2 = n0 * r, n1 * r, n2 * r
    m0 = b0 + g00 * b0 + g01 * b1 + g02 * b2
    m1 = b1 + g10 * b0 + g11 * b1 + g12 * b2
    m2 = b2 + g20 * b0 + g21 * b1 + g22 * b2
    d = m0 * a0 + m1 * a1 + m2 * a2
    m0, m1, m2 = m0 - d * a0, m1 - d * a1, m2 - d * a2
    r = 1.0 / math.sqrt(m0 * m0 + m1 * m1 + m2 * m2)
    b0, b1, b2 = m0 * r, m1 * r, m2 * r
    q[0, 0], q[1, 0], q[2, 0] = a0, a1, a2
    q[0, 1], q[1, 1], q[2, 1] = b0, b1, b2
    q[0, 2], q[1, 2], q[2, 2] = a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


@njit(cache=True)
def _kill(e, fe, sig, sv):
    for a in range(8):
        for i in range(3):
            fe[e, a, i] = 0.0
    for t in range(6):
        sig[e, t] = 0.0
        sv[e, t] = 0.0


@njit(cache=True)
def _element(
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
    hg_type,
    hg_qm,
    q1,
    q2,
    sig,
    sv,
    epsp,
    hist,
    axes,
    hgq,
    hg_kappa,
    alive,
    vol,
    rate,
    cmod,
    energy,
    hg_energy,
    w,
    fe,
):
    if alive[e] != 1:
        _kill(e, fe, sig, sv)
        rate[e] = 0.0
        return
    for a in range(8):
        n = conn[e, a]
        for i in range(3):
            w[_V + 3 * a + i] = v[n, i]
    # velocity gradient at mid-step: L_ij = Σ v_iI b_jI / V
    _load_coords(x, v, conn, e, 0.5 * dt, w)
    vm = _grad(w)
    if vm <= 0.0:
        alive[e] = -1
        _kill(e, fe, sig, sv)
        return
    l00 = l01 = l02 = l10 = l11 = l12 = l20 = l21 = l22 = 0.0
    for a in range(8):
        va0, va1, va2 = w[_V + 3 * a], w[_V + 3 * a + 1], w[_V + 3 * a + 2]
        b0, b1, b2 = w[_B + 3 * a], w[_B + 3 * a + 1], w[_B + 3 * a + 2]
        l00 += va0 * b0
        l01 += va0 * b1
        l02 += va0 * b2
        l10 += va1 * b0
        l11 += va1 * b1
        l12 += va1 * b2
        l20 += va2 * b0
        l21 += va2 * b1
        l22 += va2 * b2
    inv = 1.0 / vm
    d00, d11, d22 = l00 * inv, l11 * inv, l22 * inv
    d01, d12, d20 = 0.5 * (l01 + l10) * inv, 0.5 * (l12 + l21) * inv, 0.5 * (l20 + l02) * inv
    # rotation of the step: Cayley transform of ½Δt·W (exact for rigid rotation)
    ax = 0.25 * dt * (l21 - l12) * inv
    ay = 0.25 * dt * (l02 - l20) * inv
    az = 0.25 * dt * (l10 - l01) * inv
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
    s = sig[e]
    q = axes[e]
    m = mat_of[e]
    if mtype[m] == HONEYCOMB:  # the stress keeps its components in the convected material axes
        _to_local(q, s, 0, w, _M)
        _convect_axes(
            q,
            hist[e],
            l00 * inv * dt,
            l01 * inv * dt,
            l02 * inv * dt,
            l10 * inv * dt,
            l11 * inv * dt,
            l12 * inv * dt,
            l20 * inv * dt,
            l21 * inv * dt,
            l22 * inv * dt,
        )
        _to_global(q, w, _M, s)
    else:
        _rotate6(w, s)
        for j in range(3):  # material axes turn with the element
            c0, c1, c2 = q[0, j], q[1, j], q[2, j]
            for i in range(3):
                q[i, j] = w[_R + 3 * i] * c0 + w[_R + 3 * i + 1] * c1 + w[_R + 3 * i + 2] * c2
    _rotate6(w, sv[e])
    old0 = s[0] + sv[e, 0]
    old1 = s[1] + sv[e, 1]
    old2 = s[2] + sv[e, 2]
    old3 = s[3] + sv[e, 3]
    old4 = s[4] + sv[e, 4]
    old5 = s[5] + sv[e, 5]
    w[_DE], w[_DE + 1], w[_DE + 2] = d00 * dt, d11 * dt, d22 * dt
    w[_DE + 3], w[_DE + 4], w[_DE + 5] = d01 * dt, d12 * dt, d20 * dt
    # geometry at t(n+1)
    _load_coords(x, v, conn, e, 0.0, w)
    vn = _grad(w)
    vol[e] = vn
    if vn <= 0.0:
        alive[e] = -1
        _kill(e, fe, sig, sv)
        return
    p = props[m]
    wave, failed = update_stress(
        mtype[m], p, mcurve[m], cs, ce, cx, cy, s, w, _DE, _M, epsp, e, hist[e], q, vn / vol0[e], dt
    )
    if failed:
        alive[e] = 0
        _kill(e, fe, sig, sv)
        return
    cmod[e] = wave
    rho = rho0[e] * vol0[e] / vn
    le = vn ** (1.0 / 3.0)
    c = math.sqrt(wave / rho)
    tr = d00 + d11 + d22
    rate[e] = tr
    qb = 0.0
    if tr < 0.0 and p[7] != 0.0:  # P_BULKQ
        qb = rho * le * (q1[e] * le * tr * tr - q2[e] * c * tr)
    mu = p[6] * rho * c * le  # P_DAMP: viscous stress factor
    sv[e, 0] = mu * d00 - qb
    sv[e, 1] = mu * d11 - qb
    sv[e, 2] = mu * d22 - qb
    sv[e, 3] = mu * d01
    sv[e, 4] = mu * d12
    sv[e, 5] = mu * d20
    t0, t1, t2 = s[0] + sv[e, 0], s[1] + sv[e, 1], s[2] + sv[e, 2]
    t3, t4, t5 = s[3] + sv[e, 3], s[4] + sv[e, 4], s[5] + sv[e, 5]
    # trapezoid work of the total stress over the step, at the mid-step volume
    energy[e] += (
        0.5
        * vm
        * dt
        * (
            (old0 + t0) * d00
            + (old1 + t1) * d11
            + (old2 + t2) * d22
            + 2.0 * ((old3 + t3) * d01 + (old4 + t4) * d12 + (old5 + t5) * d20)
        )
    )
    for a in range(8):
        b0, b1, b2 = w[_B + 3 * a], w[_B + 3 * a + 1], w[_B + 3 * a + 2]
        fe[e, a, 0] = -(t0 * b0 + t3 * b1 + t5 * b2)
        fe[e, a, 1] = -(t3 * b0 + t1 * b1 + t4 * b2)
        fe[e, a, 2] = -(t5 * b0 + t4 * b1 + t2 * b2)
    _hourglass(e, w, vn, rho, c, wave, dt, hg_type[e], hg_qm[e], hgq, hg_kappa, hg_energy, fe)


@njit(cache=True)
def _hourglass(e, w, vn, rho, c, wave, dt, ihq, qm, hgq, hg_kappa, hg_energy, fe):
    """Hourglass resistance on the current geometry (w: coordinates, b and
    velocities). IHQ 1: LS-DYNA standard viscous on the base vectors Γ;
    2, 3: Flanagan–Belytschko viscous on γ = Γ − (Γ·x) b / V, orthogonal
    to linear velocity fields; 4, 5: FB stiffness, incremental, the stored
    generalized forces rotated with the element each step. 3 and 5 (exact
    volume integration in LS-DYNA) run as 2 and 4."""
    if qm == 0.0 or ihq <= 0:
        return
    bb = 0.0
    for k in range(24):
        bb += w[_B + k] * w[_B + k]
    visc = ihq <= 3
    a_visc = 0.25 * qm * rho * c * vn ** (2.0 / 3.0)
    # FB stiffness Q̇ = QM·(ρc²)·(b·b)/(3V)·q̇ with FB's shape vectors γ/8: q̇ = v·γ/8 and f = Q·γ/8,
    # hence 1/64 on the unnormalized γ used here (a cube's mode then gets ≈ QM × its physical stiffness)
    kappa = qm * wave * bb / (192.0 * vn)
    if not visc:  # stored stiffness forces turn with the element, as the stress does (objective)
        # a stiffness that fell (the modulus of a honeycomb springing back, the element's shape) scales the
        # stored forces with it: unloading along the new stiffness gives back at most what was stored, where
        # the stored forces alone would return more work than loading took (energy from nothing)
        shrink = kappa / hg_kappa[e] if 0.0 < kappa < hg_kappa[e] else 1.0
        hg_kappa[e] = kappa
        for al in range(4):
            g0, g1, g2 = shrink * hgq[e, 0, al], shrink * hgq[e, 1, al], shrink * hgq[e, 2, al]
            for i in range(3):
                hgq[e, i, al] = w[_R + 3 * i] * g0 + w[_R + 3 * i + 1] * g1 + w[_R + 3 * i + 2] * g2
    for al in range(4):
        h0 = h1 = h2 = 0.0
        for a in range(8):
            gam = HG_BASE[al, a]
            h0 += gam * w[_X + 3 * a]
            h1 += gam * w[_X + 3 * a + 1]
            h2 += gam * w[_X + 3 * a + 2]
        for a in range(8):
            g = HG_BASE[al, a]
            if ihq != 1:
                g -= (h0 * w[_B + 3 * a] + h1 * w[_B + 3 * a + 1] + h2 * w[_B + 3 * a + 2]) / vn
            w[_G + 8 * al + a] = g
        for i in range(3):
            qd = 0.0
            for a in range(8):
                qd += w[_V + 3 * a + i] * w[_G + 8 * al + a]
            old = hgq[e, i, al]
            new = a_visc * qd if visc else old + kappa * qd * dt
            hgq[e, i, al] = new
            hg_energy[e] += 0.5 * (old + new) * qd * dt
            for a in range(8):
                fe[e, a, i] -= new * w[_G + 8 * al + a]


@njit(cache=True, parallel=True)
def solid_forces(
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
    hg_type,
    hg_qm,
    q1,
    q2,
    sig,
    sv,
    epsp,
    hist,
    axes,
    hgq,
    hg_kappa,
    alive,
    vol,
    rate,
    cmod,
    energy,
    hg_energy,
    work,
    fe,
):
    """One step of the solid elements (see the module docstring for the
    arrays): stresses, energies and state to t(n+1), corner forces ``fe``."""
    n = conn.shape[0]
    nc = work.shape[0]
    for ch in prange(nc):
        w = work[ch]
        for e in range(ch * n // nc, (ch + 1) * n // nc):
            _element(
                e,
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
                hg_type,
                hg_qm,
                q1,
                q2,
                sig,
                sv,
                epsp,
                hist,
                axes,
                hgq,
                hg_kappa,
                alive,
                vol,
                rate,
                cmod,
                energy,
                hg_energy,
                w,
                fe,
            )


@njit(cache=True, parallel=True)
def solid_volumes(x, conn, work, vol):
    """vol (n,) exact volumes of the trilinear elements [length³]."""
    n = conn.shape[0]
    nc = work.shape[0]
    for ch in prange(nc):
        w = work[ch]
        for e in range(ch * n // nc, (ch + 1) * n // nc):
            _load_coords(x, x, conn, e, 0.0, w)
            vol[e] = _grad(w)


@njit(cache=True, parallel=True)
def solid_gradients(x, conn, work, b):
    """b (n, 8, 3) = ∂V/∂x of each element (the one-point B matrix times V)."""
    n = conn.shape[0]
    nc = work.shape[0]
    for ch in prange(nc):
        w = work[ch]
        for e in range(ch * n // nc, (ch + 1) * n // nc):
            _load_coords(x, x, conn, e, 0.0, w)
            _grad(w)
            for a in range(8):
                for i in range(3):
                    b[e, a, i] = w[_B + 3 * a + i]


# faces of the hexahedron (LS-DYNA node order)
FACES = np.array([[0, 1, 2, 3], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]], np.int64)


@njit(cache=True, parallel=True)
def solid_timestep(x, conn, alive, vol, rho0, vol0, cmod, rate, q1, q2, dt_out):
    """LS-DYNA critical step of each solid: Δt = L / (Q + sqrt(Q² + c²)),
    L = V / largest face area (face area ½|d1 × d2| from its diagonals),
    c = sqrt(cmod/ρ), Q = Q2·c + Q1·L·|tr D| when compressing, else 0.
    Inactive elements get +inf. dt_out (n,) [time]."""
    for e in prange(conn.shape[0]):
        if alive[e] != 1 or vol[e] <= 0.0:
            dt_out[e] = np.inf
            continue
        amax = 0.0
        for fc in range(6):
            n0 = conn[e, FACES[fc, 0]]
            n1 = conn[e, FACES[fc, 1]]
            n2 = conn[e, FACES[fc, 2]]
            n3 = conn[e, FACES[fc, 3]]
            d10, d11, d12 = x[n2, 0] - x[n0, 0], x[n2, 1] - x[n0, 1], x[n2, 2] - x[n0, 2]
            d20, d21, d22 = x[n3, 0] - x[n1, 0], x[n3, 1] - x[n1, 1], x[n3, 2] - x[n1, 2]
            c0 = d11 * d22 - d12 * d21
            c1 = d12 * d20 - d10 * d22
            c2 = d10 * d21 - d11 * d20
            amax = max(amax, 0.5 * math.sqrt(c0 * c0 + c1 * c1 + c2 * c2))
        le = vol[e] / amax
        rho = rho0[e] * vol0[e] / vol[e]
        c = math.sqrt(cmod[e] / rho)
        qv = 0.0
        if rate[e] < 0.0:
            qv = q2[e] * c + q1[e] * le * abs(rate[e])
        dt_out[e] = le / (qv + math.sqrt(qv * qv + c * c))


def corner_incidence(n_nodes: int, conn: np.ndarray):
    """CSR node -> element corners: corners of node i are
    corner_of[node_ptr[i]:node_ptr[i+1]], corner = 8·element + local node,
    in increasing order (a fixed summation order). Repeated nodes of
    degenerate elements appear once per corner."""
    nodes = np.asarray(conn, np.int64).ravel()
    corner_of = np.argsort(nodes, kind="stable").astype(np.int64)
    ptr = np.zeros(n_nodes + 1, np.int64)
    np.add.at(ptr, nodes + 1, 1)
    return np.cumsum(ptr), corner_of


@njit(cache=True, inline="always")
def _corner_sum(node_ptr, corner_of, rows, i):
    """Σ rows[c] over the corners c of node i, in their fixed order."""
    a0 = a1 = a2 = 0.0
    for k in range(node_ptr[i], node_ptr[i + 1]):
        c = corner_of[k]
        a0 += rows[c, 0]
        a1 += rows[c, 1]
        a2 += rows[c, 2]
    return a0, a1, a2


@njit(cache=True, parallel=True)
def gather_corners(node_ptr, corner_of, rows, out):
    """out[i] += Σ rows[c] over the corners c of node i, in a fixed order.

    rows (n_elem·8, 3) corner forces (fe reshaped); out (n_nodes, 3)."""
    for i in prange(out.shape[0]):
        a0, a1, a2 = _corner_sum(node_ptr, corner_of, rows, i)
        out[i, 0] += a0
        out[i, 1] += a1
        out[i, 2] += a2


@njit(cache=True, parallel=True)
def gather_corner_pair(node_ptr, corner_of, rows_a, out_a, rows_b, out_b):
    """``gather_corners`` of two corner arrays over the same incidence in one
    parallel pass (a shell's forces and moments): one launch, and each
    node's index range is read while still in cache."""
    for i in prange(out_a.shape[0]):
        a0, a1, a2 = _corner_sum(node_ptr, corner_of, rows_a, i)
        b0, b1, b2 = _corner_sum(node_ptr, corner_of, rows_b, i)
        out_a[i, 0] += a0
        out_a[i, 1] += a1
        out_a[i, 2] += a2
        out_b[i, 0] += b0
        out_b[i, 1] += b1
        out_b[i, 2] += b2
