"""Output folders of ``crashlite run``: what a run may write there, and a
manifest (``crashlite-run.json``) of what it wrote.

Rules: a run never overwrites a file it did not write. Before the run, the
folder is checked: a path that is a file, the deck (or one of its includes)
among the names a run writes, or a foreign file of such a name (one no
earlier run listed in its manifest) refuse the run, naming them (foreign
files are overwritten with ``force``; the deck never). A folder reused by
an earlier run is emptied of that run's own files first, so no stale
history file, VTK state or d3plot file stays beside the new ones. Other
files in the folder are left alone.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable
from pathlib import Path

from .lsdyna_ascii import FILES

MANIFEST = "crashlite-run.json"
FILE_NAMES = ("results.npz", *FILES, "initial_penetrations.csv", "d3plot")  # written in the folder itself
STATES = "states"  # the VTK states' sub-folder
_STATE_FILE = re.compile(r"^(state_\d{4,}\.vtk|states\.pvd)$")
_D3PLOT_FILE = re.compile(r"^d3plot\d+$")  # the d3plot's further files (d3plot01, ...: its states)


class OutputFolderError(FileExistsError):
    """The folder cannot take the run's results; the message names why."""


class OutputFolder:
    """The results folder of one run: ``check`` before the run (and again
    with the deck's files once it is read), ``clear`` the previous run's
    files, ``record`` what this run wrote (also after a stopped run)."""

    def __init__(self, path, deck=None, force: bool = False):
        if str(path) == "":
            raise OutputFolderError("the output folder is an empty path: name a folder")
        self.path = Path(path)
        self.force = force
        self.decks = [Path(deck)] if deck is not None else []
        self.previous = self._read_manifest()

    # --- what belongs to crashlite ------------------------------------------
    def _read_manifest(self) -> set[str]:
        m = self.path / MANIFEST
        if not m.is_file():
            return set()
        try:
            data = json.loads(m.read_text())
            files = {str(f) for f in data["files"]}
            if data.get("state_pattern"):  # a run that did not finish: its states are unlisted
                states = self.path / STATES
                files |= {f"{STATES}/{q.name}" for q in (states.iterdir() if states.is_dir() else ())}
                files |= set(self._d3plot_files())
        except (OSError, ValueError, KeyError, TypeError) as e:
            raise OutputFolderError(
                f"{m}: not a crashlite run manifest ({e}); remove it or choose another folder"
            ) from None
        return {f for f in files if self._ours_by_name(f)}  # nothing outside the run's own names

    @staticmethod
    def _ours_by_name(rel: str) -> bool:
        parts = rel.split("/")
        return (len(parts) == 1 and (parts[0] in FILE_NAMES or bool(_D3PLOT_FILE.match(parts[0])))) or (
            len(parts) == 2 and parts[0] == STATES and bool(_STATE_FILE.match(parts[1]))
        )

    def candidates(self) -> list[str]:
        """Relative paths of the files here that a run may write (present now)."""
        out = [n for n in FILE_NAMES if (self.path / n).exists()] + self._d3plot_files()
        states = self.path / STATES
        if states.is_dir():
            out += [f"{STATES}/{p.name}" for p in sorted(states.iterdir()) if _STATE_FILE.match(p.name)]
        elif states.exists():
            out.append(STATES)  # a file named "states": the VTK folder cannot be made
        return out

    def _d3plot_files(self) -> list[str]:
        """The d3plot's further files here (d3plot01, ...)."""
        if not self.path.is_dir():
            return []
        return sorted(p.name for p in self.path.iterdir() if _D3PLOT_FILE.match(p.name))

    # --- before the run --------------------------------------------------------
    def check(self, deck_files: Iterable[Path | str] = ()) -> None:
        """Refuse the folder before anything is run or written (raises
        OutputFolderError naming the files)."""
        p = self.path
        if p.exists() and not p.is_dir():
            raise OutputFolderError(f"{p} is a file, not a folder: -o names the folder the results go to")
        for parent in p.parents:  # the first existing ancestor must be a folder
            if parent.exists():
                if not parent.is_dir():
                    raise OutputFolderError(f"{parent} is a file: the output folder {p} cannot be made in it")
                break
        if not p.is_dir():
            return
        self.decks += [Path(f) for f in deck_files]
        mine = {self._resolve(p / rel): rel for rel in self.candidates()}
        decks = [d for d in self.decks if self._resolve(d) in mine]
        if decks:
            raise OutputFolderError(
                f"the output folder {p} holds the deck {decks[0]}, whose name is one a run "
                f"writes ({mine[self._resolve(decks[0])]}): choose another folder "
                "(-o); the deck is never overwritten"
            )
        foreign = [rel for rel in self.candidates() if rel not in self.previous]
        if foreign and not self.force:
            shown = ", ".join(foreign[:8]) + (f" and {len(foreign) - 8} more" if len(foreign) > 8 else "")
            raise OutputFolderError(
                f"the output folder {p} holds files of the names a run writes that no "
                f"crashlite run listed in its {MANIFEST}: {shown}; choose another folder "
                "(-o), remove them, or overwrite them with --force"
            )

    @staticmethod
    def _resolve(path: Path) -> Path:
        try:
            return path.resolve()
        except OSError:
            return path.absolute()

    def clear(self) -> list[str]:
        """Remove the previous run's files (and, with ``force``, foreign
        files of the run's names), then write a manifest naming every file
        this run may write, so a run killed before ``record`` leaves no file
        the next run would take for a foreign one. Returns the paths removed."""
        removed = []
        for rel in self.candidates():
            if rel in self.previous or self.force:
                target = self.path / rel
                if target.is_file():
                    target.unlink()
                    removed.append(rel)
        states = self.path / STATES
        if states.is_dir() and not any(states.iterdir()):
            states.rmdir()
        self.path.mkdir(parents=True, exist_ok=True)
        self._write(list(FILE_NAMES) + [f"{STATES}/states.pvd"], pending=True)
        return removed

    def record(self) -> list[str]:
        """Write the manifest of the files this run left (call after the run,
        also when it stopped or was interrupted)."""
        if not self.path.is_dir():
            return []
        files = self.candidates()
        self._write(files, pending=False)
        return files

    def _write(self, files: list[str], pending: bool) -> None:
        data = {
            "written_by": "crashlite run",
            "decks": [str(d) for d in self.decks[:1]],
            "complete": not pending,
            "files": files,
        }
        if pending:  # state files are numbered by the run: any of the patterns belongs to it
            data["state_pattern"] = f"{STATES}/state_NNNN.vtk"
            data["d3plot_pattern"] = "d3plotNN"
        tmp = self.path / (MANIFEST + ".tmp")
        tmp.write_text(json.dumps(data, indent=1) + "\n")
        tmp.replace(self.path / MANIFEST)
