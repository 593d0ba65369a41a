"""The explicit time loop (central difference) and ``run``.

The loop owns no I/O: states are recorded by a callback every
``output_dt``; progress is another callback.
"""

from __future__ import annotations

import time as _time
from collections.abc import Callable
from dataclasses import fields
from pathlib import Path

import numpy as np

from ..keyword.errors import Problem
from ..model.model import Model
from .frames import project_out
from .groups import BeamGroup, DiscreteGroup
from .kernels.beam import turn_nodes
from .kernels.integrate import kick_nodes, update_position
from .motions import Motions
from .parts import PartAccount
from .results import Results, element_counts
from .sections import section_forces
from .setup import Setup, SetupError, build
from .state import State
from .timestep import MAX_CYCLES, scale_masses, smallest_step, stable_dt, step_problem
from .walls import Walls


def _state(s: Setup) -> State:
    n = len(s.mass)
    rot_inertia = s.rot_inertia if s.rot_inertia is not None else np.zeros(n)
    fixed_rot = s.fixed_rot if s.fixed_rot is not None else np.zeros((n, 3), bool)
    inv_j = np.where(rot_inertia > 0, 1.0 / np.where(rot_inertia > 0, rot_inertia, 1.0), 0.0)
    w = s.w0.copy() if s.w0 is not None else np.zeros((n, 3))
    w[inv_j == 0] = 0.0
    w[fixed_rot] = 0.0
    v = s.v0.copy()
    v[s.fixed] = 0.0
    project_out(v, s.skew_nodes, s.skew_held)
    project_out(w, s.skew_nodes, s.skew_held_rot)
    inv_mass = np.where(s.mass > 0, 1.0 / np.where(s.mass > 0, s.mass, 1.0), 0.0)
    return State(
        s.x0.copy(),
        v,
        np.zeros((n, 3)),
        np.tile(np.eye(3), (n, 1, 1)),
        w,
        np.zeros((n, 3)),
        s.mass,
        inv_mass,
        rot_inertia,
        inv_j,
        s.fixed,
        fixed_rot,
    )


def groups_of(s: Setup, n: int) -> list:
    """The element groups of a Setup, in a fixed order."""
    groups = [DiscreteGroup(s.discrete, n, s.discrete_pid)]
    if s.beams is not None and len(s.beams.ids):
        groups.append(BeamGroup(s.beams, n, s.beam_pid))
    return groups + list(s.groups)


