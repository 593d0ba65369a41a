"""Elastic beams (*ELEMENT_BEAM, resultant formulation), corotational.

Each element carries a frame that follows its chord (e1) and the mean of its
end triads (e2, e3). In that frame the deformation is small: elongation,
twist and the end rotations relative to the chord; the resultants follow the
linear Euler–Bernoulli stiffness, and are turned back to the global frame.
Large rigid rotations therefore produce no strain. Per-element end forces
and moments go to ``fe``/``me`` (n, 2, 3); nodes gather them in a fixed
order (race-free, thread-count independent).
"""

import numpy as np
from numba import njit, prange

from .rigid import rotation_entries


@njit(cache=True, inline="always")
def _vee_skew(d):
    """Axial vector of the skew part of a near-identity rotation matrix."""
    return (0.5 * (d[2, 1] - d[1, 2]), 0.5 * (d[0, 2] - d[2, 0]), 0.5 * (d[1, 0] - d[0, 1]))


@njit(cache=True, parallel=True)
def beam_forces(x, rot, n1, n2, q1, q2, length0, ea, gj, ei2, ei3, fe, me, gen_force, gen_def):
    """End forces ``fe`` and moments ``me`` (n, 2, 3) exerted ON the nodes.

    rot (n_nodes, 3, 3) nodal rotations; q1, q2 (n, 3, 3) the element axes
    seen from each end node at t = 0 (columns e1, e2, e3); ea, gj, ei2
    (bending in the e1-e3 plane), ei3 (in the e1-e2 plane). gen_force and
    gen_def (n, 6): N, twist moment, M2a, M2b, M3a, M3b and their
    deformations, for the energy account.
    """
    for e in prange(n1.shape[0]):
        a = n1[e]
        b = n2[e]
        d = x[b] - x[a]
        length = np.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
        e1 = d / length
        ta = rot[a] @ q1[e]
        tb = rot[b] @ q2[e]
        g = 0.5 * (ta[:, 1] + tb[:, 1])
        g = g - (g @ e1) * e1
        e2 = g / np.sqrt(g @ g)
        e3 = np.cross(e1, e2)
        frame = np.empty((3, 3))
        frame[:, 0] = e1
        frame[:, 1] = e2
        frame[:, 2] = e3
        ra = _vee_skew(frame.T @ ta)
        rb = _vee_skew(frame.T @ tb)
        l0 = length0[e]
        u = length - l0
        twist = rb[0] - ra[0]
        n_ax = ea[e] * u / l0
        m_t = gj[e] * twist / l0
        k3 = ei3[e] / l0
        m3a = k3 * (4.0 * ra[2] + 2.0 * rb[2])
        m3b = k3 * (2.0 * ra[2] + 4.0 * rb[2])
        k2 = ei2[e] / l0
        m2a = k2 * (4.0 * ra[1] + 2.0 * rb[1])
        m2b = k2 * (2.0 * ra[1] + 4.0 * rb[1])
        v2 = (m3a + m3b) / l0
        v3 = -(m2a + m2b) / l0
        # internal force vector of the element; the nodes receive its negative
        for j in range(3):
            fe[e, 0, j] = n_ax * e1[j] - v2 * e2[j] - v3 * e3[j]
            fe[e, 1, j] = -n_ax * e1[j] + v2 * e2[j] + v3 * e3[j]
            me[e, 0, j] = m_t * e1[j] - m2a * e2[j] - m3a * e3[j]
            me[e, 1, j] = -m_t * e1[j] - m2b * e2[j] - m3b * e3[j]
        gen_force[e, 0] = n_ax
        gen_force[e, 1] = m_t
        gen_force[e, 2] = m2a
        gen_force[e, 3] = m2b
        gen_force[e, 4] = m3a
        gen_force[e, 5] = m3b
        gen_def[e, 0] = u
        gen_def[e, 1] = twist
        gen_def[e, 2] = ra[1]
        gen_def[e, 3] = rb[1]
        gen_def[e, 4] = ra[2]
        gen_def[e, 5] = rb[2]


@njit(cache=True, parallel=True)
def gather_ends(node_ptr, corner_of, ends, out):
    """out[i] += Σ ends[corner] over the element ends at node i (fixed order);
    ``ends`` (n_elem, 2, 3) is addressed as corner = 2·element + end."""
    flat = ends.reshape(ends.shape[0] * 2, 3)
    for i in prange(out.shape[0]):
        for k in range(node_ptr[i], node_ptr[i + 1]):
            c = corner_of[k]
            out[i, 0] += flat[c, 0]
            out[i, 1] += flat[c, 1]
            out[i, 2] += flat[c, 2]


@njit(cache=True, parallel=True)
def energy_step6(gf_old, gf, gd_old, gd, elem_energy):
    """Trapezoid work of the generalized resultants, per element into
    ``elem_energy``; new values become old."""
    for e in prange(gf.shape[0]):
        for k in range(6):
            elem_energy[e] += 0.5 * (gf_old[e, k] + gf[e, k]) * (gd[e, k] - gd_old[e, k])
            gf_old[e, k] = gf[e, k]
            gd_old[e, k] = gd[e, k]


@njit(cache=True)
def _turn_node(rot, w, i, dt):
    """R_i ← exp(dt·ω_i)·R_i, applied column by column (kernels.rigid's
    Rodrigues entries: no temporary arrays per node)."""
    r00, r01, r02, r10, r11, r12, r20, r21, r22 = rotation_entries(dt * w[i, 0], dt * w[i, 1], dt * w[i, 2])
    for j in range(3):
        a0, a1, a2 = rot[i, 0, j], rot[i, 1, j], rot[i, 2, j]
        rot[i, 0, j] = r00 * a0 + r01 * a1 + r02 * a2
        rot[i, 1, j] = r10 * a0 + r11 * a1 + r12 * a2
        rot[i, 2, j] = r20 * a0 + r21 * a1 + r22 * a2


@njit(cache=True)
def turn_nodes(rot, w, nodes, dt):
    """R ← exp(dt·ω)·R for the listed nodes only: the ones whose orientation
    some element reads (beams); a shell takes its rotations as rates."""
    for k in range(nodes.shape[0]):
        _turn_node(rot, w, nodes[k], dt)
