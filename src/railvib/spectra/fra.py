"""American (FRA) vertical profile classes 1-6 in the k A_v form used by Chinese papers."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.registry import parameter
from railvib.spectra._checks import as_wavenumber
from railvib.spectra.base import SPECTRA, SpatialSpectrum

__all__ = ["FRAClass"]

#: A_v of classes 1..6 in cm^2 rad/m (docs/spectra.md). Class 6 is the best track.
FRA_A_V_CM2_RAD_PER_M: dict[int, float] = {
    1: 1.2107,
    2: 1.0181,
    3: 0.6816,
    4: 0.5376,
    5: 0.2095,
    6: 0.0339,
}
FRA_K = 0.25  # dimensionless safety factor of the k A_v form
FRA_OMEGA_C_RAD_PER_M = 0.8245  # break wavenumber, rad/m, every class
CM2_TO_M2 = 1e-4


@SPECTRA.register("fra")
@dataclass(frozen=True)
class FRAClass(SpatialSpectrum):
    """FRA vertical profile spectrum in the k A_v form, classes 1-6.

    ``S(Omega) = k A_v Omega_c^2 / (Omega^2 (Omega^2 + Omega_c^2))``.

    With k = 0.25, Omega_c = 0.8245 rad/m and A_v in cm^2 rad/m the formula gives
    cm^2/(rad/m); :meth:`psd` multiplies by 1e-4 and returns m^2/(rad/m).

    The FRA fit is valid for wavelengths 1.524-304.8 m (5-1000 ft). It is *not* cut off
    outside that band: the paper uses it down to 1 m, and the band limits are left to the
    caller (e.g. :class:`~railvib.spectra.Combined`).

    Parameters
    ----------
    class_number : int
        FRA track class, 1 (worst) to 6 (best). The paper uses class 5.
    """

    class_number: int = parameter(
        "-",
        "FRA track class, 1 (worst) to 6 (best)",
        choices=tuple(FRA_A_V_CM2_RAD_PER_M),
        allowed="an integer 1, 2, 3, 4, 5 or 6 (FRA class)",
    )

    @property
    def a_v_cm2_rad_per_m(self) -> float:
        """Roughness coefficient A_v of this class in cm^2 rad/m."""
        return FRA_A_V_CM2_RAD_PER_M[self.class_number]

    def psd(self, wavenumber: ArrayLike) -> NDArray[np.float64]:
        """One-sided PSD in m^2/(rad/m) at spatial circular frequency `wavenumber` (rad/m, > 0)."""
        om = as_wavenumber(wavenumber)
        oc2 = FRA_OMEGA_C_RAD_PER_M**2
        s_cm2 = FRA_K * self.a_v_cm2_rad_per_m * oc2 / (om**2 * (om**2 + oc2))
        return CM2_TO_M2 * s_cm2
