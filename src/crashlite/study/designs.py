"""Design decks: the user's deck with one design's variable values.

*PARAMETER variables are set the way LS-OPT does it: the card that defines
the parameter is rewritten in place (its value field only), in a copy of
the file that holds it. The design folder mirrors the deck's files below
their common folder — modified files written, the others linked — so
relative *INCLUDEs resolve as in the original and the design's main deck
runs unchanged in LS-DYNA. Part variables (shell thickness T1..T4, yield
stress SIGY, by part name or ID) are set on the Model; such a design is
written by ``write_deck`` as one flat deck. A section or material that the
variable's parts share with other parts is copied first (new ID), so only
the named parts change.
"""

from __future__ import annotations

import copy
import math
import os
import shutil
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

_FLAT = "design.k"


@dataclass
class ParameterSite:
    name: str  # as defined in the deck
    type: str  # R or I
    file: int  # index into DeckTemplate.files
    line: int  # 0-based line index in that file
    width: int  # 10, or 20 for long format
    expression: bool  # *PARAMETER_EXPRESSION


@dataclass
class PartVariable:
    name: str  # the study variable
    pids: list[int]
    property: str  # thickness or yield


@dataclass
class DeckTemplate:
    """What a design deck is made from; small and picklable (sent to the
    workers with every design)."""

    deck: str  # the user's main deck (absolute)
    root: str  # common folder of every file of the deck
    files: list[str]  # every file of the deck (absolute)
    sites: dict[str, ParameterSite] = field(default_factory=dict)  # variable -> site
    part_variables: list[PartVariable] = field(default_factory=list)

    # --- building ------------------------------------------------------------
    @classmethod
    def build(cls, cfg) -> DeckTemplate:
        """Resolve the study's variables and check its responses on the deck
        (StudyError naming the study file and key)."""
        from .. import read_deck
        from ..keyword.errors import DeckError
        from .errors import StudyError
        from .responses import check_external_response, check_response

        try:
            model = read_deck(cfg.deck)
        except DeckError as e:
            raise StudyError(f"{cfg.path}: [study] deck: {e}") from None
        files = [str(Path(f).absolute()) for f in model.files]
        from ..keyword.dmig import matrix_file

        for rec in model.find("ELEMENT_DIRECT_MATRIX_INPUT"):  # matrix files mirror with the deck's files
            path = matrix_file(rec)
            if path is not None and not os.path.isabs(str(rec["filename"]).strip()):
                files.append(str(path.absolute()))
        root = os.path.commonpath([os.path.dirname(f) for f in files])
        t = cls(deck=str(Path(cfg.deck).absolute()), root=root, files=files)
        params: dict[str, list] = {}
        for p in model.parameters:
            params.setdefault(p.name.lower(), []).append(p)
        modes = None
        for var in cfg.variables:
            where = f"[variables.{var.name}]"
            if var.parameter:
                found = params.get(var.parameter.lower())
                if not found:
                    names = ", ".join(sorted({p.name for p in model.parameters})) or "none"
                    raise StudyError(
                        f"{cfg.path}: {where} parameter: {var.parameter!r} is not a *PARAMETER of "
                        f"{cfg.deck.name} (parameters: {names})"
                    )
                if len(found) > 1:
                    at = ", ".join(f"{Path(p.source[0]).name}:{p.source[1]}" for p in found)
                    raise StudyError(
                        f"{cfg.path}: {where} parameter: {var.parameter!r} is defined "
                        f"{len(found)} times ({at}); a design variable needs one definition"
                    )
                p = found[0]
                if p.type == "C":
                    raise StudyError(f"{cfg.path}: {where} parameter: {p.name!r} is a text (C) parameter")
                if p.type == "I":
                    if var.lower != int(var.lower) or var.upper != int(var.upper):
                        raise StudyError(
                            f"{cfg.path}: {where} bounds: {p.name!r} is an integer (I) parameter; "
                            f"give whole-number bounds"
                        )
                    var.integer = True
                var.baseline = float(p.value)
                if modes is None:
                    modes = _block_modes(cfg.deck)
                fname = str(Path(p.source[0]).absolute())
                t.sites[var.name] = ParameterSite(
                    p.name,
                    p.type,
                    files.index(fname),
                    p.source[1] - 1,
                    modes.get((fname, p.source[1]), 10),
                    bool(p.expression),
                )
            else:
                try:
                    pids = [int(x) for x in model.part_ids_of(var.parts)]
                except KeyError as e:
                    titles = ", ".join(repr(str(r.get("heading", "")).strip()) for r in model.parts.values())
                    raise StudyError(
                        f"{cfg.path}: {where} parts: {e.args[0]} in {cfg.deck.name} (parts: {titles})"
                    ) from None
                for pid in pids:
                    msg = _check_part(model, pid, var.property)
                    if msg:
                        raise StudyError(f"{cfg.path}: {where} parts: {msg}")
                var.baseline = _part_value(model, pids[0], var.property)
                t.part_variables.append(PartVariable(var.name, pids, var.property))
        names = cfg.variable_names
        solver = getattr(getattr(cfg, "execution", None), "solver", "crashlite")
        for name, spec in cfg.responses.items():
            try:
                check_response(spec, model, names, list(cfg.responses))
                if solver != "crashlite":
                    check_external_response(spec, model, solver)
            except ValueError as e:
                raise StudyError(f"{cfg.path}: [responses.{name}] {e}") from None
        return t

    # --- writing -------------------------------------------------------------
    def write(self, values: dict, directory) -> Path:
        """Write the design deck of ``values`` (variable -> value) into
        ``directory`` (emptied first); returns its main deck."""
        directory = Path(directory)
        if directory.exists():
            shutil.rmtree(directory)
        directory.mkdir(parents=True)
        main = Path(self.deck)
        if self.sites:
            edits: dict[int, dict[int, tuple]] = {}
            for var, site in self.sites.items():
                edits.setdefault(site.file, {})[site.line] = (site, values[var])
            for i, f in enumerate(self.files):
                dst = directory / "deck" / os.path.relpath(f, self.root)
                dst.parent.mkdir(parents=True, exist_ok=True)
                if i in edits:
                    dst.write_text(_edited(Path(f), edits[i]), encoding="latin-1")
                else:
                    _link(Path(f), dst)
            main = directory / "deck" / os.path.relpath(self.deck, self.root)
        if not self.part_variables:
            return main
        from .. import read_deck, write_deck

        model = read_deck(main)
        apply_part_variables(model, self.part_variables, values)
        out = directory / _FLAT
        write_deck(model, out)
        if self.sites:
            shutil.rmtree(directory / "deck")
        return out

    def check(self, model, values: dict) -> None:
        """Raise ValueError unless the design's Model holds ``values``."""
        defined = {p.name.lower(): p.value for p in model.parameters}
        for var, site in self.sites.items():
            got = defined.get(site.name.lower())
            if got is None or not math.isclose(float(got), float(values[var]), rel_tol=1e-12, abs_tol=0.0):
                raise ValueError(
                    f"design deck reads {site.name} = {got}, not {values[var]} (is its file "
                    f"included by an absolute path?)"
                )
        for pv in self.part_variables:
            for pid in pv.pids:
                got = _part_value(model, pid, pv.property)
                if not math.isclose(got, float(values[pv.name]), rel_tol=1e-12):
                    raise ValueError(f"design deck has {pv.property} {got} for part {pid}, not {values[pv.name]}")


