"""A real LS-DYNA binout (R12.2.1, lasso-python's test data) read through
lasso-python by ``crashlite.results.load`` and compared by ``crashlite
compare`` (the ``lsdyna`` extra)."""

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("lasso.dyna", reason="reading a binout needs lasso-python: pip install crashlite[lsdyna]")

from crashlite.results import load  # noqa: E402
from crashlite.results.lsdyna_ascii import glstat, matsum  # noqa: E402
from crashlite.verify.compare import compare_paths  # noqa: E402

RUN = Path(__file__).parents[2] / "data" / "lsdyna_r12_sph"


def test_glstat_of_a_binout_balances_as_lsdyna_wrote_it():
    """Each energy in its own column: LS-DYNA's total energy is the sum of
    kinetic, internal, sliding, hourglass, stonewall, spring/damper and
    damping energies (to single precision), and the last output is within
    the run's cycles (d3hsp: 640)."""
    h = load(RUN)
    g = {
        q: np.asarray(h.read("glstat", q), float)
        for q in (
            "time",
            "cycle",
            "kinetic_energy",
            "internal_energy",
            "sliding_interface_energy",
            "hourglass_energy",
            "stonewall_energy",
            "spring_and_damper_energy",
            "system_damping_energy",
            "total_energy",
        )
    }
    parts = sum(
        g[q]
        for q in (
            "kinetic_energy",
            "internal_energy",
            "sliding_interface_energy",
            "hourglass_energy",
            "stonewall_energy",
            "spring_and_damper_energy",
            "system_damping_energy",
        )
    )
    assert g["total_energy"].max() > 1.0
    np.testing.assert_allclose(parts, g["total_energy"], rtol=0, atol=1e-6 * g["total_energy"].max())
    cycles = int((RUN / "d3hsp").read_text(errors="replace").split("Problem cycle      =")[1].split()[0])
    assert cycles == 640 and 0.95 * cycles <= g["cycle"][-1] <= cycles
    assert np.all(np.diff(g["time"]) > 0)
    assert np.asarray(h.read("matsum", "ids")).tolist() == [1, 101]


def test_compare_a_binout_with_its_ascii_translation(tmp_path):
    """``compare`` of the binout folder against glstat and matsum written
    from it by crashlite's LS-DYNA ASCII writers: every energy and part pair
    is found (part 1 stores no internal energy) and agrees to the files'
    five significant digits."""
    h = load(RUN)
    out = tmp_path / "ascii"
    out.mkdir()
    glstat.write(
        out / "glstat",
        {
            k: np.asarray(h.read("glstat", k))
            for k in h.read("glstat")
            if k
            in (
                "time",
                "kinetic_energy",
                "internal_energy",
                "total_energy",
                "sliding_interface_energy",
                "hourglass_energy",
                "external_work",
                "time_step",
                "energy_ratio",
                "stonewall_energy",
                "spring_and_damper_energy",
                "system_damping_energy",
            )
        },
    )
    matsum.write(
        out / "matsum",
        {
            k: np.asarray(h.read("matsum", k))
            for k in h.read("matsum")
            if k
            in (
                "time",
                "ids",
                "internal_energy",
                "kinetic_energy",
                "hourglass_energy",
                "x_momentum",
                "y_momentum",
                "z_momentum",
                "x_rbvelocity",
                "y_rbvelocity",
                "z_rbvelocity",
            )
        },
    )
    c = compare_paths(RUN, out)
    groups = {p.group for p in c.pairs}
    assert {"energy", "part"} <= groups
    assert len(c.group("energy")) >= 3 and [p.name for p in c.group("part")] == ["part 101 internal energy"]
    for p in c.pairs:
        dev = p.deviation["peak_deviation_percent"]
        assert dev is None or abs(dev) < 1e-2, (p.name, dev)
        if p.rating is not None:
            assert p.rating.overall > 0.999, p.name
