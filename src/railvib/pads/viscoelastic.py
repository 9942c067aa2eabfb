"""Viscoelastic railpad models: fractional-derivative Zener and generalised Maxwell (Prony).

Both are causal and passive for the parameter ranges accepted here, which is checked
in ``__post_init__`` (see each class).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.pads.base import (
    MAX_RELAXATION_TIME_S,
    MAX_STIFFNESS_N_PER_M,
    PADS,
    FitStart,
    PadModel,
)
from railvib.registry import parameter

__all__ = ["FractionalZener", "GeneralizedMaxwell"]


@PADS.register("fractional_zener", aliases=("zener",))
@dataclass(frozen=True)
class FractionalZener(PadModel):
    """Fractional-derivative standard linear solid (Fenander 1997/1998).

    ``K* = (K0 + K_inf (i omega tau)^alpha) / (1 + (i omega tau)^alpha)``.

    Writing ``z = (i omega tau)^alpha``, ``K'' = (K_inf - K0) Im(z) / |1 + z|^2``, so the
    pad is passive at every frequency exactly when ``K_inf >= K0``; that is enforced.
    With ``alpha = 1`` it is the standard Zener solid.

    Parameters
    ----------
    k0_n_per_m : float
        Relaxed (low-frequency) stiffness K0, N/m (> 0).
    k_inf_n_per_m : float
        Unrelaxed (high-frequency) stiffness K_inf, N/m (>= K0).
    tau_s : float
        Relaxation time tau, s (> 0).
    alpha : float
        Fractional order, 0 < alpha <= 1 (dimensionless).
    """

    k0_n_per_m: float = parameter(
        "N/m",
        "relaxed (low-frequency) stiffness K0",
        gt=0.0,
        le=MAX_STIFFNESS_N_PER_M,
        typical=(1e7, 1e8),
        log=True,
    )
    k_inf_n_per_m: float = parameter(
        "N/m",
        "unrelaxed (high-frequency) stiffness K_inf, >= K0",
        gt=0.0,
        le=MAX_STIFFNESS_N_PER_M,
        typical=(2e8, 1e9),
        log=True,
    )
    tau_s: float = parameter(
        "s", "relaxation time tau", gt=0.0, le=MAX_RELAXATION_TIME_S, typical=(1e-6, 1e-2), log=True
    )
    alpha: float = parameter(
        "-",
        "fractional order",
        gt=0.0,
        le=1.0,
        allowed="must be in (0, 1]",
        typical=(0.1, 1.0),
    )

    @classmethod
    def fit_starts(
        cls, f: NDArray[np.float64], k: NDArray[np.complex128], *, n_terms: int | None, f0_hz: float
    ) -> list[FitStart]:
        """Three starts (alpha = 0.2, 0.5, 0.9) about the data's relaxed and unrelaxed stiffness."""
        return _zener_starts(f, k, float(np.median(k.real)))

    def validate(self) -> None:
        """K_inf >= K0: a non-negative loss factor at every frequency."""
        if self.k_inf_n_per_m < self.k0_n_per_m:
            raise CaseError(
                "k_inf_n_per_m",
                self.k_inf_n_per_m,
                f"must be >= k0_n_per_m = {self.k0_n_per_m:.4g} (N/m), otherwise the loss "
                "factor is negative",
            )

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """``K0 + (K_inf - K0) z / (1 + z)``, ``z = (i 2 pi f tau)^alpha``, in N/m."""
        f = np.asarray(f, dtype=float)
        # (i x)^alpha = x^alpha exp(i alpha pi / 2) for x >= 0, written out to stay exact
        z = (2 * np.pi * f * self.tau_s) ** self.alpha * np.exp(0.5j * np.pi * self.alpha)
        return self.k0_n_per_m + (self.k_inf_n_per_m - self.k0_n_per_m) * (z / (1.0 + z))

    @classmethod
    def stiffness_rows(
        cls, pads: Sequence[PadModel], f: NDArray[np.float64]
    ) -> NDArray[np.complex128]:
        """:meth:`stiffness` of every pad at once, over arrays of the parameters (N/m).

        Parameters
        ----------
        pads : sequence of FractionalZener
            The pads, ``n``.
        f : numpy.ndarray
            Frequencies in Hz, ``(n, n_freq)``: row ``i`` for ``pads[i]``.

        Returns
        -------
        numpy.ndarray of complex
            ``(n, n_freq)``, the same operations as :meth:`stiffness`, pad by pad.
        """
        k0, k_inf, tau, alpha = (
            np.array([[getattr(p, name)] for p in pads], dtype=float).reshape(-1, 1)
            for name in ("k0_n_per_m", "k_inf_n_per_m", "tau_s", "alpha")
        )
        x = 2 * np.pi * f * tau
        # the power row by row, with a scalar exponent, as `stiffness` takes it: NumPy's
        # power may take another path for another exponent or array (e.g. sqrt for 0.5,
        # SIMD lanes), which can change the last bit
        power = np.empty(x.shape, dtype=float)
        for i, a in enumerate(alpha[:, 0]):
            power[i] = x[i] ** float(a)
        z = power * np.exp(0.5j * np.pi * alpha)
        return np.asarray(k0 + (k_inf - k0) * (z / (1.0 + z)), dtype=np.complex128)