def _link(src: Path, dst: Path) -> None:
    try:
        os.symlink(src, dst)
    except OSError:  # no symlinks here (some Windows set-ups): copy
        shutil.copyfile(src, dst)


def _block_modes(deck) -> dict:
    """(file, 1-based line) -> field width of every *PARAMETER data line."""
    from ..keyword.cards import LONG
    from ..keyword.errors import Collector
    from ..keyword.lexer import Lexer

    lex = Lexer(Collector())
    lex.walk(Path(deck))
    out = {}
    for blk in lex.blocks:
        if blk.keyword.startswith("PARAMETER"):
            for j in range(len(blk.data)):
                out[(str(Path(blk.file).absolute()), blk.line_no(j))] = 20 if blk.mode == LONG else 10
    return out


def format_value(value, typ: str, width: int | None) -> str:
    """Deck text of a parameter value: the shortest that reads back
    exactly, fitting ``width`` if possible."""
    if typ == "I":
        return str(int(round(value)))
    from ..keyword.cards import format_float

    if width is not None:
        s = format_float(float(value), width)
        if s:
            return s
    return repr(float(value))


def rewrite_parameter_line(line: str, name: str, value, typ: str, width: int, expression: bool) -> str:
    """The *PARAMETER (or _EXPRESSION) data line with ``name``'s value
    replaced; fixed columns where the value fits, else free format."""
    if expression:
        if "," in line:
            head = line.partition(",")[0]
            return f"{head},{format_value(value, typ, None)}"
        text = format_value(value, typ, None)
        return line[:width].ljust(width) + text
    if "," in line:
        toks = [t.strip() for t in line.split(",")]
        for k in range(0, len(toks) - 1, 2):
            if toks[k][1:].strip().lower() == name.lower():
                toks[k + 1] = format_value(value, typ, None)
                return ",".join(toks)
        raise ValueError(f"parameter {name} not found on line {line!r}")
    pairs = [(line[i : i + width], line[i + width : i + 2 * width]) for i in range(0, len(line), 2 * width)]
    for k, (head, _) in enumerate(pairs):
        if head.strip()[1:].strip().lower() == name.lower():
            text = format_value(value, typ, width)
            if len(text) <= width:
                pairs[k] = (head.ljust(width), text.rjust(width))
                return "".join(h + v for h, v in pairs).rstrip()
            pairs[k] = (head, format_value(value, typ, None))
            return ",".join(f"{h.strip()},{v.strip()}" for h, v in pairs if h.strip())
    raise ValueError(f"parameter {name} not found on line {line!r}")