class _Recorder:
    """Collects the states written to Results."""

    def __init__(self, s: Setup, st: State, groups, parts: PartAccount, walls: Walls):
        self.s, self.st, self.groups, self.parts, self.walls = s, st, groups, parts, walls
        self.rows: dict[str, list] = {}
        self.cycle = 0
        self.discrete = groups[0]
        self.printed = s.discrete_printed  # DEFORC's discretes (PF 0)
        self.contacts = [g for g in groups if g.kind == "contact"]  # rcforc: force on each slave side
        self.flagged: set = set()  # contacts warned about negative sliding energy
        self.warnings: list[str] = []
        # nodes with a constrained DOF: their reactions are written (spcforc)
        held = s.fixed.any(axis=1)
        held[s.skew_nodes] = True
        self.spc_nodes = np.flatnonzero(held)
        self._skew_rows = np.searchsorted(self.spc_nodes, s.skew_nodes)

    def add(self, **values):
        for k, v in values.items():
            self.rows.setdefault(k, []).append(v)

    def reactions_and_sections(self):
        """Support reactions and section forces: they need the forces of
        the step, taken before the velocity update."""
        sn, st = self.spc_nodes, self.st
        self._spc = np.where(self.s.fixed[sn], -st.f[sn], 0.0)
        if len(self.s.skew_nodes):  # supports in local systems: minus the force along the held axes
            held = self.s.skew_held
            f = st.f[self.s.skew_nodes]
            self._spc[self._skew_rows] -= np.einsum("kd,kdj->kj", np.einsum("kj,kdj->kd", f, held), held)
        self._sec = section_forces(self.s.sections, self.groups, st.x)

    def __call__(self, t, v_mid, acc, ke, work, ew):
        st, h, d = self.st, self.s.history_nodes, self.discrete
        ie = float(sum(g.energy.sum() for g in self.groups if g.kind != "contact"))
        se = float(sum(g.energy.sum() for g in self.groups if g.kind == "contact"))
        hg = float(sum(g.hourglass.sum() for g in self.groups if g.hourglass is not None))
        self.add(
            time=t,
            kinetic=ke,
            internal=ie,
            hourglass=hg,
            sliding=se,
            wall=ew,
            external=work,
            time_step=st.dt,
            cycle=self.cycle,
            force=d.force[self.printed] if self.printed is not None else d.force.copy(),
            elong=d.elong[self.printed] if self.printed is not None else d.elong.copy(),
            wall_force=self.walls.force[:, :3].copy(),
            wall_velocity=self.walls.velocity.copy(),
            disp=st.x[h] - self.s.x0[h],
            vel=v_mid[h].copy(),
            acc=acc[h].copy(),
            coord=st.x[h].copy(),
            spc=self._spc.copy(),
            sec=self._sec[0].copy(),
            sec_m=self._sec[1].copy(),
            part_ie=self.parts.internal(),
            part_hg=self.parts.hourglass(),
            part_del=self.parts.deleted(),
            part_ke=self.parts.kinetic(st.mass, v_mid),
            part_p=(p := self.parts.momentum(st.mass, v_mid)),
            part_rbv=self.parts.rigid_velocity(st.mass, p),
            contact_force=np.array([g.resultant for g in self.contacts]).reshape(-1, 3),
        )
        self._check_sliding(t, ie, ke)
        return ie + se + hg

    def _check_sliding(self, t, ie, ke):
        """A contact whose energy falls below −1 % of the internal energy
        (and 0.1 % of the kinetic, and 1e-6, a µJ in mm–t–s: not round-off
        of a model at rest) gives back energy it never stored: one warning
        per interface, naming it and its deepest slave nodes now."""
        for g in self.contacts:
            e = float(g.energy[0])
            if g.cid in self.flagged or not e < -max(0.01 * ie, 1e-5 * ke, 1e-6):
                continue
            self.flagged.add(g.cid)
            deep = np.argsort(g.gap)[::-1][:5]
            deep = deep[g.gap[deep] > 0]
            ids = self.s.node_ids if self.s.node_ids is not None else np.arange(len(self.st.x))
            nodes = ", ".join(f"{int(ids[g.c.snode[i]])} ({g.gap[i]:.3g})" for i in deep) or "none in contact now"
            self.warnings.append(
                f"{self.s.source}: *{g.name} {g.cid}: sliding energy {e:.4g} at t = {t:.6g} is "
                f"below -1 % of the internal energy {ie:.4g}: the contact gives back energy "
                f"it did not store; deepest slave nodes now (penetration): {nodes}"
            )

    def array(self, key, shape):
        ns = len(self.rows["time"])
        return np.array(self.rows[key]).reshape((ns,) + shape)


class CompileClock:
    """Seconds spent compiling (or loading from the cache) Numba kernels
    while it is registered: the outermost holds of Numba's compiler lock
    (``numba:compiler_lock`` events)."""

    def __init__(self):
        self.seconds = 0.0
        self._depth = 0
        self._t0 = 0.0
        self._listener = None

    def __enter__(self):
        try:
            from numba.core import event
        except ImportError:  # no event API: compilation is not told apart
            return self
        clock = self

        class _Listener(event.Listener):
            def on_start(self, ev):
                if clock._depth == 0:
                    clock._t0 = _time.perf_counter()
                clock._depth += 1

            def on_end(self, ev):
                clock._depth -= 1
                if clock._depth == 0:
                    clock.seconds += _time.perf_counter() - clock._t0

        self._listener = _Listener()
        event.register("numba:compiler_lock", self._listener)
        return self

    def __exit__(self, *exc):
        if self._listener is not None:
            from numba.core import event

            event.unregister("numba:compiler_lock", self._listener)
            self._listener = None
        return False


