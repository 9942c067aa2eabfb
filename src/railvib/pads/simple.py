"""Simple railpad models: spring-damper, hysteretic and the paper's log-linear law."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.pads.base import PadModel

__all__ = ["ConstantPhase", "Hysteretic", "LogLinear", "SpringDamper"]


def _positive(name: str, value: float, unit: str) -> None:
    if not (np.isfinite(value) and value > 0):
        raise CaseError(name, value, f"must be > 0 ({unit})")


def _non_negative(name: str, value: float, unit: str) -> None:
    if not (np.isfinite(value) and value >= 0):
        raise CaseError(name, value, f"must be >= 0 ({unit})")


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

    stiffness_n_per_m: float
    damping_ns_per_m: float = 0.0
    model_name = "spring_damper"

    def __post_init__(self) -> None:
        _positive("track.pad.stiffness", self.stiffness_n_per_m, "N/m")
        _non_negative("track.pad.damping", self.damping_ns_per_m, "N s/m")

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """``k + i 2 pi f c`` in N/m."""
        f = np.asarray(f, dtype=float)
        return self.stiffness_n_per_m + 2j * np.pi * f * self.damping_ns_per_m


@dataclass(frozen=True)
class Hysteretic(PadModel):
    """Constant loss factor pad: ``K* = k (1 + i eta)``.

    Parameters
    ----------
    stiffness_n_per_m : float
        Storage stiffness k in N/m (> 0).
    loss_factor_ : float
        Loss factor eta (>= 0), frequency-independent.
    """

    stiffness_n_per_m: float
    loss_factor_: float
    model_name = "hysteretic"

    def __post_init__(self) -> None:
        _positive("track.pad.stiffness", self.stiffness_n_per_m, "N/m")
        _non_negative("track.pad.loss_factor", self.loss_factor_, "dimensionless")

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """``k (1 + i eta)`` in N/m, broadcast to the shape of `f`."""
        f = np.asarray(f, dtype=float)
        return np.full(f.shape, self.stiffness_n_per_m * (1.0 + 1j * self.loss_factor_))


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

    k0_n_per_m: float
    f0_hz: float = 5.0
    exponent: float = 0.07
    damping_ns_per_m: float = 0.0
    hold_below_f0: bool = True
    model_name = "log_linear"

    def __post_init__(self) -> None:
        _positive("track.pad.k0", self.k0_n_per_m, "N/m")
        _positive("track.pad.f0", self.f0_hz, "Hz")
        _non_negative("track.pad.exponent", self.exponent, "dimensionless")
        _non_negative("track.pad.damping", self.damping_ns_per_m, "N s/m")

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """``K0 (f/f0)^kappa + i 2 pi f c`` in N/m."""
        f = np.asarray(f, dtype=float)
        ratio = np.maximum(f / self.f0_hz, 1.0) if self.hold_below_f0 else f / self.f0_hz
        return self.k0_n_per_m * ratio**self.exponent + 2j * np.pi * f * self.damping_ns_per_m


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

    k0_n_per_m: float
    f0_hz: float = 5.0
    exponent: float = 0.07
    model_name = "constant_phase"

    def __post_init__(self) -> None:
        _positive("track.pad.k0", self.k0_n_per_m, "N/m")
        _positive("track.pad.f0", self.f0_hz, "Hz")
        if not (0.0 <= self.exponent < 1.0):
            raise CaseError("track.pad.exponent", self.exponent, "must be in [0, 1)")

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """``K0 (i f / f0)^kappa`` in N/m."""
        f = np.asarray(f, dtype=float)
        return self.k0_n_per_m * (1j * f / self.f0_hz) ** self.exponent
