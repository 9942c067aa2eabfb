"""The railpad model interface.

Sign convention (written once, here): time dependence is ``exp(+i omega t)``, so a
pad's complex dynamic stiffness is ``K* = K' + i K''`` with ``K'' >= 0`` for a
passive (energy-absorbing) pad. The loss factor is ``eta = K'' / K'``.

A pad model implements one method, :meth:`PadModel.stiffness`; storage and loss
stiffness, loss factor and the passivity check are derived here.
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError

__all__ = ["PadModel"]


class PadModel(ABC):
    """Complex dynamic stiffness of one railpad (one rail seat), in N/m."""

    #: short name used in case files (``[track.pad] model = "..."``)
    model_name: str = ""

    @property
    def temperature_dependent(self) -> bool:
        """Whether :meth:`stiffness` depends on its `temperature` argument."""
        return False

    @abstractmethod
    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """Complex dynamic stiffness ``K*(f, T)`` in N/m.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz (> 0). Any shape; the result has the same shape.
        temperature : float, optional
            Pad temperature in degrees Celsius. Models that do not depend on
            temperature ignore it.

        Returns
        -------
        numpy.ndarray of complex
            ``K' + i K''`` in N/m, ``exp(+i omega t)`` convention.
        """

    def storage(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.float64]:
        """Storage stiffness ``K'`` in N/m."""
        return np.real(self.stiffness(f, temperature))

    def loss(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.float64]:
        """Loss stiffness ``K''`` in N/m."""
        return np.imag(self.stiffness(f, temperature))

    def loss_factor(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.float64]:
        """Loss factor ``eta = K'' / K'`` (dimensionless)."""
        k = self.stiffness(f, temperature)
        return np.imag(k) / np.real(k)

    def check_passive(
        self, f: ArrayLike, temperature: float | None = None, *, field: str = "track.pad"
    ) -> None:
        """Raise :class:`~railvib.errors.CaseError` unless ``K' > 0`` and ``K'' >= 0`` at all `f`.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz at which to check.
        temperature : float, optional
            Temperature in degrees Celsius.
        field : str
            Field name used in the error message.
        """
        f = np.asarray(f, dtype=float)
        k = self.stiffness(f, temperature)
        bad = ~np.isfinite(k) | (np.real(k) <= 0) | (np.imag(k) < 0)
        if np.any(bad):
            i = int(np.flatnonzero(bad.ravel())[0])
            raise CaseError(
                field,
                f"K*({f.ravel()[i]:g} Hz) = {k.ravel()[i]:.4g} N/m",
                "a passive pad needs K' > 0 and K'' >= 0 at every frequency",
            )
