"""Public LS-DYNA decks with LS-DYNA's own answers, run unchanged by crashlite.

Each case names the public repository and commit its deck comes from, the
deck, the parameters LS-DYNA ran it with (a *PARAMETER override, the way
the study that produced the answers wrote them), and LS-DYNA's figures with
where they were published. The decks are not redistributed: ``fetch.sh``
clones them into ``tests/parity/data/`` (or point CRASHLITE_PARITY_DATA at
a folder holding ``owner+name`` clones).

Quantities of the small car (what the study read from LS-DYNA's binout,
what crashlite reads from its Results):
  fmax  largest x force on rigid wall 2 (the pole), in magnitude [N]
  dmax  final x displacement of history node 605 (body, rear centre) [mm]
  vfin  final matsum x rigid-body velocity of part 1 (body) [mm/s]
  IE    final glstat internal energy [N·mm]
Of the shell cantilever (LS-DYNA's own glstat, nodout and d3hsp beside the
deck; kg, mm, ms, kN):
  KE, IE, EW  final kinetic, internal energy, external work [J]
  uz5, ux5    final z, x displacement of the tip node 5 [mm]
  cycles      cycles to the end time
Of the single solid under 50 % compression (LS-DYNA's binout beside the
deck; kg, mm, ms, kN):
  IE, EW      final internal energy, external work [J]
  Fz          secforc z force of the loaded face at LS-DYNA's last secforc
              output (9.99 ms) [kN], tension positive
  cycles      cycles to the end time
LS-DYNA's last glstat kinetic energy (104 J at 10 ms, against 8.5e-9 J one
output earlier) is left out: the prescribed motion's curve ends there.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent
GSA_REPO = "dbrizard/GSA-car-crash"
GSA_COMMIT = "477fb0578b764fb8dd630608b18d0b808b1fc12a"
GSA_DECK = "lsopt_car6_v3/car6_crash_v223.k"
# *PARAMETER of the nominal design (lsopt_car6_v3/main_v223.k)
GSA_NOMINAL = {
    "tbumper": 3.0,
    "trailb": 2.0,
    "trailf": 5.0,
    "yrailb": 400.0,
    "tgrill": 1.0,
    "thood": 1.0,
    "ybumper": 400.0,
    "yrailf": 400.0,
    "ybody": 400.0,
}


@dataclass
class Case:
    name: str
    repo: str
    commit: str
    deck: str  # the included model, relative to the repository
    parameters: dict  # *PARAMETER values of the main deck LS-DYNA ran
    reference: dict  # quantity -> LS-DYNA's value
    source: str  # where LS-DYNA's figures were published
    spread: dict = field(default_factory=dict)  # quantity -> relative scatter of LS-DYNA's own repeated runs
    measure: Callable | None = None  # Results -> {quantity: value}; None: the small car's (measure)
    bounds: dict = field(default_factory=lambda: {"IE": 0.05, "dmax": 0.05, "fmax": 0.10})  # issue 29's
    d3plot: str | None = None  # folder (relative to the repository) of LS-DYNA's d3plot of this deck
    field_bounds: dict = field(default_factory=lambda: dict(FIELD_BOUNDS))  # [%], see field_deviation
    known: dict = field(default_factory=dict)  # quantity -> why crashlite is known to miss its bound
    # keywords (prefixes) whose warning the case expects: each says what crashlite runs in its place
    warned: tuple = ()


def data_root() -> Path:
    return Path(os.environ.get("CRASHLITE_PARITY_DATA", HERE / "data"))


def repo_dir(case: Case) -> Path:
    return data_root() / case.repo.replace("/", "+")


def available(case: Case) -> bool:
    return (repo_dir(case) / case.deck).is_file()


def main_deck(case: Case, folder: Path) -> Path:
    """The main deck as the study wrote it: *PARAMETER (R fields) and an
    *INCLUDE of the model, unchanged; a case without parameters runs its
    deck itself."""
    if case.parameters is None:
        return repo_dir(case) / case.deck
    lines = ["*KEYWORD", "*PARAMETER"]
    for k, v in case.parameters.items():
        lines.append(f"R{k:>9}{v:>10.6g}")
    lines += ["*INCLUDE", str(repo_dir(case) / case.deck), "*END"]
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{case.name}.k"
    path.write_text("\n".join(lines) + "\n")
    return path


def measured(case: Case, res) -> dict:
    """The case's quantities from crashlite Results."""
    return (case.measure or measure)(res)