def _edited(path: Path, edits: dict[int, tuple]) -> str:
    text = path.read_bytes().decode("latin-1")
    lines = text.splitlines(keepends=True)
    for i, (site, value) in edits.items():
        raw = lines[i]
        body = raw.rstrip("\r\n")
        end = raw[len(body) :]
        lines[i] = rewrite_parameter_line(body, site.name, value, site.type, site.width, site.expression) + end
    return "".join(lines)


# --- part variables --------------------------------------------------------------


def _check_part(model, pid: int, prop: str) -> str | None:
    part = model.parts[pid]
    title = str(part.get("heading", "")).strip() or str(pid)
    if prop == "thickness":
        sec = model.sections.get(part.get("secid"))
        if sec is None or not sec.keyword.startswith("SECTION_SHELL"):
            kind = sec.keyword if sec is not None else "no section"
            return f"part {title!r} has *{kind}: a thickness variable needs a *SECTION_SHELL"
        return None
    mat = model.materials.get(part.get("mid"))
    if mat is None or "sigy" not in mat.values:
        kind = mat.keyword if mat is not None else "no material"
        return f"part {title!r} has *{kind}, which has no yield stress SIGY"
    if mat.values.get("lcss"):
        return (
            f"part {title!r}: *{mat.keyword} {mat.id} takes its hardening from curve LCSS "
            f"{mat.values['lcss']}, so SIGY is not used; scale the curve through a *PARAMETER instead"
        )
    return None


def _part_value(model, pid: int, prop: str) -> float:
    part = model.parts[pid]
    if prop == "thickness":
        return float(model.sections[part["secid"]]["t1"])
    return float(model.materials[part["mid"]]["sigy"])


def apply_part_variables(model, part_variables: list[PartVariable], values: dict) -> None:
    """Set each part variable's value on the Model in place."""
    for pv in part_variables:
        value = float(values[pv.name])
        wanted = set(pv.pids)
        group, key, fields = (
            ("sections", "secid", ("t1", "t2", "t3", "t4"))
            if pv.property == "thickness"
            else ("materials", "mid", ("sigy",))
        )
        table = getattr(model, group)
        for rid in sorted({model.parts[p][key] for p in pv.pids}):
            users = {p for p, r in model.parts.items() if r.get(key) == rid}
            target = rid
            if users - wanted:  # shared with parts the variable does not name: copy it
                target = max(table) + 1
                rec = copy.deepcopy(table[rid])
                rec[key] = target
                if rec.title is not None:
                    rec.title = f"{rec.title} ({pv.name})"
                table[target] = rec
                for p in users & wanted:
                    model.parts[p][key] = target
            rec = table[target]
            if pv.property == "yield":
                old = float(rec.get("sigy") or 0.0)
                es = [f"es{i}" for i in range(1, 9) if rec.values.get(f"es{i}")]
                if es and old > 0:  # 8-point hardening: scale it with the yield stress
                    for k in es:
                        rec[k] = float(rec[k]) * value / old
            for f in fields:
                rec[f] = value
        if pv.property == "thickness" and len(model.shells):
            mask = np.isin(model.shells.pid, list(wanted))
            given = mask[:, None] & np.isfinite(model.shells.thickness)
            if given.any():  # element thicknesses override the section's: set them too
                th = np.array(model.shells.thickness, copy=True)
                th[given] = value
                model.shells.thickness = th
