"""Sato short-wave spectrum ``S(Omega) = A / Omega^3``."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.registry import parameter
from railvib.spectra._checks import as_wavenumber
from railvib.spectra.base import SPECTRA, SpatialSpectrum

__all__ = ["Sato"]


@SPECTRA.register("sato")
@dataclass(frozen=True)
class Sato(SpatialSpectrum):
    """Sato (RTRI 1977) short-wave spectrum, ``S(Omega) = A / Omega^3`` in m^2/(rad/m).

    Parameters
    ----------
    coefficient : float
        A (> 0). 4.15e-8 for good track (default), 5.0e-7 for poor track. The literature
        states the unit as "m rad"; it is used so that S comes out in m^2/(rad/m) with
        Omega in rad/m.
    """

    coefficient: float = parameter(
        "m rad",
        "A: 4.15e-8 good track, 5.0e-7 poor track",
        default=4.15e-8,
        gt=0.0,
        le=1e-3,
        typical=(4.15e-8, 5.0e-7),
        log=True,
    )

    def psd(self, wavenumber: ArrayLike) -> NDArray[np.float64]:
        """One-sided PSD in m^2/(rad/m) at spatial circular frequency `wavenumber` (rad/m, > 0)."""
        return self.coefficient / as_wavenumber(wavenumber) ** 3
