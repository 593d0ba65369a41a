"""Running a deck unchanged in an installed LS-DYNA or OpenRadioss.

One concept: where the solver is (its configuration), the command line it
gets, the run in the output folder, and the check that it terminated
normally. The results are then read by ``crashlite.results.load`` like any
LS-DYNA output folder (an OpenRadioss run: its ``<stem>T01`` time history,
``results.openradioss_th``).

Configuration, environment first, then a TOML file
(``$CRASHLITE_SOLVERS``, else ``~/.config/crashlite/solvers.toml``)::

    CRASHLITE_LSDYNA          executable        [lsdyna] executable
    CRASHLITE_LSDYNA_NCPU     ncpu=             [lsdyna] ncpu
    CRASHLITE_LSDYNA_MEMORY   memory=           [lsdyna] memory
    CRASHLITE_LSDYNA_ARGS     extra arguments   [lsdyna] args
    CRASHLITE_MPI             launcher prefix   [lsdyna] mpi (e.g. "mpirun -np 8")
                                                [lsdyna.env] variables of the run

LS-DYNA runs as ``<mpi> <executable> i=<deck> ncpu=<n> memory=<m> <args>``
with the output folder as its working directory (LS-DYNA writes there; the
deck is named by its path relative to the folder and left where it is, so
its includes resolve as they would anywhere). OpenRadioss reads LS-DYNA
decks through its starter and engine; crashlite runs it from command
templates (``[openradioss] commands``, defaults in ``OPENRADIOSS_COMMANDS``)
and checks the engine's listing for its normal termination.

A run records ``crashlite-solver.json`` (solver, a hash of the deck and its
includes, the command lines, the files the run wrote, its status). A folder
that already holds a normally terminated run of the same deck is not run
again unless ``force``.
"""

from __future__ import annotations

import fnmatch
import hashlib
import json
import os
import re
import shlex
import shutil
import signal
import subprocess
import time
import tomllib
from collections import deque
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

SOLVERS = ("lsdyna", "openradioss")
NAMES = {"lsdyna": "LS-DYNA", "openradioss": "OpenRadioss"}
MANIFEST = "crashlite-solver.json"
LOG = "crashlite-solver.log"
CONFIG_VARIABLE = "CRASHLITE_SOLVERS"
MPI_VARIABLE = "CRASHLITE_MPI"
TAIL = 20  # log lines an error shows

# OpenRadioss on an LS-DYNA deck: the starter reads the .k deck and writes
# the engine input <stem>_0001.rad, the engine runs it. Placeholders:
# {starter} {engine} {deck} {stem} {ncpu} {mpi} {args}.
OPENRADIOSS_COMMANDS = ("{starter} -i {deck} -np {ncpu} {args}", "{mpi} {engine} -i {stem}_0001.rad")

# What marks a normal end, and where it is written.
LSDYNA_TERMINATION = ("d3hsp", "messag", "mes0000")
_LSDYNA_NORMAL = re.compile(r"N\s*o\s*r\s*m\s*a\s*l\s+t\s*e\s*r\s*m\s*i\s*n\s*a\s*t\s*i\s*o\s*n")
_LSDYNA_ERROR = re.compile(r"E\s*r\s*r\s*o\s*r\s+t\s*e\s*r\s*m\s*i\s*n\s*a\s*t\s*i\s*o\s*n")
OPENRADIOSS_TERMINATION = ("{stem}_0001.out",)
_OPENRADIOSS_NORMAL = re.compile(r"NORMAL\s+TERMINATION")
_OPENRADIOSS_ERROR = re.compile(r"ERROR\s+TERMINATION")

# Names LS-DYNA (and crashlite) write in a run folder: present without this
# module's manifest naming them, they belong to a run crashlite did not
# start and refuse the folder (unless force).
OUTPUT_PATTERNS = (
    "d3hsp",
    "messag",
    "mes[0-9][0-9][0-9][0-9]*",
    "glstat",
    "matsum",
    "nodout",
    "rwforc",
    "deforc",
    "secforc",
    "spcforc",
    "rcforc",
    "sleout",
    "bndout",
    "nodfor",
    "elout",
    "jntforc",
    "abstat",
    "rbdout",
    "gceout",
    "sbtout",
    "swforc",
    "binout*",
    "d3plot*",
    "d3thdt*",
    "d3dump*",
    "runrsf*",
    "results.npz",
    "status.out",
)
_OPENRADIOSS_OUTPUTS = ("{stem}_[0-9][0-9][0-9][0-9]*", "{stem}T[0-9]*", "{stem}A[0-9]*")

