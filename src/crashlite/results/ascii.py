"""glstat reader and writer (kept here for existing imports; all LS-DYNA
ASCII files live in ``lsdyna_ascii``)."""

from __future__ import annotations

from .lsdyna_ascii.glstat import LABELS as GLSTAT
from .lsdyna_ascii.glstat import read as read_glstat
from .lsdyna_ascii.glstat import write as write_glstat

__all__ = ["GLSTAT", "read_glstat", "write_glstat"]
