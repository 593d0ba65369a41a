"""Rigid walls in the time loop: nodes (kernels.rigidwall) and rigid bodies.

Free nodes are corrected kinematically node by node. A node of a rigid
body cannot be: its velocity is the body's. For such nodes the wall gives
the body impulses at the contact points, each the one that makes the
point's normal velocity land it on the wall, found by a few projected
Gauss–Seidel passes over the points (impulses only push). A moving wall
takes the opposite impulses, so momentum is conserved.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .kernels.rigid import out_of_reach
from .kernels.rigidwall import N_CHUNKS, cylinder_wall, planar_wall
from .rigid import RigidBody, cross
from .state import State


class Walls:
    """The walls of a Setup with their moving state."""

    def __init__(self, walls, bodies, n_nodes: int):
        self.walls = walls
        self.point = [w.point.copy() for w in walls]
        self.hit = [np.zeros(len(w.nodes), np.bool_) for w in walls]
        self._part = np.zeros((N_CHUNKS, 2))  # planar_wall's per-chunk sums
        # velocities before the velocity update (the time loop's kick fills it): the energy a wall takes is
        # the work of its impulses over the step (kernels.rigidwall); no rows without walls
        self.before = np.zeros((n_nodes if walls else 0, 3))
        self.velocity = np.array([w.velocity for w in walls], float)  # along the normal
        self.force = np.zeros((len(walls), 4))  # force on each wall (3) and the energy it took over the step
        owner = np.full(n_nodes, -1)
        for k, b in enumerate(bodies):
            owner[b.nodes] = k
        self.bodies = bodies
        # per wall: (body, its node indices) for the rigid-body nodes it acts on
        self.body_nodes = []
        for w in walls:
            by_body = {}
            for i in w.watch:
                by_body.setdefault(int(owner[i]), []).append(int(i))
            self.body_nodes.append([(bodies[k], np.array(v, np.int64)) for k, v in by_body.items()])

    def kinetic(self) -> float:
        return sum(0.5 * w.mass * self.velocity[k] ** 2 for k, w in enumerate(self.walls))

    def move(self, dt: float) -> None:
        for k, w in enumerate(self.walls):
            if self.velocity[k] != 0.0:  # a wall at rest stays (two array temporaries a wall a cycle saved)
                self.point[k] += dt * self.velocity[k] * w.normal

    def apply(self, st: State, t: float, dt: float, place: Callable[[RigidBody], None]) -> float:
        """Correct the velocities for the next step ``dt``; returns the
        energy the walls took out of the model over the step (the work of
        their impulses, kernels.rigidwall, and what the rigid bodies lost)."""
        ew = 0.0
        self.force[:] = 0.0
        for k, w in enumerate(self.walls):
            if not (w.birth <= t <= w.death):
                continue
            if w.radius > 0:
                cylinder_wall(
                    st.x,
                    st.v,
                    self.before,
                    st.mass,
                    w.nodes,
                    self.point[k],
                    w.normal,
                    w.radius,
                    w.length,
                    w.fric,
                    dt,
                    self.force[k],
                )
            else:
                self.velocity[k] = planar_wall(
                    st.x,
                    st.v,
                    self.before,
                    st.mass,
                    w.nodes,
                    self.point[k],
                    w.normal,
                    self.velocity[k],
                    w.mass,
                    w.fric,
                    dt,
                    self.force[k],
                    self.hit[k],
                    w.edge_l,
                    w.edge_m,
                    w.len_l,
                    w.len_m,
                    self._part,
                )
            ew += float(self.force[k, 3])
            v_nodes = float(self.velocity[k])
            for body, nodes in self.body_nodes[k]:
                taken = self._push_body(k, body, nodes, st.x, dt)
                if taken is not None:  # the body was pushed: its nodes follow
                    ew += taken
                    place(body)
            if w.mass > 0:
                ew += 0.5 * w.mass * (v_nodes**2 - float(self.velocity[k]) ** 2)
        return ew

    def _gaps(self, k, x, nodes, dt):
        """Gap now (≥ 0 allowed) and outward normals of the nodes, with a
        mask of those over the wall (finite walls, cylinder length)."""
        w = self.walls[k]
        rel = x[nodes] - self.point[k]
        if w.radius > 0:
            h = rel @ w.normal
            radial = rel - np.outer(h, w.normal)
            dist = np.linalg.norm(radial, axis=1)
            over = ((w.length == 0) | ((h >= 0) & (h <= w.length))) & (dist > 0)
            normals = radial / np.where(dist > 0, dist, 1.0)[:, None]
            return dist - w.radius, normals, over
        gap = rel @ w.normal
        over = np.ones(len(nodes), bool)
        if w.len_l > 0:
            pl, pm = rel @ w.edge_l, rel @ w.edge_m
            over = (pl >= 0) & (pl <= w.len_l) & (pm >= 0) & (pm <= w.len_m)
        return gap, np.tile(w.normal, (len(nodes), 1)), over

    def _push_body(self, k, body, nodes, x, dt, passes: int = 20) -> float | None:
        """Impulses on ``body`` at its ``nodes`` against wall k over the next
        step; returns the kinetic energy taken (body and wall together), or
        None when no node of the body reaches the wall (nothing changed)."""
        w = self.walls[k]
        moving = w.mass > 0 and w.radius == 0
        wall_v = self.velocity[k] if w.radius == 0 else 0.0
        if w.radius == 0 and out_of_reach(  # no node can land on the plane over the step
            x,
            nodes,
            body.cog,
            self.point[k],
            w.normal,
            body.velocity,
            body.momentum,
            body.spin_per_momentum(),
            wall_v,
            dt,
        ):
            return None
        omega = body.omega()
        arm = x[nodes] - body.cog
        gap, normals, over = self._gaps(k, x, nodes, dt)
        # velocity each point must not fall below along its normal: it lands on the wall
        target = wall_v * (normals @ w.normal) - gap / dt if w.radius == 0 else -gap / dt
        vel_n = body.velocity @ normals.T + np.einsum("ij,ij->i", cross(omega, arm), normals)
        active = over & (vel_n < target)
        if not active.any():
            return None
        rot = body.rot
        inv_i = rot @ body.inverse_inertia_body() @ rot.T  # world-frame inverse inertia
        ke0 = body.kinetic_now()
        rxn = cross(arm, normals)
        eff = 1.0 / body.mass + np.einsum("ij,jk,ik->i", rxn, inv_i, rxn)
        if moving:
            eff = eff + 1.0 / w.mass
        total = np.zeros(len(nodes))
        for _ in range(passes):
            largest = 0.0
            for i in np.flatnonzero(active):
                omega = inv_i @ body.momentum
                vn = normals[i] @ (body.velocity + cross(omega, arm[i]))
                tgt = (self.velocity[k] - gap[i] / dt) if moving else target[i]
                dj = max((tgt - vn) / eff[i], -total[i])  # accumulated impulse stays ≥ 0
                total[i] += dj
                body.velocity += dj * normals[i] / body.mass
                body.momentum += dj * rxn[i]
                if moving:
                    self.velocity[k] -= dj / w.mass
                largest = max(largest, abs(dj))
            if largest <= 1e-12 * max(total.max(), 1e-300):
                break
        self.force[k, :3] -= (total[:, None] * normals).sum(axis=0) / dt  # the body pushes the wall
        return ke0 - body.kinetic_now()  # the moving wall's own change is booked by apply()
