"""The explicit time loop (central difference) and ``run``.

The loop owns no I/O: states are recorded by a callback every
``output_dt``; progress is another callback.
"""

from __future__ import annotations

import time as _time
from pathlib import Path
from typing import Callable

import numpy as np

from ..model.model import Model
from .kernels.discrete import discrete_forces, energy_step, gather, incidence
from .kernels.beam import beam_forces, energy_step6, gather_ends, update_rotations
from .kernels.integrate import update_position, update_velocity
from .kernels.rigidwall import cylinder_wall, planar_wall
from .results import Results
from .sections import section_forces
from .setup import Setup, build
from .timestep import scale_masses, stable_dt


class _Recorder:
    """Collects the states written to Results."""

    def __init__(self, s: Setup):
        self.s = s
        self.rows: dict[str, list] = {k: [] for k in ("time", "kinetic", "internal", "wall", "external", "force",
                                                      "elong", "wall_force", "wall_velocity", "disp", "vel",
                                                      "spc", "part_ie", "sec")}
        self.section_force = np.zeros((len(s.sections), 3))
        # nodes with a constrained DOF: their reactions are written (spcforc)
        self.spc_nodes = np.flatnonzero(s.fixed.any(axis=1))
        self.spc_force = np.zeros((len(self.spc_nodes), 3))

    def __call__(self, t, x, v_mid, ke, ie, ew, work, force, elong, wall_force, wall_v, part_ie):
        r = self.rows
        h = self.s.history_nodes
        r["time"].append(t)
        r["kinetic"].append(ke)
        r["internal"].append(ie)
        r["wall"].append(ew)
        r["external"].append(work)
        r["force"].append(force.copy())
        r["elong"].append(elong.copy())
        r["wall_force"].append(wall_force.copy())
        r["wall_velocity"].append(wall_v.copy())
        r["disp"].append(x[h] - self.s.x0[h])
        r["spc"].append(self.spc_force.copy())
        r["part_ie"].append(part_ie)
        r["sec"].append(self.section_force.copy())
        r["vel"].append(v_mid[h].copy())


