"""The replaced structure condensed onto the cut's nodes under inertia relief.

The springs of step 4 and the rigid interface hold the cut flat: the cut
moves as one rigid body relative to the rear body. The structure behind a
real cut bends (the generic car's cut bends by 15 % of the firewall's
largest intrusion out of a rigid motion), and the kept structure next to
it cannot follow the full car closer than that. This module keeps it.

``relieved_condensation`` computes the flexibility of the free replaced
structure at every translational DOF of the cut nodes, in the frame of its
own mean rigid motion (inertia relief, as ``relief`` does for a rigid
interface): a unit force on one cut DOF, balanced by the nodes' d'Alembert
forces −m_i φ_i (ΦᵀMΦ)⁻¹ φ_bᵀ (Φ the six rigid motions about the CoG), is
solved on the 3-2-1-supported static model of step 3, and the rigid motion
that best fits the displacements in the mass metric is taken out. With
P = I − MΦ(ΦᵀMΦ)⁻¹Φᵀ the loads' projection and S the supported inverse,
G = E_bᵀ Pᵀ S P E_b: symmetric, positive definite where every cut node is
joined to a structure with mass behind it. Its inverse K_s = G⁻¹ maps the
cut's displacements relative to the structure's mean rigid motion to the
forces the structure returns; the cut nodes' rotations stay free (shell
edges hinge on it).

On a rigid interface (cut nodes moving as one body about a point, T) the
condensed stiffness reduces to Tᵀ K_s T, which is the relieved 6×6 of
``relief`` where the cut nodes carry no rotations (solids; test against
3·EA/L for a bar). ``surrogate.build_surrogate(connection="condensed")``
joins the cut to the rear body with it (a linear superelement,
*ELEMENT_DIRECT_MATRIX_INPUT).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ..steps.cut import Cut
from ..steps.massprops import NodeSelection, node_indices
from ..steps.relief import _support_321, static_masses
from ..steps.statics import factor as _factor
from ..steps.statics import reduced_columns
from ..steps.stiffness import build_static
from .modes import _eigen


def rigid_modes(r: np.ndarray, c: np.ndarray) -> np.ndarray:
    """(k, 3, 6): translations of points ``r`` (k, 3) under the six rigid
    motions (translation, small rotation θ) about ``c``: u = t + θ × (r − c)."""
    d = np.asarray(r, float) - c
    out = np.zeros((len(d), 3, 6))
    out[:, :, :3] = np.eye(3)
    out[:, 0, 4], out[:, 0, 5] = d[:, 2], -d[:, 1]
    out[:, 1, 3], out[:, 1, 5] = -d[:, 2], d[:, 0]
    out[:, 2, 3], out[:, 2, 4] = d[:, 1], -d[:, 0]
    return out


@dataclass
class Condensation:
    """The replaced structure seen from the cut nodes (module docstring)."""

    nodes: np.ndarray  # (k,) node indices of the cut the structure is condensed on
    flexibility: np.ndarray  # (3k, 3k) G: displacement relative to the mean rigid motion per unit force
    stiffness: np.ndarray  # (3k, 3k) K_s = G⁻¹ [force/length]
    mass: float  # the replaced structure's mass (as the static model carries it)
    cog: np.ndarray  # (3,)
    node_mass: np.ndarray  # (n_nodes,) the replaced mass lumped to the model's nodes
    left_out: np.ndarray  # cut nodes not condensed (tied to a rigid group, or outside the static model)
    notes: list = field(default_factory=list)
    xyz_nodes: np.ndarray | None = None  # (k, 3) coordinates of ``nodes``
    modal: np.ndarray | None = None  # (3k, N) the cut's translations in the N lowest free elastic modes
    #                                  (mass-normalised)
    omega2: np.ndarray | None = None  # (N,) their ω² [1/time²]
    residual: np.ndarray | None = None  # (3k, 3k) (G − Φ Ω⁻² Φᵀ)⁻¹: the stiffness of what the modes leave

    @property
    def frequencies(self) -> np.ndarray:
        """(N,) the kept modes' frequencies [1/time]."""
        return np.sqrt(self.omega2) / (2.0 * np.pi) if self.omega2 is not None else np.zeros(0)

    def rigid_stiffness(self, point: ArrayLike) -> np.ndarray:
        """(6, 6) stiffness of the cut held rigid about ``point`` (force and
        moment against translation and rotation): Tᵀ K_s T."""
        t = rigid_modes(self.xyz_nodes, np.asarray(point, float)).reshape(-1, 6)
        return t.T @ self.stiffness @ t

    def summary(self) -> dict:
        lam = np.linalg.eigvalsh(self.stiffness)
        return {
            "nodes": int(len(self.nodes)),
            "dofs": int(3 * len(self.nodes)),
            "left_out": int(len(self.left_out)),
            "stiffness_eigenvalues": [float(lam[0]), float(lam[-1])],
            "mass": self.mass,
            "cog": self.cog.tolist(),
            "modes": int(len(self.frequencies)),
            "mode_frequencies": self.frequencies.tolist(),
            "notes": list(self.notes),
        }


