"""Spatial irregularity spectra and their conversion to temporal PSDs.

Convention: a spatial spectrum is one-sided and is evaluated at the spatial
circular frequency ``Omega`` in rad/m; its value is in m^2/(rad/m). At speed
``v`` the one-sided temporal PSD per Hz is

    S_t(f) [m^2/Hz] = (2 pi / v) * S_x(Omega = 2 pi f / v).
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.registry import Registry, check_parameters

__all__ = ["SPECTRA", "SpatialSpectrum", "temporal_psd"]


class SpatialSpectrum(ABC):
    """One-sided spatial PSD of the vertical rail irregularity, m^2/(rad/m) vs rad/m.

    A spectrum is a frozen dataclass whose fields are declared with
    :func:`railvib.registry.parameter` and registers itself in :data:`SPECTRA`
    (``docs/extending.md``); its declared parameters are checked on construction,
    conditions between them in :meth:`validate`.
    """

    def __post_init__(self) -> None:
        check_parameters(self, "finite")
        self.validate()

    def validate(self) -> None:  # noqa: B027 (a hook: most spectra need no extra check)
        """Check conditions between parameters (each parameter alone is checked already)."""

    def steps_rad_per_m(self) -> tuple[float, ...]:
        """Wavenumbers (rad/m) where the spectrum jumps by definition (a hard join); none here.

        Returns
        -------
        tuple of float
            Ascending wavenumbers in rad/m; at speed v a step at Omega is seen at
            ``f = v Omega / (2 pi)`` Hz in the temporal PSD.
        """
        return ()

    @abstractmethod
    def psd(self, wavenumber: ArrayLike) -> NDArray[np.float64]:
        """One-sided PSD in m^2/(rad/m) at spatial circular frequency `wavenumber` (rad/m, > 0)."""

    def psd_cycles(self, spatial_frequency: ArrayLike) -> NDArray[np.float64]:
        """One-sided PSD in m^2/(cycle/m) at spatial frequency n in cycle/m: ``2 pi S(2 pi n)``.

        Parameters
        ----------
        spatial_frequency : array_like
            Spatial frequencies n in cycle/m (1/wavelength, > 0), any shape.

        Returns
        -------
        numpy.ndarray
            One-sided PSD in m^2/(cycle/m), shape of `spatial_frequency`.
        """
        n = np.asarray(spatial_frequency, dtype=float)
        return 2.0 * np.pi * self.psd(2.0 * np.pi * n)

    def temporal(self, f: ArrayLike, speed: float) -> NDArray[np.float64]:
        """One-sided temporal PSD in m^2/Hz seen at speed `speed` (m/s) at frequencies `f` (Hz)."""
        return temporal_psd(self, f, speed)


def temporal_psd(spectrum: SpatialSpectrum, f: ArrayLike, speed: float) -> NDArray[np.float64]:
    """One-sided temporal PSD ``S_t(f) = (2 pi / v) S_x(2 pi f / v)`` in m^2/Hz.

    Parameters
    ----------
    spectrum : SpatialSpectrum
        The spatial spectrum (m^2/(rad/m)).
    f : array_like
        Temporal frequencies in Hz.
    speed : float
        Vehicle speed in m/s (> 0).
    """
    if not (np.isfinite(speed) and speed > 0):
        raise CaseError("speed", speed, "must be > 0 (m/s)")
    f = np.asarray(f, dtype=float)
    return (2.0 * np.pi / speed) * spectrum.psd(2.0 * np.pi * f / speed)


#: every irregularity spectrum a case file can name (``[irregularity] type = "..."``)
SPECTRA: Registry[SpatialSpectrum] = Registry(
    "irregularity spectrum",
    SpatialSpectrum,
    "type",
    style="finite",
    plural="irregularity spectra",
    where="[irregularity]",
)
