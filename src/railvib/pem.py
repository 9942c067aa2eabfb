"""Pseudo-excitation method for fully coherent, delayed inputs at the wheels.

All wheels see the same stationary profile ``r(x)``; wheel ``j`` sees it
``t_j = s_j / v`` later than the leading wheel, ``s_j`` being its distance behind
the leading wheel. The input PSD matrix is rank one, ``S_r v v^H`` with
``v_j = exp(-i omega t_j)``, so one pseudo excitation ``r~ = v sqrt(S_r)`` gives
every response PSD exactly: ``S_yy = |y~|^2 = |H v|^2 S_r`` (paper Eqs. 17-19).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError

__all__ = ["acceleration_psd", "excitation_vector", "response_psd", "wheel_delays"]


def wheel_delays(wheel_offsets: ArrayLike, speed: float) -> NDArray[np.float64]:
    """Time delays ``t_j = s_j / v`` in s of wheels `s_j` m behind the leading wheel.

    Parameters
    ----------
    wheel_offsets : array_like
        Distances ``s_j`` of the wheels behind the leading wheel in m, shape ``(n_wheel,)``
        (the leading wheel at 0).
    speed : float
        Vehicle speed ``v`` in m/s (finite, > 0).

    Returns
    -------
    numpy.ndarray
        Delays ``t_j`` in s, shape ``(n_wheel,)``.

    Raises
    ------
    CaseError
        If `speed` is not a finite number > 0.
    """
    if not (np.isfinite(speed) and speed > 0):
        raise CaseError("speed", speed, "must be > 0 (m/s)")
    return np.asarray(wheel_offsets, dtype=float) / speed


def excitation_vector(f: ArrayLike, delays: ArrayLike) -> NDArray[np.complex128]:
    """``v_j(f) = exp(-i 2 pi f t_j)``, shape ``(n_freq, n_wheel)``.

    Parameters
    ----------
    f : array_like
        Frequencies in Hz, shape ``(n_freq,)``.
    delays : array_like
        Wheel time delays ``t_j`` in s, shape ``(n_wheel,)`` (see :func:`wheel_delays`).

    Returns
    -------
    numpy.ndarray
        Complex unit phasors ``v_j(f)`` (dimensionless), shape ``(n_freq, n_wheel)``.
    """
    f = np.asarray(f, dtype=float)
    return np.exp(-2j * np.pi * f[:, None] * np.asarray(delays, dtype=float)[None, :])


def response_psd(frf: ArrayLike, input_psd: ArrayLike) -> NDArray[np.float64]:
    """Response PSD ``|H|^2 S`` from an FRF ``(n_freq, ...)`` and an input PSD ``(n_freq,)``.

    Parameters
    ----------
    frf : array_like
        Complex frequency response ``H`` (response unit per input unit, e.g. m/m or N/m),
        frequency first, shape ``(n_freq, ...)``.
    input_psd : array_like
        One-sided input PSD ``S`` per Hz (input unit^2/Hz, e.g. m^2/Hz for a rail
        irregularity), shape ``(n_freq,)``.

    Returns
    -------
    numpy.ndarray
        One-sided response PSD in (response unit)^2/Hz, shape of `frf`.
    """
    h = np.asarray(frf)
    s = np.asarray(input_psd, dtype=float)
    return np.abs(h) ** 2 * s.reshape(s.shape + (1,) * (h.ndim - 1))


def acceleration_psd(f: ArrayLike, displacement_psd: ArrayLike) -> NDArray[np.float64]:
    """``omega^4 S_u`` in (m/s^2)^2/Hz from a displacement PSD in m^2/Hz (frequency first).

    Parameters
    ----------
    f : array_like
        Frequencies in Hz, shape ``(n_freq,)``.
    displacement_psd : array_like
        One-sided displacement PSD ``S_u`` in m^2/Hz, frequency first, shape ``(n_freq, ...)``.

    Returns
    -------
    numpy.ndarray
        One-sided acceleration PSD in (m/s^2)^2/Hz, shape of `displacement_psd`.
    """
    f = np.asarray(f, dtype=float)
    s = np.asarray(displacement_psd, dtype=float)
    omega4 = (2.0 * np.pi * f) ** 4
    return s * omega4.reshape(omega4.shape + (1,) * (s.ndim - 1))
