"""``read_deck``: a keyword deck (with its includes) into a Model."""

from __future__ import annotations

from pathlib import Path

from ..model.model import Model
from .convert import build_model
from .errors import Collector, DeckError
from .lexer import Lexer
from .parameters import ParameterTable
from .parse import parse_block
from .references import check_references
from .schema import RawKeyword, Record, lookup
from .transform import apply_offsets, matrix, transform_nodes


def read_deck(path: Path | str, strict: bool = False) -> Model:
    """Read an LS-DYNA keyword deck.

    Every problem of the deck (bad numbers, missing cards, undefined
    parameters, dangling references, duplicate IDs, missing include files)
    is collected and raised together as one ``DeckError``. Keywords
    crashlite does not type are kept verbatim and listed once in
    ``model.warnings``; with ``strict=True`` they are errors.
    """
    path = Path(path)
    problems = Collector()
    records, lexer, params = read_records(path, problems, strict)
    model, bulk = build_model(records, problems)
    check_references(model, problems, bulk)
    problems.raise_if_any()
    model.parameters = params.defined
    model.source = str(path)
    model.files = [str(p) for p in lexer.files]
    model.warnings = problems.warnings
    return model


def read_records(
    path: Path | str, problems: Collector | None = None, strict: bool = False
) -> tuple[list[Record | RawKeyword], Lexer, ParameterTable]:
    """The typed records and verbatim keywords of a deck in input order,
    before they become a Model (no reference checks). Returns (records,
    lexer, parameter table); raises DeckError when ``problems`` is None and
    the deck has any."""
    own = problems is None
    problems = Collector() if own else problems
    path = Path(path)
    try:
        found = path.is_file()
    except (OSError, ValueError) as e:  # a name too long, a NUL byte in it
        raise DeckError([_problem(path, f"deck file name cannot be used: {getattr(e, 'strerror', None) or e}")])  # noqa: B904
    if not found:
        raise DeckError(
            [_problem(path, "deck path is a folder, not a file" if path.is_dir() else "deck file not found")]
        )
    lexer = Lexer(problems)
    lexer.walk(path)
    params = ParameterTable(lexer.scopes)
    for blk in lexer.blocks:
        if blk.keyword.startswith("PARAMETER"):
            params.process(blk, problems)
    visible: dict[int, dict] = {}
    records: list[Record | RawKeyword] = []
    unknown: dict[str, tuple[str, int, int]] = {}
    transformed = []
    for blk in lexer.blocks:
        if blk.keyword.startswith("PARAMETER"):
            continue
        spec, options = lookup(blk.keyword)
        if spec is None:
            raw = RawKeyword(blk.line_text, blk.raw_lines(), (blk.file, blk.line), blk.mode)
            records.append(raw)
            f, ln, n = unknown.get(blk.keyword, (blk.file, blk.line, 0))
            unknown[blk.keyword] = (f, ln, n + 1)
            if blk.contexts and any(c.offsets for c in blk.contexts):
                problems.warn(
                    blk.file,
                    blk.line,
                    blk.keyword,
                    None,
                    "kept verbatim: *INCLUDE_TRANSFORM ID offsets are not applied to it",
                )
            continue
        if blk.scope not in visible:
            visible[blk.scope] = params.visible(blk.scope)
        recs = parse_block(blk, spec, options, visible[blk.scope], problems)
        for ctx in reversed(blk.contexts):  # innermost include first
            for r in recs:
                apply_offsets(r, ctx, problems)
        if blk.contexts:
            transformed.append((blk, recs))
        records.extend(recs)
    _apply_coordinate_transforms(records, transformed, problems)
    for kw, (f, ln, n) in sorted(unknown.items()):
        msg = f"keyword not typed by crashlite ({n}x); kept verbatim and written back unchanged"
        (problems.error if strict else problems.warn)(f, ln, kw, None, msg)
    if own:
        problems.raise_if_any()
    return records, lexer, params


def _apply_coordinate_transforms(records, transformed, problems) -> None:
    trans = {r.id: r for r in records if isinstance(r, Record) and r.keyword == "DEFINE_TRANSFORMATION"}
    for blk, recs in transformed:
        for ctx in reversed(blk.contexts):
            if not ctx.tranid:
                continue
            tr = trans.get(ctx.tranid)
            if tr is None:
                problems.error(
                    ctx.file,
                    ctx.line,
                    "INCLUDE_TRANSFORM",
                    "TRANID",
                    f"*DEFINE_TRANSFORMATION {ctx.tranid} is not defined",
                )
                continue
            m = matrix(tr, problems)
            for r in recs:
                if r.keyword == "NODE":
                    transform_nodes(r, m)


def _problem(path, msg):
    from .errors import Problem

    return Problem(str(path), 0, "", None, msg)