def measure(res) -> dict:
    """The small car's quantities from crashlite Results (see the module docstring)."""
    wall = list(res.wall_ids).index(2)
    node = list(res.history_nodes).index(605)
    part = list(res.part_ids).index(1)
    # LS-DYNA's rwforc x force of the pole is positive (the study takes its largest value), crashlite
    # writes the nodes' force on the wall (negative here): the peak magnitude is compared
    return {
        "fmax": float(np.max(np.abs(res.wall_force[:, wall, 0]))),
        "dmax": float(res.node_displacement[-1, node, 0]),
        "vfin": float(res.part_rigid_velocity[-1, part, 0]),
        "IE": float(res.internal[-1]),
    }


def _lhs(n: int) -> list[Case]:
    """LS-DYNA's answers for the first ``n`` designs of the study's 200-point
    Latin hypercube over (tbumper, trailb, trailf, yrailf)."""
    root = data_root() / GSA_REPO.replace("/", "+") / "LHS" / "4param"
    if not (root / "LHS-200_X.csv").is_file():
        return []
    x = np.loadtxt(root / "LHS-200_X.csv", delimiter=",", ndmin=2)
    y = {q: np.loadtxt(root / f"LHS-200_Y_{q}.csv", ndmin=1) for q in ("fmax", "dmax", "vfin", "IE")}
    out = []
    for i in range(min(n, len(x))):
        p = dict(GSA_NOMINAL, tbumper=x[i, 0], trailb=x[i, 1], trailf=x[i, 2], yrailf=x[i, 3])
        out.append(
            Case(
                f"gsa-car-lhs{i:03d}",
                GSA_REPO,
                GSA_COMMIT,
                GSA_DECK,
                p,
                {q: float(y[q][i]) for q in y},
                "LHS/4param/LHS-200_{X,Y_*}.csv, row %d" % i,
            )
        )
    return out


def cases(lhs: int = 5) -> list[Case]:
    """The parity set: the nominal small car against a pole (LS-DYNA R10.1,
    five repeated runs, their mean and scatter), and ``lhs`` designs of the
    study's Latin hypercube."""
    runs = {
        "fmax": [772836.8, 775579.75, 772913.4, 770100.4, 773196.4],
        "dmax": [-641.87, -643.65, -642.13, -643.91, -642.20],
        "vfin": [-710.95, -716.19, -693.02, -730.54, -706.61],
        "IE": [1.20394832e8, 1.2032208e8, 1.20379344e8, 1.2035144e8, 1.20424064e8],
    }
    nominal = Case(
        "gsa-car-nominal",
        GSA_REPO,
        GSA_COMMIT,
        GSA_DECK,
        dict(GSA_NOMINAL),
        {q: float(np.mean(v)) for q, v in runs.items()},
        "lsopt_car6_v3/MODIFICATIONS_LOG.md, 'base design output 2024-05-03' (5 runs)",
        {q: float(np.ptp(v) / abs(np.mean(v))) for q, v in runs.items()},
    )
    return [nominal] + _lhs(lhs) + _cantilevers() + [_cube(), _plate(), _hat()]


TUG_REPO = "scheckmate/test_fe_simulation"
TUG_COMMIT = "c68038116845f02a3ba27f8d9bd378396140174d"
CANTILEVER_BOUNDS = {"KE": 0.05, "IE": 0.05, "EW": 0.05, "uz5": 0.05, "ux5": 0.05, "cycles": 0.05}


def measure_cantilever(res) -> dict:
    """The cantilever's quantities from crashlite Results."""
    k = list(res.history_nodes).index(5)
    return {
        "KE": float(res.kinetic[-1]),
        "IE": float(res.internal[-1]),
        "EW": float(res.external[-1]),
        "uz5": float(res.node_displacement[-1, k, 2]),
        "ux5": float(res.node_displacement[-1, k, 0]),
        "cycles": float(res.cycles),
    }


