"""Running decks in an external solver (crashlite.external) on a stand-in
for LS-DYNA: a Python script made executable that records its command
line, working directory and environment, and writes real LS-DYNA ASCII
history files (crashlite's writers: glstat, matsum, nodout, deforc) plus a
d3hsp and messag with LS-DYNA's termination line into its working
directory. Checked: the command line, the folder, the environment, the
results read back, a non-zero exit, a missing normal termination, a
missing configuration, resumption, the CLI and a study of two designs
(in this process and on a Dask cluster object with a scheduler_address,
as dask-jobqueue's clusters have)."""

from __future__ import annotations

import json
import os
import shutil
import stat
import sys
from pathlib import Path

import numpy as np
import pytest

from crashlite import external
from crashlite.cli import main
from crashlite.external import ExternalFolderError, ExternalSolverError, command_lines, settings
from crashlite.results import load
from crashlite.results.from_history import results_from_history

PULSE = Path(__file__).parents[2] / "src" / "crashlite" / "examples" / "pulse" / "pulse.k"

STANDIN = r'''#!{python}
"""Stand-in for LS-DYNA: i=deck in the working directory; STANDIN_MODE
normal | fail | error; every call appended to $STANDIN_RECORD."""
import json, os, re, sys
from pathlib import Path

import numpy as np

from crashlite.results.lsdyna_ascii import deforc, glstat, matsum, nodout

args = dict(a.split("=", 1) for a in sys.argv[1:] if "=" in a)
with open(os.environ["STANDIN_RECORD"], "a") as f:
    f.write(json.dumps({{"argv": sys.argv, "cwd": os.getcwd(),
                        "env": {{k: v for k, v in os.environ.items() if k.startswith(("STANDIN", "LSTC"))}}}}) + "\n")
deck = Path(args["i"])
params = {{"m": 1.263, "crush": 600.0, "v0": 15555.6}}
block = False
for line in deck.read_text().splitlines():
    if line.startswith("*"):
        block = line.strip().upper() == "*PARAMETER"
        continue
    if block and line.strip() and not line.startswith("$"):
        tok = re.split(r"[,\s]+", line.strip())  # "R m          1.263", "R m,1.02853"
        params[tok[1].lower()] = float(tok[2])
mode = os.environ.get("STANDIN_MODE", "normal")
print(" Date: 01/01/2025      Time: 00:00:00")
print(" ls-dyna stand-in: input " + str(deck))
for c in (0, 1000, 2000):
    print(f"      {{c}} t 0.0000E+00 dt 5.00E-05 flush i/o buffers")
sys.stdout.flush()
if mode == "fail":
    print(" *** Error 10246 (KEY+246)")
    print("     stand-in: keyword not recognised")
    sys.exit(7)
m, crush, v0 = params["m"], params["crush"], params["v0"]
w = v0 / crush
tg = np.linspace(0.0, 0.12, 61)  # glstat, matsum, deforc interval
tn = np.linspace(0.0, 0.12, 241)  # nodout: a finer interval, as LS-DYNA's files each have their own
x, v, a = (-crush * np.sin(w * tn), -v0 * np.cos(w * tn), crush * w * w * np.sin(w * tn))
ke = 0.5 * m * (v0 * np.cos(w * tg)) ** 2
ie = 0.5 * m * v0 ** 2 - ke
g = {{"time": tg, "cycle": np.arange(61) * 40, "time_step": np.full(61, 5e-5), "kinetic_energy": ke,
     "internal_energy": ie, "spring_and_damper_energy": ie, "external_work": np.zeros(61),
     "total_energy": ke + ie, "energy_ratio": np.ones(61)}}
glstat.write("glstat", g, "stand-in")
mat = {{"time": tg, "ids": np.array([1]), "internal_energy": ie[:, None], "kinetic_energy": ke[:, None]}}
matsum.write("matsum", mat, "stand-in")
nod = {{"time": tn, "ids": np.array([2]), "x_displacement": x[:, None], "x_velocity": v[:, None],
       "x_acceleration": a[:, None], "x_coordinate": 1000.0 + x[:, None]}}
for q in ("displacement", "velocity", "acceleration"):
    for c in "yz":
        nod[f"{{c}}_{{q}}"] = np.zeros((241, 1))
nod["y_coordinate"] = nod["z_coordinate"] = np.zeros((241, 1))
nodout.write("nodout", nod, "stand-in")
f = m * v0 * w * np.sin(w * tg)
deforc.write("deforc", {{"time": tg, "ids": np.array([1]), "resultant_force": f[:, None],
                        "x_force": f[:, None], "displacement": (-crush * np.sin(w * tg))[:, None]}}, "stand-in")
np.savez("standin-data.npz", glstat_time=tg, kinetic=ke, internal=ie, nodout_time=tn, x=x, v=v, force=f)
end = " N o r m a l    t e r m i n a t i o n" if mode == "normal" else " E r r o r   t e r m i n a t i o n"
Path("d3hsp").write_text(" ls-dyna stand-in\n ...\n" + end + "                    01/01/25 00:00:01\n")
Path("messag").write_text(end + "\n")
print(end)
'''


