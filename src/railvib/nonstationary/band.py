"""The spatial band: log-spaced wavenumbers, their widths and pseudo-excitation amplitudes."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from railvib.errors import CaseError
from railvib.spectra.base import SpatialSpectrum

__all__ = ["SpatialBand"]


@dataclass(frozen=True, eq=False)
class SpatialBand:
    """Wavenumbers ``Omega_k`` (rad/m) with widths ``dOmega_k`` and amplitudes ``sqrt(S dOmega)``.

    The band ``[2 pi / wavelength_max, 2 pi / wavelength_min]`` is cut into cells of
    equal ratio; ``Omega_k`` is the geometric centre of cell k (midpoint rule in log
    wavenumber). The irregularity is represented as ``sum_k sqrt(S(Omega_k) dOmega_k)
    exp(i Omega_k x)`` with independent random phases: its variance is the band's.

    Attributes
    ----------
    wavenumber : numpy.ndarray
        ``Omega_k``, rad/m, ``(n,)``.
    width : numpy.ndarray
        ``dOmega_k``, rad/m, ``(n,)``.
    amplitude : numpy.ndarray
        ``sqrt(S(Omega_k) dOmega_k)``, m, ``(n,)``.
    """

    wavenumber: NDArray[np.float64]
    width: NDArray[np.float64]
    amplitude: NDArray[np.float64]

    @classmethod
    def log_spaced(
        cls, spectrum: SpatialSpectrum, wavelength_min: float, wavelength_max: float, n: int
    ) -> SpatialBand:
        """`n` cells of equal ratio between two wavelengths (m).

        Parameters
        ----------
        spectrum : SpatialSpectrum
            One-sided spatial PSD, m^2/(rad/m).
        wavelength_min, wavelength_max : float
            Shortest and longest wavelength, m (``0 < min < max``).
        n : int
            Number of wavenumbers (>= 1).

        Returns
        -------
        SpatialBand
        """
        if not (0 < wavelength_min < wavelength_max and np.isfinite(wavelength_max)):
            raise CaseError(
                "nonstationary.wavelength_min_m", wavelength_min, f"in (0, {wavelength_max}) (m)"
            )
        edges = np.geomspace(2 * np.pi / wavelength_max, 2 * np.pi / wavelength_min, int(n) + 1)
        omega = np.sqrt(edges[1:] * edges[:-1])
        width = np.diff(edges)
        return cls(omega, width, np.sqrt(spectrum.psd(omega) * width))

    @property
    def variance(self) -> float:
        """Variance of the irregularity in the band, m^2."""
        return float(np.sum(self.amplitude**2))
