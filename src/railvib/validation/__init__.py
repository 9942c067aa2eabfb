"""Independent validation: finite-track model, time-domain Monte Carlo, comparison with PEM.

Public API
----------
sample_profile, wheel_irregularities
    Irregularity samples by the spectral representation (seeded).
FiniteTrack, hermite_element_matrices
    Long finite rail on discrete pads (Hermite elements, sparse).
FiniteCoupledSystem, finite_track_frf
    Vehicle on the finite track, direct sparse solve per frequency.
simulate_time_domain, TimeHistory
    Newmark average acceleration with one factorisation.
monte_carlo, MonteCarloSettings
    Realisations, Welch PSDs.
welch_psd, welch_expectation, confidence_band
    Statistics.
validate_case, ValidationSettings, ValidationResult, plot_overlays
    The three-way comparison of issue 5.
validate_to_folder, validation_files, write_validation, agreement_markdown, agreement_text
    The comparison's files (overlays, Markdown, netCDF) and its terminal table: the
    library behind ``railvib validate``.
check_scope
    What the reference models can check (Euler-Bernoulli rail, viscous pad), tested first.

Every reference model takes the :class:`~railvib.coupling.CoupledSystem` of the
symplectic path (its parameters only); the older parameter-bundle call forms still
work and emit a :class:`~railvib.errors.RailvibDeprecationWarning`.
"""

from railvib.validation.compare import validate_case
from railvib.validation.coupled import FiniteCoupledSystem, FiniteFRF, finite_track_frf
from railvib.validation.finite_track import FiniteTrack, hermite_element_matrices
from railvib.validation.monte_carlo import MonteCarloResult, MonteCarloSettings, monte_carlo
from railvib.validation.plots import DEFAULT_PLOT_RESPONSES, plot_overlays
from railvib.validation.report import (
    agreement_markdown,
    agreement_text,
    validate_to_folder,
    validation_files,
    write_validation,
)
from railvib.validation.result import ValidationResult, ValidationSettings, monte_carlo_work
from railvib.validation.samples import sample_profile, wheel_irregularities
from railvib.validation.scope import check_scope
from railvib.validation.statistics import (
    WelchEstimate,
    confidence_band,
    welch_dof,
    welch_expectation,
    welch_psd,
)
from railvib.validation.time_domain import (
    TimeHistory,
    newmark_frequency_warp,
    simulate_time_domain,
)

__all__ = [
    "DEFAULT_PLOT_RESPONSES",
    "FiniteCoupledSystem",
    "FiniteFRF",
    "FiniteTrack",
    "MonteCarloResult",
    "MonteCarloSettings",
    "TimeHistory",
    "ValidationResult",
    "ValidationSettings",
    "WelchEstimate",
    "agreement_markdown",
    "agreement_text",
    "check_scope",
    "confidence_band",
    "finite_track_frf",
    "hermite_element_matrices",
    "monte_carlo",
    "monte_carlo_work",
    "newmark_frequency_warp",
    "plot_overlays",
    "sample_profile",
    "simulate_time_domain",
    "validate_case",
    "validate_to_folder",
    "validation_files",
    "welch_dof",
    "welch_expectation",
    "welch_psd",
    "wheel_irregularities",
    "write_validation",
]