@pytest.fixture
def standin(tmp_path, monkeypatch):
    """The stand-in executable, configured through the environment (no
    solvers file of the user's is read)."""
    exe = tmp_path / "bin" / "lsdyna_smp_d"
    exe.parent.mkdir()
    exe.write_text(STANDIN.format(python=sys.executable))
    exe.chmod(exe.stat().st_mode | stat.S_IXUSR | stat.S_IXGRP)
    record = tmp_path / "calls.jsonl"
    for k in list(os.environ):
        if k.startswith("CRASHLITE_") and k != "CRASHLITE_NUMBA_CACHE":
            monkeypatch.delenv(k)
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "no-config"))
    monkeypatch.setenv("CRASHLITE_LSDYNA", str(exe))
    monkeypatch.setenv("CRASHLITE_LSDYNA_NCPU", "4")
    monkeypatch.setenv("CRASHLITE_LSDYNA_MEMORY", "200m")
    monkeypatch.setenv("STANDIN_RECORD", str(record))
    monkeypatch.setenv("STANDIN_TAG", "from-the-caller")
    monkeypatch.delenv("STANDIN_MODE", raising=False)

    return StandIn(exe, record)


class StandIn:
    """The stand-in's path (str() of it) and the calls it recorded."""

    def __init__(self, path: Path, record: Path):
        self.path, self.record = path, record

    def __str__(self) -> str:
        return str(self.path)

    def calls(self) -> list[dict]:
        return [json.loads(x) for x in self.record.read_text().splitlines()] if self.record.is_file() else []


def _deck(tmp_path, name="model/pulse.k", history=True):
    p = tmp_path / name
    p.parent.mkdir(parents=True, exist_ok=True)
    text = PULSE.read_text()
    if history:
        text = text.replace(
            "*END",
            "*DATABASE_GLSTAT\n   1.0E-3\n*DATABASE_MATSUM\n   1.0E-3\n*DATABASE_NODOUT\n"
            "   1.0E-3\n*DATABASE_DEFORC\n   1.0E-3\n*END",
        )
    p.write_text(text)
    return p


# --- configuration and command line ----------------------------------------------