def integrate(s: Setup, output_dt: float | None = None,
              progress: Callable[[float, int, float, float], None] | None = None,
              ) -> Results:
    """Run the time loop on a Setup; states every ``output_dt`` (default:
    1/200 of the end time) and at the end."""
    t_start = _time.perf_counter()
    added_mass = scale_masses(s, s.discrete_pid if len(s.discrete_pid) == len(s.discrete.ids) else None)
    d = s.discrete
    n, ne, nw = len(s.mass), len(d.ids), len(s.walls)
    x = s.x0.copy()
    v = s.v0.copy()
    v[s.fixed] = 0.0
    inv_mass = np.where(s.mass > 0, 1.0 / np.where(s.mass > 0, s.mass, 1.0), 0.0)
    f = np.zeros((n, 3))
    fe = np.zeros((ne, 3))
    force, elong = np.zeros(ne), np.zeros(ne)
    force_old, elong_old = np.zeros(ne), np.zeros(ne)  # previous state, for the work
    plastic = np.zeros(ne)  # S08 plastic deflection
    wall_force = np.zeros((nw, 4))  # force on each wall (3) and the energy it took this step
    output_dt = output_dt or s.end_time / 200.0
    rec = _Recorder(s)

    node_ptr, elem_of, sign_of = incidence(n, d.n1, d.n2)
    # beams: rotations, moments and the node -> element-end incidence
    bm = s.beams
    nb = len(bm.ids) if bm is not None else 0
    rot = np.tile(np.eye(3), (n, 1, 1))
    w = s.w0.copy() if s.w0 is not None else np.zeros((n, 3))
    rot_inertia = s.rot_inertia if s.rot_inertia is not None else np.zeros(n)
    fixed_rot = s.fixed_rot if s.fixed_rot is not None else np.zeros((n, 3), bool)
    inv_j = np.where(rot_inertia > 0, 1.0 / np.where(rot_inertia > 0, rot_inertia, 1.0), 0.0)
    w[inv_j == 0] = 0.0
    w[fixed_rot] = 0.0
    moment = np.zeros((n, 3))
    bfe, bme = np.zeros((nb, 2, 3)), np.zeros((nb, 2, 3))
    gf, gd, gf_old, gd_old = (np.zeros((nb, 6)) for _ in range(4))
    disc_energy, beam_energy = np.zeros(ne), np.zeros(nb)  # per element, for matsum
    # part of each element (0 where a hand-built Setup gives none)
    dpid = s.discrete_pid if len(s.discrete_pid) == ne else np.zeros(ne, np.int64)
    bpid = s.beam_pid if len(s.beam_pid) == nb else np.zeros(nb, np.int64)
    part_ids = np.unique(np.concatenate([dpid, bpid]))
    disc_part = np.searchsorted(part_ids, dpid)
    beam_part = np.searchsorted(part_ids, bpid)

    def part_energy():
        return (np.bincount(disc_part, disc_energy, len(part_ids))
                + np.bincount(beam_part, beam_energy, len(part_ids)))
    if nb:
        corner_nodes = np.stack([bm.n1, bm.n2], axis=1).ravel()
        order = np.argsort(corner_nodes, kind="stable")
        corner_of = order.astype(np.int64)
        corner_ptr = np.zeros(n + 1, np.int64)
        np.add.at(corner_ptr, corner_nodes + 1, 1)
        corner_ptr = np.cumsum(corner_ptr)

    def internal_forces(v_for_rate, t):
        """f: the force the elements (and body loads) exert on the nodes."""
        if ne:
            discrete_forces(x, v_for_rate, d.n1, d.n2, d.kind, d.k, d.scale, d.offset, d.length0,
                            d.direction, d.curve_start, d.curve_stop, d.curve_x, d.curve_y, d.ground,
                            d.ctf, plastic, fe, force, elong)
        gather(node_ptr, elem_of, sign_of, fe, f)
        if nb:
            beam_forces(x, rot, bm.n1, bm.n2, bm.q1, bm.q2, bm.length0, bm.ea, bm.gj, bm.ei2, bm.ei3,
                        bfe, bme, gf, gd)
            gather_ends(corner_ptr, corner_of, bfe, f)
            moment[:] = 0.0
            gather_ends(corner_ptr, corner_of, bme, moment)
        for axis, curve, sf in s.body_loads:  # base acceleration a: inertial load -m a
            f[:] -= np.outer(s.mass * sf * np.interp(t, *curve), axis)

    walls = [(w, w.point.copy(), np.zeros(len(w.nodes), np.bool_)) for w in s.walls]
    wall_v = np.array([w.velocity for w in s.walls])

    x_prev = np.zeros_like(x)
    f_body_prev = np.zeros_like(x)

    def body_force(t):
        out = np.zeros_like(x)
        for axis, curve, sf in s.body_loads:
            out -= np.outer(s.mass * sf * np.interp(t, *curve), axis)
        return out

    free_mass = s.mass.copy()
    rot_free = rot_inertia.copy()
    for b in s.bodies:
        free_mass[b.nodes] = 0.0  # counted through the body
        rot_free[b.nodes] = 0.0

    w_prev = w.copy()

    def kinetic(v_mid, w_mid=None):
        ke = 0.5 * float(np.einsum("i,ij,ij->", free_mass, v_mid, v_mid))
        if nb:
            wm = w if w_mid is None else w_mid
            ke += 0.5 * float(np.einsum("i,ij,ij->", rot_free, wm, wm))
        ke += sum(b.kinetic() for b in s.bodies)
        return ke + sum(0.5 * w.mass * wall_v[k] ** 2 for k, w in enumerate(s.walls))

    def kick_bodies(dt_v):
        for b in s.bodies:
            b.kick(f, x, dt_v, moment if nb else None)
            b.place(x, v, rot if nb else None, w if nb else None)

    def drift_bodies(dt):
        for b in s.bodies:
            b.drift(dt)
            b.place(x, v, rot if nb else None, w if nb else None)

    def apply_walls(t, dt):
        """Wall corrections; returns the kinetic energy they took out."""
        ew = 0.0
        wall_force[:] = 0.0
        for k, (w, point, hit) in enumerate(walls):
            if not (w.birth <= t <= w.death):
                continue
            if len(w.watch):
                rel = x[w.watch] - point
                if w.radius > 0:  # distance outside the cylinder surface
                    h = rel @ w.normal
                    inside = (h >= 0) & ((w.length == 0) | (h <= w.length))
                    radial = np.linalg.norm(rel - np.outer(h, w.normal), axis=1) - w.radius
                    gap = np.where(inside, radial, np.inf)
                else:
                    gap = rel @ w.normal
                if gap.min() < 0:
                    raise FloatingPointError(
                        f"a rigid-body node (index {int(w.watch[np.argmin(gap)])}) reached rigid wall "
                        f"{w.wall_id} at t = {t:.6g}: walls acting on rigid bodies are not supported yet")
            v_old = wall_v[k]
            if w.radius > 0:
                cylinder_wall(x, v, s.mass, w.nodes, point, w.normal, w.radius, w.length, w.fric, dt,
                              wall_force[k])
            else:
                wall_v[k] = planar_wall(x, v, s.mass, w.nodes, point, w.normal, v_old, w.mass, w.fric, dt,
                                        wall_force[k], hit, w.edge_l, w.edge_m, w.len_l, w.len_m)
            ew += wall_force[k, 3]  # kinetic energy the kernel took from the nodes
            ew += 0.5 * w.mass * (v_old**2 - wall_v[k] ** 2)
        return ew

    def impose_motions(t, dt_v, dt):
        """Prescribed velocities for the half step t .. t + dt (dt_v: time
        since the previous half step); returns the kinetic energy they put in
        (the work of the prescribed motion)."""
        work = 0.0
        for mo in s.motions:
            if not (mo.birth <= t <= mo.death):
                continue
            if mo.body_pid:
                work += impose_body_motion(mo, t, dt_v, dt)
                continue
            vn = v[mo.nodes] @ mo.direction
            if mo.vad == 0:
                target = mo.scale * np.interp(t + 0.5 * dt, *mo.curve)
            elif mo.vad == 1:
                # replace the acceleration of the forces by the prescribed one
                vn_before = vn - dt_v * (f[mo.nodes] @ mo.direction) * inv_mass[mo.nodes]
                target = vn_before + dt_v * mo.scale * np.interp(t, *mo.curve)
            else:
                u = (x[mo.nodes] - s.x0[mo.nodes]) @ mo.direction
                target = (mo.scale * np.interp(t + dt, *mo.curve) - u) / dt
            before = 0.5 * float(np.sum(s.mass[mo.nodes] * np.einsum("ij,ij->i", v[mo.nodes], v[mo.nodes])))
            v[mo.nodes] += np.outer(target - vn, mo.direction)
            after = 0.5 * float(np.sum(s.mass[mo.nodes] * np.einsum("ij,ij->i", v[mo.nodes], v[mo.nodes])))
            work += after - before
        return work

    bodies_by_id = {b.body_id: b for b in s.bodies}
    cog0 = {b.body_id: b.cog.copy() for b in s.bodies}

    def impose_body_motion(mo, t, dt_v, dt):
        """Prescribed motion of a rigid part: its CoG velocity along the
        direction is set (the force along it is taken by the prescription)."""
        b = bodies_by_id[mo.body_pid]
        vn = float(b.velocity @ mo.direction)
        if mo.vad == 0:
            target = mo.scale * np.interp(t + 0.5 * dt, *mo.curve)
        elif mo.vad == 1:
            force = float(f[b.nodes].sum(axis=0) @ mo.direction)
            target = vn - dt_v * force / b.mass + dt_v * mo.scale * np.interp(t, *mo.curve)
        else:
            u = float((b.cog - cog0[b.body_id]) @ mo.direction)
            target = (mo.scale * np.interp(t + dt, *mo.curve) - u) / dt
        before = 0.5 * b.mass * float(b.velocity @ b.velocity)
        b.velocity += (target - vn) * mo.direction
        b.place(x, v, rot if nb else None, w if nb else None)
        return 0.5 * b.mass * float(b.velocity @ b.velocity) - before

    def move_walls(dt):
        for k, (w, point, _) in enumerate(walls):
            point += dt * wall_v[k] * w.normal

    dt_stable = stable_dt(s)

    def step_size(t):
        if s.dt_max is None:
            return dt_stable
        return min(dt_stable, float(np.interp(t, *s.dt_max)))

    # t = 0: forces, half-step velocity
    internal_forces(v, 0.0)
    force_old[:] = force
    elong_old[:] = elong
    gf_old[:] = gf
    gd_old[:] = gd
    ie = 0.0
    ew_total = 0.0
    dt = step_size(0.0)
    dt_first = dt
    t = 0.0
    v_prev = v.copy()
    rec.spc_force[:] = np.where(s.fixed[rec.spc_nodes], -f[rec.spc_nodes], 0.0)
    rec.section_force[:] = section_forces(s.sections, fe, bfe)
    rec(t, x, v, kinetic(v), ie, ew_total, 0.0, force, elong, wall_force[:, :3], wall_v, part_energy())
    update_velocity(v, f, inv_mass, s.fixed, 0.5 * dt)
    if nb:
        update_rotations(rot, w, moment, inv_j, fixed_rot, 0.5 * dt, 0.0)
    kick_bodies(0.5 * dt)
    w_ext = impose_motions(0.0, 0.5 * dt, dt)
    dw = 0.0
    ew_total += apply_walls(t, dt)
    next_out = output_dt
    states_t, states_x = [0.0], [x.copy()]  # field states at the d3plot interval
    next_state = s.state_dt if s.state_dt > 0 else np.inf
    cycle = 0
    stopped = None
    try:
        while t < s.end_time and (not s.end_cycle or cycle < s.end_cycle):
            dt_step = dt  # full steps; the run ends at the first state past ENDTIM
            if s.body_loads:
                x_prev[:] = x
                f_body_prev[:] = body_force(t + 0.5 * dt_step)
            update_position(x, v, dt_step)
            if nb:
                update_rotations(rot, w, moment, inv_j, fixed_rot, 0.0, dt_step)
            drift_bodies(dt_step)
            move_walls(dt_step)
            t += dt_step
            cycle += 1
            internal_forces(v, t)
            energy_step(force_old, force, elong_old, elong, disc_energy)
            if nb:
                energy_step6(gf_old, gf, gd_old, gd, beam_energy)
            dt_new = step_size(t)
            if s.dt_min > 0 and dt_new < s.dt_min * dt_first:
                raise FloatingPointError(f"time step {dt_new:.4g} at t = {t:.6g} (cycle {cycle}) fell below "
                                         f"DTMIN x first step = {s.dt_min * dt_first:.4g}: the run is stopped")
            output = t >= next_out * (1 - 1e-9) or t >= s.end_time
            if t >= next_state * (1 - 1e-9) or (t >= s.end_time and np.isfinite(next_state)):
                states_t.append(t)
                states_x.append(x.copy())
                next_state += s.state_dt
            if output:  # the state at t needs the velocity on both sides of it
                v_prev[:] = v
                w_prev[:] = w
                # reaction of the supports: minus the force on the held DOFs
                sn = rec.spc_nodes
                rec.spc_force[:] = np.where(s.fixed[sn], -f[sn], 0.0)
                rec.section_force[:] = section_forces(s.sections, fe, bfe)
            if s.body_loads:  # work of the body loads over the last step (positions t-dt .. t)
                w_ext += float(np.einsum("ij,ij->", f_body_prev, x - x_prev))
            update_velocity(v, f, inv_mass, s.fixed, 0.5 * (dt_step + dt_new))
            if nb:
                update_rotations(rot, w, moment, inv_j, fixed_rot, 0.5 * (dt_step + dt_new), 0.0)
            kick_bodies(0.5 * (dt_step + dt_new))
            dw = impose_motions(t, 0.5 * (dt_step + dt_new), dt_new)
            w_ext += dw
            ew_total += apply_walls(t, dt_new)
            dt = dt_new
            if output:
                ie = float(disc_energy.sum() + beam_energy.sum())
                if not np.all(np.isfinite(v)):
                    bad = int(np.argwhere(~np.isfinite(v))[0, 0])
                    raise FloatingPointError(f"non-finite velocity at node index {bad}, t = {t:.6g} "
                                             f"(cycle {cycle}): the run diverged")
                v_mid = 0.5 * (v_prev + v)
                w_mid = 0.5 * (w_prev + w)
                # the last work increment belongs to the half step after t: count half of it
                rec(t, x, v_mid, kinetic(v_mid, w_mid), ie, ew_total, w_ext - 0.5 * dw, force, elong,
                    wall_force[:, :3], wall_v, part_energy())
                next_out += output_dt
                supplied = rec.rows["kinetic"][0] + rec.rows["internal"][0] + w_ext - 0.5 * dw
                ratio = (kinetic(v_mid, w_mid) + ie + ew_total) / max(supplied, 1e-300)
                if progress is not None:
                    progress(t, cycle, dt, ratio)
                if s.end_energy > 0 and abs(ratio - 1.0) * 100.0 > s.end_energy:
                    raise FloatingPointError(f"energy ratio {ratio:.4f} at t = {t:.6g} (cycle {cycle}) is "
                                             f"beyond ENDENG = {s.end_energy} %: the run is stopped")
    except FloatingPointError as e:
        stopped = str(e)
    except KeyboardInterrupt:
        stopped = f"interrupted at t = {t:.6g} (cycle {cycle})"
    r = rec.rows
    ns = len(r["time"])
    return Results(
        time=np.array(r["time"]), kinetic=np.array(r["kinetic"]), internal=np.array(r["internal"]),
        wall=np.array(r["wall"]), external=np.array(r["external"]), discrete_force=np.array(r["force"]).reshape(ns, ne),
        discrete_elong=np.array(r["elong"]).reshape(ns, ne),
        wall_force=np.array(r["wall_force"]).reshape(ns, nw, 3),
        wall_velocity=np.array(r["wall_velocity"]).reshape(ns, nw),
        node_displacement=np.array(r["disp"]).reshape(ns, len(s.history_nodes), 3),
        node_velocity=np.array(r["vel"]).reshape(ns, len(s.history_nodes), 3),
        spc_force=np.array(r["spc"]).reshape(ns, len(rec.spc_nodes), 3), spc_nodes=rec.spc_nodes,
        history_nodes=s.history_nodes, discrete_ids=d.ids,
        wall_ids=np.array([w.wall_id for w in s.walls], np.int64), final_x=x, final_v=v,
        cycles=cycle, dt=dt, wall_time=_time.perf_counter() - t_start,
        section_ids=np.array([sec.csid for sec in s.sections], np.int64),
        section_force=np.array(r["sec"]).reshape(ns, len(s.sections), 3),
        part_ids=part_ids, part_internal=np.array(r["part_ie"]).reshape(ns, len(part_ids)),
        states_time=np.array(states_t) if s.state_dt > 0 else np.zeros(0),
        states_x=np.array(states_x) if s.state_dt > 0 else np.zeros((0, n, 3)),
        info={"added_mass": added_mass, "stopped": stopped, "bodies": {b.body_id: {"cog": b.cog.copy(), "velocity": b.velocity.copy(),
                                     "momentum": b.momentum.copy(), "rotation": b.rot.copy()}
                         for b in s.bodies}})