_TABLE_KEYS = {
    "lsdyna": ("executable", "ncpu", "memory", "mpi", "args", "env"),
    "openradioss": ("starter", "engine", "ncpu", "mpi", "args", "env", "commands", "termination_files"),
}


class ExternalSolverError(RuntimeError):
    """The solver is not configured, cannot start, or its run failed; the
    message says which and, for a run, ends with the last lines of its log."""


class ExternalFolderError(FileExistsError):
    """The output folder holds another run's files; the message names them."""


@dataclass(frozen=True)
class SolverSettings:
    """How to start one external solver, and where each setting came from."""

    solver: str  # "lsdyna" or "openradioss"
    executable: str  # LS-DYNA's executable, OpenRadioss's starter (absolute)
    engine: str = ""  # OpenRadioss's engine (absolute)
    ncpu: int | None = None
    memory: str | None = None
    mpi: tuple[str, ...] = ()  # launcher prefix, e.g. ("mpirun", "-np", "8")
    args: tuple[str, ...] = ()  # extra arguments
    env: dict = field(default_factory=dict)  # variables set for the run
    commands: tuple[str, ...] = ()  # OpenRadioss command templates
    termination_files: tuple[str, ...] = ()
    sources: dict = field(default_factory=dict)  # setting -> "CRASHLITE_LSDYNA" or "file [table] key"

    @property
    def name(self) -> str:
        return NAMES[self.solver]


# --- configuration ------------------------------------------------------------


def config_file(environ: Mapping[str, str] | None = None) -> Path | None:
    """The solvers file: $CRASHLITE_SOLVERS (which must exist), else
    ~/.config/crashlite/solvers.toml (or under $XDG_CONFIG_HOME) if present."""
    env = os.environ if environ is None else environ
    named = env.get(CONFIG_VARIABLE, "").strip()
    if named:
        p = Path(named).expanduser()
        if not p.is_file():
            raise ExternalSolverError(
                f"{CONFIG_VARIABLE}={named}: no such file (it names the TOML file of the external solvers' settings)"
            )
        return p
    base = Path(env.get("XDG_CONFIG_HOME") or Path(env.get("HOME") or Path.home()) / ".config").expanduser()
    p = base / "crashlite" / "solvers.toml"
    return p if p.is_file() else None


def _read_table(path: Path | None, solver: str) -> dict:
    if path is None:
        return {}
    try:
        data = tomllib.loads(path.read_text())
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as e:
        raise ExternalSolverError(f"{path}: malformed TOML: {e}") from None
    t = data.get(solver, {})
    if not isinstance(t, dict):
        raise ExternalSolverError(f"{path}: [{solver}] must be a table")
    extra = [k for k in t if k not in _TABLE_KEYS[solver]]
    if extra:
        raise ExternalSolverError(
            f"{path}: [{solver}] unknown key(s) {', '.join(map(repr, extra))} (known: {', '.join(_TABLE_KEYS[solver])})"
        )
    return t


def _words(value, where: str) -> tuple[str, ...]:
    """A command prefix or argument list: a string (shell words) or a list of strings."""
    if value is None:
        return ()
    if isinstance(value, str):
        try:
            return tuple(shlex.split(value))
        except ValueError as e:
            raise ExternalSolverError(f"{where}: {e}") from None
    if isinstance(value, list) and all(isinstance(v, str) for v in value):
        return tuple(value)
    raise ExternalSolverError(f"{where}: must be a string or a list of strings, got {value!r}")


def _ncpu(value, where: str, negative: bool) -> int | None:
    """ncpu: a whole number; LS-DYNA's negative ncpu=-N (N CPUs, results
    independent of N) passes where ``negative``."""
    if value is None or value == "":
        return None
    try:
        n = int(str(value).strip()) if not isinstance(value, (bool, float)) else None
    except ValueError:
        n = None
    if n is None or n == 0 or (n < 0 and not negative):
        raise ExternalSolverError(
            f"{where}: must be a whole number of 1 or more"
            + (" (or -N: LS-DYNA's consistent mode on N CPUs)" if negative else "")
        )
    return n