def lsdyna_cantilever(folder: Path) -> dict:
    """LS-DYNA's figures from its own output beside the deck: glstat's last
    state, nodout's tip node (where written) and d3hsp's cycle count."""
    from crashlite.results.lsdyna_ascii import read_folder

    out = read_folder(folder)
    g = out["glstat"]
    ref = {
        "KE": float(g["kinetic_energy"][-1]),
        "IE": float(g["internal_energy"][-1]),
        "EW": float(g["external_work"][-1]),
    }
    if "nodout" in out:
        n = out["nodout"]
        k = list(n["ids"]).index(5)
        ref.update(uz5=float(n["z_displacement"][-1, k]), ux5=float(n["x_displacement"][-1, k]))
    ref["cycles"] = d3hsp_cycles(folder)
    return ref


def d3hsp_cycles(folder: Path) -> float:
    """The cycle count of LS-DYNA's d3hsp in ``folder`` (its closing "... for N cycles")."""
    return float(re.findall(r"for\s+(\d+)\s+cycles", (folder / "d3hsp").read_text(errors="replace"))[-1])


def _cantilevers() -> list[Case]:
    """TU Graz's shell cantilever (a 300 × 30 mm strip of 90 Belytschko–Tsay
    shells, MAT_024, gravity and a tip load, 10 ms; LS-DYNA R10.1 SMP single
    precision), 1 mm with 3 integration points and 2 mm with 5."""
    out = []
    for name, sub in (("tug-shell-t1-nip3", "T1_NIP3"), ("tug-shell-t2-nip5", "T2_NIP5")):
        case = Case(
            name,
            TUG_REPO,
            TUG_COMMIT,
            f"Element_Types/01_Shell/{sub}/01_Shell.dyn",
            None,
            {},
            f"Element_Types/01_Shell/{sub}/{{glstat,nodout,d3hsp,d3plot}}",
            measure=measure_cantilever,
            bounds=dict(CANTILEVER_BOUNDS),
            d3plot=f"Element_Types/01_Shell/{sub}",
        )
        if available(case):
            case.reference = lsdyna_cantilever((repo_dir(case) / case.deck).parent)
            case.bounds = {q: b for q, b in case.bounds.items() if q in case.reference}
        out.append(case)
    return out


def field_deviation(lsdyna: Path, crashlite: Path) -> dict:
    """Whole-field deviation of crashlite's d3plot from LS-DYNA's, both read
    through crashlite's d3plot reader and lasso-python [%]:
      u_field       largest displacement difference of any node at any of
                    LS-DYNA's states (crashlite's interpolated to its time),
                    against the largest displacement of any node and state
      stress_field  largest difference of any shell stress component at any
                    of the three layers LS-DYNA writes (mid, inner, outer) at
                    the last state, against the largest stress there
    Nodes and shells are matched by ID."""
    from lasso.dyna import ArrayType, D3plot

    from crashlite.verify.fields import compare_fields, load_states

    ref, got = load_states(lsdyna), load_states(crashlite)
    states = [compare_fields(ref, got, float(min(t, got.time[-1]))).figures for t in ref.time[1:]]
    u = 100 * max(f["max_difference"] for f in states) / max(f["max_displacement_ref"] for f in states)
    sig = []
    for folder in (lsdyna, crashlite):
        a = D3plot(str(folder / "d3plot")).arrays
        order = np.argsort(a[ArrayType.element_shell_ids])
        sig.append(np.asarray(a[ArrayType.element_shell_stress][-1], float)[order])
    return {"u_field": float(u), "stress_field": float(100 * np.abs(sig[1] - sig[0]).max() / np.abs(sig[0]).max())}


FIELD_BOUNDS = {"u_field": 1.0, "stress_field": 1.0}  # [%] of the largest displacement, stress


CUBE_BOUNDS = {"IE": 0.05, "EW": 0.05, "Fz": 0.05, "cycles": 0.05}
CUBE_FZ_TIME = 9.99014378  # LS-DYNA's last secforc output [ms]


def measure_cube(res) -> dict:
    """The compressed cube's quantities from crashlite Results."""
    fz = float(np.interp(CUBE_FZ_TIME, res.time, res.section_force[:, 0, 2]))
    return {"IE": float(res.internal[-1]), "EW": float(res.external[-1]), "Fz": fz, "cycles": float(res.cycles)}