def relieved_condensation(
    cut: Cut, nodes: NodeSelection | None = None, modes: int = 0, drill: float = 1e-3, shells: str = "static"
) -> Condensation:
    """The replaced structure of ``cut`` condensed onto the translations of
    the cut nodes (default: all its interface nodes) under inertia relief
    (module docstring); with ``modes`` > 0 also its lowest free elastic
    modes and the residual stiffness of what they leave (residual
    flexibility, module docstring); ``shells``: the shells' stiffness
    (``stiffness.build_static``)."""
    model = cut.model
    ls, _, notes = build_static(model, cut.replaced, drill, shells=shells)
    b = cut.interface_nodes if nodes is None else node_indices(model, nodes)
    ok = ls.in_structure[b] & ~ls.tied()[b]  # a tied node moves with its group's master: no DOFs of its own
    b, left = b[ok], b[~ok]
    if not len(b):
        raise ValueError("no cut node is a free node of the replaced structure")
    if len(left):
        notes.append(f"{len(left)} cut node(s) of rigid groups or outside the replaced structure not condensed")
    m, carry, big_m, c, mnotes = static_masses(cut, ls)
    xyz = model.nodes.xyz
    phi_c = rigid_modes(xyz[carry], c)  # (n_carry, 3, 6)
    a = np.linalg.inv(np.einsum("n,nai,naj->ij", m[carry], phi_c, phi_c))  # (ΦᵀMΦ)⁻¹
    nb3 = 3 * len(b)
    phi_b = rigid_modes(xyz[b], c).reshape(nb3, 6)
    cand = np.flatnonzero(ls.in_structure & ~ls.tied())
    off_cut = np.setdiff1d(cand, b)
    cand = off_cut if len(off_cut) >= 3 else cand  # (the cut's DOFs stay free)
    for n, dofs in _support_321(xyz, cand):
        ls.fix([n], dofs)
    t, fixed, slave_of, rnotes = ls.reduction()
    indep = (slave_of < 0)[:, None] & ~fixed
    col = reduced_columns(fixed, slave_of)
    kr = (t.T @ ls.stiffness_matrix() @ t).tocsr()
    diag = kr.diagonal()
    live = diag > 1e-12 * max(float(np.abs(diag).max(initial=0.0)), 1e-300)
    bdofs = col[(6 * b[:, None] + np.arange(3)).ravel()]
    if np.any(bdofs < 0) or not live[bdofs].all():
        raise ValueError("a cut node's translation is held or has no stiffness: it cannot be condensed")
    # the d'Alembert loads of the rigid accelerations, in the reduced DOFs: M Φ
    mphi = np.zeros((6 * ls.n_total, 6))
    mphi[(6 * carry[:, None] + np.arange(3)).ravel()] = (m[carry, None, None] * phi_c).reshape(-1, 6)
    mphi = t.T @ mphi
    s_b, w = _schur_inverse(kr, live, bdofs, mphi, ls.n_total, indep)
    # G = E_bᵀ Pᵀ S P E_b with P = I − MΦAΦ_bᵀ...: S_b − W_b A Φ_bᵀ − Φ_b A W_bᵀ + Φ_b A Q A Φ_bᵀ
    w_b = w[bdofs]
    q = mphi.T @ w
    g = s_b - w_b @ a @ phi_b.T - phi_b @ a @ w_b.T + phi_b @ a @ q @ a @ phi_b.T
    asym = float(np.abs(g - g.T).max() / np.abs(g).max())
    if asym > 1e-6:
        notes.append(f"the condensed flexibility is unsymmetric by {asym:.2g} (relative)")
    g = 0.5 * (g + g.T)
    lam = np.linalg.eigvalsh(g)
    if not lam[0] > 1e-12 * lam[-1]:
        raise ValueError(
            f"the condensed flexibility is singular (eigenvalues {lam[0]:.3g} to {lam[-1]:.3g}): "
            "cut nodes that move together (tied) or a cut node joined to nothing with mass"
        )
    ks = np.linalg.inv(g)
    ks = 0.5 * (ks + ks.T)
    out = Condensation(b, g, ks, big_m, c, m, left, list(cut.notes) + notes + mnotes + rnotes, xyz[b].copy())
    if modes > 0:
        _, _, _, _, u, lam, rigid, enotes = _eigen(cut, modes, "free", None, drill, shells)
        if rigid != 6:
            out.notes.append(f"{rigid} free modes at zero frequency (six for one free structure)")
        el = slice(rigid, rigid + modes)
        phi = u[b, :3, el].reshape(nb3, -1)
        w2 = lam[el]
        g_res = g - (phi / w2) @ phi.T
        g_res = 0.5 * (g_res + g_res.T)
        low = np.linalg.eigvalsh(g_res)[0]
        if not low > 0:
            raise ValueError(
                f"the residual flexibility is not positive ({low:.3g}): the modes are not accurate "
                "enough; ask for fewer"
            )
        res = np.linalg.inv(g_res)
        out.modal, out.omega2, out.residual = phi, w2, 0.5 * (res + res.T)
    return out


