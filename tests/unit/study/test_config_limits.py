"""Study files that asked for the impossible: negative workers (a
LocalCluster waiting forever for -4 workers), a billion designs (a
MemoryError traceback), a storage that cannot be written (an error that
did not name the key). Each is now an error naming the study file and key,
before anything starts (issue 35)."""

import shutil
import textwrap
from pathlib import Path

import pytest

from crashlite.cli import main
from crashlite.study import StudyError, load_study
from crashlite.study import config as study_config
from crashlite.study.executor import DaskExecutor, make_executor
from crashlite.study.storage import StudyStore

PULSE = Path(__file__).parents[3] / "src" / "crashlite" / "examples" / "pulse" / "pulse.k"

STUDY = """
[study]
name = "s"
deck = "pulse.k"

[variables.v]
parameter = "v0"
bounds = [12000.0, 16000.0]

[responses.crush]
type = "node_displacement"
node = 2
stat = "min"

[doe]
designs = 3
"""


@pytest.fixture
def study(tmp_path):
    shutil.copy(PULSE, tmp_path / "pulse.k")

    def write(extra: str = "", replace: dict | None = None) -> Path:
        t = textwrap.dedent(STUDY) + textwrap.dedent(extra)
        for a, b in (replace or {}).items():
            assert a in t, a
            t = t.replace(a, b)
        p = tmp_path / "study.toml"
        p.write_text(t)
        return p

    return write


@pytest.mark.parametrize("workers", [-4, -1])
def test_negative_workers_are_refused_naming_the_key(study, workers):
    p = study(f"[execution]\nworkers = {workers}\n")
    with pytest.raises(StudyError, match=rf"study.toml: \[execution\] workers: must be 1 or more.*got {workers}"):
        load_study(p)


def test_zero_workers_is_still_one_per_core(study):
    ex = make_executor(load_study(study("[execution]\nworkers = 0\n")).execution)
    assert ex.workers >= 1


def test_negative_workers_never_reach_a_cluster(study, capsys):
    with pytest.raises(ValueError, match="workers must be 1 or more"):
        DaskExecutor(workers=-4)
    with pytest.raises(SystemExit) as e:
        main(["study", "run", str(study()), "--workers", "-4"])
    assert e.value.code == 2 and "--workers: must be 1 or more" in capsys.readouterr().err


def test_negative_allowed_failures_are_refused(study):
    with pytest.raises(StudyError, match=r"\[execution\] allowed_failures: must not be negative"):
        load_study(study("[execution]\nallowed_failures = -2\n"))


def test_a_billion_designs_is_refused_naming_the_key(study):
    """Refused from the memory a plan of that size needs, before any of it
    is allocated."""
    p = study(replace={"designs = 3": "designs = 1000000000"})
    with pytest.raises(StudyError, match=r"study.toml: \[doe\] designs: 1000000000 asks for 1,000,000,000"):
        load_study(p)


def test_the_design_bound_follows_the_memory(study, monkeypatch):
    """With 1 GiB of memory a quarter holds 256 MiB / (4096 + 64) B = 64,527
    designs of one variable: 60,000 pass, 70,000 are refused with the bound."""
    monkeypatch.setattr(study_config, "memory_bytes", lambda: 1 << 30)
    assert load_study(study(replace={"designs = 3": "designs = 60000"})).doe.designs == 60000
    with pytest.raises(StudyError, match=r"holds at most 64,527"):
        load_study(study(replace={"designs = 3": "designs = 70000"}))
    with pytest.raises(StudyError, match=r"\[sensitivity\] trajectories"):  # r·(d + 1) Morris designs
        load_study(study('[sensitivity]\nmethod = "morris"\ntrajectories = 40000\n'))


@pytest.mark.parametrize("where", ["under_a_file", "a_folder"])
def test_a_storage_that_cannot_be_written_names_its_key(study, tmp_path, where):
    (tmp_path / "plain").write_text("not a folder\n")
    (tmp_path / "folder").mkdir()
    url = {"under_a_file": f"sqlite:///{tmp_path}/plain/s.db", "a_folder": f"sqlite:///{tmp_path}/folder"}[where]
    cfg = load_study(study(replace={'name = "s"': f'name = "s"\nstorage = "{url}"'}))
    with pytest.raises(StudyError, match=r"study.toml: \[study\] storage: cannot open the study storage"):
        StudyStore(cfg)
    assert (tmp_path / "plain").read_text() == "not a folder\n"


@pytest.mark.parametrize(
    "content, says",
    [
        (b"\x00\x00\x00\x00binary", "binary data"),
        (b"just some text\nno keywords\n", "no keyword"),
        (b"", "the file is empty"),
    ],
)
def test_a_deck_path_that_is_no_deck_is_refused_naming_the_key(study, tmp_path, content, says):
    """A study on a binary, keyword-less or empty "deck" ran its designs on
    an empty model."""
    p = study()
    (tmp_path / "pulse.k").write_bytes(content)
    with pytest.raises(StudyError, match=r"(?s)study.toml: \[study\] deck: .*not a keyword deck") as e:
        load_study(p)
    assert says in str(e.value)
    assert not list(tmp_path.rglob("*.db")) and not list(tmp_path.rglob("designs"))  # nothing stored or run