def lsdyna_cube(binout: Path) -> dict:
    """LS-DYNA's figures from its binout (lasso-python through crashlite.results)."""
    from crashlite.results import load

    h = load(binout)
    fz = np.asarray(h.read("secforc", "z_force"), float).ravel()
    ts = np.asarray(h.read("secforc", "time"), float)
    return {
        "IE": float(h.read("glstat", "internal_energy")[-1]),
        "EW": float(h.read("glstat", "external_work")[-1]),
        "Fz": float(np.interp(CUBE_FZ_TIME, ts, fz)),
        "cycles": float(h.read("glstat", "cycle")[-1]),
    }


def _cube() -> Case:
    """TU Graz's single-element material test: a 1 mm *MAT_ELASTIC cube
    (ν = 0.49, ELFORM 1) pressed to half its height in 10 ms by a
    *BOUNDARY_PRESCRIBED_MOTION_SET on its top face, with a
    *DATABASE_CROSS_SECTION_SET through that face (LS-DYNA R10.1 SMP; its
    binout at the repository root holds glstat, nodout, secforc, elout and
    curvout of exactly this deck's requests)."""
    case = Case(
        "tug-solid-cube",
        TUG_REPO,
        TUG_COMMIT,
        "Exercise 1/cube_complete.key",
        None,
        {},
        "binout (repository root): glstat, secforc",
        measure=measure_cube,
        bounds=dict(CUBE_BOUNDS),
    )
    binout = repo_dir(case) / "binout"
    if available(case) and binout.is_file():  # lasso-python reads it (in the test extra)
        case.reference = lsdyna_cube(binout)
    return case


UQ_REPO = "chiaraf10/uqpy_test"
UQ_COMMIT = "46f7206dd52c1d60e83e1abc8d81b9a2193bb3f4"
UQ_FOLDER = "dyna_test_2023_03_08_01_53_113621/run_0/InputFiles"


def lsdyna_plate(folder: Path) -> dict:
    """LS-DYNA's figures of the swinging plate: the largest internal energy
    of its d3plot states (every 1 ms) and d3hsp's cycle count."""
    from lasso.dyna import ArrayType, D3plot

    a = D3plot(str(folder / "d3plot")).arrays
    return {"IEmax": float(np.max(a[ArrayType.global_internal_energy])), "cycles": d3hsp_cycles(folder)}


def measure_plate(res) -> dict:
    """The swinging plate's quantities from crashlite Results (the internal
    energy taken, as LS-DYNA's, at the 1 ms states)."""
    states = np.arange(0.0, res.time[-1] + 1e-9, 1.0)
    return {"IEmax": float(np.interp(states, res.time, res.internal).max()), "cycles": float(res.cycles)}


def _plate() -> Case:
    """A 200 × 20 mm elastic steel strip of 75 fully integrated shells
    (ELFORM 16, 0.833 mm, NIP 3) held at one end by four
    *BOUNDARY_SPC_NODE_BIRTH_DEATH_ID cards, its other end's nodes driven
    by a prescribed z acceleration for 10 ms (four motions as ID/data pairs
    under one *BOUNDARY_PRESCRIBED_MOTION_NODE_ID, the last one's fields
    shifted so that LS-DYNA reads BIRTH = 38 ms, the end time: it never
    acts), then swinging free to 38 ms; kg, mm, ms, GPa. LS-DYNA R11.1 SMP
    single precision, its d3plot (every 1 ms) and d3hsp beside the deck."""
    case = Case(
        "uq-plate-elform16",
        UQ_REPO,
        UQ_COMMIT,
        f"{UQ_FOLDER}/run_0.k",
        None,
        {},
        f"{UQ_FOLDER}/{{d3plot,d3plot01,d3plot02,d3hsp}}",
        measure=measure_plate,
        bounds={"IEmax": 0.05, "cycles": 0.05},
        d3plot=UQ_FOLDER,
        # the stresses at the last state, after 28 ms of free swing, against single-precision output
        field_bounds={"u_field": 1.0, "stress_field": 2.0},
    )
    if available(case):
        case.reference = lsdyna_plate(repo_dir(case) / UQ_FOLDER)
    return case


HAT_REPO = "Renumics/mesh2vec"
HAT_COMMIT = "01f717ea5896da09dc6078d24e697e2836dfc315"
HAT_END = 1.5  # *CONTROL_TERMINATION [ms]
HAT_BOUNDS = {"cycles": 0.05, "eps_max": 0.10, "zmax0": 1e-6}