def _program(value: str, where: str) -> str:
    """The absolute path of an executable named by a path or a command on PATH."""
    p = Path(value).expanduser()
    shown = where if value in where else f"{where}: {value}"
    if os.sep in value or p.is_absolute():
        if not p.is_file():
            raise ExternalSolverError(f"{shown}: no such file")
        if not os.access(p, os.X_OK):
            raise ExternalSolverError(f"{shown}: not executable (chmod +x?)")
        return str(p.absolute())
    found = shutil.which(value)
    if found is None:
        raise ExternalSolverError(f"{shown}: {value} not found on PATH (give the full path)")
    return found


def settings(
    solver: str = "lsdyna", environ: Mapping[str, str] | None = None, path: Path | str | None = None
) -> SolverSettings:
    """The settings of ``solver`` from the environment (first) and the
    solvers file; ExternalSolverError names the variable or key at fault."""
    if solver not in SOLVERS:
        raise ValueError(f"unknown external solver {solver!r} (known: {', '.join(SOLVERS)})")
    env = os.environ if environ is None else environ
    path = Path(path) if path is not None else config_file(env)
    table = _read_table(path, solver)
    prefix = f"CRASHLITE_{solver.upper()}"
    sources: dict = {}

    def pick(key: str, variable: str | None):
        if variable and env.get(variable, "").strip():
            sources[key] = variable
            return env[variable].strip()
        if key in table:
            sources[key] = f"{path} [{solver}] {key}"
            return table[key]
        return None

    def where(key: str) -> str:
        """The setting as the user wrote it: NAME=value or file [table] key = value."""
        src = sources.get(key)
        if src is None:
            return key
        if src.startswith("CRASHLITE_"):
            return f"{src}={env[src].strip()}"
        return f"{src} = {table[key]!r}"

    file_hint = (
        f"{path}" if path is not None else f"~/.config/crashlite/solvers.toml (or the file {CONFIG_VARIABLE} names)"
    )
    if solver == "lsdyna":
        exe = pick("executable", prefix)
        if not exe:
            raise ExternalSolverError(
                f"no LS-DYNA executable configured: set {prefix}=/path/to/lsdyna (options: {prefix}_NCPU, "
                f'{prefix}_MEMORY, {prefix}_ARGS, {MPI_VARIABLE}), or executable = "..." under [lsdyna] '
                f"in {file_hint}"
            )
        engine = ""
        executable = _program(str(exe), where("executable"))
    else:
        starter, eng = pick("starter", f"{prefix}_STARTER"), pick("engine", f"{prefix}_ENGINE")
        if not starter or not eng:
            lack = " and ".join(k for k, v in (("starter", starter), ("engine", eng)) if not v)
            raise ExternalSolverError(
                f"no OpenRadioss {lack} configured: set {prefix}_STARTER and {prefix}_ENGINE (the starter and "
                f"engine executables; options: {prefix}_NCPU, {prefix}_ARGS, {MPI_VARIABLE}), or starter and "
                f"engine under [openradioss] in {file_hint}"
            )
        executable = _program(str(starter), where("starter"))
        engine = _program(str(eng), where("engine"))
    ncpu = _ncpu(pick("ncpu", f"{prefix}_NCPU"), where("ncpu"), negative=solver == "lsdyna")
    memory = pick("memory", f"{prefix}_MEMORY") if solver == "lsdyna" else None
    if memory is not None and (
        isinstance(memory, bool) or not isinstance(memory, (str, int)) or not str(memory).strip()
    ):
        raise ExternalSolverError(
            f'{where("memory")}: must be LS-DYNA\'s memory= value (e.g. "2000m" or a number of words), got {memory!r}'
        )
    mpi = _words(pick("mpi", MPI_VARIABLE), where("mpi"))
    if mpi:
        _program(mpi[0], where("mpi"))
    args = _words(pick("args", f"{prefix}_ARGS"), where("args"))
    run_env = table.get("env", {})
    if not isinstance(run_env, dict) or not all(isinstance(v, (str, int, float)) for v in run_env.values()):
        raise ExternalSolverError(f'{path} [{solver}.env]: must be a table of NAME = "value"')
    commands: tuple[str, ...] = ()
    term: tuple[str, ...] = LSDYNA_TERMINATION
    if solver == "openradioss":
        commands = _templates(table.get("commands", list(OPENRADIOSS_COMMANDS)), f"{path} [openradioss] commands")
        term = _templates(
            table.get("termination_files", list(OPENRADIOSS_TERMINATION)), f"{path} [openradioss] termination_files"
        )
    return SolverSettings(
        solver=solver,
        executable=executable,
        engine=engine,
        ncpu=ncpu,
        memory=None if memory is None else str(memory).strip(),
        mpi=mpi,
        args=args,
        env={str(k): str(v) for k, v in run_env.items()},
        commands=commands,
        termination_files=term,
        sources=sources,
    )