def _schur_inverse(kr, live, bdofs, loads, n_total, indep):
    """(S_b, W): the supported inverse S = K⁻¹ at the cut DOFs ``bdofs``
    (the inverse of K's Schur complement on them) and S applied to the
    few columns ``loads``, on one factorisation. The interior is ordered
    for little fill (minimum degree on K_ii) and the cut DOFs last, so that
    the factor's trailing block is the Schur complement: L_bb U_bb."""
    n = kr.shape[0]
    keep = np.flatnonzero(live)
    pos = np.full(n, -1)
    pos[keep] = np.arange(len(keep))
    bl = pos[bdofs]
    inner = np.setdiff1d(np.arange(len(keep)), bl)
    k = kr[keep][:, keep].tocsc()
    dof_node = np.repeat(np.arange(n_total), 6)[indep.ravel()][keep]  # a mechanism is named by its nodes
    kii = k[inner][:, inner].tocsc()
    order = inner[_ordering(kii, dof_node[inner])]
    perm = np.concatenate([order, bl])
    kp = k[perm][:, perm].tocsc()
    lu = _factor(kp, dof_node[perm], "NATURAL")
    nb = len(bl)
    if not np.array_equal(lu.perm_c[-nb:], np.arange(len(perm) - nb, len(perm))):
        raise RuntimeError("the factorisation reordered the cut DOFs")  # (SuperLU's postorder keeps roots last)
    low = lu.L.tocsc()[-nb:, -nb:].toarray()
    up = lu.U.tocsc()[-nb:, -nb:].toarray()
    s_b = np.linalg.inv(low @ up)
    s_b = 0.5 * (s_b + s_b.T)
    rhs = loads[keep][perm]
    x = lu.solve(np.asarray(rhs))
    for _ in range(2):  # iterative refinement of the few columns
        x = x + lu.solve(np.asarray(rhs - kp @ x))
    w = np.zeros((n, loads.shape[1]))
    w[keep[perm]] = x
    # S_b in the order of bdofs: perm's last nb entries are bl, in bdofs' order
    return s_b, w


def _ordering(k, dof_node) -> np.ndarray:
    """A fill-reducing symmetric ordering of ``k`` (SuperLU's minimum degree on Kᵀ+K)."""
    return _factor(k, dof_node, "MMD_AT_PLUS_A").perm_c.argsort()