def test_command_line_cwd_environment_and_results(tmp_path, standin, monkeypatch):
    monkeypatch.setenv("CRASHLITE_MPI", f"{sys.executable} -c 'import os,sys; os.execv(sys.argv[1], sys.argv[1:])'")
    deck = _deck(tmp_path)
    out = tmp_path / "runs" / "lsdyna"
    lines = []
    ext = external.run(deck, out, "lsdyna", echo=lines.append)
    (call,) = standin.calls()
    # <mpi> <exe> i=<deck> ncpu= memory=: the launcher (a python that execs its arguments) ran the stand-in
    assert call["argv"][0] == str(standin)
    assert call["argv"][1:] == ["i=../../model/pulse.k", "ncpu=4", "memory=200m"]
    assert ext.commands[0][:3] == [sys.executable, "-c", "import os,sys; os.execv(sys.argv[1], sys.argv[1:])"]
    assert ext.commands[0][3:] == [str(standin), "i=../../model/pulse.k", "ncpu=4", "memory=200m"]
    assert Path(call["cwd"]).resolve() == out.resolve()
    assert call["env"]["STANDIN_TAG"] == "from-the-caller"
    # the log streamed line by line, and kept
    assert any("flush i/o buffers" in x for x in lines) and "N o r m a l" in lines[-1]
    assert "N o r m a l" in (out / external.LOG).read_text()
    assert ext.ran and ext.termination == "d3hsp"
    # the deck is left where it is, unchanged; the folder holds the solver's output and the manifest
    assert deck.read_text().startswith("*KEYWORD") and not (out / "pulse.k").exists()
    manifest = json.loads((out / external.MANIFEST).read_text())
    assert manifest["status"] == "complete" and {"glstat", "nodout", "d3hsp"} <= set(manifest["files"])
    assert manifest["settings"]["executable"] == "CRASHLITE_LSDYNA"
    # read back through the same loader: equal to what the stand-in wrote (to the files' printed digits)
    data = np.load(out / "standin-data.npz")
    h = load(out)
    assert {"glstat", "matsum", "nodout", "deforc"} <= set(h.categories())
    np.testing.assert_allclose(h.read("glstat", "kinetic_energy"), data["kinetic"], rtol=1e-5, atol=1e-5 * 1.6e8)
    np.testing.assert_allclose(h.read("nodout", "x_displacement")[:, 0], data["x"], rtol=1e-4, atol=1e-4 * 600)
    np.testing.assert_allclose(h.read("nodout", "time"), data["nodout_time"], rtol=1e-7, atol=1e-12)
    res = results_from_history(h)  # nodout's finer time axis is the common one
    assert len(res.time) == 241 and res.history_nodes.tolist() == [2] and res.part_ids.tolist() == [1]
    np.testing.assert_allclose(
        res.kinetic, np.interp(data["nodout_time"], data["glstat_time"], data["kinetic"]), rtol=1e-5, atol=1e-5 * 1.6e8
    )
    np.testing.assert_allclose(res.final_x[0], [1000.0 + data["x"][-1], 0.0, 0.0], atol=0.1)


def test_settings_from_a_solvers_file(tmp_path, standin, monkeypatch):
    for k in ("CRASHLITE_LSDYNA", "CRASHLITE_LSDYNA_NCPU", "CRASHLITE_LSDYNA_MEMORY"):
        monkeypatch.delenv(k)
    cfg = tmp_path / "solvers.toml"
    cfg.write_text(
        f'[lsdyna]\nexecutable = "{standin}"\nncpu = 2\nmemory = "20m"\nmpi = ["{sys.executable}", '
        f'"-c", "import os,sys; os.execv(sys.argv[1], sys.argv[1:])"]\nargs = "d=nodump"\n'
        '[lsdyna.env]\nLSTC_LICENSE = "network"\n'
    )
    monkeypatch.setenv("CRASHLITE_SOLVERS", str(cfg))
    s = settings("lsdyna")
    assert (s.executable, s.ncpu, s.memory, s.args, s.env) == (
        str(standin),
        2,
        "20m",
        ("d=nodump",),
        {"LSTC_LICENSE": "network"},
    )
    assert command_lines(s, "deck.k")[0][3:] == [str(standin), "i=deck.k", "ncpu=2", "memory=20m", "d=nodump"]
    external.run(_deck(tmp_path), tmp_path / "out", config=s)
    (call,) = standin.calls()
    assert call["env"]["LSTC_LICENSE"] == "network" and call["argv"][-1] == "d=nodump"
    # the environment wins over the file, key by key
    monkeypatch.setenv("CRASHLITE_LSDYNA_NCPU", "6")
    s = settings("lsdyna")
    assert s.ncpu == 6 and s.memory == "20m" and s.sources["ncpu"] == "CRASHLITE_LSDYNA_NCPU"


def test_openradioss_command_templates(tmp_path, standin, monkeypatch):
    cfg = tmp_path / "solvers.toml"
    cfg.write_text(f'[openradioss]\nstarter = "{standin}"\nengine = "{standin}"\nncpu = 4\n')
    monkeypatch.setenv("CRASHLITE_SOLVERS", str(cfg))
    s = settings("openradioss")
    assert command_lines(s, "../car.k") == [
        [str(standin), "-i", "../car.k", "-np", "4"],
        [str(standin), "-i", "car_0001.rad"],
    ]
    assert s.termination_files == ("{stem}_0001.out",)


