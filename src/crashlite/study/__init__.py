"""Design studies on crashlite decks: design of experiments, sensitivity,
metamodels and optimisation, each design a crashlite run, executed on Dask
and stored in an optuna RDB storage so that studies resume.

    from crashlite.study import load_study, run_study, build_report
    cfg = load_study("study.toml")
    run_study(cfg)            # LocalCluster, one worker per core
    build_report(cfg)         # figures, summary.json, best design's deck
"""

from .config import StudyConfig, StudyError, load_study
from .report import build_report
from .runner import run_study

__all__ = ["StudyConfig", "StudyError", "build_report", "load_study", "run_study"]
