"""`crashlite run` and `convert` never lose a file and always say how a run
ended (issue 35): output folders are checked before the run (the deck and
foreign files are never overwritten), a reused folder keeps no stale file
of the previous run, Ctrl-C exits 130 with "interrupted at t = ..." and
every result file written, and bad paths end in an error line, never a
traceback.

All on the pulse example (one mass on a spring, about a second a run).
"""

import json
import os
import signal
from importlib import resources

import numpy as np
import pytest

from crashlite.cli import INTERRUPTED, main
from crashlite.results import load
from crashlite.results.folder import MANIFEST

PULSE = (resources.files("crashlite") / "examples" / "pulse" / "pulse.k").read_text()
ASCII = ("glstat", "matsum", "nodout", "deforc", "spcforc")


def _deck(folder, name="pulse.k", extra: str = "", old: str | None = None, new: str | None = None):
    folder.mkdir(parents=True, exist_ok=True)
    text = PULSE if old is None else PULSE.replace(old, new, 1)
    p = folder / name
    p.write_text(text.replace("*END", extra.rstrip("\n") + "\n*END") if extra else text)
    return p


def _states(dt: float) -> str:
    return f"*DATABASE_BINARY_D3PLOT\n{dt}\n"


WALL = "*RIGIDWALL_PLANAR\n0\n5000.0,0,0,6000.0,0,0\n"  # far ahead: never touched, but rwforc is written


def test_the_deck_in_the_output_folder_is_never_overwritten(tmp_path, capsys):
    """A deck named glstat in its own folder was overwritten by the run."""
    deck = _deck(tmp_path, "glstat")
    before = deck.read_text()
    for extra in ([], ["--force"]):
        assert main(["run", str(deck), "-o", str(tmp_path), "--quiet", *extra]) == 2
        err = capsys.readouterr().err
        assert "holds the deck" in err and "glstat" in err and "Traceback" not in err
    assert deck.read_text() == before
    assert not (tmp_path / "results.npz").exists() and not (tmp_path / MANIFEST).exists()