def test_missing_configuration_names_the_variable(tmp_path, standin, monkeypatch):
    monkeypatch.delenv("CRASHLITE_LSDYNA")
    with pytest.raises(ExternalSolverError, match="CRASHLITE_LSDYNA=/path/to/lsdyna.*solvers.toml"):
        settings("lsdyna")
    monkeypatch.setenv("CRASHLITE_LSDYNA", str(tmp_path / "nowhere" / "lsdyna"))
    with pytest.raises(ExternalSolverError, match=r"CRASHLITE_LSDYNA=.*nowhere/lsdyna: no such file"):
        settings("lsdyna")
    monkeypatch.setenv("CRASHLITE_LSDYNA", str(standin))
    monkeypatch.setenv("CRASHLITE_LSDYNA_NCPU", "four")
    with pytest.raises(ExternalSolverError, match="CRASHLITE_LSDYNA_NCPU=four: must be a whole number"):
        settings("lsdyna")
    monkeypatch.setenv("CRASHLITE_LSDYNA_NCPU", "-4")  # LS-DYNA's consistent mode on 4 CPUs
    assert command_lines(settings("lsdyna"), "d.k")[0][-2] == "ncpu=-4"
    monkeypatch.setenv("CRASHLITE_MPI", "no-such-mpirun-here -np 8")
    with pytest.raises(ExternalSolverError, match="CRASHLITE_MPI=.*not found on PATH"):
        settings("lsdyna")
    monkeypatch.delenv("CRASHLITE_MPI")
    monkeypatch.setenv("CRASHLITE_SOLVERS", str(tmp_path / "missing.toml"))
    with pytest.raises(ExternalSolverError, match="CRASHLITE_SOLVERS=.*missing.toml: no such file"):
        settings("lsdyna")
    bad = tmp_path / "bad.toml"
    bad.write_text('[lsdyna]\nexecutable = "x"\nthreads = 4\n')
    monkeypatch.setenv("CRASHLITE_SOLVERS", str(bad))
    with pytest.raises(ExternalSolverError, match=r"\[lsdyna\] unknown key\(s\) 'threads'"):
        settings("lsdyna")
    monkeypatch.delenv("CRASHLITE_SOLVERS")
    with pytest.raises(ExternalSolverError, match="CRASHLITE_OPENRADIOSS_STARTER and CRASHLITE_OPENRADIOSS_ENGINE"):
        settings("openradioss")
    assert standin.calls() == []


# --- failures and resumption ------------------------------------------------------


def test_nonzero_exit_shows_the_log_tail(tmp_path, standin, monkeypatch):
    monkeypatch.setenv("STANDIN_MODE", "fail")
    out = tmp_path / "out"
    with pytest.raises(ExternalSolverError, match=r"exited with status 7(.|\n)*Error 10246(.|\n)*not recognised"):
        external.run(_deck(tmp_path), out)
    assert json.loads((out / external.MANIFEST).read_text())["status"] == "failed"
    # a failed run is not kept: the next call runs again
    monkeypatch.setenv("STANDIN_MODE", "normal")
    assert external.run(_deck(tmp_path), out).ran and len(standin.calls()) == 2


def test_exit_zero_without_normal_termination_is_an_error(tmp_path, standin, monkeypatch):
    monkeypatch.setenv("STANDIN_MODE", "error")
    with pytest.raises(
        ExternalSolverError,
        match=r"status 0 but reports no normal termination \(d3hsp: error "
        r"termination; messag: error termination\)(.|\n)*E r r o r",
    ):
        external.run(_deck(tmp_path), tmp_path / "out")


def test_resumption_and_force(tmp_path, standin, capsys):
    deck = _deck(tmp_path)
    out = tmp_path / "out"
    assert main(["run", str(deck), "--solver", "lsdyna", "-o", str(out)]) == 0
    first = capsys.readouterr().out
    assert "flush i/o buffers" in first and "lsdyna: normal termination (d3hsp)" in first
    assert "glstat" in first and "nodout" in first
    assert len(standin.calls()) == 1
    # the same deck again: kept, not rerun
    assert main(["run", str(deck), "--solver", "lsdyna", "-o", str(out)]) == 0
    assert "not run again" in capsys.readouterr().out and len(standin.calls()) == 1
    # --force runs it again
    assert main(["run", str(deck), "--solver", "lsdyna", "-o", str(out), "--force", "--quiet"]) == 0
    assert "flush" not in capsys.readouterr().out and len(standin.calls()) == 2
    # a changed deck (an include's content counts) runs again, the earlier run's files removed first
    inc = deck.parent / "extra.k"
    inc.write_text("*KEYWORD\n*END\n")
    deck.write_text(deck.read_text().replace("*END", "*INCLUDE\nextra.k\n*END"))
    (out / "rcforc").write_text("stale\n")  # a file LS-DYNA writes, from no run of crashlite's
    assert main(["run", str(deck), "--solver", "lsdyna", "-o", str(out)]) == 2
    assert "rcforc" in capsys.readouterr().err and len(standin.calls()) == 2
    (out / "rcforc").unlink()
    assert main(["run", str(deck), "--solver", "lsdyna", "-o", str(out)]) == 0
    assert len(standin.calls()) == 3
    inc.write_text("*KEYWORD\n$ changed\n*END\n")
    external.run(deck, out)
    assert len(standin.calls()) == 4
    external.run(deck, out)
    assert len(standin.calls()) == 4


