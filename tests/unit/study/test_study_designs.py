"""Design decks: *PARAMETER cards rewritten in place, include trees
mirrored, part thickness and yield stress set only on the named parts."""

import os
import shutil
from pathlib import Path

import numpy as np
import pytest

from crashlite import read_deck
from crashlite.study import load_study
from crashlite.study.designs import rewrite_parameter_line
from crashlite.study.models import front_structure

EXAMPLES = Path(__file__).parents[3] / "src" / "crashlite" / "examples"


@pytest.mark.parametrize(
    "line, name, value, typ, width, expr, expected",
    [
        (
            "r thick          1.5r mass        0.05",
            "mass",
            0.0625,
            "R",
            10,
            False,
            "r thick          1.5r mass    " + "0.0625".rjust(10),
        ),
        (
            "r thick          1.5r mass        0.05",
            "thick",
            1.25,
            "R",
            10,
            False,
            "r thick         1.25r mass        0.05",
        ),
        ("R v0,-1.0e4", "v0", -12000.0, "R", 10, False, "R v0,-12000.0"),
        ("R t,1.0,R u,2.0", "u", 3.5, "R", 10, False, "R t,1.0,R u,3.5"),
        ("R sigy    235.0*1.05", "sigy", 250.0, "R", 10, True, "R sigy    250.0"),
        ("I n             3", "n", 5, "I", 10, False, "I n       " + "5".rjust(10)),
        (
            "R long_name_param                 1.0",
            "long_name_param",
            2.0,
            "R",
            20,
            False,
            "R long_name_param   " + "2.0".rjust(20),
        ),
    ],
)
def test_rewrite_parameter_line(line, name, value, typ, width, expr, expected):
    assert rewrite_parameter_line(line, name, value, typ, width, expr) == expected


def test_value_that_does_not_fit_goes_free_format():
    out = rewrite_parameter_line("R t              1.5", "t", 1.2345678901234567, "R", 10, False)
    assert out == "R t,1.2345678901234567"


def _study(tmp_path, deck, variables, responses='[responses.m]\ntype = "mass"\n'):
    p = tmp_path / "study.toml"
    p.write_text(f'[study]\ndeck = "{deck}"\n{variables}\n{responses}\n[doe]\ndesigns = 2\n')
    return load_study(p)


def test_parameter_design_mirrors_includes(tmp_path):
    """The tube example keeps its mesh in an include and derives sigy and
    tend by *PARAMETER_EXPRESSION: a design of thick and v0 reads back with
    the new values, expressions evaluated from them, the mesh linked."""
    shutil.copytree(EXAMPLES / "tube", tmp_path / "tube")
    cfg = _study(
        tmp_path,
        "tube/tube.k",
        '[variables.t]\nparameter = "thick"\nbounds = [1.0, 2.0]\n'
        '[variables.v]\nparameter = "v0"\nbounds = [-12000.0, -8000.0]\n',
    )
    out = cfg.template.write({"t": 1.75, "v": -8000.0}, tmp_path / "d1")
    assert out == tmp_path / "d1" / "deck" / "tube.k"
    assert (tmp_path / "d1" / "deck" / "tube_mesh.k").is_symlink()
    m = read_deck(out)
    vals = {p.name.lower(): p.value for p in m.parameters}
    assert vals["thick"] == 1.75 and vals["v0"] == -8000.0
    assert vals["tend"] == pytest.approx(0.6 * 200.0 / 8000.0)
    assert m.sections[1]["t1"] == 1.75
    cfg.template.check(m, {"t": 1.75, "v": -8000.0})
    # only the parameter lines changed
    a = (EXAMPLES / "tube" / "tube.k").read_text().splitlines()
    b = out.read_text().splitlines()
    assert len(a) == len(b) and sum(x != y for x, y in zip(a, b)) == 2
    base = read_deck(EXAMPLES / "tube" / "tube.k")
    assert len(m.shells) == len(base.shells)


