"""A minimal central-difference driver for the solid element group, calling
it as the time loop does (forces at t(n+1) from the half-step velocities,
then critical_dt), with fixed and prescribed-velocity degrees of freedom.

Reactions at held and driven DOFs are m·a − f; their work is integrated by
the trapezoid rule over the displacements, so the energy balance
KE + IE + HG = KE0 + W_ext can be checked. Also: brick meshes and the deck
text that builds a group through crashlite's reader and build_solids.
"""

from __future__ import annotations

import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from crashlite import read_deck
from crashlite.solver.solids import SolidGroup, build_solids, lumped_mass


def brick_mesh(nx: int, ny: int, nz: int, hx: float, hy: float, hz: float):
    """Nodes (n, 3) [length] and hexahedra (ne, 8) int64 (0-based, LS-DYNA
    order) of a block [0, nx·hx] × [0, ny·hy] × [0, nz·hz]."""
    g = np.stack(
        np.meshgrid(np.arange(nx + 1) * hx, np.arange(ny + 1) * hy, np.arange(nz + 1) * hz, indexing="ij"), axis=-1
    ).reshape(-1, 3)

    def nid(i, j, k):
        return (i * (ny + 1) + j) * (nz + 1) + k

    el = []
    for i in range(nx):
        for j in range(ny):
            for k in range(nz):
                el.append(
                    [
                        nid(i, j, k),
                        nid(i + 1, j, k),
                        nid(i + 1, j + 1, k),
                        nid(i, j + 1, k),
                        nid(i, j, k + 1),
                        nid(i + 1, j, k + 1),
                        nid(i + 1, j + 1, k + 1),
                        nid(i, j + 1, k + 1),
                    ]
                )
    return g.astype(float), np.array(el, np.int64)


def deck_text(
    x: np.ndarray, conn: np.ndarray, material: str, section: str = "1,1", hourglass: str | None = None, extra: str = ""
) -> str:
    """Keyword deck of one solid part (PID 1, SECID 1, MID 1, HGID 1 when
    ``hourglass`` card text is given); ``material`` is the *MAT keyword
    with its cards, ``extra`` more keywords (curves, controls)."""
    lines = ["*KEYWORD", "*NODE"] + [f"{i + 1},{float(a)!r},{float(b)!r},{float(c)!r}" for i, (a, b, c) in enumerate(x)]
    lines.append("*ELEMENT_SOLID")
    lines += [f"{e + 1},1," + ",".join(str(int(n) + 1) for n in row) for e, row in enumerate(conn)]
    lines += ["*PART", "block", f"1,1,1,0,{1 if hourglass else 0}", "*SECTION_SOLID", section, material.strip()]
    if hourglass:
        lines += ["*HOURGLASS", hourglass]
    lines += [extra.strip(), "*CONTROL_TERMINATION", "1.0", "*END"]
    return "\n".join(ln for ln in lines if ln) + "\n"


def group_from_deck(tmp_path: Path, text: str, name: str = "solid.k"):
    """(group, model, warnings) built from deck text by build_solids;
    raises AssertionError listing the problems if any."""
    p = tmp_path / name
    p.write_text(text)
    model = read_deck(p)
    problems, warnings = [], []
    s = build_solids(model, [], problems, warnings)
    assert not problems, problems
    return SolidGroup(s, len(model.nodes.xyz)), model, warnings