def _templates(value, where: str) -> tuple[str, ...]:
    if not isinstance(value, list) or not value or not all(isinstance(v, str) and v.strip() for v in value):
        raise ExternalSolverError(f"{where}: must be a list of command templates (strings), got {value!r}")
    return tuple(value)


# --- command line ---------------------------------------------------------------


def command_lines(s: SolverSettings, deck: str) -> list[list[str]]:
    """The argument lists the run executes, in order, with ``deck`` the
    deck's path as the solver sees it (relative to the run folder)."""
    if s.solver == "lsdyna":
        cmd = [*s.mpi, s.executable, f"i={deck}"]
        if s.ncpu is not None:
            cmd.append(f"ncpu={s.ncpu}")
        if s.memory is not None:
            cmd.append(f"memory={s.memory}")
        return [cmd + list(s.args)]
    values = {
        "starter": shlex.quote(s.executable),
        "engine": shlex.quote(s.engine),
        "deck": shlex.quote(deck),
        "stem": shlex.quote(Path(deck).stem),
        "ncpu": str(s.ncpu or 1),
        "mpi": " ".join(map(shlex.quote, s.mpi)),
        "args": " ".join(map(shlex.quote, s.args)),
    }
    out = []
    for t in s.commands:
        try:
            out.append(shlex.split(t.format(**values)))
        except (KeyError, IndexError, ValueError) as e:
            raise ExternalSolverError(
                f"[openradioss] commands: {t!r}: {type(e).__name__}: {e} (placeholders: "
                f"{', '.join('{' + k + '}' for k in values)})"
            ) from None
    return [c for c in out if c]


def normal_termination(folder: Path | str, s: SolverSettings, stem: str = "") -> tuple[str | None, str]:
    """(file that reports a normal termination or None, what was found
    instead), from the end of the solver's listing files."""
    folder = Path(folder)
    normal, error = (
        (_LSDYNA_NORMAL, _LSDYNA_ERROR) if s.solver == "lsdyna" else (_OPENRADIOSS_NORMAL, _OPENRADIOSS_ERROR)
    )
    seen = []
    for pattern in s.termination_files:
        name = pattern.format(stem=stem)
        p = folder / name
        if not p.is_file():
            continue
        text = _tail_text(p)
        if normal.search(text):
            return name, ""
        seen.append(f"{name}: error termination" if error.search(text) else f"{name}: no termination line")
    return None, "; ".join(seen) or f"none of {', '.join(t.format(stem=stem) for t in s.termination_files)} was written"


def _tail_text(path: Path, size: int = 1 << 16) -> str:
    with open(path, "rb") as f:
        f.seek(0, os.SEEK_END)
        f.seek(max(0, f.tell() - size))
        return f.read().decode("latin-1")


# --- the deck ---------------------------------------------------------------------


def deck_files(deck: Path | str) -> list[Path]:
    """The deck and the include files it names (as crashlite's reader finds them)."""
    from .keyword.errors import Collector
    from .keyword.lexer import Lexer

    lex = Lexer(Collector())
    try:
        lex.walk(Path(deck))
    except Exception:  # noqa: BLE001 - the hash then covers the deck itself; the solver judges the deck
        return [Path(deck)]
    out: list[Path] = []
    for f in [Path(deck), *lex.files]:
        if f.resolve() not in {o.resolve() for o in out}:
            out.append(f)
    return out


def deck_hash(files: list[Path]) -> str:
    """SHA-256 over the files' contents and their paths relative to the deck."""
    h = hashlib.sha256()
    root = Path(files[0]).resolve().parent
    for f in files:
        rp = Path(f).resolve()
        try:
            name = str(rp.relative_to(root))
        except ValueError:
            name = str(rp)
        h.update(name.encode() + b"\0")
        with open(rp, "rb") as fh:
            for chunk in iter(lambda: fh.read(1 << 20), b""):
                h.update(chunk)
        h.update(b"\0")
    return h.hexdigest()


# --- the run -----------------------------------------------------------------------


@dataclass
class ExternalRun:
    """What ``run`` did: the folder holds the solver's results."""

    solver: str
    folder: Path
    deck: Path
    commands: list  # argument lists
    ran: bool  # False: the folder held a normal-terminated run of the same deck, kept
    wall_time: float  # of this run (0 when kept)
    termination: str  # the file reporting the normal termination
    log: Path


