"""The quasi-stationary response: the stationary solution at the instantaneous speed.

At each instant the response PSD is taken as the stationary one at the speed
``v(t)``: wavenumber ``Omega`` is seen at ``f = v Omega / (2 pi)``, and its pseudo
response is the stationary coupled solution (:func:`railvib.coupling.coupled_response`,
the solver of every stationary run, here with the rail held rigid) to the inputs
``a_k exp(-i Omega_k o_j)`` at the wheels — the wheel delays ``o_j / v`` times
``2 pi f`` are ``Omega o_j`` whatever the speed, so all instants are one batch of
frequencies ``v(t_i) Omega_k / (2 pi)``.

It holds while the speed changes little over one period of the slowest mode:
``epsilon(t) = |dv/dt| / (v(t) f_1)`` small (:func:`validity_parameter`); braking to a
stop breaks it at the end, where ``v -> 0``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.coupling import coupled_response
from railvib.nonstationary.band import SpatialBand
from railvib.nonstationary.profile import SpeedProfile
from railvib.nonstationary.statespace import RigidTrackVehicle

__all__ = ["QS_LIMIT", "quasi_stationary_psd", "validity_parameter"]

#: frequencies solved in one batch (a few tens of MB of working set)
TIME_BLOCK = 16384

#: the validity parameter below which the quasi-stationary estimate is taken to hold: a
#: speed change of 10 % over one period of the slowest mode (the paper's car braking at
#: 1 m/s^2 from 80 km/h: 0.058 at the start; where it is <= 0.1 the quasi-stationary and
#: exact RMS differ by <= 4 %; docs/nonstationary.md)
QS_LIMIT = 0.1


def validity_parameter(
    profile: SpeedProfile, t: ArrayLike, slowest_mode_hz: float
) -> NDArray[np.float64]:
    """``epsilon(t) = |dv/dt| / (v f_1)``: the relative speed change over one slowest period.

    Parameters
    ----------
    profile : SpeedProfile
        The speed profile.
    t : array_like
        Times, s.
    slowest_mode_hz : float
        Natural frequency of the slowest mode ``f_1``, Hz.

    Returns
    -------
    numpy.ndarray
        Dimensionless, shape of `t`; infinite where the speed is 0 and changing, 0 at
        constant speed.
    """
    a = np.abs(profile.acceleration(t))
    v = profile.speed(t)
    with np.errstate(divide="ignore", invalid="ignore"):
        eps = a / (v * slowest_mode_hz)
    return np.where(a == 0, 0.0, eps)


def quasi_stationary_psd(
    model: RigidTrackVehicle, profile: SpeedProfile, band: SpatialBand, t: ArrayLike
) -> NDArray[np.float64]:
    """Squared pseudo responses ``|y_k|^2`` at times `t` by the stationary solver.

    Parameters
    ----------
    model : RigidTrackVehicle
        The vehicle and its contact stiffness (the rail rigid).
    profile : SpeedProfile
        The speed profile.
    band : SpatialBand
        Wavenumbers and amplitudes.
    t : array_like
        Times, s, ``(n_t,)``.

    Returns
    -------
    numpy.ndarray
        ``(n_t, n_wavenumber, n_out)``, output unit^2 (the outputs of
        :attr:`RigidTrackVehicle.matrices`: DOF displacements, accelerations, contact
        forces); ``sum`` over wavenumbers is the variance, ``/ dOmega`` the PSD per rad/m.
    """
    t = np.atleast_1d(np.asarray(t, dtype=float))
    step = max(1, TIME_BLOCK // max(1, band.wavenumber.size))
    if t.size > step:  # bounded memory: the solver's working set grows with the batch
        parts = [
            quasi_stationary_psd(model, profile, band, t[i : i + step])
            for i in range(0, t.size, step)
        ]
        return np.concatenate(parts)
    vehicle = model.vehicle
    om = band.wavenumber
    f = (profile.speed(t)[:, None] * om[None, :] / (2.0 * np.pi)).ravel()
    n_w = model.n_wheel
    back = band.amplitude[:, None] * np.exp(-1j * om[:, None] * vehicle.wheel_offsets[None, :])
    excitation = np.broadcast_to(back, (t.size, om.size, n_w)).reshape(-1, n_w, 1)
    rigid = np.zeros((f.size, n_w, n_w), dtype=complex)
    u, force, _ = coupled_response(
        vehicle.condensed_to_wheels(f),
        rigid,
        model.contact_stiffness,
        np.ascontiguousarray(excitation),
    )
    u = u[..., 0]
    acc = -((2.0 * np.pi * f[:, None]) ** 2) * u
    y = np.concatenate([u, acc, force[..., 0]], axis=1)
    return (np.abs(y) ** 2).reshape(t.size, om.size, -1)
