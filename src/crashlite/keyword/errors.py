"""Problems found in a deck, collected and reported together."""

from __future__ import annotations

import os
from dataclasses import dataclass


@dataclass(frozen=True)
class Problem:
    file: str
    line: int  # 1-based; 0 when not tied to a line
    keyword: str
    field: str | None
    message: str

    def __str__(self) -> str:
        where = f"{self.file}:{self.line}" if self.line else self.file
        fld = f", field {self.field}" if self.field else ""
        kw = f" *{self.keyword}" if self.keyword else ""
        return f"{where}:{kw}{fld}: {self.message}"


class DeckError(Exception):
    """A deck could not be read (or written); ``problems`` lists every cause."""

    def __init__(self, problems: list[Problem]):
        self.problems = sorted(problems, key=lambda p: (p.file, p.line))
        n = len(self.problems)
        head = f"{n} problem{'s' if n != 1 else ''} in deck"
        shown = "\n".join(f"  {p}" for p in self.problems[:50])
        more = f"\n  ... and {n - 50} more" if n > 50 else ""
        super().__init__(f"{head}:\n{shown}{more}")


class Collector:
    """Gathers problems while a deck is read; raises them all at the end."""

    def __init__(self) -> None:
        self.problems: list[Problem] = []
        self.warnings: list[Problem] = []

    def error(self, file: str | os.PathLike, line: int, keyword: str, field: str | None, message: str) -> None:
        self.problems.append(Problem(str(file), int(line), keyword, field, message))

    def warn(self, file: str | os.PathLike, line: int, keyword: str, field: str | None, message: str) -> None:
        self.warnings.append(Problem(str(file), int(line), keyword, field, message))

    def raise_if_any(self) -> None:
        if self.problems:
            raise DeckError(self.problems)
