"""Study files: what they define, and clear errors naming the file and key."""

import shutil
import textwrap
from pathlib import Path

import pytest

from crashlite.study import StudyError, load_study
from crashlite.study.models import front_structure

PULSE = Path(__file__).parents[3] / "src" / "crashlite" / "examples" / "pulse" / "pulse.k"

GOOD = """
[study]
name = "s"
deck = "car.k"

[variables.t_box]
part = "crash box"
property = "thickness"
bounds = [0.8, 1.6]

[variables.v]
parameter = "speed"
bounds = [12000.0, 16000.0]

[responses.mass]
type = "mass"
parts = ["crash box", "rail"]
scale = 1000.0

[responses.crush]
type = "node_displacement"
node = 900001
stat = "min"

[objectives]
mass = "minimize"

[constraints]
crush = { lower = -40.0 }

[doe]
designs = 4
"""


@pytest.fixture
def study(tmp_path):
    front_structure(tmp_path / "car.k", "surrogate", element_size=25.0)

    def write(text=GOOD, replace=None):
        t = textwrap.dedent(text)
        for a, b in (replace or {}).items():
            assert a in t, a
            t = t.replace(a, b)
        p = tmp_path / "study.toml"
        p.write_text(t)
        return p

    return write


def test_good_study(study, tmp_path):
    cfg = load_study(study())
    assert cfg.name == "s"
    assert cfg.deck == (tmp_path / "car.k").resolve()
    assert [v.name for v in cfg.variables] == ["t_box", "v"]
    assert cfg.variables[0].baseline == pytest.approx(1.2)
    assert cfg.variables[1].baseline == pytest.approx(15000.0)
    assert cfg.storage == f"sqlite:///{tmp_path / 'study_study' / 'study.db'}"
    assert cfg.objectives[0].goal == "minimize"
    assert cfg.constraints[0].violations(-30.0) == [pytest.approx(-0.25)]
    assert cfg.constraints[0].violations(-50.0) == [pytest.approx(0.25)]
    assert cfg.template.part_variables[0].pids == [1]
    assert "v" in cfg.template.sites


def _error(study, **kw):
    with pytest.raises(StudyError) as e:
        load_study(study(**kw))
    msg = str(e.value)
    assert "study.toml" in msg, msg
    return msg


def test_malformed_toml(study):
    msg = _error(study, replace={'name = "s"': 'name = "s'})
    assert "malformed TOML" in msg and "line" in msg


def test_bounds_reversed(study):
    msg = _error(study, replace={"bounds = [0.8, 1.6]": "bounds = [1.6, 0.8]"})
    assert "[variables.t_box] bounds" in msg and "not below" in msg


def test_part_not_in_deck(study):
    msg = _error(study, replace={'part = "crash box"': 'part = "crashbox"'})
    assert "[variables.t_box] parts" in msg and "'crashbox'" in msg and "'crash box'" in msg


def test_parameter_not_in_deck(study):
    msg = _error(study, replace={'parameter = "speed"': 'parameter = "sped"'})
    assert "[variables.v] parameter" in msg and "'sped'" in msg and "speed" in msg


def test_unknown_response_in_objectives_and_constraints(study):
    msg = _error(study, replace={'mass = "minimize"': 'weight = "minimize"'})
    assert "[objectives] weight" in msg and "unknown response" in msg
    msg = _error(study, replace={"crush = { lower": "intrusion = { lower"})
    assert "[constraints] intrusion" in msg and "unknown response" in msg


def test_unknown_response_type_and_key(study):
    msg = _error(study, replace={'type = "mass"': 'type = "masses"'})
    assert "[responses.mass]" in msg and "'masses'" in msg
    msg = _error(study, replace={'stat = "min"': 'stat = "min"\nnodes = 3'})
    assert "[responses.crush]" in msg and "'nodes'" in msg


def test_response_entity_not_in_deck(study):
    msg = _error(study, replace={"node = 900001": "node = 77"})
    assert "[responses.crush] node" in msg and "77" in msg
    # a time history of a node that is not a history node
    msg = _error(study, replace={"node = 900001": "node = 5"})
    assert "[responses.crush] node" in msg and "history node" in msg


def test_unknown_keys_and_missing_parts(study):
    msg = _error(study, replace={"[doe]\n": "[doe]\nsamples = 3\n"})
    assert "[doe]" in msg and "'samples'" in msg
    msg = _error(study, replace={'property = "thickness"': 'property = "density"'})
    assert "[variables.t_box]" in msg and "density" in msg
    msg = _error(study, replace={"[doe]\ndesigns = 4": ""})
    assert "nothing to run" in msg


def test_yield_of_elastic_part_refused(tmp_path):
    front_structure(tmp_path / "car.k", "full", element_size=25.0)
    p = tmp_path / "study.toml"
    p.write_text(
        '[study]\ndeck = "car.k"\n[variables.s]\npart = "rear frame"\nproperty = "yield"\n'
        'bounds = [200.0, 300.0]\n[responses.m]\ntype = "mass"\n[doe]\ndesigns = 2\n'
    )
    with pytest.raises(StudyError, match=r"\[variables.s\] parts: part 'rear frame' has \*MAT_ELASTIC"):
        load_study(p)


def test_integer_and_text_parameters(tmp_path):
    shutil.copy(PULSE, tmp_path / "pulse.k")
    text = (tmp_path / "pulse.k").read_text().replace("R crush      600.0", "R crush      600.0\nI n            3")
    (tmp_path / "pulse.k").write_text(text)
    p = tmp_path / "study.toml"
    p.write_text(
        '[study]\ndeck = "pulse.k"\n[variables.n]\nparameter = "n"\nbounds = [1.5, 4]\n'
        '[responses.m]\ntype = "mass"\n[doe]\ndesigns = 2\n'
    )
    with pytest.raises(StudyError, match=r"\[variables.n\] bounds: 'n' is an integer"):
        load_study(p)
    p.write_text(p.read_text().replace("[1.5, 4]", "[1, 4]"))
    assert load_study(p).variables[0].integer
