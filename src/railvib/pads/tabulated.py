"""A railpad given as a table of measured or computed complex stiffness against frequency."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.pads.base import MAX_STIFFNESS_N_PER_M, PADS, PadModel
from railvib.registry import parameter

__all__ = ["TabulatedPad"]


@PADS.register("tabulated")
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

    frequency_hz: tuple[float, ...] = parameter(
        "Hz", "frequencies, strictly increasing, at least 2", gt=0.0, le=1e30
    )
    storage_n_per_m: tuple[float, ...] = parameter(
        "N/m", "storage stiffness K' at each frequency", gt=0.0, le=MAX_STIFFNESS_N_PER_M
    )
    loss_n_per_m: tuple[float, ...] = parameter(
        "N/m", "loss stiffness K'' at each frequency", ge=0.0, le=MAX_STIFFNESS_N_PER_M
    )

    def validate(self) -> None:
        """At least 2 rows of equal length, strictly increasing frequencies."""
        f = np.asarray(self.frequency_hz)
        n1, n2 = len(self.storage_n_per_m), len(self.loss_n_per_m)
        if f.size < 2 or n1 != f.size or n2 != f.size:
            raise CaseError(
                "frequency_hz",
                f"{f.size} frequencies, {n1} storage, {n2} loss values",
                "at least 2 rows and equal lengths",
            )
        if np.any(np.diff(f) <= 0):
            raise CaseError("frequency_hz", list(f), "finite, > 0, strictly increasing (Hz)")

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
