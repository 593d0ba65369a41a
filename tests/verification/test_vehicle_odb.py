"""The generic car against the simplified ODB (Euro NCAP, 40 %, 64 km/h):
the car's front pushes the barrier's soft face in instead of passing
through it."""

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.solver import run
from crashlite.vehicle import generic_vehicle, odb_deck


@pytest.mark.slow
def test_car_crushes_the_simplified_barrier_face(tmp_path):
    """60 mm car, first 12 ms: the barrier's cladding is 1000 times softer
    than steel, so the vehicle-to-barrier contact is a soft constraint
    (SOFT = 1; a penalty from the cladding's modulus let the car pass
    through with 23 kN). The barrier face under the car is pushed in by
    more than 50 mm, the contact carries more than 100 kN, the car's lost
    kinetic energy is found as internal energy, total energy within 1 %."""
    car = generic_vehicle(60.0).write(tmp_path / "car.k")
    deck = odb_deck(car, tmp_path / "odb.k", barrier="simplified", end_time=0.012)
    r = run(deck)
    m = read_deck(deck)
    barrier = np.isin(m.nodes.ids, read_deck(tmp_path / "odb_barrier.k").nodes.ids)
    pushed = r.final_x[barrier, 0] - m.nodes.xyz[barrier, 0]
    assert pushed.max() > 50.0
    assert np.abs(r.contact_force).max() > 100e3
    assert np.all(np.abs(r.energy_ratio - 1.0) < 0.01)
    lost = r.kinetic[0] - r.kinetic[-1]
    assert lost > 0.0 and r.internal[-1] == pytest.approx(lost, rel=0.1)
