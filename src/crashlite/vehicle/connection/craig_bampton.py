"""The replaced structure as a Craig–Bampton superelement: its dynamics, not only its statics.

The quasi-static condensation (``condense``) returns the force the replaced
structure gives back for a cut displacement as if the structure were in
equilibrium under its own rigid deceleration; its mass rides one rigid
body. In a crash the structure next to the cut is loaded before the mass
behind it has followed (the elastic twin's cut moves 3–8 mm against the
cell frame where the condensed rear's moves under 1 mm), and that is what
a rigid rear body cannot carry.

Craig–Bampton keeps the structure's dynamics with few DOFs (Craig and
Bampton 1968): the boundary DOFs u_b (the translations of the cut nodes
and of the nodes kept for output behind it) and the amplitudes q of the
N lowest modes of the structure with its boundary held. The interior
follows u_i = Ψ u_b + Φ q, Ψ = −K_ii⁻¹ K_ib the constraint modes (static
response to each boundary DOF, the rigid motions among them), Φ the held
modes (mass-normalised, Φᵀ M_ii Φ = I, Φᵀ K_ii Φ = Ω²). With T = [[I, 0],
[Ψ, Φ]] the reduced matrices are Tᵀ K T = diag(K_bb + K_bi Ψ, Ω²) and
Tᵀ M T (dense): the boundary carries the structure's whole mass and
inertia (exact for the rigid motions, which T spans) and the coupling of
each mode to it. Frequencies of the reduced model lie above the full
model's (a Rayleigh–Ritz projection) and below its highest: its stable
step is never shorter than the structure's own.

The static model is step 3's (``stiffness.build_static``: shells,
solids, beams and springs of the replaced structure, lumped translational
masses of ``relief.replaced_node_masses``); mass it cannot carry (on
nodes outside it) is not in the reduction (``cb_surrogate`` puts it on the
boundary). The cut nodes' rotations are
interior DOFs (shell edges hinge on the cut as on a line of the
structure).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.sparse.linalg import eigsh

from ..steps.cut import Cut
from ..steps.relief import mass_matrix, static_masses
from ..steps.statics import factor, reduced_columns
from ..steps.stiffness import build_static
from .condense import rigid_modes


@dataclass
class CraigBampton:
    """The replaced structure reduced on boundary translations and held modes (module docstring)."""

    nodes: np.ndarray  # (k,) boundary node indices (cut nodes first, then the kept ones)
    stiffness: np.ndarray  # (3k + N, 3k + N) Tᵀ K T: boundary translations (node-major x, y, z), then q
    mass: np.ndarray  # (3k + N, 3k + N) Tᵀ M T
    omega2: np.ndarray  # (N,) the held modes' ω² [1/time²]
    structure_mass: float  # what the static model carries
    cog: np.ndarray  # (3,) its centre of gravity
    cut_nodes: int = 0  # how many of ``nodes`` are cut nodes
    notes: list = field(default_factory=list)

    @property
    def frequencies(self) -> np.ndarray:
        return np.sqrt(self.omega2) / (2.0 * np.pi)

    def rigid_mass(self, xyz: np.ndarray) -> np.ndarray:
        """(6, 6) the reduced mass matrix against the six rigid motions about
        the CoG (``xyz`` the boundary nodes' coordinates): mass thrice and
        the inertia tensor, exactly the structure's."""
        r = np.zeros((len(self.mass), 6))
        r[: 3 * len(self.nodes)] = rigid_modes(xyz, self.cog).reshape(-1, 6)
        return r.T @ self.mass @ r

    def summary(self) -> dict:
        return {
            "boundary_nodes": int(len(self.nodes)),
            "cut_nodes": int(self.cut_nodes),
            "dofs": int(len(self.mass)),
            "modes": int(len(self.omega2)),
            "mode_frequencies": self.frequencies.tolist(),
            "mass": self.structure_mass,
            "cog": self.cog.tolist(),
            "notes": list(self.notes),
        }


def craig_bampton(
    cut: Cut, modes: int = 20, kept: np.ndarray | None = None, drill: float = 1e-3, shells: str = "static"
) -> CraigBampton:
    """Reduce the replaced structure of ``cut`` on the translations of its
    interface nodes and of ``kept`` (node indices behind the cut that the
    surrogate keeps for output), with its ``modes`` lowest held modes
    (module docstring); ``shells``: the shells' stiffness, "static" or
    "kernel" (``stiffness.build_static``)."""
    model = cut.model
    ls, _, notes = build_static(model, cut.replaced, drill, shells=shells)
    b = cut.interface_nodes
    if kept is not None and len(kept):
        b = np.concatenate([b, np.setdiff1d(np.asarray(kept, np.int64), b)])
    n_cut = len(cut.interface_nodes)
    ok = ls.in_structure[b] & ~ls.tied()[b]  # a tied node moves with its master: no DOFs of its own
    if not ok[:n_cut].any():
        raise ValueError("no cut node is a free node of the replaced structure")
    if not ok.all():
        notes.append(f"{int((~ok).sum())} boundary node(s) of rigid groups or outside the replaced structure left out")
    n_cut = int(ok[:n_cut].sum())
    b = b[ok]
    m, _, big_m, c, mnotes = static_masses(cut, ls)
    t, fixed, slave_of, rnotes = ls.reduction()
    k_all = (t.T @ ls.stiffness_matrix() @ t).tocsr()
    m_all = (t.T @ mass_matrix(ls, m) @ t).tocsr()
    col = reduced_columns(fixed, slave_of)
    bdofs = col[(6 * b[:, None] + np.arange(3)).ravel()]
    kd = k_all.diagonal()
    live = kd > 1e-12 * float(np.abs(kd).max())
    if np.any(bdofs < 0) or not live[bdofs].all():
        raise ValueError("a boundary node's translation is held or has no stiffness")
    is_b = np.zeros(k_all.shape[0], bool)
    is_b[bdofs] = True
    idofs = np.flatnonzero(live & ~is_b)
    dof_node = np.repeat(np.arange(ls.n_total), 6)[np.flatnonzero(col >= 0)]  # a mechanism is named by its nodes
    kii = k_all[idofs][:, idofs].tocsc()
    kib = k_all[idofs][:, bdofs]
    mii = m_all[idofs][:, idofs].tocsc()
    mib = m_all[idofs][:, bdofs]
    lu = factor(kii, dof_node[idofs])
    kib_d = np.asarray(kib.toarray())
    psi = -lu.solve(kib_d)
    psi += lu.solve(-kib_d - kii @ psi)  # one step of iterative refinement
    kbb = k_all[bdofs][:, bdofs].toarray() + kib.T @ psi
    mpsi = mii @ psi
    mbb = m_all[bdofs][:, bdofs].toarray() + mib.T @ psi + psi.T @ (mib.toarray() + mpsi)
    if modes > 0:
        lam, phi = eigsh(kii, k=modes, M=mii, sigma=0.0, which="LM", v0=np.ones(len(idofs)))
        order = np.argsort(lam)
        lam, phi = lam[order], phi[:, order]
        phi /= np.sqrt(np.einsum("ik,ik->k", phi, mii @ phi))  # M-normalised (eigsh's already are, to round-off)
        mbq = mib.T @ phi + mpsi.T @ phi
    else:
        lam, mbq = np.zeros(0), np.zeros((len(bdofs), 0))
    nb, nq = len(bdofs), len(lam)
    kr = np.zeros((nb + nq, nb + nq))
    kr[:nb, :nb] = 0.5 * (kbb + kbb.T)
    kr[nb:, nb:] = np.diag(lam)
    mr = np.zeros_like(kr)
    mr[:nb, :nb] = 0.5 * (mbb + mbb.T)
    mr[:nb, nb:], mr[nb:, :nb], mr[nb:, nb:] = mbq, mbq.T, np.eye(nq)
    out = CraigBampton(b, kr, mr, lam, big_m, c, n_cut, list(cut.notes) + notes + mnotes + rnotes)
    rm = out.rigid_mass(model.nodes.xyz[b])
    if abs(rm[0, 0] - big_m) > 1e-6 * big_m:
        out.notes.append(f"the reduced mass moves {rm[0, 0]:.6g} rigidly, the structure weighs {big_m:.6g}")
    return out
