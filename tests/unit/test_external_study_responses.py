"""Study responses of LS-DYNA runs that need more than nodout: contact
forces (rcforc, as an ASCII file or a binout's branch) and final
displacements of nodes that are not history nodes (the d3plot's final
state), on a stand-in for LS-DYNA (as in test_external_solver.py: an
executable Python script that writes real LS-DYNA files with crashlite's
writers and lasso-python into its working directory).

The deck: two masses (m at node 2, a history node, and 2m at node 3, not
one) driving at v0 into one linear spring each, tied to the fixed node 1,
whose push reaches them through contact 7 (slave side: the masses) with a
tangential tenth; a single surface contact 2 beside it. Closed form: node
displacement u = -(v0/ω)·sin(ωt), ω² = k/mass, contact force
-k·(u2 + u3) along x on the slave side."""

from __future__ import annotations

import math
import os
import stat
import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("lasso.dyna", reason="the stand-in writes its d3plot and binout through lasso-python")

PULSE = Path(__file__).parents[2] / "src" / "crashlite" / "examples" / "pulse" / "pulse.k"
V0, T_END = 15555.6, 0.12
T_SAMPLES = np.linspace(0.0, T_END, 61)  # the stand-in's glstat, nodout and rcforc interval: 2 ms

STANDIN = r'''
"""Stand-in for LS-DYNA on the two-mass deck: i=deck; glstat, nodout and
rcforc as ASCII files (STANDIN_BINOUT=1: one binout), a d3plot of three
states, d3hsp and messag with the normal termination."""
import os
import sys
from pathlib import Path

import numpy as np

from crashlite import read_deck
from crashlite.results import d3plot
from crashlite.results.lsdyna_ascii import FILES

args = dict(a.split("=", 1) for a in sys.argv[1:] if "=" in a)
model = read_deck(args["i"])
p = {q.name.lower(): float(q.value) for q in model.parameters}
k, v0 = p["k"], p["v0"]
w2, w3 = np.sqrt(k / p["m"]), np.sqrt(k / p["m3"])


def u(w, t):  # displacement along x of a mass on its spring
    return -(v0 / w) * np.sin(w * t)


def v(w, t):
    return -v0 * np.cos(w * t)


t = np.linspace(0.0, 0.12, 61)
n = len(t)
zero = np.zeros((n, 1))
ke = 0.5 * p["m"] * v(w2, t) ** 2 + 0.5 * p["m3"] * v(w3, t) ** 2
f = -k * (u(w2, t) + u(w3, t))  # the springs' push on both masses, through contact 7's slave side
cats = {
    "glstat": {"time": t, "kinetic_energy": ke, "internal_energy": ke[0] - ke, "total_energy": np.full(n, ke[0]),
               "external_work": np.zeros(n)},
    "nodout": {"time": t, "ids": np.array([2]), "x_displacement": u(w2, t)[:, None], "y_displacement": zero,
               "z_displacement": zero, "x_velocity": v(w2, t)[:, None], "y_velocity": zero, "z_velocity": zero},
    "rcforc": {"time": t, "ids": np.array([7, 7]), "side": np.array([0, 1]),
               "x_force": np.stack([f, -f], axis=1), "y_force": np.stack([-0.1 * f, 0.1 * f], axis=1),
               "z_force": np.zeros((n, 2)), "mass": np.tile([p["m"] + p["m3"], 0.0], (n, 1))},
}


def binout(path, cats):
    """Each category as LS-DYNA's binout holds it: metadata ids (and side),
    a directory per state."""
    from lasso.dyna.lsda_py3 import Lsda

    b = Lsda(path, "w")
    for name, data in cats.items():
        b.cd(f"/{name}/metadata")
        b.write("title", Lsda.I1, b"stand-in".ljust(80))
        for key in ("ids", "side"):
            if key in data:
                b.write(key, Lsda.I4, [int(i) for i in data[key]])
        for i, ti in enumerate(data["time"]):
            b.cd(f"/{name}/d{i + 1:06d}")
            b.write("time", Lsda.R4, [float(ti)])
            for key, a in data.items():
                if key not in ("time", "ids", "side"):
                    b.write(key, Lsda.R4, [float(x) for x in np.atleast_1d(a[i])])
    b.close()


if os.environ.get("STANDIN_BINOUT") == "1":
    binout("binout", cats)
else:
    for name, data in cats.items():
        FILES[name].write(Path(name), data, "stand-in")
ts = np.array([0.0, 0.06, 0.12])  # the d3plot's states
coords = np.repeat(model.nodes.xyz[None], len(ts), axis=0)
for node, w in ((2, w2), (3, w3)):
    coords[:, model.node_index(np.array([node]))[0], 0] += u(w, ts)
fields = [{"velocity": np.zeros(coords.shape[1:], np.float32), "acceleration": np.zeros(coords.shape[1:], np.float32)}
          for _ in ts]
d3plot.write("d3plot", model, ts, coords, fields, title="stand-in")
end = " N o r m a l    t e r m i n a t i o n"
Path("d3hsp").write_text(" ls-dyna stand-in\n ...\n" + end + "                    01/01/25 00:00:01\n")
Path("messag").write_text(end + "\n")
print(end)
'''