def _manifest(folder: Path) -> dict | None:
    p = folder / MANIFEST
    if not p.is_file():
        return None
    try:
        data = json.loads(p.read_text())
        if not isinstance(data, dict) or not isinstance(data.get("files", []), list):
            raise ValueError("not a table with a list of files")
        return data
    except (OSError, ValueError) as e:
        raise ExternalFolderError(
            f"{p}: not a crashlite solver manifest ({e}); remove it or choose another folder"
        ) from None


def _write_manifest(folder: Path, data: dict) -> None:
    tmp = folder / (MANIFEST + ".tmp")
    tmp.write_text(json.dumps(data, indent=1) + "\n")
    tmp.replace(folder / MANIFEST)


def _listing(folder: Path) -> dict[str, tuple[int, int]]:
    out = {}
    for p in folder.iterdir() if folder.is_dir() else ():
        if p.is_file() and p.name not in (MANIFEST, MANIFEST + ".tmp"):
            st = p.stat()
            out[p.name] = (st.st_mtime_ns, st.st_size)
    return out


def _outputs_present(folder: Path, s: SolverSettings, stem: str) -> list[str]:
    patterns = OUTPUT_PATTERNS + (
        tuple(p.format(stem=stem) for p in _OPENRADIOSS_OUTPUTS) if s.solver == "openradioss" else ()
    )
    return sorted(n for n in _listing(folder) if any(fnmatch.fnmatchcase(n, p) for p in patterns))


def _prepare(
    folder: Path, s: SolverSettings, stem: str, previous: dict | None, protected: set[Path], force: bool
) -> list[str]:
    """Remove the previous run's files (and, with force, other runs' files
    of the names a solver writes); refuse the folder when it holds files of
    a run crashlite did not start. Returns the names removed."""
    from .results.folder import MANIFEST as CRASHLITE_MANIFEST
    from .results.folder import OutputFolder

    ours = set(previous.get("files", [])) if previous else set()
    embedded = OutputFolder(folder).previous if (folder / CRASHLITE_MANIFEST).is_file() else set()
    present = _outputs_present(folder, s, stem)
    foreign = [n for n in present if n not in ours and n not in embedded and (folder / n).resolve() not in protected]
    if foreign and not force:
        shown = ", ".join(foreign[:8]) + (f" and {len(foreign) - 8} more" if len(foreign) > 8 else "")
        raise ExternalFolderError(
            f"the output folder {folder} holds files of a run crashlite did not start "
            f"({shown}): choose another folder (-o), remove them, or overwrite them with "
            "--force"
        )
    removed = []
    targets = sorted(ours | set(foreign) | {n for n in embedded if "/" not in n})
    for name in targets:
        p = folder / name
        if "/" in name or p.resolve() in protected or not p.is_file():
            continue
        p.unlink()
        removed.append(name)
    if embedded:  # a crashlite run's results.npz would shadow the solver's files in results.load
        states = folder / "states"
        for name in embedded:
            if name.startswith("states/") and (folder / name).is_file():
                (folder / name).unlink()
        if states.is_dir() and not any(states.iterdir()):
            states.rmdir()
        (folder / CRASHLITE_MANIFEST).unlink(missing_ok=True)
    return removed