def integrate(
    s: Setup,
    output_dt: float | None = None,
    progress: Callable[[float, int, float, float], None] | None = None,
    fields: list | None = None,
) -> Results:
    """Run the time loop on a Setup; states every ``output_dt`` (default:
    1/200 of the end time) and at the end. ``fields``: a list that receives
    the nodal and element fields of each field state (results.d3plot.state).

    Times of the Results: ``loop_time`` and ``cpu_time`` are the wall and
    CPU (all threads) seconds of the time loop less the Numba compilation
    met in it, the figure runs are compared by; ``setup_time`` is the rest
    of ``wall_time`` (mass scaling, first forces, compilation);
    ``compile_time`` the compilation and cache loads."""
    with CompileClock() as clock:
        return _integrate(s, output_dt, progress, clock, fields)


def _integrate(s: Setup, output_dt, progress, clock: CompileClock, fields: list | None = None) -> Results:
    t_start = _time.perf_counter()
    added_mass = scale_masses(s, s.discrete_pid if len(s.discrete_pid) == len(s.discrete.ids) else None)
    st = _state(s)
    n = len(s.mass)
    nb = bool((st.rot_inertia > 0).any())  # nodes with rotational DOFs (beams, shells)
    x, v, f = st.x, st.v, st.f
    groups = groups_of(s, n)
    # only beams read the nodal orientations: only their nodes turn
    turned = np.unique(np.concatenate([g.conn.ravel() for g in groups if g.kind == "beam"] + [np.zeros(0, np.int64)]))
    turned = turned[st.inv_j[turned] != 0.0]  # as update_rotations: nodes with rotational inertia
    turn = nb and len(turned) > 0
    walls = Walls(s.walls, s.bodies, n)
    motions = Motions(s.motions, s.bodies, s.x0)
    parts = PartAccount(groups, s.bodies, n)
    output_dt = output_dt or s.end_time / 200.0
    rec = _Recorder(s, st, groups, parts, walls)
    free_mass = s.mass.copy()
    rot_free = st.rot_inertia.copy()
    in_body = np.zeros(n, bool)
    for b in s.bodies:
        free_mass[b.nodes] = 0.0  # counted through the body
        rot_free[b.nodes] = 0.0
        in_body[b.nodes] = True
    dense = [c for g in groups if hasattr(g, "consistent") and (c := g.consistent(n)) is not None]
    for c in dense:  # superelements' mass matrices, solved as given
        c.start(st.mass, s.fixed, in_body)
        rec.warnings += [f"{s.source}: *ELEMENT_DIRECT_MATRIX_INPUT: {w}" for w in c.notes]

    def place(b):
        b.place(x, v, st.rot if nb else None, st.w if nb else None)

    def body_force(t):
        out = np.zeros_like(x)
        for axis, curve, sf in s.body_loads:  # base acceleration a: inertial load -m a
            acc = sf * np.interp(t, *curve)
            out -= np.outer(s.mass * acc, axis)
            for c in dense:
                c.body_force(out, axis, acc)
        return out

    def internal_forces(t, zeroed=False):
        """f (and moment): the force the elements and body loads exert on the
        nodes (``zeroed``: f and moment are zero already, update_position)."""
        if not zeroed:
            f[:] = 0.0
            st.moment[:] = 0.0
        for g in groups:
            g.forces(st)
        if s.body_loads:
            f[:] += body_force(t)
        if s.nodal_loads is not None:
            s.nodal_loads.apply(t, f, st.moment if nb else None)
        for c in s.constraints:  # tied contacts, spot welds: slave forces to the masters
            c.forces(st)

    def kinetic(v_mid, w_mid):
        ke = 0.5 * float(np.einsum("i,ij,ij->", free_mass, v_mid, v_mid))
        if nb:
            ke += 0.5 * float(np.einsum("i,ij,ij->", rot_free, w_mid, w_mid))
        ke += sum(b.kinetic() for b in s.bodies) + sum(c.kinetic(v_mid) for c in dense)
        return ke + walls.kinetic()

    no_w = np.zeros((0, 3))

    def kick(dt_v):
        w_kick = st.w if nb else no_w
        kick_nodes(v, f, st.inv_mass, s.fixed, dt_v, walls.before, w_kick, st.moment, st.inv_j, st.fixed_rot)
        for c in dense:
            c.kick(f, v, dt_v)
        project_out(v, s.skew_nodes, s.skew_held)
        if nb:
            project_out(st.w, s.skew_nodes, s.skew_held_rot)
        for b in s.bodies:
            b.kick(f, x, dt_v, st.moment if nb else None)
            place(b)
        for c in s.constraints:
            c.velocities(st)

    dt_static = stable_dt(s)  # discrete elements and beams: fixed for the run
    updated = [g for g in groups if hasattr(g, "critical_dt")]  # shells, solids: from the current shape

    def step_size(t):
        dt_s = dt_static
        for g in updated:
            dt_g = g.critical_dt(st) * s.tssfac
            if dt_g != dt_g or dt_s != dt_s:
                return np.nan  # not a number: the caller stops with a diagnosis
            dt_s = min(dt_s, dt_g)
        if dt_s == np.inf:
            dt_s = s.end_time / 1000.0  # nothing to resolve: masses, walls and motions only
        if s.dt_max is not None and not np.isnan(dt_s):
            dt_s = min(dt_s, float(np.interp(t, *s.dt_max)))
        return float(dt_s)

    def unusable(dt_s, t_now):
        """(diagnosis, element keyword) of a step that is no step (zero, NaN,
        or one the run would not end with), naming the element that sets
        it; None if the step is usable."""
        why = step_problem(dt_s, t_now, s.end_time, s.end_cycle)
        if why is None:
            return None
        _, who = smallest_step(s, groups, st)
        kw = who.split()[0].lstrip("*") if who.startswith("*") else "CONTROL_TIMESTEP"
        return why + f"; the smallest element step is that of {who}", kw

    # t = 0: forces, half-step velocity
    internal_forces(0.0)
    for g in groups:
        if hasattr(g, "start"):
            g.start()
    ew_total = 0.0
    dt = step_size(0.0)
    why = unusable(dt, 0.0)
    if why is not None:  # stop before the first cycle, never hang
        raise SetupError([Problem(s.source, 0, why[1], None, why[0])])
    t_loop, cpu_loop, compile_loop = _time.perf_counter(), _time.process_time(), clock.seconds
    dt_first = dt
    for g in groups:
        g.first_step(dt_first / s.tssfac)  # ERODE's limit is the run's own (TSMIN)
    t = 0.0
    v_prev, w_prev = v.copy(), st.w.copy()
    x_prev = np.zeros_like(x)
    f_body_prev = np.zeros_like(x)
    rec.reactions_and_sections()
    rec(t, v, np.zeros_like(v), kinetic(v, st.w), 0.0, ew_total)
    if fields is not None:  # the d3plot's fields at each state (the velocity after it: once kicked)
        from ..results.d3plot import complete, state

        fields.append(state(groups, x, v))
    kick(0.5 * dt)
    w_ext = motions.apply(st, 0.0, 0.5 * dt, dt, place)
    dw = 0.0
    ew_total += walls.apply(st, t, dt, place)
    if fields is not None:
        complete(fields[-1], v, 0.5 * dt, 0.0)
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
            if s.nodal_loads is not None:  # work over t .. t + dt with the half-step velocities
                w_ext += s.nodal_loads.work(t + 0.5 * dt_step, v, st.w if nb else None, dt_step)
            update_position(x, v, dt_step, f, st.moment)
            if turn:
                turn_nodes(st.rot, st.w, turned, dt_step)
            for b in s.bodies:
                b.drift(dt_step)
                place(b)
            walls.move(dt_step)
            t += dt_step
            cycle += 1
            st.t, st.dt = t, dt_step
            internal_forces(t, zeroed=True)
            for g in groups:
                g.account()
            dt_new = step_size(t)
            if not dt_new > 0 or (s.end_time - t) > MAX_CYCLES * dt_new:  # zero, NaN or no end in sight
                why = unusable(dt_new, t)
                if why is not None:
                    raise FloatingPointError(why[0] + f" (cycle {cycle}): the run is stopped")
            if s.dt_min > 0 and dt_new < s.dt_min * dt_first:
                _, who = smallest_step(s, groups, st)
                raise FloatingPointError(
                    f"time step {dt_new:.4g} at t = {t:.6g} (cycle {cycle}) fell below "
                    f"DTMIN x first step = {s.dt_min * dt_first:.4g}: the run is stopped; "
                    f"the smallest element step is that of {who}"
                )
            output = t >= next_out * (1 - 1e-9) or t >= s.end_time
            field_state = t >= next_state * (1 - 1e-9) or (t >= s.end_time and np.isfinite(next_state))
            if field_state:
                states_t.append(t)
                states_x.append(x.copy())
                next_state += s.state_dt
                if fields is not None:
                    fields.append(state(groups, x, v))
            if output:  # the state at t needs the velocity on both sides of it
                v_prev[:] = v
                w_prev[:] = st.w
                rec.reactions_and_sections()
            if s.body_loads:  # work of the body loads over the last step (positions t-dt .. t)
                w_ext += float(np.einsum("ij,ij->", f_body_prev, x - x_prev))
            dt_v = 0.5 * (dt_step + dt_new)
            kick(dt_v)
            dw = motions.apply(st, t, dt_v, dt_new, place)
            w_ext += dw
            ew_total += walls.apply(st, t, dt_new, place)
            if field_state and fields is not None:
                complete(fields[-1], v, dt_v, 0.5 * dt_v)
            dt = dt_new
            if output:
                if not np.all(np.isfinite(v)):
                    bad = int(np.argwhere(~np.isfinite(v))[0, 0])
                    name = f"node {int(s.node_ids[bad])}" if s.node_ids is not None else f"node index {bad}"
                    raise FloatingPointError(
                        f"non-finite velocity at {name}, t = {t:.6g} (cycle {cycle}): the run diverged"
                    )
                v_mid = 0.5 * (v_prev + v)
                ke = kinetic(v_mid, 0.5 * (w_prev + st.w))
                # the last work increment belongs to the half step after t: count half of it
                rec.cycle = cycle
                ie = rec(t, v_mid, (v - v_prev) / dt_v, ke, w_ext - 0.5 * dw, ew_total)
                next_out += output_dt
                supplied = (
                    sum(rec.rows[k][0] for k in ("kinetic", "internal", "sliding", "hourglass")) + w_ext - 0.5 * dw
                )
                ratio = (ke + ie + ew_total) / max(supplied, 1e-300)
                if progress is not None:
                    progress(t, cycle, dt, ratio)
                if s.end_energy > 0 and abs(ratio - 1.0) * 100.0 > s.end_energy:
                    raise FloatingPointError(
                        f"energy ratio {ratio:.4f} at t = {t:.6g} (cycle {cycle}) is "
                        f"beyond ENDENG = {s.end_energy} %: the run is stopped"
                    )
    except FloatingPointError as e:
        stopped = str(e)
    except KeyboardInterrupt:
        stopped = f"interrupted at t = {t:.6g} (cycle {cycle})"
    with HeldInterrupts() as held:  # a further Ctrl-C now would lose the states: held until they are out
        res = _results(
            s,
            rec,
            groups,
            parts,
            walls,
            st,
            locals_=dict(
                cycles=cycle,
                dt=dt,
                wall_time=_time.perf_counter() - t_start,
                states_t=states_t,
                states_x=states_x,
                loop_time=_time.perf_counter() - t_loop - (clock.seconds - compile_loop),
                cpu_time=_time.process_time() - cpu_loop - (clock.seconds - compile_loop),
                compile_time=clock.seconds,
                added_mass=added_mass,
                stopped=stopped,
            ),
        )
    if held.hit and not stopped:
        res.info["stopped"] = f"interrupted at t = {t:.6g} (cycle {cycle}), after the last cycle"
    return res


