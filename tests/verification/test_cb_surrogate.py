"""The structure behind a cut as a Craig–Bampton superelement with its mass
(``vehicle.connection.craig_bampton`` / ``cb_surrogate``) against the full
model it replaces, in the time loop (the superelement's mass matrix solved
as given: ``solver.consistent``)."""

import sys
from pathlib import Path

import numpy as np
import pytest

from crashlite import read_deck, write_deck
from crashlite.keyword.dmig import read_dmig
from crashlite.solver import run
from crashlite.vehicle.connection.cb_surrogate import build_cb_surrogate
from crashlite.vehicle.steps.cut import cut_behind
from crashlite.vehicle.steps.massprops import replaced_mass

sys.path.insert(0, str(Path(__file__).parent))
from _pushed_tube import END, L, X, pushed_tube  # noqa: E402


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """A free elastic tube pushed sideways at its front end by a step force:
    the full tube, and its front 200 mm with the rear 1000 mm a
    Craig–Bampton superelement on the cut and on one far-end node kept
    for output (a history node), without and with its four lowest held
    modes."""
    d = tmp_path_factory.mktemp("cb")
    m, order = pushed_tube((L, X + 100.0, 0.0))
    out = {"full": run(write_deck(m, d / "full.k")[0], out=d / "full", output_dt=END / 400)}
    out["order"] = order
    cut = cut_behind(m, x=X)
    mass = replaced_mass(cut)
    for n in (0, 4):
        sur = build_cb_surrogate(cut, mass, modes=n)
        out[f"sur{n}"] = sur
        out[f"deck{n}"] = sur.write(d / f"cb{n}.k")
        out[n] = run(out[f"deck{n}"], out=d / f"cb{n}", output_dt=END / 400)
    out["dir"] = d
    return out


def test_craig_bampton_tube_follows_the_full_one(runs):
    """The front swings 3.1 mm in 10 ms while the rear rings. The
    superelement's constraint modes alone (static response to the boundary,
    with the structure's mass through them) follow the front within 3.5 %
    of its largest excursion (measured 2.8 %); its four lowest held modes
    bring the front within 1.2 % (0.94 %), the point 100 mm ahead of the cut
    within 0.5 % (0.30 %) and the far end, kept behind the cut, within 1 %
    (0.49 %). Energy (kinetic with the mass matrix, ½uᵀKu) is conserved to
    0.3 % in every run."""

    def uy(r):  # front, near, far
        col = [int(np.flatnonzero(r.history_nodes == i)[0]) for i in runs["order"]]
        return r.node_displacement[:, col, 1]

    full = uy(runs["full"])
    scale = np.abs(full).max(axis=0)
    assert scale[0] > 3.0
    err = {n: np.abs(uy(runs[n]) - full).max(axis=0) / scale for n in (0, 4)}
    assert err[0][0] < 0.035
    assert err[4][0] < 0.012 and err[4][1] < 0.005 and err[4][2] < 0.01
    assert err[4][0] < 0.5 * err[0][0]
    for k in ("full", 0, 4):
        assert np.abs(runs[k].energy_ratio[1:] - 1.0).max() < 3e-3


def test_craig_bampton_deck_keeps_the_mass_and_the_step(runs):
    """The surrogate deck's shells plus the superelement's mass matrix,
    moved rigidly, weigh what the full tube does (to 1e-8: read back from
    the DMIG file's large fields, 2e-9 measured); the run's step is the full tube's (the reduced model's
    frequencies lie within the full model's)."""
    full, sur = read_deck(runs["dir"] / "full.k"), read_deck(runs["deck4"])
    mats = read_dmig(runs["dir"] / "cb4.dmig")
    dofs, mm = mats["MCUT"]
    modal = np.isin(dofs[:, 0], runs["sur4"].node_ids["modes"])
    rigid_x = ((dofs[:, 1] == 1) & ~modal).astype(float)  # the modes stay at rest in a rigid translation
    assert sur.mass_properties().mass + rigid_x @ mm @ rigid_x == pytest.approx(full.mass_properties().mass, rel=1e-8)
    assert runs[4].time_step[1] >= runs["full"].time_step[1] * (1 - 1e-9)
