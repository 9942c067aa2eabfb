"""Roughness in the rolling-noise format: levels in one-third-octave wavelength bands.

EN 15610:2009 reports rail (and wheel) roughness as levels
``L = 10 log10(r_rms^2 / r0^2)`` dB re ``r0 = 1 um`` in one-third-octave bands of
wavelength; railvib's spectra are one-sided wavenumber PSDs ``S(Omega)`` in
m^2/(rad/m) (:mod:`railvib.spectra.base`). A band of centre wavelength
``lambda_c`` spans the wavenumbers ``Omega_c 10^(-1/20) .. Omega_c 10^(+1/20)``,
``Omega_c = 2 pi / lambda_c`` (the base-10 bands of IEC 61260-1 in wavenumber), so
with the PSD taken constant across a band (the usual conversion of a band level)

    r_rms^2 = S(Omega_c) * Omega_c (10^(1/20) - 10^(-1/20)),

and :func:`level_to_psd` and :func:`psd_to_level` invert each other exactly. A
spectrum of band levels (:class:`RoughnessLevels`, ``type = "roughness_levels"``)
takes the PSD at the band centres and interpolates it linearly in log-log between
them (zero outside the bands, like :class:`~railvib.spectra.Tabulated`), so it can be
the short-wave part of a :class:`~railvib.spectra.Combined` irregularity.

ISO 3095:2013, 6.2.5 and Figure 2, gives the upper limit of rail roughness of the
reference track of a pass-by test: the 22 levels printed beside the points of
Figure 2, from 40 cm to 0.315 cm (:data:`ISO3095_LIMIT`, ``type = "iso3095_limit"``);
EN 15610:2009, Annex B.9.2 lists the same values.

Contact filter (optional, ``contact_half_length_m``): the wheel averages the
roughness over its contact patch; modelled here as the uniform average over the
contact length ``2a`` in the rolling direction, ``|H(Omega)|^2 = (sin(Omega a) /
(Omega a))^2``. This one-dimensional filter is the simplest of those reviewed by
Thompson, *Railway Noise and Vibration* (2009), section 5.5 (after Remington 1987,
J. Acoust. Soc. Am. 81, 1805-1823); the two-dimensional filters there, which
average across the width of the contact too, attenuate differently at wavelengths
shorter than the contact length.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.registry import parameter
from railvib.spectra._checks import as_wavenumber
from railvib.spectra.base import SPECTRA, SpatialSpectrum

__all__ = [
    "ISO3095_LIMIT",
    "ROUGHNESS_REFERENCE_M",
    "ISO3095Limit",
    "RoughnessLevels",
    "band_width_rad_per_m",
    "contact_filter",
    "level_to_psd",
    "psd_to_level",
]

#: reference roughness of the levels, m (1 um, as EN 15610:2009 reports levels)
ROUGHNESS_REFERENCE_M = 1e-6

#: ISO 3095:2013, Figure 2: (nominal wavelength, m; limit level, dB re 1 um), as printed
ISO3095_LIMIT: tuple[tuple[float, float], ...] = tuple(
    (cm / 100.0, level)
    for cm, level in zip(
        (40.0, 31.5, 25.0, 20.0, 16.0, 12.5, 10.0, 8.0, 6.3, 5.0, 4.0,
         3.15, 2.5, 2.0, 1.6, 1.25, 1.0, 0.8, 0.63, 0.5, 0.4, 0.315),
        (17.1, 15.0, 13.0, 11.0, 9.0, 7.0, 4.9, 2.9, 0.9, -1.1, -3.2,
         -5.0, -5.6, -6.2, -6.8, -7.4, -8.0, -8.6, -9.2, -9.8, -10.4, -11.0),
        strict=True,
    )
)  # fmt: skip


def band_width_rad_per_m(wavelength_m: ArrayLike) -> NDArray[np.float64]:
    """Wavenumber width of the one-third-octave band centred on `wavelength_m`, rad/m.

    Parameters
    ----------
    wavelength_m : array_like
        Band centre wavelengths, m (> 0).

    Returns
    -------
    numpy.ndarray
        ``(2 pi / lambda) (10^(1/20) - 10^(-1/20))``, rad/m.
    """
    omega = 2.0 * np.pi / np.asarray(wavelength_m, dtype=float)
    return np.asarray(omega * (10.0 ** (1.0 / 20.0) - 10.0 ** (-1.0 / 20.0)))


def level_to_psd(
    wavelength_m: ArrayLike, level_db: ArrayLike, reference_m: float = ROUGHNESS_REFERENCE_M
) -> NDArray[np.float64]:
    """The one-sided wavenumber PSD at band centres from one-third-octave band levels.

    Parameters
    ----------
    wavelength_m : array_like
        Band centre wavelengths, m.
    level_db : array_like
        Roughness levels, dB re `reference_m` (m; 1e-6 m: dB re 1 um).
    reference_m : float
        Reference roughness, m (1e-6: dB re 1 um).

    Returns
    -------
    numpy.ndarray
        ``S(2 pi / lambda)`` in m^2/(rad/m).
    """
    ms = reference_m**2 * 10.0 ** (np.asarray(level_db, dtype=float) / 10.0)
    return np.asarray(ms / band_width_rad_per_m(wavelength_m))


def psd_to_level(
    wavelength_m: ArrayLike, psd: ArrayLike, reference_m: float = ROUGHNESS_REFERENCE_M
) -> NDArray[np.float64]:
    """One-third-octave band levels from the one-sided wavenumber PSD at the band centres.

    Parameters
    ----------
    wavelength_m : array_like
        Band centre wavelengths, m.
    psd : array_like
        ``S(2 pi / lambda)``, m^2/(rad/m).
    reference_m : float
        Reference roughness, m.

    Returns
    -------
    numpy.ndarray
        Levels, dB re `reference_m` (the inverse of :func:`level_to_psd`).
    """
    ms = np.asarray(psd, dtype=float) * band_width_rad_per_m(wavelength_m)
    return np.asarray(10.0 * np.log10(ms / reference_m**2))


def contact_filter(wavenumber: ArrayLike, half_length_m: float) -> NDArray[np.float64]:
    """``|H|^2 = (sin(Omega a) / (Omega a))^2``: a uniform average over the contact length 2a.

    Parameters
    ----------
    wavenumber : array_like
        Omega, rad/m.
    half_length_m : float
        a, half the contact length in the rolling direction, m (0: no filter).

    Returns
    -------
    numpy.ndarray
        The power transfer, dimensionless, 1 at long wavelengths.
    """
    x = np.asarray(wavenumber, dtype=float) * half_length_m / np.pi
    return np.asarray(np.sinc(x) ** 2)  # numpy's sinc(x) = sin(pi x) / (pi x)


def _interpolated(
    wavelength_m: NDArray[np.float64], psd: NDArray[np.float64], wavenumber: NDArray[np.float64]
) -> NDArray[np.float64]:
    """PSD at `wavenumber`, log-log between band centres, zero outside them."""
    om = 2.0 * np.pi / wavelength_m
    order = np.argsort(om)
    om, psd = om[order], psd[order]
    s = np.exp(np.interp(np.log(wavenumber), np.log(om), np.log(psd)))
    return np.where((wavenumber >= om[0]) & (wavenumber <= om[-1]), s, 0.0)


@SPECTRA.register("roughness_levels")
@dataclass(frozen=True)
class RoughnessLevels(SpatialSpectrum):
    """Roughness given as one-third-octave band levels (dB re 1 um), e.g. an EN 15610 measurement.

    Parameters
    ----------
    wavelength_m : tuple of float
        Band centre wavelengths, m (at least 2, distinct).
    level_db : tuple of float
        Levels in those bands, dB re 1 um.
    contact_half_length_m : float
        Half the contact length of the optional contact filter, m (0: none).
    """

    wavelength_m: tuple[float, ...] = parameter(
        "m", "centre wavelengths of the one-third-octave bands", gt=0.0, le=100.0
    )
    level_db: tuple[float, ...] = parameter(
        "dB re 1 um", "roughness level in each band", ge=-100.0, le=100.0
    )
    contact_half_length_m: float = parameter(
        "m",
        "half the contact length of the contact filter (0: none); about 5e-3 m for a "
        "wheel on a rail",
        default=0.0,
        ge=0.0,
        le=0.1,
    )

    def validate(self) -> None:
        """As many levels as wavelengths, at least 2 distinct wavelengths."""
        if len(self.wavelength_m) < 2 or len(set(self.wavelength_m)) != len(self.wavelength_m):
            raise CaseError(
                "wavelength_m", list(self.wavelength_m), "at least 2 distinct wavelengths (m)"
            )
        if len(self.level_db) != len(self.wavelength_m):
            raise CaseError(
                "level_db",
                f"<{len(self.level_db)} levels>",
                f"one level per wavelength ({len(self.wavelength_m)}) (dB re 1 um)",
            )

    def psd(self, wavenumber: ArrayLike) -> NDArray[np.float64]:
        """One-sided PSD in m^2/(rad/m) at `wavenumber` (rad/m, > 0); zero outside the bands."""
        om = as_wavenumber(wavenumber)
        lam = np.asarray(self.wavelength_m, dtype=float)
        s = _interpolated(lam, level_to_psd(lam, self.level_db), om)
        if self.contact_half_length_m:
            s = s * contact_filter(om, self.contact_half_length_m)
        return s


@SPECTRA.register("iso3095_limit")
@dataclass(frozen=True)
class ISO3095Limit(SpatialSpectrum):
    """The rail roughness limit of ISO 3095:2013, Figure 2 (40 cm to 0.315 cm), as a spectrum.

    Parameters
    ----------
    contact_half_length_m : float
        Half the contact length of the optional contact filter, m (0: none).
    """

    contact_half_length_m: float = parameter(
        "m", "half the contact length of the contact filter (0: none)", default=0.0, ge=0.0, le=0.1
    )

    def psd(self, wavenumber: ArrayLike) -> NDArray[np.float64]:
        """One-sided PSD in m^2/(rad/m) at `wavenumber` (rad/m); zero outside 0.315-40 cm."""
        om = as_wavenumber(wavenumber)
        lam = np.array([w for w, _ in ISO3095_LIMIT])
        s = _interpolated(lam, level_to_psd(lam, [lv for _, lv in ISO3095_LIMIT]), om)
        if self.contact_half_length_m:
            s = s * contact_filter(om, self.contact_half_length_m)
        return s