class HeldInterrupts:
    """Ctrl-C (SIGINT) held while results are assembled and written: one
    pressed meanwhile is remembered in ``hit`` instead of raising
    KeyboardInterrupt half-way through a file. Only in the main thread
    (elsewhere Python delivers no SIGINT); nests."""

    def __init__(self):
        self.hit = False
        self._old = None

    def _hold(self, *_):
        self.hit = True

    def __enter__(self):
        import signal
        import threading

        if threading.current_thread() is threading.main_thread():
            try:
                self._old = signal.signal(signal.SIGINT, self._hold)
            except (ValueError, OSError):  # no signals here (embedded interpreter)
                self._old = None
        return self

    def __exit__(self, *exc):
        import signal

        if self._old is not None:
            signal.signal(signal.SIGINT, self._old)
            outer = getattr(self._old, "__self__", None)
            if self.hit and isinstance(outer, HeldInterrupts):  # an outer hold learns of the Ctrl-C too
                outer.hit = True
            self._old = None
        return False


def _results(s, rec, groups, parts, walls, st, locals_) -> Results:
    d = groups[0]
    printed = d.ids if s.discrete_printed is None else d.ids[s.discrete_printed]
    ne, nw, nh, nsec, npart = len(printed), len(s.walls), len(s.history_nodes), len(s.sections), len(parts.part_ids)
    a = rec.array
    extra = dict(
        part_kinetic=a("part_ke", (npart,)),
        part_momentum=a("part_p", (npart, 3)),
        part_rigid_velocity=a("part_rbv", (npart, 3)),
        part_hourglass=a("part_hg", (npart,)),
        part_deleted=a("part_del", (npart,)).astype(np.int64),
        section_moment=a("sec_m", (nsec, 3)),
        node_acceleration=a("acc", (nh, 3)),
        node_coordinates=a("coord", (nh, 3)),
        hourglass=a("hourglass", ()),
        sliding=a("sliding", ()),
        time_step=a("time_step", ()),
        cycle_number=a("cycle", ()).astype(np.int64),
        contact_force=a("contact_force", (len(rec.contacts), 3)),
        contact_ids=np.array([g.cid for g in rec.contacts], np.int64),
    )
    for g in groups:
        eps = g.plastic_strain() if g.kind in ("shell", "solid") else None
        if eps is not None:
            extra[f"{g.kind}_ids"], extra[f"{g.kind}_plastic_strain"] = np.asarray(g.ids, np.int64), eps
            extra[f"{g.kind}_internal_energy"] = np.array(g.energy, float)
    known = {f.name for f in fields(Results)}
    n = len(st.x)
    return Results(
        time=a("time", ()),
        kinetic=a("kinetic", ()),
        internal=a("internal", ()),
        wall=a("wall", ()),
        external=a("external", ()),
        discrete_force=a("force", (ne,)),
        discrete_elong=a("elong", (ne,)),
        wall_force=a("wall_force", (nw, 3)),
        wall_velocity=a("wall_velocity", (nw,)),
        node_displacement=a("disp", (nh, 3)),
        node_velocity=a("vel", (nh, 3)),
        spc_force=a("spc", (len(rec.spc_nodes), 3)),
        spc_nodes=rec.spc_nodes,
        history_nodes=s.history_nodes,
        discrete_ids=printed,
        wall_ids=np.array([w.wall_id for w in s.walls], np.int64),
        final_x=st.x,
        final_v=st.v,
        cycles=locals_["cycles"],
        dt=locals_["dt"],
        wall_time=locals_["wall_time"],
        loop_time=locals_["loop_time"],
        cpu_time=max(locals_["cpu_time"], 0.0),
        setup_time=locals_["wall_time"] - locals_["loop_time"],
        compile_time=locals_["compile_time"],
        section_ids=np.array([sec.csid for sec in s.sections], np.int64),
        section_force=a("sec", (nsec, 3)),
        part_ids=parts.part_ids,
        part_internal=a("part_ie", (npart,)),
        states_time=np.array(locals_["states_t"]) if s.state_dt > 0 else np.zeros(0),
        states_x=np.array(locals_["states_x"]) if s.state_dt > 0 else np.zeros((0, n, 3)),
        info={
            "added_mass": locals_["added_mass"],
            "stopped": locals_["stopped"],
            "warnings": list(rec.warnings),
            "elements": {g.kind: len(g) for g in groups if len(g)},
            "bodies": {
                b.body_id: {
                    "cog": b.cog.copy(),
                    "velocity": b.velocity.copy(),
                    "momentum": b.momentum.copy(),
                    "rotation": b.rot.copy(),
                }
                for b in s.bodies
            },
        },
        **{k: v for k, v in extra.items() if k in known},
    )


