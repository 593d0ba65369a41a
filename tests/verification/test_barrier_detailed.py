"""The detailed reference ODB (honeycomb solids, MAT_026): crush force."""

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.barrier import ODBSpec, Placement
from crashlite.barrier.detailed import detailed_barrier
from crashlite.barrier.loadcases import Impactor, write_impactor_case
from crashlite.solver import run


def test_detailed_main_block_crushes_on_its_honeycomb_curve(tmp_path):
    """Coarse main block of MAT_026 solids crushed by a 5 t wall at 5 m/s:
    the force is the honeycomb's crush stress × face area (the paper's
    230 kN; R94: 0.342 MPa × 0.65 m² = 222 kN, within 5 %), the energy
    is conserved, hourglass energy stays small."""
    pl = Placement()
    b = detailed_barrier(placement=pl, element_size=75.0, bumper=False)
    m = read_deck(b.write(tmp_path / "det.k"))
    assert len(m.solids) == b.solids > 0
    assert m.mass_properties().mass == pytest.approx(ODBSpec().main.mass, rel=1e-9)
    main = write_impactor_case(tmp_path, b, pl, Impactor(mass=5.0, speed=5000.0), end_time=0.02)
    r = run(main, output_dt=2e-4)
    f = -r.wall_force[:, 0, 0]
    plateau = np.median(f[r.time > 0.002])
    spec = ODBSpec()
    assert plateau == pytest.approx(spec.main.curve.plateau, rel=0.02)
    assert plateau == pytest.approx(spec.main.strength * spec.main.area, rel=0.05)
    assert np.all(np.abs(r.energy_ratio - 1.0) < 0.01)
    assert r.hourglass.max() < 0.1 * r.internal.max()