def lsdyna_hat(folder: Path) -> dict:
    """LS-DYNA's figures of the hat profile from its binout (elout of the
    history shells: plastic strain at every integration point, with the
    cycle of each output) and its d3plot's geometry (the coordinates
    LS-DYNA set up, after *PART_MOVE)."""
    from lasso.dyna import ArrayType, Binout, D3plot

    b = Binout(str(folder / "HAT.binout0000"))
    ids = np.asarray(b.read("eloutdet", "shell", "ids"))[-1]
    eps = np.asarray(b.read("eloutdet", "shell", "plastic_strain"), float)
    eps = eps[-1].reshape(len(ids), -1).max(axis=1)  # the largest over each shell's points
    t = np.asarray(b.read("eloutdet", "shell", "time"), float)
    cyc = np.asarray(b.read("eloutdet", "shell", "cycle"), float)
    x = D3plot(str(folder / "HAT.d3plot")).arrays[ArrayType.node_coordinates]
    return {
        # the last output is 0.45 µs before the end time: the cycles left at the last outputs' step
        "cycles": float(cyc[-1] + (HAT_END - t[-1]) * (cyc[-1] - cyc[-2]) / (t[-1] - t[-2])),
        "eps_max": float(eps.max()),
        "zmax0": float(x[:, 2].max()),
    }


def measure_hat(res) -> dict:
    """The hat profile's quantities from crashlite Results: cycles, the
    largest effective plastic strain over LS-DYNA's history shells (the
    largest over each shell's points), the highest initial z (the top of
    the impactor, moved 30 mm by *PART_MOVE)."""
    rows = np.searchsorted(res.shell_ids, HAT_HISTORY_SHELLS)
    return {
        "cycles": float(res.cycles),
        "eps_max": float(res.shell_plastic_strain[rows].max()),
        "zmax0": float(res.states_x[0][:, 2].max()),
    }


HAT_HISTORY_SHELLS = [1002198] + list(range(4700000, 4700020))  # *DATABASE_HISTORY_SHELL(_SET) of the deck


def _hat() -> Case:
    """A hat profile closed by a sheet, 500 mm long, hit at mid-span by a
    rigid 5 kg cylinder at 20 m/s on two rigid cylindrical supports (a
    three-point bending crash test, 1.5 ms): 6 400 fully integrated shells
    (ELFORM 16, NIP 5) of *MAT_PLASTICITY_WITH_DAMAGE with a strain-rate
    *DEFINE_TABLE, the profile's flanges tied to the sheet across a 2 mm gap
    (*CONTACT_TIED_SHELL_EDGE_TO_SURFACE_BEAM_OFFSET), part-based contact
    thickness (*PART_CONTACT OPTT 2 mm), *CONTACT_AUTOMATIC_SINGLE_SURFACE
    of every part with SOFT 1, the impactor placed by *PART_MOVE and given
    its speed by *INITIAL_VELOCITY_RIGID_BODY and its mass by
    *ELEMENT_MASS_PART; kg, mm, ms, GPa. Its binout holds LS-DYNA's elout of
    21 history shells (every 0.1 ms with the cycle); its d3plot holds the
    set-up geometry only (the states' file is not in the repository)."""
    case = Case(
        "mesh2vec-hat",
        HAT_REPO,
        HAT_COMMIT,
        "data/hat/Hatprofile.k",
        None,
        {},
        "data/hat/{HAT.binout0000 (elout), HAT.d3plot (geometry)}",
        measure=measure_hat,
        bounds=dict(HAT_BOUNDS),
        # ISTUPD 4, IHQ 8 (of the part cards) and the shells' bulk viscosity (TYPE -1) run as crashlite runs
        # them: each says how
        warned=(
            "CONTROL_ACCURACY",
            "CONTROL_SOLUTION",
            "CONTROL_BULK_VISCOSITY",
            "CONTACT_TIED_SHELL_EDGE_TO_SURFACE",
            "CONTROL_SHELL",
            "PART",
        ),
    )
    if available(case):
        case.reference = lsdyna_hat(repo_dir(case) / "data" / "hat")
    return case