def test_a_foreign_file_of_a_result_name_refuses_the_run_unless_forced(tmp_path, capsys):
    deck = _deck(tmp_path / "deck")
    out = tmp_path / "out"
    out.mkdir()
    (out / "nodout").write_text("LS-DYNA's nodout of another run\n")
    (out / "notes.txt").write_text("mine\n")
    assert main(["run", str(deck), "-o", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "nodout" in err and "--force" in err
    assert (out / "nodout").read_text() == "LS-DYNA's nodout of another run\n"
    assert not (out / "results.npz").exists()
    assert main(["run", str(deck), "-o", str(out), "--quiet", "--force"]) == 0
    assert load(out).read("nodout", "ids").tolist() == [2]
    assert (out / "notes.txt").read_text() == "mine\n"  # other names: left alone
    assert "notes.txt" not in json.loads((out / MANIFEST).read_text())["files"]


def test_a_reused_folder_keeps_no_file_of_the_previous_run(tmp_path):
    """The second run has no rigid wall and fewer states: the first run's
    rwforc and its extra VTK states were left beside the new ones."""
    out = tmp_path / "out"
    first = _deck(tmp_path / "a", extra=WALL + _states(0.005))
    assert main(["run", str(first), "-o", str(out), "--quiet"]) == 0
    n_first = len(list((out / "states").glob("state_*.vtk")))
    assert (out / "rwforc").is_file() and n_first > 20
    (out / "notes.txt").write_text("mine\n")
    second = _deck(tmp_path / "b", extra=_states(0.05))
    assert main(["run", str(second), "-o", str(out), "--quiet"]) == 0
    states = sorted(p.name for p in (out / "states").glob("state_*.vtk"))
    assert not (out / "rwforc").exists()
    assert len(states) == 4 < n_first  # t = 0, 0.05, 0.10 and the last
    pvd = (out / "states" / "states.pvd").read_text()
    assert all(name in pvd for name in states)
    assert (out / "notes.txt").read_text() == "mine\n"
    listed = json.loads((out / MANIFEST).read_text())
    assert listed["complete"] and "rwforc" not in listed["files"] and f"states/{states[-1]}" in listed["files"]


def test_an_output_path_that_is_a_file_is_refused_before_the_run(tmp_path, capsys, monkeypatch):
    deck = _deck(tmp_path)
    target = tmp_path / "results.txt"
    target.write_text("keep me\n")
    import crashlite.solver

    def no_run(*a, **k):
        raise AssertionError("the run started")

    monkeypatch.setattr(crashlite.solver, "run", no_run)
    assert main(["run", str(deck), "-o", str(target), "--quiet"]) == 2
    assert main(["run", str(deck), "-o", str(target / "sub"), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "is a file" in err and "Traceback" not in err
    assert target.read_text() == "keep me\n"


def test_convert_to_a_folder_or_an_empty_path_is_an_error_not_a_traceback(tmp_path, capsys):
    deck = _deck(tmp_path)
    assert main(["convert", str(deck), "-o", str(tmp_path)]) == 2
    assert "is a folder" in capsys.readouterr().err
    for cmd in (["convert", str(deck), "-o", ""], ["run", str(deck), "-o", ""]):
        with pytest.raises(SystemExit) as e:
            main(cmd)
        assert e.value.code == 2
        assert "empty path" in capsys.readouterr().err
    assert deck.read_text() == PULSE and not (tmp_path / "results.npz").exists()


def _interrupt_at_record(monkeypatch, n: int):
    """Ctrl-C (KeyboardInterrupt) at the n-th recorded state of the loop."""
    from crashlite.solver import loop

    calls = {"n": 0}
    check = loop._Recorder._check_sliding

    def check_then_interrupt(self, *a):
        calls["n"] += 1
        if calls["n"] == n:
            raise KeyboardInterrupt
        return check(self, *a)

    monkeypatch.setattr(loop._Recorder, "_check_sliding", check_then_interrupt)


def test_an_interrupted_run_exits_130_says_so_and_keeps_its_results(tmp_path, capsys, monkeypatch):
    _interrupt_at_record(monkeypatch, 40)
    out = tmp_path / "out"
    assert main(["run", str(_deck(tmp_path)), "-o", str(out), "--quiet"]) == INTERRUPTED
    line = capsys.readouterr().out
    assert line.startswith("interrupted at t = ") and "results so far" in line
    t = load(out).read("glstat", "time")
    assert 30 < len(t) < 200 and t[-1] < 0.12
    assert all((out / f).is_file() for f in ASCII)
    assert json.loads((out / MANIFEST).read_text())["complete"]


def _ctrl_c_while_writing_glstat(monkeypatch):
    """A Ctrl-C (SIGINT to this process) each time glstat is being written."""
    from crashlite.results.lsdyna_ascii import glstat

    write = glstat.write

    def write_and_ctrl_c(*a, **k):
        os.kill(os.getpid(), signal.SIGINT)
        return write(*a, **k)

    monkeypatch.setattr(glstat, "write", write_and_ctrl_c)


def test_a_second_ctrl_c_while_saving_leaves_every_file_written(tmp_path, capsys, monkeypatch):
    """The first Ctrl-C stops the loop; a second one, while glstat is being
    written, used to raise half-way and leave the other files unwritten."""
    _interrupt_at_record(monkeypatch, 40)
    _ctrl_c_while_writing_glstat(monkeypatch)
    out = tmp_path / "out"
    assert main(["run", str(_deck(tmp_path)), "-o", str(out), "--quiet"]) == INTERRUPTED
    assert capsys.readouterr().out.startswith("interrupted at t = ")
    assert all((out / f).is_file() for f in ASCII)
    h = load(out)
    assert len(h.read("nodout", "time")) == len(h.read("glstat", "time")) > 30


def test_ctrl_c_while_saving_a_finished_run_still_writes_every_file(tmp_path, capsys, monkeypatch):
    _ctrl_c_while_writing_glstat(monkeypatch)
    out = tmp_path / "out"
    assert main(["run", str(_deck(tmp_path)), "-o", str(out), "--quiet"]) == INTERRUPTED
    assert "while saving" in capsys.readouterr().out
    assert all((out / f).is_file() for f in ASCII)
    assert load(out).read("glstat", "time")[-1] >= 0.12


def test_ctrl_c_during_set_up_is_reported_without_a_traceback(tmp_path, capsys, monkeypatch):
    from crashlite.solver import loop

    def interrupted_build(model):
        raise KeyboardInterrupt

    monkeypatch.setattr(loop, "build", interrupted_build)
    out = tmp_path / "out"
    assert main(["run", str(_deck(tmp_path)), "-o", str(out), "--quiet"]) == INTERRUPTED
    err = capsys.readouterr().err
    assert "interrupted during set-up" in err and "Traceback" not in err
    assert not (out / "results.npz").exists()


def test_the_mass_added_by_mass_scaling_is_printed(tmp_path, capsys):
    """DT2MS = -1 s on the pulse spring: each free node needs k·dt²/4 =
    212.2 t, 211 t more than the car's 1.263 t (the run prints it)."""
    deck = _deck(tmp_path, old="       0.0      0.01\n", new="       0.0       0.9         0       0.0      -1.0\n")
    assert main(["run", str(deck), "-o", str(tmp_path / "out"), "--quiet"]) == 0
    line = capsys.readouterr().out
    k = 1.263 * 15555.6**2 / 600.0**2
    added = k * 1.0**2 / 4 - 1.263
    assert f"mass scaling (DT2MS) added {added:.4g} to a model of 1.263" in line
    assert f"+{100 * added / 1.263:.3g} %" in line and "part 1:" in line
    assert np.isclose(added, 211, rtol=0.01)
