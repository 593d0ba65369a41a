"""Value-by-value equality of records and models (NaN equals NaN).

The functions live with the types they compare -- records in
``keyword.schema``, models in ``model.model`` -- so that neither imports
this module back (issue 32: no import circles); they stay importable from
here.
"""

from __future__ import annotations

from ..model.model import model_differences, models_equal
from .schema import records_equal

__all__ = ["model_differences", "models_equal", "records_equal"]
