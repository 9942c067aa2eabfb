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
from collections.abc import Callable, Sequence
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

__all__ = [
    "MAX_DAMPING_NS_PER_M",
    "MAX_RELAXATION_TIME_S",
    "MAX_STIFFNESS_N_PER_M",
    "PADS",
    "PASSIVITY_TOLERANCE",
    "FitStart",
    "PadModel",
]

# Hard bounds of every pad model's parameters: about a million times any railpad's value
# (pads are 1e7-1e9 N/m, 1e3-2e5 N s/m, relaxation times below 1 s), so that no pad and
# no fit is refused, while every stiffness stays finite, also at a reduced frequency
# f a_T of up to 1e105 Hz (railvib.pads.tts.MAX_LOG10_SHIFT). Values beyond are typos.
#: largest stiffness parameter of a pad model, N/m (1e9 kN/mm)
MAX_STIFFNESS_N_PER_M = 1e15
#: largest viscous damping parameter of a pad model, N s/m
MAX_DAMPING_NS_PER_M = 1e12
#: largest relaxation time of a pad model, s (about 300 years)
MAX_RELAXATION_TIME_S = 1e10

#: loss stiffness taken as round-off by :meth:`PadModel.check_passive`, relative to ``|K*|``.
#: ``K*`` is evaluated in double precision by a few operations (a complex power, a
#: division, a product with the vertical TTS factor), each rounding by up to eps/2 of
#: ``|K*|``, so where the true ``K''`` is 0 or tiny the computed one can be a few eps ``|K*|``
#: below it (e.g. ``K*(9.2 Hz) = 1.352e+08 - 6.6e-09j`` N/m for a Zener pad at -85 degC:
#: -5e-17 ``|K*|``). 16 eps = 3.6e-15 is a loss factor 12 orders of magnitude below that of
#: any real pad (>= 1e-3), so no physical loss of passivity hides below it.
PASSIVITY_TOLERANCE = 16 * float(np.finfo(float).eps)


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

    @property
    def temperature_range_c(self) -> tuple[float, float] | None:
        """``(T_lo, T_hi)`` in degC over which the temperature dependence can be trusted.

        None for a model without temperature dependence (and by default). A case whose
        pad temperature lies outside the range is run, with a
        :class:`~railvib.errors.PlausibilityWarning`.
        """
        return None

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

    @classmethod
    def stiffness_rows(
        cls, pads: Sequence[PadModel], f: NDArray[np.float64]
    ) -> NDArray[np.complex128]:
        """``K*`` in N/m of pads of this model, each at its own row of frequencies.

        Models whose stiffness is written over arrays of their parameters override
        this (one pass for all the pads); here each pad is evaluated in turn.

        Parameters
        ----------
        pads : sequence of PadModel
            Pads of this model, ``n``, at their reference (no temperature given).
        f : numpy.ndarray
            Frequencies in Hz, ``(n, n_freq)``: row ``i`` for ``pads[i]``.

        Returns
        -------
        numpy.ndarray of complex
            ``(n, n_freq)``; row ``i`` is ``pads[i].stiffness(f[i])``.
        """
        out = np.empty(f.shape, dtype=np.complex128)
        for i, pad in enumerate(pads):
            out[i] = pad.stiffness(f[i])
        return out

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

        A loss stiffness down to ``-PASSIVITY_TOLERANCE |K*|`` (16 eps ``|K*|``) is taken as
        round-off, not as a pad that gives energy back: see :data:`PASSIVITY_TOLERANCE`.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz at which to check.
        temperature : float, optional
            Temperature in degrees Celsius.
        field : str
            Field name used in the error message.

        Raises
        ------
        CaseError
            Naming the first frequency (and the temperature) where ``K*`` is not finite,
            ``K' <= 0`` or ``K'' < -16 eps |K*|``, and why that is not allowed.
        """
        f = np.asarray(f, dtype=float)
        k = np.asarray(self.stiffness(f, temperature), dtype=complex)
        finite = np.isfinite(k)
        storage_bad = finite & (np.real(k) <= 0)
        loss_bad = finite & (np.imag(k) < -PASSIVITY_TOLERANCE * np.abs(k))
        bad = ~finite | storage_bad | loss_bad
        if not np.any(bad):
            return
        i = int(np.flatnonzero(bad.ravel())[0])
        fi, ki = float(f.ravel()[i]), complex(k.ravel()[i])
        at = f"{fi:g} Hz" + ("" if temperature is None else f", {temperature:g} degC")
        if not finite.ravel()[i]:
            why = "a finite stiffness at every frequency of the grid"
        elif storage_bad.ravel()[i]:
            why = (
                "K' > 0 at every frequency of the grid (a storage stiffness <= 0 is no "
                "spring: the rail would not rest on the pad)"
            )
        else:
            why = (
                f"K'' >= 0 at every frequency of the grid (a passive pad absorbs energy; a "
                f"loss factor K''/K' = {ki.imag / ki.real:.3g} < 0 gives energy to the track; "
                f"K'' down to -16 eps |K*| = {-PASSIVITY_TOLERANCE * abs(ki):.2g} N/m is "
                "taken as round-off)"
            )
        raise CaseError(field, f"K*({at}) = {ki:.4g} N/m", why)


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
