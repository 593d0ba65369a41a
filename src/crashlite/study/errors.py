"""The study's error type, below every module that raises it (``config``
and ``designs`` among them), so that none imports another for it."""

from __future__ import annotations


class StudyError(ValueError):
    """A study file that cannot be run, with the file and key named."""
