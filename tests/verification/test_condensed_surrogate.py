"""The structure behind a cut condensed onto the cut nodes (a linear
superelement, ``vehicle.connection.condense`` / ``vehicle.connection.condensed``) against the
full model it replaces, in the time loop."""

import sys
from pathlib import Path

import numpy as np
import pytest

from crashlite import read_deck, write_deck
from crashlite.solver import run
from crashlite.vehicle.car.records import id_list, record
from crashlite.vehicle.connection.condense import relieved_condensation
from crashlite.vehicle.connection.condensed import build_condensed_surrogate
from crashlite.vehicle.steps.cut import cut_behind
from crashlite.vehicle.steps.massprops import replaced_mass

sys.path.insert(0, str(Path(__file__).parents[1] / "unit" / "vehicle"))
from _structures import shell_model, tube_mesh  # noqa: E402

sys.path.insert(0, str(Path(__file__).parent))
from _pushed_tube import END, B, L, T, X, pushed_tube  # noqa: E402


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """A free elastic tube pushed sideways at its front end by a step
    force: the full tube, and its front 200 mm with the rear 1000 mm
    condensed, quasi-statically and with its four lowest free modes (the
    condensation alone: no cut dashpots, which would damp the ringing that
    is compared)."""
    d = tmp_path_factory.mktemp("condensed")
    m, _ = pushed_tube()
    out = {"full": run(write_deck(m, d / "full.k")[0], out=d / "full", output_dt=END / 400)}
    cut = cut_behind(m, x=X)
    mass = replaced_mass(cut)
    for n in (0, 4):
        cond = relieved_condensation(cut, modes=n)
        deck = build_condensed_surrogate(cut, cond, mass, dashpots=False).write(d / f"modes{n}.k")
        out[n] = run(deck, out=d / f"modes{n}", output_dt=END / 400)
        out[f"cond{n}"] = cond
    out["dir"] = d
    return out


def test_modes_bring_the_condensed_tube_to_the_full_one(runs):
    """The tube's front swings 3.1 mm in 10 ms while its rear rings in its
    first bending mode (two of the four kept modes, one per plane). The
    quasi-static condensation follows the front and a point 100 mm ahead of
    the cut within 2 % of their largest excursion (measured 1.6 %); its
    four lowest free modes moving on their own (the rest as residual
    stiffness) bring it within 0.6 % (0.46 %), over three times closer. Energy is conserved to
    0.3 % in every run (a linear superelement stores ½uᵀKu; the step
    load's first cycles)."""
    full = runs["full"].node_displacement[:, :, 1]
    scale = np.abs(full).max(axis=0)
    err = {n: (np.abs(runs[n].node_displacement[:, :, 1] - full).max(axis=0) / scale).max() for n in (0, 4)}
    f = runs["cond4"].frequencies
    # free–free Euler–Bernoulli: (4.730²/2πL²)·√(EI/ρA) = 376 Hz; shear and the coarse ring a few % less
    assert f[:2] == pytest.approx([376.0, 376.0], rel=0.05)
    assert scale[0] > 3.0
    assert err[0] < 0.02 and err[4] < 0.006 and err[4] < err[0] / 3
    for k in ("full", 0, 4):
        assert np.abs(runs[k].energy_ratio[1:] - 1.0).max() < 3e-3


def test_condensed_surrogate_keeps_the_mass(runs):
    """The surrogate deck's point masses and shells plus its rear body
    (less the modal nodes' 1 g each, which it gives up) weigh what the
    full tube does."""
    full, sur = read_deck(runs["dir"] / "full.k"), read_deck(runs["dir"] / "modes4.k")
    body = sur.find("CONSTRAINED_NODAL_RIGID_BODY_INERTIA")[0]
    assert sur.mass_properties().mass + body["tm"] == pytest.approx(full.mass_properties().mass, rel=1e-9)


