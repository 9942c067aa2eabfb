"""German high-speed vertical profile spectra (low and high interference)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.registry import parameter
from railvib.spectra._checks import as_wavenumber
from railvib.spectra.base import SPECTRA, SpatialSpectrum

__all__ = ["GermanVertical"]

GERMAN_OMEGA_C_RAD_PER_M = 0.8246
GERMAN_OMEGA_R_RAD_PER_M = 0.0206
#: A_v in m^2 rad/m (docs/spectra.md).
GERMAN_A_V_M2_RAD_PER_M: dict[str, float] = {"low": 4.032e-7, "high": 1.080e-6}


@SPECTRA.register("german")
@dataclass(frozen=True)
class GermanVertical(SpatialSpectrum):
    """German high-speed vertical profile spectrum (low or high interference).

    ``S(Omega) = A_v Omega_c^2 / ((Omega^2 + Omega_r^2)(Omega^2 + Omega_c^2))``.

    Omega_c = 0.8246 rad/m, Omega_r = 0.0206 rad/m; A_v = 4.032e-7 (low interference) or
    1.080e-6 (high interference) m^2 rad/m. Result in m^2/(rad/m).

    Parameters
    ----------
    level : {"low", "high"}
        Interference level.
    """

    level: str = parameter(
        "",
        "interference level",
        choices=tuple(GERMAN_A_V_M2_RAD_PER_M),
        allowed="'low' or 'high' (German spectrum interference)",
    )

    @property
    def a_v_m2_rad_per_m(self) -> float:
        """Roughness coefficient A_v in m^2 rad/m."""
        return GERMAN_A_V_M2_RAD_PER_M[self.level]

    def psd(self, wavenumber: ArrayLike) -> NDArray[np.float64]:
        """One-sided PSD in m^2/(rad/m) at spatial circular frequency `wavenumber` (rad/m, > 0)."""
        om2 = as_wavenumber(wavenumber) ** 2
        oc2 = GERMAN_OMEGA_C_RAD_PER_M**2
        or2 = GERMAN_OMEGA_R_RAD_PER_M**2
        return self.a_v_m2_rad_per_m * oc2 / ((om2 + or2) * (om2 + oc2))
