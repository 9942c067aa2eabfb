"""Shi-tai (Shijiazhuang-Taiyuan line) short-wave vertical irregularity spectrum."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.registry import parameter
from railvib.spectra._checks import as_wavenumber
from railvib.spectra.base import SPECTRA, SpatialSpectrum

__all__ = ["ShiTai"]

MM2_TO_M2 = 1e-6


@SPECTRA.register("shitai")
@dataclass(frozen=True)
class ShiTai(SpatialSpectrum):
    """Short-wave spectrum ``S(n) = coefficient * n^(-exponent)`` in mm^2/(cycle/m), n in cycle/m.

    Converted to radians and SI: ``S(Omega) = 1e-6 * S(n = Omega / 2 pi) / (2 pi)`` in
    m^2/(rad/m). Intended for wavelengths below 1 m (n > 1 cycle/m); no cut-off is applied.

    Parameters
    ----------
    coefficient : float
        Level at n = 1 cycle/m, in mm^2/(cycle/m) (> 0). Default 0.036.
    exponent : float
        Power-law exponent, dimensionless (> 0). Default 3.15.
    """

    coefficient: float = parameter(
        "mm^2/(cycle/m)",
        "level at n = 1 cycle/m",
        default=0.036,
        gt=0.0,
        le=1e3,
        typical=(0.01, 0.1),
    )
    exponent: float = parameter(
        "-", "power-law exponent of n", default=3.15, gt=0.0, le=10.0, typical=(2.5, 3.5)
    )

    def psd(self, wavenumber: ArrayLike) -> NDArray[np.float64]:
        """One-sided PSD in m^2/(rad/m) at spatial circular frequency `wavenumber` (rad/m, > 0)."""
        n = as_wavenumber(wavenumber) / (2.0 * np.pi)
        return MM2_TO_M2 * self.coefficient * n ** (-self.exponent) / (2.0 * np.pi)
