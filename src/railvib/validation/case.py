"""Where the validation's settings, result and comparison used to live (kept for old imports).

The settings and the result are in :mod:`railvib.validation.result`, the
comparison in :mod:`railvib.validation.compare`; import them from
:mod:`railvib.validation`.
"""

from railvib.validation.compare import validate_case
from railvib.validation.result import (
    BAND_FRACTION,
    FRF_TOLERANCE,
    ValidationResult,
    ValidationSettings,
    monte_carlo_work,
)

__all__ = [
    "BAND_FRACTION",
    "FRF_TOLERANCE",
    "ValidationResult",
    "ValidationSettings",
    "monte_carlo_work",
    "validate_case",
]
