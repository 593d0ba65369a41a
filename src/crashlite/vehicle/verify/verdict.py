"""The simplified vehicle's figures against their bounds: a verdict table.

The bounds are issue 31's restatement of the paper's claims for the
surrogate in US NCAP: energy ratings (ISO/TS 18571, deceleration phase)
≥ 0.95, crash-box internal energy within 2 %, firewall intrusion within 3 %
on average and, at its worst node, within the elastic twin's own largest
deviation + 5 points (what the method's elastic premise costs on this car
plus the paper's 5 %; 5 % where no twin ran), vehicle time reduction
≥ 60 % (the paper: 65 %).
"""

from __future__ import annotations

from dataclasses import dataclass

RATING_MIN, CRASH_BOX_PERCENT, INTRUSION_MEAN_PERCENT, INTRUSION_MAX_PERCENT, TIME_PERCENT = 0.95, 2.0, 3.0, 5.0, 60.0


@dataclass
class Verdict:
    figure: str
    value: float | None
    bound: str
    passed: bool | None  # None: not measured

    def as_dict(self) -> dict:
        return {"figure": self.figure, "value": self.value, "bound": self.bound, "passed": self.passed}


def intrusion_bound(figures: dict) -> float:
    """Largest firewall intrusion deviation allowed [%]: the elastic twin's
    own (premise) largest deviation + 5 points, or 5 % without a twin."""
    premise = ((figures.get("elastic_twin") or {}).get("premise") or {}).get("firewall_intrusion_max_deviation_percent")
    return INTRUSION_MAX_PERCENT + (float(premise) if premise is not None else 0.0)


def verdict(figures: dict) -> list[Verdict]:
    """Each figure of a vehicle verification (summary.json's keys) with its
    bound and whether it holds."""

    def row(name, value, bound_text, ok):
        return Verdict(
            name, None if value is None else float(value), bound_text, None if value is None else bool(ok(float(value)))
        )

    limit = intrusion_bound(figures)
    twin = figures.get("elastic_twin") is not None
    return [
        row(
            "energy ratings, lowest", figures.get("energy_rating_min"), f">= {RATING_MIN:g}", lambda v: v >= RATING_MIN
        ),
        row(
            "crash-box internal energy deviation [%]",
            figures.get("crash_box_internal_energy_deviation_percent"),
            f"within {CRASH_BOX_PERCENT:g} %",
            lambda v: abs(v) <= CRASH_BOX_PERCENT,
        ),
        row(
            "firewall intrusion, mean deviation [%]",
            figures.get("firewall_intrusion_mean_deviation_percent"),
            f"<= {INTRUSION_MEAN_PERCENT:g} %",
            lambda v: v <= INTRUSION_MEAN_PERCENT,
        ),
        row(
            "firewall intrusion, largest deviation [%]",
            figures.get("firewall_intrusion_max_deviation_percent"),
            f"<= {limit:.1f} %" + (" (elastic twin's + 5)" if twin else ""),
            lambda v: v <= limit,
        ),
        row(
            "vehicle time reduction [%]",
            figures.get("time_reduction_percent"),
            f">= {TIME_PERCENT:g} %",
            lambda v: v >= TIME_PERCENT,
        ),
    ]


def verdict_lines(rows: list[Verdict]) -> list[str]:
    """The table as text lines: figure, measured value, bound, pass/fail."""
    out = [f"{'figure':<44}{'measured':>10}  {'bound':<34}verdict"]
    for r in rows:
        value = "–" if r.value is None else f"{r.value:.3g}" if abs(r.value) < 1 else f"{r.value:.1f}"
        mark = "not measured" if r.passed is None else "pass" if r.passed else "FAIL"
        out.append(f"{r.figure:<44}{value:>10}  {r.bound:<34}{mark}")
    return out
