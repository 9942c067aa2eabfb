"""Chinese high-speed ballastless track vertical profile spectrum (TB/T 3352-2014)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.registry import parameter
from railvib.spectra._checks import as_wavenumber
from railvib.spectra.base import SPECTRA, SpatialSpectrum

__all__ = ["ChineseHSR"]

#: Segment break points in n (1/m), and per-segment A (mm^2/(1/m) (1/m)^k) and k.
HSR_BREAKS_CYCLE_PER_M = np.array([0.0187, 0.0474, 0.1533])
HSR_A = np.array([1.0544e-5, 3.5588e-3, 1.9784e-2, 3.9488e-4])
HSR_K = np.array([3.3891, 1.9271, 1.3643, 3.4516])
#: Validity band of the standard, n in cycle/m (wavelength 2-200 m).
HSR_N_MIN = 0.005
HSR_N_MAX = 0.5
MM2_TO_M2 = 1e-6


@SPECTRA.register("chinese_hsr")
@dataclass(frozen=True)
class ChineseHSR(SpatialSpectrum):
    """TB/T 3352-2014 vertical profile, piecewise ``S(n) = A_i / n^k_i`` in mm^2/(cycle/m).

    Converted to ``S(Omega) = 1e-6 S(n = Omega / 2 pi) / (2 pi)`` in m^2/(rad/m). Segment i
    covers ``b_(i-1) < n <= b_i`` with breaks b = 0.0187, 0.0474, 0.1533 cycle/m.

    Choice outside the validity band 0.005 <= n <= 0.5 cycle/m (wavelength 2-200 m): the
    spectrum is **zero** there by default, because the standard defines nothing outside it
    and a silent power-law extrapolation would invent short-wave content. Pair it with a
    short-wave spectrum (see :class:`~railvib.spectra.Combined`) for wheel/rail frequencies.
    Set ``extrapolate=True`` to extend the first and last segments instead.

    Parameters
    ----------
    extrapolate : bool
        False (default): zero outside the band. True: extend the end power laws.
    """

    extrapolate: bool = parameter(
        "", "extend the end power laws beyond 2-200 m (default: zero there)", default=False
    )

    def psd(self, wavenumber: ArrayLike) -> NDArray[np.float64]:
        """One-sided PSD in m^2/(rad/m) at spatial circular frequency `wavenumber` (rad/m, > 0)."""
        n = as_wavenumber(wavenumber) / (2.0 * np.pi)
        seg = np.searchsorted(HSR_BREAKS_CYCLE_PER_M, n, side="left")
        s = MM2_TO_M2 * HSR_A[seg] * n ** (-HSR_K[seg]) / (2.0 * np.pi)
        if not self.extrapolate:
            s = np.where((n >= HSR_N_MIN) & (n <= HSR_N_MAX), s, 0.0)
        return s