def run(
    deck: Path | str,
    out: Path | str,
    solver: str = "lsdyna",
    *,
    config: SolverSettings | None = None,
    force: bool = False,
    echo: Callable[[str], None] | None = None,
) -> ExternalRun:
    """Run ``deck`` unchanged in the external ``solver`` with ``out`` as its
    working directory; ``echo(line)`` gets the solver's output lines as they
    come. Raises ExternalSolverError (not configured, cannot start, non-zero
    exit, no normal termination: with the log's last lines) or
    ExternalFolderError (the folder holds another run's files)."""
    s = config or settings(solver)
    deck = Path(deck)
    if not deck.is_file():
        raise FileNotFoundError(
            f"{deck}: deck file not found" if not deck.is_dir() else f"{deck}: a folder, not a deck file"
        )
    deck = deck.resolve()
    folder = Path(out)
    if folder.exists() and not folder.is_dir():
        raise ExternalFolderError(f"{folder} is a file, not a folder: -o names the folder the solver runs in")
    folder.mkdir(parents=True, exist_ok=True)
    folder = folder.resolve()
    files = deck_files(deck)
    digest = deck_hash(files)
    protected = {f.resolve() for f in files}
    previous = _manifest(folder)
    log = folder / LOG
    stem = deck.stem
    from .results.folder import MANIFEST as CRASHLITE_MANIFEST

    if (
        previous
        and not force
        and previous.get("solver") == s.solver
        and previous.get("deck_sha256") == digest
        and previous.get("status") == "complete"
        and not (folder / CRASHLITE_MANIFEST).exists()
    ):
        found, _ = normal_termination(folder, s, stem)
        if found:
            return ExternalRun(s.solver, folder, deck, previous.get("commands", []), False, 0.0, found, log)
    _prepare(folder, s, stem, previous, protected, force)
    ref = os.path.relpath(deck, folder)
    if len(ref) > len(str(deck)):
        ref = str(deck)
    commands = command_lines(s, ref)
    env = dict(os.environ)
    env.update(s.env)
    before = _listing(folder)
    record = {
        "written_by": "crashlite run --solver",
        "solver": s.solver,
        "deck": str(deck),
        "deck_files": [str(f) for f in files],
        "deck_sha256": digest,
        "commands": commands,
        "settings": dict(s.sources),
        "status": "running",
        "started": time.time(),
        "files": [LOG],
    }
    _write_manifest(folder, record)
    t0 = time.perf_counter()
    tail: deque = deque(maxlen=TAIL)
    status, message, termination = "failed", "", ""
    try:
        with open(log, "w", encoding="utf-8", errors="replace") as fh:
            for cmd in commands:
                fh.write(f"$ {shlex.join(cmd)}\n")
                fh.flush()
                rc = _execute(cmd, folder, env, fh, tail, echo, s)
                if rc != 0:
                    message = (
                        f"{s.name} exited with status {rc} ({shlex.join(cmd[:3])} ...); last lines of "
                        f"{log}:\n" + "\n".join(tail)
                    )
                    raise ExternalSolverError(message)
        found, instead = normal_termination(folder, s, stem)
        if found is None:
            message = (
                f"{s.name} exited with status 0 but reports no normal termination ({instead}); last lines "
                f"of {log}:\n" + "\n".join(tail)
            )
            raise ExternalSolverError(message)
        status, termination = "complete", found
    except KeyboardInterrupt:
        status, message = "interrupted", "interrupted (Ctrl-C)"
        raise
    except ExternalSolverError as e:
        message = str(e)
        raise
    finally:
        after = _listing(folder)
        written = sorted(
            n
            for n, st in after.items()
            if (before.get(n) != st or n == LOG) and (folder / n).resolve() not in protected
        )
        record.update(
            status=status,
            message=message[:4000],
            files=written,
            finished=time.time(),
            wall_time=time.perf_counter() - t0,
            termination=termination,
        )
        _write_manifest(folder, record)
    return ExternalRun(s.solver, folder, deck, commands, True, record["wall_time"], termination, log)


def _execute(cmd: list[str], cwd: Path, env: dict, fh, tail: deque, echo, s: SolverSettings) -> int:
    """Run one command, its output (stdout and stderr) into the log, the
    tail and ``echo``; the exit status. Ctrl-C stops the solver's process
    group (terminate, then kill after 10 s) and is raised again."""
    try:
        proc = subprocess.Popen(
            cmd,
            cwd=cwd,
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
    except OSError as e:
        which = s.sources.get("mpi" if s.mpi and cmd[0] == s.mpi[0] else "executable", "the executable")
        raise ExternalSolverError(f"cannot start {s.name} ({which}): {cmd[0]}: {e.strerror or e}") from None
    try:
        for raw in proc.stdout:
            line = raw.decode("utf-8", errors="replace").rstrip("\r\n")
            fh.write(line + "\n")
            fh.flush()
            tail.append(line)
            if echo is not None:
                echo(line)
        return proc.wait()
    except BaseException:
        _stop(proc)
        raise
    finally:
        if proc.stdout is not None:
            proc.stdout.close()


def _stop(proc: subprocess.Popen) -> None:
    if proc.poll() is not None:
        return
    for sig, wait in ((signal.SIGTERM, 10.0), (getattr(signal, "SIGKILL", signal.SIGTERM), 5.0)):
        try:
            if hasattr(os, "killpg"):
                os.killpg(proc.pid, sig)  # the solver's own group: mpirun and its ranks too
            else:
                proc.send_signal(sig)
        except (ProcessLookupError, PermissionError):
            return
        try:
            proc.wait(timeout=wait)
            return
        except subprocess.TimeoutExpired:
            continue
