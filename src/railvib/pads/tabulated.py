"""A railpad given as a table of measured or computed complex stiffness against frequency."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.pads.base import PadModel

__all__ = ["TabulatedPad"]


@dataclass(frozen=True)
class TabulatedPad(PadModel):
    """Pad stiffness tabulated against frequency, interpolated linearly in log-frequency.

    Storage and loss stiffness are interpolated separately, linearly in ``log10 f``.
    Outside the table the end values are held (no extrapolation of the trend); the
    table does not depend on temperature.

    Parameters
    ----------
    frequency_hz : tuple of float
        Frequencies, Hz, strictly increasing, > 0, at least 2.
    storage_n_per_m : tuple of float
        Storage stiffness K' at each frequency, N/m (> 0).
    loss_n_per_m : tuple of float
        Loss stiffness K'' at each frequency, N/m (>= 0).
    """

    frequency_hz: tuple[float, ...]
    storage_n_per_m: tuple[float, ...]
    loss_n_per_m: tuple[float, ...]
    model_name = "tabulated"

    def __post_init__(self) -> None:
        f = np.atleast_1d(np.asarray(self.frequency_hz, dtype=float))
        k1 = np.atleast_1d(np.asarray(self.storage_n_per_m, dtype=float))
        k2 = np.atleast_1d(np.asarray(self.loss_n_per_m, dtype=float))
        if f.size < 2 or k1.size != f.size or k2.size != f.size:
            raise CaseError(
                "track.pad.frequency_hz",
                f"{f.size} frequencies, {k1.size} storage, {k2.size} loss values",
                "at least 2 rows and equal lengths",
            )
        if not np.all(np.isfinite(f) & (f > 0)) or np.any(np.diff(f) <= 0):
            raise CaseError(
                "track.pad.frequency_hz", list(f), "finite, > 0, strictly increasing (Hz)"
            )
        if not np.all(np.isfinite(k1) & (k1 > 0)):
            raise CaseError(
                "track.pad.storage_n_per_m", list(k1), "every value finite and > 0 (N/m)"
            )
        if not np.all(np.isfinite(k2) & (k2 >= 0)):
            raise CaseError("track.pad.loss_n_per_m", list(k2), "every value finite and >= 0 (N/m)")
        for name, arr in (("frequency_hz", f), ("storage_n_per_m", k1), ("loss_n_per_m", k2)):
            object.__setattr__(self, name, tuple(float(v) for v in arr))

    @classmethod
    def from_model(
        cls, model: PadModel, frequency_hz: ArrayLike, temperature: float | None = None
    ) -> TabulatedPad:
        """Tabulate another pad model at `frequency_hz` (Hz) and `temperature` (degC)."""
        f = np.asarray(frequency_hz, dtype=float)
        k = np.asarray(model.stiffness(f, temperature), dtype=complex)
        return cls(tuple(f), tuple(k.real), tuple(k.imag))

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """Interpolated ``K' + i K''`` in N/m (end values held outside the table)."""
        f = np.asarray(f, dtype=float)
        logf = np.log10(self.frequency_hz)
        x = np.log10(f)
        real = np.interp(x, logf, self.storage_n_per_m)
        imag = np.interp(x, logf, self.loss_n_per_m)
        return np.asarray(real + 1j * imag, dtype=np.complex128)