class Driver:
    """Central difference on the nodes of one solid group.

    x0 (n, 3) [length]; fixed (n, 3) bool held DOFs; driven: list of
    (node indices, dof, v(t) -> velocity [length/time]); v0 (n, 3) initial
    velocity; dt_max caps the step [time].
    """

    def __init__(
        self,
        group: SolidGroup,
        x0: np.ndarray,
        fixed=None,
        driven=(),
        v0=None,
        tssfac: float = 0.9,
        dt_max: float = np.inf,
    ):
        n = len(x0)
        self.g = group
        self.mass = lumped_mass(group.s, n)
        self.fixed = np.zeros((n, 3), bool) if fixed is None else np.asarray(fixed, bool)
        self.driven = list(driven)
        self.tssfac, self.dt_max = tssfac, dt_max
        self.st = SimpleNamespace(
            x=np.array(x0, float),
            v=np.zeros((n, 3)) if v0 is None else np.array(v0, float),
            f=np.zeros((n, 3)),
            t=0.0,
            dt=0.0,
            mass=self.mass,
        )
        self.held = self.fixed.copy()
        for nodes, dof, _ in self.driven:
            self.held[nodes, dof] = True
        self.kinetic0 = self.kinetic(self.st.v)
        self.work = 0.0  # work of the reactions at held and driven DOFs [energy]
        self.reaction = np.zeros((n, 3))  # m·a − f at held DOFs at t(n) [force]

    def kinetic(self, v) -> float:
        return 0.5 * float(np.einsum("i,ij,ij->", self.mass, v, v))

    def _forces(self):
        self.st.f[:] = 0.0
        self.g.forces(self.st)
        self.g.account()

    def _half_velocity(self, t_mid: float, dt_v: float) -> np.ndarray:
        """v(n+½) from v(n−½) and the forces; prescribed values where held.
        Returns the reaction m·a − f at the held DOFs."""
        st = self.st
        old = st.v.copy()
        acc = st.f / self.mass[:, None]
        st.v += dt_v * np.where(self.held, 0.0, acc)
        st.v[self.fixed] = 0.0
        for nodes, dof, fn in self.driven:
            st.v[nodes, dof] = fn(t_mid)
        return np.where(self.held, self.mass[:, None] * (st.v - old) / dt_v - st.f, 0.0)

    def step_size(self) -> float:
        dt = min(self.g.critical_dt(self.st) * self.tssfac, self.dt_max)
        if not np.isfinite(dt):  # every element eroded: keep the last step
            dt = self.st.dt
        return dt

    def run(self, t_end: float, record=None, every: int = 1) -> None:
        """Integrate to t_end; record(driver, v_n) at t = 0 and every
        ``every`` steps, with v_n the velocity at t(n) (mean of the half
        steps)."""
        st = self.st
        st.dt = 0.0
        self._forces()
        dt = self.step_size()
        v_prev = st.v.copy()
        r_old = self._half_velocity(0.5 * dt, 0.5 * dt)
        if record is not None:
            record(self, v_prev)
        k = 0
        while st.t < t_end * (1 - 1e-12):
            x_old = st.x.copy()
            st.x += dt * st.v
            st.t += dt
            st.dt = dt
            self._forces()
            dt_new = self.step_size()
            v_prev[:] = st.v
            r_new = self._half_velocity(st.t + 0.5 * dt_new, 0.5 * (dt + dt_new))
            self.work += 0.5 * float(np.einsum("ij,ij->", r_old + r_new, st.x - x_old))
            self.reaction, r_old = r_new, r_new
            dt = dt_new
            k += 1
            if record is not None and (k % every == 0 or st.t >= t_end * (1 - 1e-12)):
                record(self, 0.5 * (v_prev + st.v))

    def balance(self, v_n) -> tuple[float, float]:
        """(energy error, energy scale): KE + IE + HG − KE0 − W_ext, and the
        largest of KE0, |W_ext|, IE [energy]."""
        ke, ie, hg = self.kinetic(v_n), float(self.g.energy.sum()), float(self.g.hourglass.sum())
        return ke + ie + hg - self.kinetic0 - self.work, max(self.kinetic0, abs(self.work), ie)


# --- materials, shapes and helpers shared by the one-point and fully integrated element tests ----------------

E, NU, RHO = 210000.0, 0.3, 7.85e-9  # MPa, -, t/mm³
LAM, MU = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
STEEL = f"*MAT_ELASTIC\n1,{RHO},{E},{NU}"
GRAD = np.array([[1.0, 0.3, -0.2], [0.1, -0.5, 0.4], [0.2, 0.0, 0.7]])  # velocity gradient [1/s]
HC_RHO, HC_E, HC_SIGY, HC_VF = 2.89e-11, 1000.0, 200.0, 0.2  # t/mm³, MPa, MPa, -
HC_CURVE = np.array([[0.0, 0.342], [0.7, 0.5], [0.8, 0.8]])  # crush stress [MPa] vs volumetric strain
HC_EAAU, HC_WEAK = 34.2, 0.0171  # crush modulus (0.342 MPa at 1 %) [MPa]; lateral and shear strength [MPa]


def sym(sig):
    """(6,) Voigt xx yy zz xy yz zx -> (3, 3)."""
    return np.array([[sig[0], sig[3], sig[5]], [sig[3], sig[1], sig[4]], [sig[5], sig[4], sig[2]]])


def one_step(g, x_mid, v, dt):
    """One force evaluation with the mid-step shape x_mid and velocity v:
    x(n+1) = x_mid + ½Δt·v. Returns the nodal forces (n, 3)."""
    st = SimpleNamespace(x=x_mid + 0.5 * dt * v, v=v, dt=dt, t=dt, f=np.zeros_like(x_mid))
    g.forces(st)
    return st.f


def distorted_block(seed=3):
    """2x2x2 block of 10 mm cubes with its interior node and the in-plane
    positions of the face nodes moved (outer faces stay planar)."""
    x, conn = brick_mesh(2, 2, 2, 10.0, 10.0, 10.0)
    rng = np.random.default_rng(seed)
    d = rng.uniform(-2.0, 2.0, x.shape)
    for k in range(3):  # nodes on a face of the block keep that coordinate
        d[np.isclose(x[:, k], 0.0) | np.isclose(x[:, k], 20.0), k] = 0.0
    return x + d, conn


def rotation(axis, angle):
    """Rotation matrix of ``angle`` [rad] about ``axis`` (Rodrigues)."""
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * k @ k
