"""Reports of comparisons: a self-contained HTML page (plots embedded as
PNG, tables, pictures of the deformed structures side by side, the run
settings) and summary.json with every figure. No computation here: the
figures come from ``crashlite.verify.compare``."""

from .build import write_report

__all__ = ["write_report"]