def test_folder_of_another_run(tmp_path, standin):
    out = tmp_path / "out"
    out.mkdir()
    (out / "d3hsp").write_text("a run crashlite did not start\n")
    with pytest.raises(ExternalFolderError, match="did not start.*d3hsp"):
        external.run(_deck(tmp_path), out)
    assert external.run(_deck(tmp_path), out, force=True).ran
    # a crashlite run's results.npz (listed in its manifest) would shadow the solver's files: removed
    (out / "results.npz").write_bytes(b"")
    (out / "crashlite-run.json").write_text(json.dumps({"files": ["results.npz", "glstat"]}))
    external.run(_deck(tmp_path), out, force=True)
    assert not (out / "results.npz").exists() and not (out / "crashlite-run.json").exists()
    assert "glstat" in load(out).categories()


def test_cli_reports_a_missing_configuration(tmp_path, standin, monkeypatch, capsys):
    monkeypatch.delenv("CRASHLITE_LSDYNA")
    assert main(["run", str(_deck(tmp_path)), "--solver", "lsdyna", "-o", str(tmp_path / "out")]) == 2
    assert "CRASHLITE_LSDYNA" in capsys.readouterr().err


# --- studies ------------------------------------------------------------------------

STUDY = """
[study]
name = "pulse"
deck = "model/pulse.k"

[variables.m]
parameter = "m"
bounds = [1.0, 2.0]

[variables.crush]
parameter = "crush"
bounds = [400.0, 800.0]

[responses.stroke]
type = "node_displacement"
node = 2
stat = "min"
scale = -1.0

[responses.energy]
type = "energy"
quantity = "kinetic"
stat = "max"

[responses.spring]
type = "part_energy"
parts = [1]
stat = "max"

[responses.force]
type = "discrete_force"
stat = "max"

[responses.mass]
type = "mass"
scale = 1000.0

[doe]
method = "lhs"
designs = 2

[execution]
solver = "lsdyna"
{extra}
"""


def _study(tmp_path, extra=""):
    from crashlite.study import load_study

    _deck(tmp_path)
    p = tmp_path / "study.toml"
    p.write_text(STUDY.format(extra=extra))
    return load_study(p)


def _check_designs(cfg, standin):
    from crashlite.study.storage import StudyStore

    designs = StudyStore(cfg).designs()
    assert len(designs) == 2 and all(d.status == "complete" for d in designs), [d.message for d in designs]
    assert len(standin.calls()) == 2
    for d in designs:
        folder = cfg.directory / "designs" / d.key / "results"
        data = np.load(folder / "standin-data.npz")
        r, v = d.responses, d.values
        assert r["stroke"] == pytest.approx(-data["x"].min(), rel=1e-4)
        assert r["stroke"] == pytest.approx(v["crush"], rel=1e-3)  # the design's own deck was run
        assert r["energy"] == pytest.approx(data["kinetic"].max(), rel=1e-5)
        assert r["spring"] == pytest.approx(data["internal"].max(), rel=1e-4)  # matsum: 5 digits
        assert r["spring"] == pytest.approx(0.5 * v["m"] * 15555.6**2, rel=5e-3)
        assert r["force"] == pytest.approx(data["force"].max(), rel=1e-5)
        assert r["mass"] == pytest.approx(1000.0 * v["m"], rel=1e-9)
        assert json.loads((folder / external.MANIFEST).read_text())["status"] == "complete"


