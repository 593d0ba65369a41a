"""Nodal rigid bodies (*CONSTRAINED_NODAL_RIGID_BODY): the nodes of a set move
as one body with the mass, centre of gravity and inertia of their lumped
masses (or those given with _INERTIA).

Translation follows the summed nodal forces; rotation integrates the angular
momentum L (world frame) with the applied moment, and turns the body by the
angular velocity ω = R I⁻¹ Rᵀ L taken at mid-rotation (two fixed-point
passes), so a torque-free body keeps L exactly and its energy with
second-order accuracy. Node positions are then rebuilt from the body
position and orientation, so the body stays rigid to round-off.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .kernels.rigid import body_drift, body_kick, body_omega, place_body, rodrigues

_NO_ROT = np.zeros((0, 3, 3))  # stands in for the nodal orientations where the nodes have none
_NO_W = np.zeros((0, 3))


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a × b along the last axis of (..., 3) arrays: np.cross without its
    axis handling, which costs tens of µs on the few points of a body."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=-1)


def rotation(phi: np.ndarray) -> np.ndarray:
    """Rotation matrix of the rotation vector ``phi`` (Rodrigues)."""
    out = np.empty((3, 3))
    rodrigues(float(phi[0]), float(phi[1]), float(phi[2]), out)
    return out


@dataclass
class RigidBody:
    body_id: int
    nodes: np.ndarray  # (k,) int64 member node indices
    mass: float
    cog: np.ndarray  # (3,) position of the centre of gravity
    inertia_body: np.ndarray  # (3, 3) inertia about the CoG in the body frame (= global at t = 0)
    r_body: np.ndarray  # (k, 3) node positions relative to the CoG, body frame
    velocity: np.ndarray  # (3,) CoG velocity (half step)
    momentum: np.ndarray  # (3,) angular momentum about the CoG, world frame (half step)
    rot: np.ndarray  # (3, 3) body-to-world rotation
    held_v: np.ndarray | None = None  # (3, 3) rows: held translation directions, zero rows free (MAT_RIGID)
    held_w: np.ndarray | None = None  # (3, 3) rows: held rotation axes, zero rows free
    prev: tuple | None = None  # (velocity, momentum) before the last kick
    # (j, 3) unit axes (body frame) about which the nodes' masses give no inertia (a point mass: all
    # three, masses on a line: that line); a tiny inertia stands in for it (see build_body)
    no_inertia: np.ndarray | None = None

    def __post_init__(self):
        self.rot = np.array(self.rot, dtype=float)  # its own C-ordered copy: the drift kernel turns it in place
        self._sums, self._omega, self._drift = np.zeros(6), np.zeros(3), np.zeros((3, 3, 3))  # kernels' scratch

    def inverse_mass_at(self, r: np.ndarray) -> np.ndarray:
        """(k,) largest inverse effective mass of points at arms r (k, 3)
        (body frame) for a force in any direction: 1/M + λmax(Sᵀ I⁻¹ S)
        with S the cross-product matrix of r [1/mass]."""
        r = np.atleast_2d(np.asarray(r, float))
        z = np.zeros(len(r))
        skew = np.stack(
            [
                np.stack([z, -r[:, 2], r[:, 1]], 1),
                np.stack([r[:, 2], z, -r[:, 0]], 1),
                np.stack([-r[:, 1], r[:, 0], z], 1),
            ],
            1,
        )
        a = np.einsum("kji,jl,klm->kim", skew, np.linalg.inv(self.inertia_body), skew)
        return 1.0 / self.mass + np.linalg.eigvalsh(a)[:, -1]

    def _inverse(self) -> tuple:
        """(inertia_body, its inverse, the inverse's largest eigenvalue),
        formed once per inertia."""
        cached = getattr(self, "_inv", None)
        if cached is None or cached[0] is not self.inertia_body:
            inv = np.linalg.inv(self.inertia_body)
            cached = self._inv = (self.inertia_body, inv, float(np.abs(np.linalg.eigvalsh(inv)).max()))
        return cached

    def inverse_inertia_body(self) -> np.ndarray:
        """(3, 3) inverse of ``inertia_body``."""
        return self._inverse()[1]

    def spin_per_momentum(self) -> float:
        """λmax(I⁻¹): |ω| ≤ it·|L| whatever the body's orientation."""
        return self._inverse()[2]

    def spin_bound(self) -> float:
        """An upper bound of |ω| without forming ω: |R I⁻¹ Rᵀ L| ≤ λmax(I⁻¹)·|L|."""
        m = self.momentum
        return self.spin_per_momentum() * float(np.sqrt(m @ m))

    def omega(self, rot: np.ndarray | None = None, mom: np.ndarray | None = None) -> np.ndarray:
        """(3,) angular velocity R I⁻¹ Rᵀ L (at ``rot`` and ``mom`` if given)."""
        out = np.empty(3)
        body_omega(
            self.rot if rot is None else rot, self.inverse_inertia_body(), self.momentum if mom is None else mom, out
        )
        return out

    def kinetic(self) -> float:
        """Kinetic energy at the full step: the mean of the half-step momenta
        around it (as for the nodes)."""
        vel, mom = self.velocity, self.momentum
        if self.prev is not None:
            vel, mom = 0.5 * (vel + self.prev[0]), 0.5 * (mom + self.prev[1])
        w = self.omega(mom=mom)
        return 0.5 * self.mass * float(vel @ vel) + 0.5 * float(w @ mom)

    def kinetic_now(self) -> float:
        """Kinetic energy of the current (half-step) momenta."""
        w = self.omega()
        return 0.5 * self.mass * float(self.velocity @ self.velocity) + 0.5 * float(w @ self.momentum)

    def kick(self, f: np.ndarray, x: np.ndarray, dt_v: float, moment: np.ndarray | None = None) -> None:
        """Change momenta by the nodal forces (and moments) over dt_v."""
        if self.prev is None:
            self.prev = (np.zeros(3), np.zeros(3))  # filled by every kick from now on
        p_vel, p_mom = self.prev
        use_moment = moment is not None
        body_kick(
            f, x, moment if use_moment else f, self.nodes, self.cog, use_moment, self.mass, dt_v,
            self.velocity, self.momentum, p_vel, p_mom, self._sums,
        )  # fmt: skip
        if self.held_v is not None or self.held_w is not None:
            self.constrain()

    def constrain(self) -> None:
        """Zero the velocity along held directions and the angular velocity
        about held axes; the reaction torque acts about the held axes only,
        so the momentum about the free ones is kept."""
        if self.held_v is not None:
            self.velocity -= self.held_v.T @ (self.held_v @ self.velocity)
        if self.held_w is None or not self.held_w.any():
            return
        held = self.held_w[np.any(self.held_w != 0, axis=1)]
        if len(held) >= 3:
            self.momentum[:] = 0.0
            return
        # free axes: the orthonormal complement of the held ones
        q = np.linalg.qr(np.vstack([held, np.eye(3)]).T)[0].T
        free = q[len(held) : 3]
        inertia = self.rot @ self.inertia_body @ self.rot.T
        a = np.linalg.solve(free @ inertia @ free.T, free @ self.momentum)
        self.momentum[:] = inertia @ (free.T @ a)

    def drift(self, dt: float) -> None:
        """Move and turn the body over dt (kernels.rigid.body_drift: ω at
        mid-rotation)."""
        body_drift(self.cog, self.velocity, self.momentum, self.rot, self.inverse_inertia_body(), dt, self._drift)

    def place(self, x: np.ndarray, v: np.ndarray, rot: np.ndarray | None = None, w: np.ndarray | None = None) -> None:
        """Write member node positions and velocities (and, for nodes with
        rotations, their orientation and angular velocity) from the body."""
        turns = rot is not None
        place_body(
            x, v, rot if turns else _NO_ROT, w if turns else _NO_W, self.nodes, self.r_body, self.cog, self.rot,
            self.velocity, self.inverse_inertia_body(), self.momentum, turns, self._omega,
        )  # fmt: skip


def build_body(
    body_id: int,
    nodes: np.ndarray,
    x: np.ndarray,
    v: np.ndarray,
    mass: np.ndarray,
    given: dict | None = None,
    node_inertia: np.ndarray | None = None,
    node_rot: np.ndarray | None = None,
) -> RigidBody:
    """A body from its nodes' lumped masses (plus the inertia tensors of
    *ELEMENT_INERTIA on them, ``node_inertia`` (n, 3, 3) global, and the
    isotropic rotary inertia of shell and beam nodes, ``node_rot`` (n,):
    the body takes their moments, so it carries their inertia too; a row
    of shell nodes then turns about its own line with the inertia the
    shells' step was sized for), or from _INERTIA values (``given``: tm,
    cog (3,), inertia (3, 3) global, v, w)."""
    m = mass[nodes]
    if given and given.get("tm", 0.0) > 0:
        total, cog, inertia = given["tm"], np.asarray(given["cog"], float), np.asarray(given["inertia"], float)
    else:
        total = float(m.sum())
        if total <= 0:
            raise ValueError(f"nodal rigid body {body_id}: its nodes have no mass")
        cog = (m[:, None] * x[nodes]).sum(axis=0) / total
        r = x[nodes] - cog
        inertia = np.einsum("k,kij->ij", m, (r * r).sum(1)[:, None, None] * np.eye(3) - r[:, :, None] * r[:, None, :])
        if node_inertia is not None:
            inertia = inertia + node_inertia[nodes].sum(axis=0)
        if node_rot is not None:
            inertia = inertia + np.eye(3) * float(node_rot[nodes].sum())
    no_inertia = None
    if np.linalg.matrix_rank(inertia) < 3:
        # collinear nodes (no inertia about their line) or a point mass (none
        # at all): a tiny inertia keeps the rotation defined; nodes with
        # elements off those axes would get a zero time step (setup refuses them)
        lam, vec = np.linalg.eigh(inertia)
        no_inertia = vec[:, lam <= 1e-12 * max(float(lam[-1]), 0.0)].T.copy()
        inertia = inertia + np.eye(3) * max(np.trace(inertia), 1e-30) * 1e-9
    r = x[nodes] - cog
    if given and given.get("tm", 0.0) > 0 and (np.any(given.get("v", 0)) or np.any(given.get("w", 0))):
        vel, w = np.asarray(given["v"], float), np.asarray(given["w"], float)
    else:  # from the nodes' initial velocities (least squares for ω)
        wt = m if m.sum() > 0 else np.ones(len(nodes))  # massless nodes (element mass): equal weights
        vel = (wt[:, None] * v[nodes]).sum(axis=0) / wt.sum()
        ang = np.cross(r, wt[:, None] * (v[nodes] - vel)).sum(axis=0)
        i_nodes = np.einsum("k,kij->ij", wt, (r * r).sum(1)[:, None, None] * np.eye(3) - r[:, :, None] * r[:, None, :])
        w = np.linalg.lstsq(i_nodes, ang, rcond=None)[0]
    return RigidBody(
        body_id,
        nodes.astype(np.int64),
        float(total),
        cog.copy(),
        inertia.copy(),
        r.copy(),
        vel.copy(),
        inertia @ w,
        np.eye(3),
        no_inertia=no_inertia,
    )
