"""The detailed honeycomb's options the barrier benches share. Each is passed
to ``detailed_barrier`` only when given, so the rest keep its defaults."""

from __future__ import annotations

import argparse

NAMES = ("shear_strength", "lateral", "honeycomb")


def add_honeycomb_options(ap: argparse.ArgumentParser) -> None:
    """--shear-strength, --lateral, --honeycomb (default: the detailed barrier's)."""
    ap.add_argument(
        "--shear-strength",
        type=float,
        default=None,
        help="the honeycomb's transverse shear strength × its plateau (default: the detailed barrier's, 0.5)",
    )
    ap.add_argument(
        "--lateral",
        type=float,
        default=None,
        help="the honeycomb across its cells × its crush values (default: the detailed barrier's, 0.05)",
    )
    ap.add_argument(
        "--honeycomb",
        choices=("classic", "transverse"),
        default=None,
        help="MAT_026 (classic, torn elements deleted) or MAT_126's transversely isotropic form (kept); "
        "default: the detailed barrier's",
    )


def given(args: argparse.Namespace, names: tuple[str, ...] = NAMES) -> dict:
    """The options of ``names`` that were given, by detailed_barrier's names."""
    return {k: getattr(args, k) for k in names if getattr(args, k) is not None}
