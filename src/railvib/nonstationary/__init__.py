"""Non-stationary random vibration: trains accelerating and braking (``docs/nonstationary.md``).

The speed varies along a profile, so the response to a spatially stationary
irregularity is non-stationary. :func:`exact_response` integrates the pseudo
responses of every wavenumber through the profile (the exact non-stationary
pseudo-excitation method, on a rigid track); :func:`quasi_stationary_psd` takes the
stationary solution at the instantaneous speed; :func:`covariance_response` is the
independent reference (the covariance equation of a one-wheel vehicle on filtered
white noise).
"""

from railvib.nonstationary.band import SpatialBand
from railvib.nonstationary.build import NonstationaryRun, build_run, check_duration
from railvib.nonstationary.covariance import ShapingFilter, covariance_response
from railvib.nonstationary.dataset import frequency_map, nonstationary_dataset
from railvib.nonstationary.exact import MomentHistory, exact_response, phase_error_bound
from railvib.nonstationary.extremes import first_passage_probability, upcrossing_rate
from railvib.nonstationary.folder import (
    NONSTATIONARY_FILES,
    NonstationaryOutput,
    run_nonstationary,
    run_nonstationary_to_folder,
)
from railvib.nonstationary.profile import SpeedProfile
from railvib.nonstationary.quasi import QS_LIMIT, quasi_stationary_psd, validity_parameter
from railvib.nonstationary.statespace import RigidTrackVehicle

__all__ = [
    "NONSTATIONARY_FILES",
    "QS_LIMIT",
    "MomentHistory",
    "NonstationaryOutput",
    "NonstationaryRun",
    "RigidTrackVehicle",
    "ShapingFilter",
    "SpatialBand",
    "SpeedProfile",
    "build_run",
    "check_duration",
    "covariance_response",
    "exact_response",
    "first_passage_probability",
    "frequency_map",
    "nonstationary_dataset",
    "phase_error_bound",
    "quasi_stationary_psd",
    "run_nonstationary",
    "run_nonstationary_to_folder",
    "upcrossing_rate",
    "validity_parameter",
]
