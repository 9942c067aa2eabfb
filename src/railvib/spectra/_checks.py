"""Validation helpers shared by the spectrum classes (private)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError

__all__ = ["as_wavenumber"]


def as_wavenumber(wavenumber: ArrayLike) -> NDArray[np.float64]:
    """Return spatial circular frequencies as a float array; every value must be finite and > 0.

    Parameters
    ----------
    wavenumber : array_like
        Spatial circular frequency Omega in rad/m.

    Raises
    ------
    CaseError
        If any value is not finite or is <= 0 (the spectra below diverge or are undefined there).
    """
    omega = np.asarray(wavenumber, dtype=float)
    ok = np.isfinite(omega) & (omega > 0.0)
    if not np.all(ok):
        bad = float(omega[~ok].flat[0]) if omega.ndim else float(omega)
        raise CaseError("wavenumber", bad, "every wavenumber must be finite and > 0 (rad/m)")
    return omega