END_W, F_W = 5e-4, 10000.0  # s, N: the axial wave's window (its echo from the full tube's far end comes at 0.45 ms)


@pytest.fixture(scope="module")
def waves(tmp_path_factory):
    """The tube's front end pushed back along its axis by a step force:
    the full tube, and its front 200 mm condensed with and without the
    cut dashpots (``impedance``)."""
    d = tmp_path_factory.mktemp("waves")
    xyz, q = tube_mesh(B, L, 2, 96)
    m = shell_model(xyz, q, thickness=T, poisson=0.3)
    ids = m.nodes.ids
    front = np.flatnonzero(np.isclose(xyz[:, 0], L))
    m.sets[("NODE", 1)] = id_list("SET_NODE_LIST_TITLE", 1, ids[front], title="front")
    m.curves[1] = record("DEFINE_CURVE", lcid=1, rows={"a1": np.array([0.0, 1.0]), "o1": np.array([1.0, 1.0])})
    m.keywords += [
        record(
            "LOAD_NODE_SET",
            rows={
                "nsid": np.array([1]),
                "dof": np.array([1]),
                "lcid": np.array([1]),
                "sf": np.array([-F_W / len(front)]),
            },
        ),
        record("CONTROL_TERMINATION", endtim=END_W),
        record("DATABASE_HISTORY_NODE_ID", rows={"id": ids[front[:1]], "heading": np.array(["front"], object)}),
    ]
    out = {"full": run(write_deck(m, d / "full.k")[0], out=d / "full", output_dt=END_W / 200)}
    cut = cut_behind(m, x=X)
    cond, mass = relieved_condensation(cut), replaced_mass(cut)
    for damped in (False, True):
        deck = build_condensed_surrogate(cut, cond, mass, dashpots=damped).write(d / f"dashpots{damped}.k")
        out[damped] = run(deck, out=d / f"dashpots{damped}", output_dt=END_W / 200)
    return out


def test_cut_dashpots_let_the_wave_run_out(waves):
    """A step force F on the tube's front end starts a compression wave:
    until its echo from the far end returns (0.45 ms), the full tube's front
    moves at v = F/(ρ·c·A), c = √(E/ρ) the bar speed of a tube free to
    contract (its mean over 0.05–0.42 ms measured 1.000 v). The condensed
    tube's cut 200 mm behind the front sends the wave back after 0.074 ms
    (its nodes are light, held by the rear's static stiffness), and the
    front swings between −0.7 v and 3.5 v; with the cut dashpots most of
    the wave runs out: the front's velocity stays within 0.8 v of the full
    tube's where it strays 2.7 v without, its root-mean-square deviation
    over the window 0.37 v against 1.18 v (measured; bounds: under 0.6 and
    0.5 times). What remains is the rear body taking
    the load as a rigid body from the start, where the full tube's far part
    waits for the wave. The dashpots' work counts as internal energy: the
    balance holds to 1 % in every run from 0.05 ms on (a step load's first
    cycles miss a few % of its work as the time integration starts)."""
    v = F_W / (7.85e-9 * np.sqrt(210000.0 / 7.85e-9) * 4 * B * T)
    r = waves["full"]
    w = (r.time > 5e-5) & (r.time < 4.2e-4)
    full = -r.node_velocity[w, 0, 0]
    assert np.abs(full / v - 1.0).max() < 0.25 and full.mean() == pytest.approx(v, rel=0.02)
    dev = {}
    for k in ("full", False, True):
        assert np.abs(waves[k].energy_ratio[waves[k].time > 5e-5] - 1.0).max() < 0.01
        if k != "full":
            dev[k] = (-waves[k].node_velocity[w, 0, 0] - full) / v
    rms = {k: float(np.sqrt((d * d).mean())) for k, d in dev.items()}
    assert rms[True] < 0.5 * rms[False]
    assert np.abs(dev[True]).max() < 0.6 * np.abs(dev[False]).max()
