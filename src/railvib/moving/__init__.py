"""The vehicle moving along the periodic track: a linear periodically time-varying system.

:mod:`railvib.moving.harmonic` couples the vehicle's receptance to the moving-load
receptances of :mod:`railvib.track.moving` by harmonic balance (contact forces at
``f + m v / d``, ``m = -N .. N``); :mod:`railvib.moving.parametric` gives the steady
sleeper-passing response on a smooth rail, :mod:`railvib.moving.random` the harmonic
transfer functions of the random response and its time-averaged and phase-resolved PSDs.
The derivation and the checks are in ``docs/moving-vehicle.md``.
"""

from railvib.moving.harmonic import MovingSettings, check_moving, harmonic_blocks
from railvib.moving.parametric import ParametricResponse, parametric_response
from railvib.moving.random import MovingFRF, moving_frf

__all__ = [
    "MovingFRF",
    "MovingSettings",
    "ParametricResponse",
    "check_moving",
    "harmonic_blocks",
    "moving_frf",
    "parametric_response",
]