@PADS.register("generalized_maxwell", aliases=("prony",))
@dataclass(frozen=True)
class GeneralizedMaxwell(PadModel):
    """Generalised Maxwell pad (Prony series; Oregui et al. 2017).

    ``K* = K_inf + sum_i K_i (i omega tau_i) / (1 + i omega tau_i)``. Every branch is
    passive when ``K_i >= 0``; that is enforced.

    Parameters
    ----------
    k_inf_n_per_m : float
        Equilibrium (zero-frequency) stiffness, N/m (> 0).
    k_n_per_m : tuple of float
        Branch stiffnesses K_i, N/m (each >= 0).
    tau_s : tuple of float
        Branch relaxation times tau_i, s (each > 0), same length as `k_n_per_m`.
    """

    k_inf_n_per_m: float = parameter(
        "N/m", "equilibrium (zero-frequency) stiffness", gt=0.0, le=MAX_STIFFNESS_N_PER_M
    )
    k_n_per_m: tuple[float, ...] = parameter(
        "N/m", "branch stiffnesses K_i", ge=0.0, le=MAX_STIFFNESS_N_PER_M
    )
    tau_s: tuple[float, ...] = parameter(
        "s", "branch relaxation times tau_i", gt=0.0, le=MAX_RELAXATION_TIME_S
    )

    @classmethod
    def fit_starts(
        cls, f: NDArray[np.float64], k: NDArray[np.complex128], *, n_terms: int | None, f0_hz: float
    ) -> list[FitStart]:
        """One start: relaxation times log-uniform over the band widened by a decade each side."""
        return _prony_starts(f, k, float(np.median(k.real)), n_terms)

    def validate(self) -> None:
        """One relaxation time per branch stiffness, at least one branch."""
        if len(self.k_n_per_m) == 0 or len(self.k_n_per_m) != len(self.tau_s):
            raise CaseError(
                "tau_s",
                f"{len(self.tau_s)} values for {len(self.k_n_per_m)} stiffnesses",
                "one relaxation time per branch stiffness, at least one branch",
            )

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """``K_inf + sum_i K_i i omega tau_i / (1 + i omega tau_i)`` in N/m."""
        f = np.asarray(f, dtype=float)
        iwt = 2j * np.pi * f[..., None] * np.asarray(self.tau_s)
        branches = np.asarray(self.k_n_per_m) * iwt / (1.0 + iwt)
        return self.k_inf_n_per_m + branches.sum(axis=-1)


def _zener_starts(f: NDArray[np.float64], k: NDArray[np.complex128], ks: float) -> list[FitStart]:
    """Three starts (alpha = 0.2, 0.5, 0.9) around the data's relaxed/unrelaxed stiffness."""
    k0, kinf = float(k.real.min()), float(k.real.max())
    f_peak = float(f[np.argmax(k.imag / k.real)])
    lo, hi = [np.log(1e-6), np.log(1e-6), -np.inf, 0.01], [np.inf, np.inf, np.inf, 1.0]

    def build(x: NDArray[np.float64]) -> PadModel:
        k0 = float(ks * np.exp(x[0]))
        return FractionalZener(k0, k0 + float(ks * np.exp(x[1])), float(10.0 ** x[2]), float(x[3]))

    x0 = [np.log(k0 / ks), np.log(max(kinf - k0, 1e-3 * k0) / ks), -np.log10(2 * np.pi * f_peak)]
    names = ("k0_n_per_m", "k_inf_n_per_m", "tau_s", "alpha")
    return [FitStart([*x0, a], lo, hi, build, names) for a in (0.2, 0.5, 0.9)]


def _prony_starts(
    f: NDArray[np.float64], k: NDArray[np.complex128], ks: float, n_terms: int | None
) -> list[FitStart]:
    """Relaxation times log-uniform over the band widened by a decade each side."""
    lo, hi = np.log10(f.min()) - 1.0, np.log10(f.max()) + 1.0
    n = n_terms or int(np.ceil(2 * (hi - lo))) + 1
    fi = np.logspace(lo, hi, n) if n > 1 else np.array([float(np.exp(np.mean(np.log(f))))])
    tau = 1.0 / (2 * np.pi * fi)
    k0 = float(k.real.min())
    x0 = [k0 / ks] + [max(k.real.max() - k0, 1e-3 * k0) / ks / n] * n
    return [
        FitStart(
            x0,
            [1e-9] + [0.0] * n,
            [np.inf] * (n + 1),
            lambda x: GeneralizedMaxwell(float(x[0] * ks), tuple(x[1:] * ks), tuple(tau)),
            ("k_inf_n_per_m", *(f"k_n_per_m[{i}]" for i in range(n))),
        )
    ]
