"""Unit strings and the few conversions done at the edges (case files, plots).

Everything inside railvib is SI: Hz, m, s, kg, N, N/m, N s/m, K.
"""

from __future__ import annotations

from typing import TypeVar

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "ACCELERATION_PSD",
    "DISPLACEMENT_PSD",
    "FORCE_PSD",
    "celsius_to_kelvin",
    "kelvin_to_celsius",
    "kmh_to_ms",
]

ACCELERATION_PSD = "(m/s^2)^2/Hz"
DISPLACEMENT_PSD = "m^2/Hz"
FORCE_PSD = "N^2/Hz"
ZERO_CELSIUS_K = 273.15

#: a float or an array of floats (conversions keep the kind they are given)
FloatOrArray = TypeVar("FloatOrArray", float, NDArray[np.float64])


def kmh_to_ms(speed_kmh: float) -> float:
    """Convert km/h to m/s.

    Parameters
    ----------
    speed_kmh : float
        Speed in km/h.

    Returns
    -------
    float
        The same speed in m/s.
    """
    return speed_kmh / 3.6


def celsius_to_kelvin(t_celsius: FloatOrArray) -> FloatOrArray:
    """Convert degrees Celsius to kelvin.

    Parameters
    ----------
    t_celsius : float or numpy.ndarray
        Temperature in degC.

    Returns
    -------
    float or numpy.ndarray
        The same temperature in K, of the kind given.
    """
    return t_celsius + ZERO_CELSIUS_K


def kelvin_to_celsius(t_kelvin: FloatOrArray) -> FloatOrArray:
    """Convert kelvin to degrees Celsius.

    Parameters
    ----------
    t_kelvin : float or numpy.ndarray
        Temperature in K.

    Returns
    -------
    float or numpy.ndarray
        The same temperature in degC, of the kind given.
    """
    return t_kelvin - ZERO_CELSIUS_K