NODES = """\
       3          1000.0           100.0             0.0       5       7
      11           -10.0          -200.0          -200.0       7       7
      12           -10.0           300.0          -200.0       7       7
      13           -10.0           300.0           200.0       7       7
      14           -10.0          -200.0           200.0       7       7
"""
BARRIER = """\
*PART
barrier
         2         2         2
*SECTION_SHELL
         2         2
       1.0       1.0       1.0       1.0
*MAT_RIGID
         2   7.85E-9  210000.0       0.3
*ELEMENT_SHELL
       1       2      11      12      13      14
*SET_NODE_LIST
         1
         2         3
*CONTACT_AUTOMATIC_NODES_TO_SURFACE_ID
         7front on barrier
         1         2         4         3


*CONTACT_AUTOMATIC_SINGLE_SURFACE
         2         0         2


"""
OUTPUT = ("GLSTAT", "NODOUT", "RCFORC", "BINARY_D3PLOT")


def _deck(path: Path, output=OUTPUT) -> Path:
    """The pulse example with a second mass (2m, node 3, not a history
    node) on a second spring, a rigid barrier and its contacts."""
    s = PULSE.read_text()
    node2 = "       2          1000.0             0.0             0.0       5       7\n"
    s = s.replace(node2, node2 + NODES)
    s = s.replace("R k       m*v0**2/crush**2\n", "R k       m*v0**2/crush**2\nR m3      2.0*m\n")
    s = s.replace(
        "     100       2              &m\n", "     100       2              &m\n     101       3             &m3\n"
    )
    spring = "       1       1       1       2       0             1.0       0             0.0\n"
    s = s.replace(
        spring, spring + spring.replace("       1       1       1       2", "       2       1       1       3")
    )
    velocity = "         2      -&v0       0.0       0.0\n"
    s = s.replace(velocity, velocity + velocity.replace("2", "3", 1))
    s = s.replace("*CONTROL_TERMINATION", BARRIER + "*CONTROL_TERMINATION")
    s = s.replace("*END", "".join(f"*DATABASE_{kw}\n   1.0E-3\n" for kw in output) + "*END")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(s)
    return path


STUDY = """
[study]
name = "two masses"
deck = "model/pulse2.k"

[variables.m]
parameter = "m"
bounds = [1.0, 2.0]

[variables.crush]
parameter = "crush"
bounds = [400.0, 800.0]

{responses}

[doe]
method = "lhs"
designs = 2

[execution]
solver = "{solver}"
"""

RESPONSES = """
[responses.push]
type = "contact_force"
id = 7
component = "x"

[responses.pull]
type = "contact_force"
id = 7
component = "x"
stat = "min"

[responses.friction]
type = "contact_force"
component = "y"
stat = "min"

[responses.resultant]
type = "contact_force"
id = 7
component = "magnitude"

[responses.far]
type = "node_displacement"
node = 3

[responses.gap]
type = "intrusion"
nodes = [3]
reference = 1
component = "x"

[responses.front]
type = "intrusion"
nodes = [2, 3]

[responses.stroke]
type = "node_displacement"
node = 2
"""


@pytest.fixture
def standin(tmp_path, monkeypatch):
    exe = tmp_path / "bin" / "lsdyna_smp_d"
    exe.parent.mkdir()
    exe.write_text(f"#!{sys.executable}\n" + STANDIN)
    exe.chmod(exe.stat().st_mode | stat.S_IXUSR)
    for k in list(os.environ):
        if k.startswith("CRASHLITE_") and k != "CRASHLITE_NUMBA_CACHE":
            monkeypatch.delenv(k)
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "no-config"))
    monkeypatch.setenv("CRASHLITE_LSDYNA", str(exe))
    monkeypatch.delenv("STANDIN_BINOUT", raising=False)
    return exe


def _study(tmp_path, responses=RESPONSES, solver="lsdyna", output=OUTPUT):
    from crashlite.study import load_study

    _deck(tmp_path / "model" / "pulse2.k", output)
    p = tmp_path / "study.toml"
    p.write_text(STUDY.format(responses=responses, solver=solver))
    return load_study(p)


