"""Smoke run of the generic car in the US NCAP load case (coarse mesh, the
first milliseconds): the deck runs, energy is conserved, the front
structure takes the load and the interface sections see it.

The full 56 km/h plausibility run (deceleration peak, dynamic crush) takes
minutes and is not part of the suite."""

import numpy as np
import pytest

from crashlite.solver import run
from crashlite.units import kmh
from crashlite.vehicle import generic_vehicle, usncap_deck

# s: about 120 mm of travel into the wall, past the first folds of the bumper beam (at 4 ms, its
# first fold, the hourglass energy is 13 % of a still small internal energy, with LS-DYNA's IHQ 4)
END = 0.008


@pytest.fixture(scope="module")
def crash(tmp_path_factory):
    d = tmp_path_factory.mktemp("usncap")
    v = generic_vehicle(38.0)
    car = v.write(d / "car.k")
    lc = usncap_deck(car, d / "usncap.k", end_time=END)
    return v, run(lc, output_dt=END / 40)


@pytest.mark.slow
def test_energy_is_conserved_and_hourglass_small(crash):
    v, r = crash
    ke0 = 0.5 * v.mass * 1e-3 * kmh(56.0) ** 2
    assert r.kinetic[0] == pytest.approx(ke0, rel=1e-3)
    assert np.all(np.abs(r.energy_ratio - 1.0) < 0.01)
    assert r.internal[-1] > 0.02 * ke0  # the structure is crushing
    assert r.hourglass[-1] < 0.1 * r.internal[-1]


@pytest.mark.slow
def test_front_structure_takes_the_load(crash):
    v, r = crash
    names = {pid: n for n, pid in v.part_ids.items()}
    ie = dict(zip((names[int(p)] for p in r.part_ids), r.part_internal[-1]))
    front = sum(ie.get(n, 0.0) for n in ("bumper beam", "crash box left", "crash box right"))
    assert front > 0.5 * sum(ie.values())
    f = r.wall_force[:, 0, 0]  # force of the car on the wall, +x
    assert f.min() >= 0.0 and f[len(f) // 2 :].mean() > 50e3
    ids = list(r.history_nodes)
    assert set(v.history.values()) <= set(ids)
    k = ids.index(v.history["rear seat left"])
    assert r.node_velocity[-1, k, 0] < kmh(56.0)  # the passenger cell has started to slow down
    sec = np.abs(r.section_force[:, :, 0]).max(axis=0)
    assert len(sec) == 11 and np.all(sec > 0.0)  # every interface assembly carries load