def run(model_or_path, out=None, quiet: bool = True, output_dt: float | None = None) -> Results:
    """Run a deck (path) or Model; results saved to ``out`` when given."""
    from .. import read_deck

    model = model_or_path if isinstance(model_or_path, Model) else read_deck(model_or_path)
    s = build(model)
    progress = None if quiet else _progress_bar(s.end_time)
    try:
        res = integrate(s, output_dt, progress)
    finally:
        if progress is not None:
            progress.close()
    res.history_nodes = model.nodes.ids[s.history_nodes]
    res.spc_nodes = model.nodes.ids[res.spc_nodes]
    if out is not None:
        res.save(Path(out))  # also when the run stopped early: the states so far are kept
        if len(res.states_time):
            from ..results.vtk import write_states

            write_states(Path(out) / "states", model, res.states_time, res.states_x)
    if res.info["stopped"] and not res.info["stopped"].startswith("interrupted"):
        raise RunError(res.info["stopped"], res)
    return res


class RunError(FloatingPointError):
    """The run diverged or hit a termination criterion; ``results`` holds
    the states recorded until then (also saved when an output folder was
    given)."""

    def __init__(self, message: str, results: Results):
        super().__init__(message)
        self.results = results


class _progress_bar:
    """Simulated time, cycle, time step and energy ratio, with an ETA."""

    def __init__(self, end_time: float):
        from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

        self.p = Progress(TextColumn("t={task.fields[t]:.4g}"), BarColumn(),
                          TextColumn("cycle {task.fields[cycle]} dt={task.fields[dt]:.3g} "
                                     "E/E0={task.fields[ratio]:.4f}"), TimeRemainingColumn())
        self.p.start()
        self.task = self.p.add_task("run", total=end_time, t=0.0, cycle=0, dt=0.0, ratio=1.0)

    def __call__(self, t, cycle, dt, ratio):
        self.p.update(self.task, completed=t, t=t, cycle=cycle, dt=dt, ratio=ratio)

    def close(self):
        self.p.stop()