def test_study_on_the_external_solver(tmp_path, standin):
    from crashlite.study import run_study
    from crashlite.study.executor import SerialExecutor
    from crashlite.study.runner import Progress

    cfg = _study(tmp_path)
    assert cfg.execution.solver == "lsdyna"
    s = run_study(cfg, executor=SerialExecutor(), progress=Progress(cfg, quiet=True))
    assert (s.ran, s.complete, s.failed) == (2, 2, 0)
    _check_designs(cfg, standin)


def test_study_on_a_cluster_object(tmp_path, standin):
    """run_study(cfg, cluster=...) with a LocalCluster standing in for a
    dask-jobqueue SLURMCluster: only its scheduler_address is used."""
    from distributed import LocalCluster

    from crashlite.study import run_study
    from crashlite.study.runner import Progress

    cfg = _study(tmp_path)

    class Batch:  # what run_study may rely on: dask-jobqueue clusters have scheduler_address
        def __init__(self, cluster):
            self.scheduler_address = cluster.scheduler_address

    with LocalCluster(
        n_workers=1, threads_per_worker=1, processes=False, protocol="tcp", dashboard_address=None, silence_logs=40
    ) as lc:
        s = run_study(cfg, progress=Progress(cfg, quiet=True), cluster=Batch(lc))
        assert s.executor.startswith("Dask cluster Batch (scheduler tcp://")
    assert (s.ran, s.complete, s.failed) == (2, 2, 0)
    _check_designs(cfg, standin)


def test_study_config_for_external_runs(tmp_path, standin, monkeypatch):
    from crashlite.study import StudyError, load_study, run_study

    cfg = _study(tmp_path, extra='cluster = "mymodule:make_cluster"')
    assert cfg.execution.cluster == "mymodule:make_cluster"
    p = tmp_path / "study.toml"
    for extra, match in (
        ('cluster = "nocolon"', "module:callable"),
        ('cluster = "a:b"\nscheduler = "tcp://x:8786"', "scheduler or cluster, not both"),
        ('solver = "abaqus"', "solver = 'abaqus' is not one of"),
    ):
        p.write_text(STUDY.format(extra="").replace('solver = "lsdyna"\n', "") + extra + "\n")
        with pytest.raises(StudyError, match=match):
            load_study(p)
    # responses an LS-DYNA run cannot give, said before anything runs
    for response, match in (
        ('type = "contact_force"', r"no \*CONTACT_ card"),
        ('type = "node_displacement"\nnode = 1', r"node\(s\) 1: .*\*DATABASE_HISTORY_NODE"),
        ('type = "wall_force"', None),
    ):
        p.write_text(STUDY.format(extra="") + "\n[responses.extra]\n" + response + "\n")
        if match is None:
            with pytest.raises(StudyError, match="rigid wall"):  # crashlite's own check comes first
                load_study(p)
            continue
        with pytest.raises(StudyError, match=match):
            load_study(p)
    _deck(tmp_path, history=False)
    p.write_text(STUDY.format(extra=""))
    with pytest.raises(StudyError, match=r"\[responses.stroke\] node_displacement reads nodout.*add \*DATABASE_NODOUT"):
        load_study(p)
    # the solver not configured: said when the study starts, before any design
    _deck(tmp_path)
    cfg = load_study(p)
    monkeypatch.delenv("CRASHLITE_LSDYNA")
    with pytest.raises(StudyError, match=r"\[execution\] solver = 'lsdyna': no LS-DYNA executable.*CRASHLITE_LSDYNA"):
        run_study(cfg)
    assert not (cfg.directory / "designs").exists()
    shutil.rmtree(cfg.directory, ignore_errors=True)


def test_compare_reads_solver_runs(tmp_path, standin, capsys):
    """What takes a results folder takes the solver's: crashlite compare."""
    deck = _deck(tmp_path)
    assert main(["run", str(deck), "--solver", "lsdyna", "-o", str(tmp_path / "a"), "--quiet"]) == 0
    deck.write_text(deck.read_text().replace("R crush      600.0", "R crush      650.0"))
    assert main(["run", str(deck), "--solver", "lsdyna", "-o", str(tmp_path / "b"), "--quiet"]) == 0
    capsys.readouterr()
    assert (
        main(["compare", str(tmp_path / "a"), str(tmp_path / "b"), "-o", str(tmp_path / "report"), "--no-plots"]) == 0
    )
    assert "curve pairs" in capsys.readouterr().out and (tmp_path / "report").is_dir()
