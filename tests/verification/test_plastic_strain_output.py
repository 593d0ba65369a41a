"""The effective plastic strain every shell and solid ends a run with
(results.npz ``shell_plastic_strain``, ``solid_plastic_strain``): a strip
and a bar of linearly hardening steel stretched slowly in uniaxial tension
end with the εp = (σ − σy)/H of the stress that the stretch gives, an
element that stays elastic with 0; the vehicle interface reads it by
element ID."""

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.solver import run
from crashlite.vehicle.connection.interface import shell_plastic_strain

E, SY, ET, L = 200000.0, 200.0, 2000.0, 100.0
H = E * ET / (E - ET)  # plastic hardening modulus
END, RAMP = 2e-3, 5e-4  # s: 1.75 mm at up to 1 m/s (ramped in), about 100 wave transits: quasi-static


def _strip(tmp_path, solid: bool) -> str:
    """Four elements in a row, 100 mm long; the left end held along x, the
    right end pulled at up to 1 m/s; the last element of the row is of a steel
    twice as strong (part 2), so it stays elastic while the others yield."""
    lines = ["*KEYWORD", "*NODE"]
    xs = np.linspace(0.0, L, 5)
    corners = [(0.0, 0.0), (0.0, 10.0)] + ([(10.0, 0.0), (10.0, 10.0)] if solid else [])
    nid = {}
    for i, x in enumerate(xs):
        for j, (z, y) in enumerate(corners):
            nid[i, j] = 1 + i * len(corners) + j
            lines.append(f"{nid[i, j]},{float(x)!r},{y!r},{z!r}")
    held = [nid[0, j] for j in range(len(corners))]
    pulled = [nid[4, j] for j in range(len(corners))]
    if solid:
        lines += ["*ELEMENT_SOLID"] + [
            f"{100 + i},{1 + i // 3},"
            + ",".join(
                str(nid[k, j])
                for k, j in ((i, 0), (i + 1, 0), (i + 1, 1), (i, 1), (i, 2), (i + 1, 2), (i + 1, 3), (i, 3))
            )
            for i in range(4)
        ]
        lines += ["*PART", "bar", "1,1,1", "*PART", "strong", "2,1,2", "*SECTION_SOLID", "1,1"]
    else:
        lines += ["*ELEMENT_SHELL"] + [
            f"{100 + i},{1 + i // 3},{nid[i, 0]},{nid[i + 1, 0]},{nid[i + 1, 1]},{nid[i, 1]}" for i in range(4)
        ]
        lines += [
            "*PART",
            "strip",
            "1,1,1",
            "*PART",
            "strong",
            "2,1,2",
            "*SECTION_SHELL",
            "1,2,1.0,3",
            "1.0,1.0,1.0,1.0",
        ]
    for mid, sy in ((1, SY), (2, 2 * SY)):  # *MAT_PIECEWISE_LINEAR_PLASTICITY with ETAN
        lines += ["*MAT_PIECEWISE_LINEAR_PLASTICITY", f"{mid},7.85e-9,{E!r},0.3,{sy!r},{ET!r}", "0.0,0.0", "", ""]
    lines += [
        "*SET_NODE_LIST",
        "1",
        *[",".join(map(str, held))],
        "*SET_NODE_LIST",
        "2",
        *[",".join(map(str, pulled))],
        "*BOUNDARY_SPC_SET",
        "1,0,1,0,0,0,0,0",
        "*BOUNDARY_SPC_NODE",
        f"{nid[0, 0]},0,0,1,1,0,0,0",
        "*DEFINE_CURVE",
        "5",
        "0.0,0.0",
        f"{RAMP!r},1000.0",
        "1.0,1000.0",
        "*BOUNDARY_PRESCRIBED_MOTION_SET",
        "2,1,0,5,1.0",
        "*CONTROL_TERMINATION",
        repr(END),
        "*DATABASE_BINARY_D3PLOT",
        repr(END / 2),
    ]
    # one solid through the section: its corner nodes carry 1/8 of an element, and the bulk mode of
    # such a bar is unstable at 0.9 x V/A_max / c for ν = 0.3 (critical factor 0.73)
    lines += ["*CONTROL_TIMESTEP", "0.0,0.7", "*END"] if solid else ["*END"]
    p = tmp_path / ("bar.k" if solid else "strip.k")
    p.write_text("\n".join(lines) + "\n")
    return str(p)