def _closed_form(m: float, crush: float) -> dict:
    """The responses of a design from the closed form (the contact force
    as the stand-in samples it, every 2 ms)."""
    k = m * V0**2 / crush**2
    w2, w3 = V0 / crush, math.sqrt(k / (2.0 * m))
    u2, u3 = (-(V0 / w) * math.sin(w * T_END) for w in (w2, w3))
    f = k * ((V0 / w2) * np.sin(w2 * T_SAMPLES) + (V0 / w3) * np.sin(w3 * T_SAMPLES))
    return {
        "push": f.max(),
        "pull": f.min(),
        "friction": (-0.1 * f).min(),
        "resultant": math.sqrt(1.01) * np.abs(f).max(),
        "far": u3,
        "gap": abs(u3),
        "front": max(abs(u2), abs(u3)),
        "stroke": u2,
    }


@pytest.mark.parametrize("output", ["ascii", "binout"])
def test_contact_forces_and_final_displacements_of_lsdyna_runs(tmp_path, standin, monkeypatch, output):
    """contact_force from rcforc's slave lines (the ASCII file or the
    binout's branch), final displacements of node 3 from the d3plot's final
    state (by node ID), of the history node 2 from nodout: each design's
    against its closed form."""
    from crashlite.study import run_study
    from crashlite.study.executor import SerialExecutor
    from crashlite.study.runner import Progress
    from crashlite.study.storage import StudyStore

    if output == "binout":
        monkeypatch.setenv("STANDIN_BINOUT", "1")
    cfg = _study(tmp_path)
    s = run_study(cfg, executor=SerialExecutor(), progress=Progress(cfg, quiet=True))
    designs = StudyStore(cfg).designs()
    assert (s.ran, s.complete) == (2, 2), [d.message for d in designs]
    for d in designs:
        folder = cfg.directory / "designs" / d.key / "results"
        assert (folder / "d3plot").is_file() and (folder / "binout").is_file() == (output == "binout")
        want = _closed_form(d.values["m"], d.values["crush"])
        r = d.responses
        digits = 1e-6 if output == "binout" else 1e-5  # float32, or rcforc's %12.5E
        for name in ("push", "pull", "friction", "resultant"):
            assert r[name] == pytest.approx(want[name], rel=digits), name
        assert r["push"] > 0 > r["friction"]  # the slave side: the masses pushed back (+x)
        for name in ("far", "gap", "front"):  # single-precision coordinates near 1000 mm
            assert r[name] == pytest.approx(want[name], abs=2e-3), name
        assert abs(r["far"]) > 100.0  # node 3 is far from where it started
        assert r["stroke"] == pytest.approx(want["stroke"], rel=1e-4, abs=1e-3)  # nodout: 5 digits


def test_refused_before_any_run(tmp_path, standin):
    """What an LS-DYNA run cannot give is refused when the study is read,
    naming the study file and the response key."""
    from crashlite.study import StudyError

    far = '[responses.far]\ntype = "node_displacement"\nnode = 3\n'
    with pytest.raises(
        StudyError,
        match=r"study\.toml: \[responses\.far\] the final displacement of node\(s\) 3: .* asks for no d3plot: "
        r"add \*DATABASE_BINARY_D3PLOT, or add the nodes to \*DATABASE_HISTORY_NODE",
    ):
        _study(tmp_path, far, output=("GLSTAT", "NODOUT", "RCFORC"))
    gap = '[responses.gap]\ntype = "intrusion"\nnodes = [2]\nreference = 1\n'
    with pytest.raises(StudyError, match=r"\[responses\.gap\] the final displacement of node\(s\) 1: "):
        _study(tmp_path, gap, output=("GLSTAT", "NODOUT"))
    _study(tmp_path, far, output=("GLSTAT", "BINARY_D3PLOT"))  # no nodout needed: the d3plot gives every node
    push = '[responses.push]\ntype = "contact_force"\n'
    for table, output, match in (
        (push, ("GLSTAT",), r"\[responses\.push\] contact_force reads rcforc, .* add \*DATABASE_RCFORC"),
        (push + "id = 8\n", OUTPUT, r"\[responses\.push\] id: contact interface 8 is not in the deck "),
        (push + "id = 2\n", OUTPUT, r"id: contact interface 2 is a single surface contact .*FORCE_TRANSDUCER"),
    ):
        with pytest.raises(StudyError, match=match):
            _study(tmp_path, table, output=output)
    _study(tmp_path, push + "id = 7\n", solver="openradioss")  # its /INTER 7 (model.contacts)
    with pytest.raises(StudyError, match=r"\[responses\.push\] id: contact interface 2 is a single surface contact"):
        _study(tmp_path, push + "id = 2\n", solver="openradioss")
    with pytest.raises(StudyError, match=r"\[responses\.far\] the final displacement .* history nodes only"):
        _study(tmp_path, far, solver="openradioss")
