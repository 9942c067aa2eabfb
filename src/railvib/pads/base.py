"""The railpad model interface.

Sign convention (written once, here): time dependence is ``exp(+i omega t)``, so a
pad's complex dynamic stiffness is ``K* = K' + i K''`` with ``K'' >= 0`` for a
passive (energy-absorbing) pad. The loss factor is ``eta = K'' / K'``.

A pad model implements one method, :meth:`PadModel.stiffness`; storage and loss
stiffness, loss factor and the passivity check are derived here. It is a frozen
dataclass whose fields are declared with :func:`railvib.registry.parameter` and
registers itself in :data:`PADS` (see ``docs/extending.md``); its declared
parameters are checked on construction, cross-parameter conditions in
:meth:`PadModel.validate`.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.docstrings import fill_doc
from railvib.errors import CaseError
from railvib.registry import Registry, check_parameters

#: parameter documentation shared by the pad methods (:func:`railvib.docstrings.fill_doc`)
_SHARED = {
    "f": """f : array_like
    Frequencies in Hz (> 0). Any shape; the result has the same shape.""",
    "temperature": """temperature : float, optional
    Pad temperature in degrees Celsius (degC). Models that do not depend on
    temperature ignore it.""",
}

__all__ = ["PADS", "FitStart", "PadModel"]


class PadModel(ABC):
    """Complex dynamic stiffness of one railpad (one rail seat), in N/m."""

    #: short name used in case files (``[track.pad] model = "..."``), set on registration
    model_name: ClassVar[str] = ""

    def __post_init__(self) -> None:
        check_parameters(self, "must")
        self.validate()

    def validate(self) -> None:  # noqa: B027 (a hook: most models need no extra check)
        """Check conditions between parameters (each parameter alone is checked already).

        Raises
        ------
        CaseError
            Naming the parameter's key.
        """

    @classmethod
    def fit_starts(
        cls, f: NDArray[np.float64], k: NDArray[np.complex128], *, n_terms: int | None, f0_hz: float
    ) -> list[FitStart] | None:
        """Start points and bounds for fitting this model to ``K*(f)``, or None if not fittable.

        Parameters
        ----------
        f : numpy.ndarray
            Frequencies, Hz.
        k : numpy.ndarray
            Complex stiffness at `f`, N/m.
        n_terms : int, optional
            Number of terms of a series model.
        f0_hz : float
            Reference frequency of power-law models, Hz.
        """
        return None

    @property
    def temperature_dependent(self) -> bool:
        """Whether :meth:`stiffness` depends on its `temperature` argument."""
        return False

    @abstractmethod
    @fill_doc(_SHARED)
    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """Complex dynamic stiffness ``K*(f, T)`` in N/m.

        Parameters
        ----------
        {f}
        {temperature}

        Returns
        -------
        numpy.ndarray of complex
            ``K' + i K''`` in N/m, ``exp(+i omega t)`` convention.
        """

    @fill_doc(_SHARED)
    def storage(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.float64]:
        """Storage stiffness ``K'`` in N/m.

        Parameters
        ----------
        {f}
        {temperature}

        Returns
        -------
        numpy.ndarray
            ``K'`` in N/m, shape of `f`.
        """
        return np.real(self.stiffness(f, temperature))

    @fill_doc(_SHARED)
    def loss(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.float64]:
        """Loss stiffness ``K''`` in N/m.

        Parameters
        ----------
        {f}
        {temperature}

        Returns
        -------
        numpy.ndarray
            ``K''`` in N/m, shape of `f`.
        """
        return np.imag(self.stiffness(f, temperature))

    @fill_doc(_SHARED)
    def loss_factor(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.float64]:
        """Loss factor ``eta = K'' / K'`` (dimensionless).

        Parameters
        ----------
        {f}
        {temperature}

        Returns
        -------
        numpy.ndarray
            ``eta`` (dimensionless), shape of `f`.
        """
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


@dataclass(frozen=True)
class FitStart:
    """One start of a least-squares fit of a pad model (see :func:`railvib.pads.fit_model`).

    Parameters
    ----------
    x0 : list of float
        Start point of the scaled parameters (dimensionless).
    lower, upper : list of float
        Bounds of the scaled parameters.
    build : callable
        ``build(x)`` -> the pad model at scaled parameters `x`.
    names : tuple of str
        The case-file key of the parameter each scaled parameter sets (``"tau_s"``,
        ``"k_n_per_m[2]"``), so a fit ending at a search bound can name it; empty:
        they are called by their position.
    """

    x0: list[float]
    lower: list[float]
    upper: list[float]
    build: Callable[[NDArray[np.float64]], PadModel]
    names: tuple[str, ...] = ()


#: every pad model a case file can name (``[track.pad] model = "..."``)
PADS: Registry[PadModel] = Registry(
    "pad model", PadModel, "model", style="must", where="[track.pad]"
)