@pytest.mark.parametrize("solid", [False, True], ids=["shells", "solids"])
def test_uniaxial_tension_ends_with_the_plastic_strain(tmp_path, solid):
    deck = _strip(tmp_path, solid)
    r = run(deck, out=tmp_path / "run", quiet=True)
    kind = "solid" if solid else "shell"
    ids, eps = getattr(r, f"{kind}_ids"), getattr(r, f"{kind}_plastic_strain")
    assert ids.tolist() == [100, 101, 102, 103]
    # one stress σ all along: the strong element stretches by σ/E, the others by σ/E + (σ − σy)/H
    stretch = (END - 0.5 * RAMP) * 1000.0
    sigma = (stretch / L + 0.75 * SY / H) / (1.0 / E + 0.75 / H)
    # each within 5 % (the elastic neighbour holds back the lateral contraction of the element beside it)
    assert eps[:3] == pytest.approx((sigma - SY) / H, rel=0.05)
    assert eps[:3].mean() == pytest.approx((sigma - SY) / H, rel=0.02)
    assert eps[3] == 0.0
    saved = np.load(tmp_path / "run" / "results.npz")
    assert np.array_equal(saved[f"{kind}_plastic_strain"], eps)
    # and the internal energy each ends with: elastic σ²/2E plus the plastic work (σy + σ)/2 · εp per
    # volume, summing to the run's internal energy
    energy = getattr(r, f"{kind}_internal_energy")
    volume = L / 4 * 10.0 * (10.0 if solid else 1.0)
    plastic = (SY + sigma) / 2 * (sigma - SY) / H
    assert energy[:3] == pytest.approx(volume * (sigma**2 / (2 * E) + plastic), rel=0.05)
    assert energy[3] == pytest.approx(volume * sigma**2 / (2 * E), rel=0.1)
    assert energy.sum() == pytest.approx(r.internal[-1], rel=1e-9)
    assert np.array_equal(saved[f"{kind}_internal_energy"], energy)
    if not solid:
        assert shell_plastic_strain(read_deck(deck), tmp_path / "run") == pytest.approx(eps)
    # the last field state for ParaView carries it as cell data
    lines = sorted((tmp_path / "run" / "states").glob("state_*.vtk"))[-1].read_text().splitlines()
    k = lines.index("SCALARS plastic_strain double 1")
    assert [float(c) for c in lines[k + 2 : k + 6]] == pytest.approx(eps.tolist(), rel=1e-8)


def test_passenger_cell_summary_takes_the_cell_assemblies_only(tmp_path):
    """The strip's yielding part as an assembly of the cell ("floor left"),
    its strong part as one outside it: the cell summary rates the first
    only, by the strains of the run."""
    from crashlite.vehicle.connection.interface import assembly_parts, cell_plastic_strain, part_plastic_strain

    deck = _strip(tmp_path, False)
    text = (
        open(deck)
        .read()
        .replace(
            "*END",
            "*SET_PART_LIST_TITLE\nassembly floor left\n11\n1\n"
            "*SET_PART_LIST_TITLE\nassembly engine and gearbox\n12\n2\n*END",
        )
    )
    open(deck, "w").write(text)
    r = run(deck, out=tmp_path / "run", quiet=True)
    model = read_deck(deck)
    assert assembly_parts(model).tolist() == [1]
    cell = cell_plastic_strain(model, tmp_path / "run")
    assert cell["shells"] == 3 and cell["max"] == pytest.approx(r.shell_plastic_strain[:3].max())
    assert cell["yielded_area_percent"] == pytest.approx(100.0)
    assert list(cell["parts"]) == ["strip"]
    parts = part_plastic_strain(model, tmp_path / "run")
    assert parts["strong"]["max"] == 0.0 and parts["strong"]["yielded_area_percent"] == 0.0
    with pytest.raises(KeyError, match="assembly"):
        assembly_parts(model, ["roof"])