def run(
    model_or_path: Model | Path | str,
    out: Path | str | None = None,
    quiet: bool = True,
    output_dt: float | None = None,
) -> Results:
    """Run a deck (path) or Model; results saved to ``out`` when given."""
    from .. import read_deck

    model = model_or_path if isinstance(model_or_path, Model) else read_deck(model_or_path)
    t0 = _time.perf_counter()
    with CompileClock() as clock:
        s = build(model)
    t_build = _time.perf_counter() - t0
    progress = None if quiet else _progress_bar(s.end_time)
    d3plot = fields = None
    if out is not None and s.state_dt > 0:
        from ..results import d3plot

        fields = [] if d3plot.lasso() is not None else None
    try:
        res = integrate(s, output_dt, progress, fields)
    finally:
        if progress is not None:
            progress.close()
    res.setup_time += t_build  # set-up of the arrays (and the kernels it compiles)
    res.wall_time += t_build
    res.compile_time += clock.seconds
    res.history_nodes = model.nodes.ids[s.history_nodes]
    res.spc_nodes = model.nodes.ids[res.spc_nodes]
    res.node_ids = model.nodes.ids.astype(np.int64)
    res.info["elements"] = element_counts(model)
    from .support import PASSED

    passed = {w.keyword for w in s.warnings if w.message.startswith(PASSED)}  # said once, by the solver
    res.info["warnings"] = (
        [str(w) for w in model.warnings if w.keyword not in passed]
        + [str(w) for w in s.warnings]
        + res.info.get("warnings", [])
    )
    if out is not None:
        with HeldInterrupts() as held:  # Ctrl-C while saving: every file is still written, then reported
            res.save(Path(out))  # also when the run stopped early: the states so far are kept
            if s.moved:
                from .penetrations import write_csv

                write_csv(Path(out) / "initial_penetrations.csv", s.moved, model.nodes.ids)
            if len(res.states_time):
                from ..results.vtk import element_field, write_states
                from .part_moves import moved_model

                placed = moved_model(model, [])  # the geometry the run set up (*PART_MOVE applied)
                eps = element_field(
                    placed,
                    {"shells": res.shell_ids, "solids": res.solid_ids},
                    {"shells": res.shell_plastic_strain, "solids": res.solid_plastic_strain},
                )
                write_states(Path(out) / "states", placed, res.states_time, res.states_x, {"plastic_strain": eps})
                if fields is None:
                    res.info["warnings"].append(d3plot.MISSING)
                else:
                    d3plot.write(
                        Path(out) / "d3plot",
                        placed,
                        res.states_time,
                        res.states_x,
                        fields,
                        {"time": res.time, "kinetic": res.kinetic, "internal": res.internal, "total": res.total},
                    )
        if held.hit and not res.info["stopped"]:
            res.info["stopped"] = (
                f"interrupted at t = {res.time[-1]:.6g} (cycle {res.cycles}), while saving "
                "the results (every file written)"
            )
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

        self.p = Progress(
            TextColumn("t={task.fields[t]:.4g}"),
            BarColumn(),
            TextColumn("cycle {task.fields[cycle]} dt={task.fields[dt]:.3g} E/E0={task.fields[ratio]:.4f}"),
            TimeRemainingColumn(),
        )
        self.p.start()
        self.task = self.p.add_task("run", total=end_time, t=0.0, cycle=0, dt=0.0, ratio=1.0)

    def __call__(self, t, cycle, dt, ratio):
        self.p.update(self.task, completed=t, t=t, cycle=cycle, dt=dt, ratio=ratio)

    def close(self):
        self.p.stop()
