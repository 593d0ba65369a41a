"""The error of comparisons that cannot be made as asked."""


class CompareError(ValueError):
    """Two runs (or curves, or fields) that cannot be compared as asked: no
    common time range, no matching entities, missing data the request needs.
    Raised instead of returning NaN or guessed figures."""
