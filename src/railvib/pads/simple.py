"""Simple railpad models: spring-damper, hysteretic, the paper's log-linear law, constant phase."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.pads.base import (
    MAX_DAMPING_NS_PER_M,
    MAX_STIFFNESS_N_PER_M,
    PADS,
    FitStart,
    PadModel,
)
from railvib.registry import parameter

__all__ = ["ConstantPhase", "Hysteretic", "LogLinear", "SpringDamper"]

_K_TYPICAL = (1e7, 1e9)  # N/m: soft to stiff railpads
_C_TYPICAL = (1e3, 2e5)  # N s/m


def _scales(f: NDArray[np.float64], k: NDArray[np.complex128]) -> tuple[float, float, float]:
    """Median storage stiffness (N/m), geometric-mean circular frequency (rad/s), loss factor."""
    ks = float(np.median(k.real))
    wm = 2 * np.pi * float(np.exp(np.mean(np.log(f))))
    return ks, wm, float(np.median(k.imag / k.real))


def _stiffness_and_loss_start(
    eta: float, build: Callable[[NDArray[np.float64]], PadModel], names: tuple[str, str]
) -> list[FitStart]:
    """One start ``[1, eta]`` (stiffness scaled by the data's median, loss), both >= 0."""
    return [FitStart([1.0, eta], [1e-9, 0.0], [np.inf, np.inf], build, names)]


def _power_law_start(
    f: NDArray[np.float64], k: NDArray[np.complex128], f0_hz: float, ks: float
) -> list[float]:
    """Start ``[K0 / ks, kappa]`` from a straight line through ``log|K*|`` against ``log f``."""
    slope, icpt = np.polyfit(np.log10(f / f0_hz), np.log10(np.abs(k)), 1)
    return [10**icpt / ks, float(np.clip(slope, 0.0, 0.9))]


@PADS.register("spring_damper")
@dataclass(frozen=True)
class SpringDamper(PadModel):
    """Kelvin-Voigt pad: ``K* = k + i omega c`` (the paper's Table 2 model).

    Parameters
    ----------
    stiffness_n_per_m : float
        Spring stiffness k in N/m (> 0).
    damping_ns_per_m : float
        Viscous damping c in N s/m (>= 0).
    """

    stiffness_n_per_m: float = parameter(
        "N/m", "spring stiffness k", gt=0.0, le=MAX_STIFFNESS_N_PER_M, typical=_K_TYPICAL, log=True
    )
    damping_ns_per_m: float = parameter(
        "N s/m",
        "viscous damping c",
        default=0.0,
        ge=0.0,
        le=MAX_DAMPING_NS_PER_M,
        typical=_C_TYPICAL,
        log=True,
    )

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """``k + i 2 pi f c`` in N/m."""
        f = np.asarray(f, dtype=float)
        return self.stiffness_n_per_m + 2j * np.pi * f * self.damping_ns_per_m

    @classmethod
    def stiffness_rows(
        cls, pads: Sequence[PadModel], f: NDArray[np.float64]
    ) -> NDArray[np.complex128]:
        """:meth:`stiffness` of every pad at once, over arrays of the parameters (N/m).

        Parameters
        ----------
        pads : sequence of SpringDamper
            The pads, ``n``.
        f : numpy.ndarray
            Frequencies in Hz, ``(n, n_freq)``: row ``i`` for ``pads[i]``.

        Returns
        -------
        numpy.ndarray of complex
            ``(n, n_freq)``, the same operations as :meth:`stiffness`, pad by pad.
        """
        own = cast("Sequence[SpringDamper]", pads)
        k = np.array([p.stiffness_n_per_m for p in own], dtype=float).reshape(-1, 1)
        c = np.array([p.damping_ns_per_m for p in own], dtype=float).reshape(-1, 1)
        return np.asarray(k + 2j * np.pi * f * c, dtype=np.complex128)

    @classmethod
    def fit_starts(
        cls, f: NDArray[np.float64], k: NDArray[np.complex128], *, n_terms: int | None, f0_hz: float
    ) -> list[FitStart]:
        """Start at the median stiffness and loss factor of the data."""
        ks, wm, eta = _scales(f, k)
        return _stiffness_and_loss_start(
            eta,
            lambda x: SpringDamper(float(x[0] * ks), float(x[1] * ks / wm)),
            ("stiffness_n_per_m", "damping_ns_per_m"),
        )


@PADS.register("hysteretic")
@dataclass(frozen=True)
class Hysteretic(PadModel):
    """Constant loss factor pad: ``K* = k (1 + i eta)``.

    Parameters
    ----------
    stiffness_n_per_m : float
        Storage stiffness k in N/m (> 0).
    loss_factor_ : float
        Loss factor eta (>= 0), frequency-independent (key ``loss_factor`` in tables).
    """

    stiffness_n_per_m: float = parameter(
        "N/m", "storage stiffness k", gt=0.0, le=MAX_STIFFNESS_N_PER_M, typical=_K_TYPICAL, log=True
    )
    loss_factor_: float = parameter(
        "-",
        "loss factor eta, frequency-independent",
        key="loss_factor",
        ge=0.0,
        le=100.0,
        typical=(0.02, 0.6),
    )

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """``k (1 + i eta)`` in N/m, broadcast to the shape of `f`."""
        f = np.asarray(f, dtype=float)
        return np.full(f.shape, self.stiffness_n_per_m * (1.0 + 1j * self.loss_factor_))

    @classmethod
    def stiffness_rows(
        cls, pads: Sequence[PadModel], f: NDArray[np.float64]
    ) -> NDArray[np.complex128]:
        """:meth:`stiffness` of every pad at once (N/m): one constant per pad.

        Parameters
        ----------
        pads : sequence of Hysteretic
            The pads, ``n``.
        f : numpy.ndarray
            Frequencies in Hz, ``(n, n_freq)``: row ``i`` for ``pads[i]``.

        Returns
        -------
        numpy.ndarray of complex
            ``(n, n_freq)``, each pad's ``k (1 + i eta)`` as :meth:`stiffness` computes it.
        """
        k = [
            p.stiffness_n_per_m * (1.0 + 1j * p.loss_factor_)
            for p in cast("Sequence[Hysteretic]", pads)
        ]
        return np.broadcast_to(np.array(k, dtype=np.complex128).reshape(-1, 1), f.shape).copy()

    @classmethod
    def fit_starts(
        cls, f: NDArray[np.float64], k: NDArray[np.complex128], *, n_terms: int | None, f0_hz: float
    ) -> list[FitStart]:
        """Start at the median stiffness and loss factor of the data."""
        ks, _, eta = _scales(f, k)
        return _stiffness_and_loss_start(
            eta,
            lambda x: Hysteretic(float(x[0] * ks), float(x[1])),
            ("stiffness_n_per_m", "loss_factor"),
        )


@PADS.register("log_linear")
@dataclass(frozen=True)
class LogLinear(PadModel):
    """The paper's frequency-dependent pad: ``K'(f) = K0 (f / f0)^kappa`` plus viscous damping.

    This is the intended reading of the paper's garbled Eq. 27,
    ``log10 K = kappa (log10 f - log10 f0) + log10 K0`` (see ``docs/design``).
    Below `f0` the stiffness is held at `K0` when `hold_below_f0` is true, so the
    law is not extrapolated to quasi-static frequencies.

    Parameters
    ----------
    k0_n_per_m : float
        Initial stiffness K0 at `f0`, N/m (> 0).
    f0_hz : float
        Reference frequency f0, Hz (> 0). The paper says 3-5 Hz; default 5 Hz.
    exponent : float
        Log-log slope kappa (>= 0). WJ-7: 0.07.
    damping_ns_per_m : float
        Viscous damping c in N s/m added as ``i omega c`` (>= 0).
    hold_below_f0 : bool
        Hold ``K' = K0`` for ``f < f0``.
    """

    k0_n_per_m: float = parameter(
        "N/m",
        "initial stiffness K0 at f0",
        gt=0.0,
        le=MAX_STIFFNESS_N_PER_M,
        typical=_K_TYPICAL,
        log=True,
    )
    f0_hz: float = parameter(
        "Hz", "reference frequency f0", default=5.0, ge=1e-6, le=1e6, typical=(1.0, 10.0)
    )
    exponent: float = parameter(
        "-",
        "log-log slope kappa of K' against f",
        default=0.07,
        ge=0.0,
        le=1.0,
        typical=(0.0, 0.2),
    )
    damping_ns_per_m: float = parameter(
        "N s/m",
        "viscous damping c",
        default=0.0,
        ge=0.0,
        le=MAX_DAMPING_NS_PER_M,
        typical=_C_TYPICAL,
        log=True,
    )
    hold_below_f0: bool = parameter("", "hold K' = K0 below f0", default=True)

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """``K0 (f/f0)^kappa + i 2 pi f c`` in N/m."""
        f = np.asarray(f, dtype=float)
        ratio = np.maximum(f / self.f0_hz, 1.0) if self.hold_below_f0 else f / self.f0_hz
        return self.k0_n_per_m * ratio**self.exponent + 2j * np.pi * f * self.damping_ns_per_m

    @classmethod
    def fit_starts(
        cls, f: NDArray[np.float64], k: NDArray[np.complex128], *, n_terms: int | None, f0_hz: float
    ) -> list[FitStart]:
        """Start from the log-log line through ``|K*|``; fitted without the hold below f0."""
        ks, wm, eta = _scales(f, k)
        return [
            FitStart(
                [*_power_law_start(f, k, f0_hz, ks), eta],
                [1e-9, 0.0, 0.0],
                [np.inf, np.inf, np.inf],
                lambda x: LogLinear(
                    float(x[0] * ks), f0_hz, float(x[1]), float(x[2] * ks / wm), False
                ),
                ("k0_n_per_m", "exponent", "damping_ns_per_m"),
            )
        ]


@PADS.register("constant_phase")
@dataclass(frozen=True)
class ConstantPhase(PadModel):
    """Causal power-law pad ``K* = K0 (i f / f0)^kappa`` (Kramers-Kronig partner of LogLinear).

    Its modulus is ``K0 (f/f0)^kappa`` and its loss factor ``tan(pi kappa / 2)``.

    Parameters
    ----------
    k0_n_per_m : float
        Modulus at `f0`, N/m (> 0).
    f0_hz : float
        Reference frequency, Hz (> 0).
    exponent : float
        kappa, 0 <= kappa < 1.
    """

    k0_n_per_m: float = parameter(
        "N/m", "modulus |K*| at f0", gt=0.0, le=MAX_STIFFNESS_N_PER_M, typical=_K_TYPICAL, log=True
    )
    f0_hz: float = parameter(
        "Hz", "reference frequency f0", default=5.0, ge=1e-6, le=1e6, typical=(1.0, 10.0)
    )
    exponent: float = parameter(
        "-", "log-log slope kappa of |K*|", default=0.07, ge=0.0, lt=1.0, typical=(0.02, 0.2)
    )

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """``K0 (i f / f0)^kappa`` in N/m."""
        f = np.asarray(f, dtype=float)
        return self.k0_n_per_m * (1j * f / self.f0_hz) ** self.exponent

    @classmethod
    def fit_starts(
        cls, f: NDArray[np.float64], k: NDArray[np.complex128], *, n_terms: int | None, f0_hz: float
    ) -> list[FitStart]:
        """Start from the log-log line through ``|K*|``."""
        ks = _scales(f, k)[0]
        return [
            FitStart(
                _power_law_start(f, k, f0_hz, ks),
                [1e-9, 0.0],
                [np.inf, 0.999],
                lambda x: ConstantPhase(float(x[0] * ks), f0_hz, float(x[1])),
                ("k0_n_per_m", "exponent"),
            )
        ]
