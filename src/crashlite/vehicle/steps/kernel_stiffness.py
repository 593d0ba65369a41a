"""Shell stiffness matrices taken from the time loop's own shell kernel.

The static model's shells (``elements.shell_stiffness``: QM6 membrane,
MITC4 plate) are what a linear solver would use, not what the explicit
run integrates: a Belytschko–Lin–Tsay shell has one membrane point and
hourglass control (IHQ 4–5: stiffness, QM), a fully integrated one
(ELFORM 16) four points. On a coarse mesh the difference is that of the
structure itself: a 60 mm rail web bent in its plane is held by the
hourglass stiffness in one, by incompatible modes in the other. A reduced
structure that is to stand in for the run's elements (the elastic twin of
the vehicle) must have the run's stiffness.

``kernel_shell_stiffness`` linearises the kernel: each element gets its
own four nodes, and for each of its 24 DOFs (three translations and three
rotations per node) all elements take one step of that DOF alone, of a
size δ small enough to stay elastic (1e-7 of the element's size), with a
step dt of one time unit, so that rate terms (viscous hourglass control,
δ/dt) are negligible against the stiffness; the corner forces and
moments the kernel returns are −K·δ e_j, column j of the element's
stiffness in global axes. A small drilling penalty (as the static
model's) holds the in-plane rotation that the kernel leaves free.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...model.model import Model
from . import elements as el


def kernel_shell_stiffness(model: Model, idx: np.ndarray, drill: float = 1e-3) -> np.ndarray:
    """(n, 24, 24) stiffness of the shells ``idx`` (rows of model.shells) as
    the explicit shell kernel integrates them (module docstring); DOFs as
    ``elements.shell_stiffness``: per node ux uy uz rx ry rz."""
    from ...solver.kernels import plane_stress as ps
    from ...solver.rigid_parts import rigid_part_ids
    from ...solver.shells import build_shell_set, compute_forces, new_state

    problems: list = []
    s = build_shell_set(model, np.array(sorted(rigid_part_ids(model)), np.int64), problems, [])
    if s is None or problems:
        raise ValueError(f"the shells cannot be built for the time loop: {problems[:3]}")
    row = np.full(len(model.shells), -1, np.int64)
    row[np.flatnonzero(np.isin(model.shells.ids, s.ids))] = np.arange(len(s))
    rows = row[np.asarray(idx, np.int64)]
    if np.any(rows < 0):
        raise ValueError("some shells are rigid: no stiffness from the kernel")
    n = len(rows)
    sub = s.subset(rows)
    conn = model.shells.nodes[np.asarray(idx, np.int64)].astype(np.int64)
    x0 = model.nodes.xyz[conn].reshape(-1, 3).copy()  # private corners: 4 per element
    tri = sub.tri.astype(bool)
    priv = np.arange(4 * n).reshape(n, 4)
    priv[tri, 3] = priv[tri, 2]  # a triangle's fourth corner is its third
    sub = replace(sub, conn=priv)
    size = np.sqrt(np.maximum(sub.area0, 1e-300))
    delta = 1e-7 * size  # (n,) per element
    k = np.zeros((n, 24, 24))
    dt = 1.0
    for j in range(24):
        a, c = divmod(j, 6)
        node = priv[:, a]
        st = new_state(sub, 4 * n)
        v = np.zeros((4 * n, 3))
        w = np.zeros((4 * n, 3))
        (v if c < 3 else w)[node, c % 3] = delta / dt
        x = x0 + dt * v
        compute_forces(sub, st, x, v, w, dt)
        col = np.concatenate([st.fe, st.me], axis=2).reshape(n, 24)  # ON the nodes: −K δ e_j
        k[:, :, j] = -col / delta[:, None]
    if np.any(tri):  # a triangle's corner 4 is its corner 3: forces there are node 3's; its columns repeat node 3's
        t = np.flatnonzero(tri)
        k[t, 12:18, :] += k[t, 18:24, :]
        k[t, 18:24, :] = 0.0
        k[t, :, 18:24] = 0.0
    k = 0.5 * (k + np.transpose(k, (0, 2, 1)))
    young, nu = sub.props[sub.mat_of, ps.P_E], sub.props[sub.mat_of, ps.P_PR]
    return k + el.drilling_stiffness(x0.reshape(n, 4, 3), sub.thick0, young, nu, drill)