def test_parameter_in_an_include(tmp_path):
    (tmp_path / "sub").mkdir()
    shutil.copy(EXAMPLES / "pulse" / "pulse.k", tmp_path / "sub" / "model.k")
    text = (tmp_path / "sub" / "model.k").read_text()
    params = text[text.index("*PARAMETER\n") : text.index("*NODE")]
    (tmp_path / "sub" / "model.k").write_text(text.replace(params, ""))
    (tmp_path / "params.k").write_text("*KEYWORD\n" + params + "*END\n")
    (tmp_path / "main.k").write_text("*KEYWORD\n*INCLUDE\nparams.k\n*INCLUDE\nsub/model.k\n*END\n")
    cfg = _study(tmp_path, "main.k", '[variables.m]\nparameter = "m"\nbounds = [1.0, 2.0]\n')
    out = cfg.template.write({"m": 1.5}, tmp_path / "d")
    assert (tmp_path / "d" / "deck" / "sub" / "model.k").is_symlink()
    assert not (tmp_path / "d" / "deck" / "params.k").is_symlink()
    m = read_deck(out)
    assert m.masses.mass[0] == 1.5
    k = {p.name.lower(): p.value for p in m.parameters}["k"]
    assert k == pytest.approx(1.5 * 15555.6**2 / 600.0**2)


def test_part_variables_copy_shared_section_and_material(tmp_path):
    """crash box and rail share section 1 and material 1 here: a thickness
    and a yield variable of the crash box change only the crash box."""
    path = front_structure(tmp_path / "car.k", "surrogate", element_size=25.0)
    text = path.read_text().replace("1,2,0.8333,5\n1.2,1.2,1.2,1.2", "1,2,0.8333,5\n1.2,1.2,1.2,1.2", 1)
    text = text.replace("rail\n2,2,2,0,0", "rail\n2,1,1,0,0")  # rail: section 1, material 1
    path.write_text(text)
    cfg = _study(
        tmp_path,
        "car.k",
        '[variables.t]\npart = "crash box"\nproperty = "thickness"\nbounds = [0.5, 2.0]\n'
        '[variables.s]\npart = "crash box"\nproperty = "yield"\nbounds = [200.0, 400.0]\n',
    )
    out = cfg.template.write({"t": 0.9, "s": 350.0}, tmp_path / "d")
    m = read_deck(out)
    box, rail = m.parts[1], m.parts[2]
    assert rail["secid"] == 1 and rail["mid"] == 1
    assert m.sections[1]["t1"] == 1.2 and m.materials[1]["sigy"] == 300.0
    assert box["secid"] != 1 and box["mid"] != 1
    assert [m.sections[box["secid"]][k] for k in ("t1", "t2", "t3", "t4")] == [0.9] * 4
    assert m.materials[box["mid"]]["sigy"] == 350.0
    # the box's mass follows its thickness
    base = read_deck(path)
    assert m.mass_properties(["crash box"]).mass == pytest.approx(base.mass_properties(["crash box"]).mass * 0.9 / 1.2)
    cfg.template.check(m, {"t": 0.9, "s": 350.0})
    with pytest.raises(ValueError, match="thickness"):
        cfg.template.check(m, {"t": 1.0, "s": 350.0})


def test_eight_point_hardening_scales_with_yield(tmp_path):
    path = front_structure(tmp_path / "car.k", "surrogate", element_size=25.0)
    text = path.read_text().replace(
        "1,7.85e-9,210000.0,0.3,300.0,1.0\n0,0,0,0",
        "1,7.85e-9,210000.0,0.3,300.0,1.0\n0,0,0,0\n0.0,0.1,0.2\n300.0,360.0,390.0",
    )
    path.write_text(text)
    cfg = _study(tmp_path, "car.k", '[variables.s]\npart = "crash box"\nproperty = "yield"\nbounds = [200.0, 400.0]\n')
    m = read_deck(cfg.template.write({"s": 330.0}, tmp_path / "d"))
    mat = m.materials[m.parts[1]["mid"]]
    assert [mat[f"es{i}"] for i in (1, 2, 3)] == pytest.approx([330.0, 396.0, 429.0])
    assert np.isclose(mat["sigy"], 330.0)
    assert os.path.exists(tmp_path / "d" / "design.k")
