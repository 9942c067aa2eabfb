"""Viscoelastic railpad models: fractional-derivative Zener and generalised Maxwell (Prony).

Both are causal and passive for the parameter ranges accepted here, which is checked
in ``__post_init__`` (see each class).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.pads.base import PadModel

__all__ = ["FractionalZener", "GeneralizedMaxwell"]


def _check(field: str, value: float, ok: bool, allowed: str) -> None:
    if not (np.isfinite(value) and ok):
        raise CaseError(field, value, allowed)


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

    k0_n_per_m: float
    k_inf_n_per_m: float
    tau_s: float
    alpha: float
    model_name = "fractional_zener"

    def __post_init__(self) -> None:
        _check("track.pad.k0_n_per_m", self.k0_n_per_m, self.k0_n_per_m > 0, "must be > 0 (N/m)")
        _check(
            "track.pad.k_inf_n_per_m",
            self.k_inf_n_per_m,
            self.k_inf_n_per_m >= self.k0_n_per_m,
            f"must be >= k0_n_per_m = {self.k0_n_per_m:.4g} (N/m), otherwise the loss "
            "factor is negative",
        )
        _check("track.pad.tau_s", self.tau_s, self.tau_s > 0, "must be > 0 (s)")
        _check("track.pad.alpha", self.alpha, 0 < self.alpha <= 1, "must be in (0, 1]")

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """``K0 + (K_inf - K0) z / (1 + z)``, ``z = (i 2 pi f tau)^alpha``, in N/m."""
        f = np.asarray(f, dtype=float)
        # (i x)^alpha = x^alpha exp(i alpha pi / 2) for x >= 0, written out to stay exact
        z = (2 * np.pi * f * self.tau_s) ** self.alpha * np.exp(0.5j * np.pi * self.alpha)
        return self.k0_n_per_m + (self.k_inf_n_per_m - self.k0_n_per_m) * (z / (1.0 + z))


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

    k_inf_n_per_m: float
    k_n_per_m: tuple[float, ...]
    tau_s: tuple[float, ...]
    model_name = "generalized_maxwell"

    def __post_init__(self) -> None:
        k = tuple(float(x) for x in np.atleast_1d(np.asarray(self.k_n_per_m, dtype=float)))
        tau = tuple(float(x) for x in np.atleast_1d(np.asarray(self.tau_s, dtype=float)))
        object.__setattr__(self, "k_n_per_m", k)
        object.__setattr__(self, "tau_s", tau)
        _check(
            "track.pad.k_inf_n_per_m",
            self.k_inf_n_per_m,
            self.k_inf_n_per_m > 0,
            "must be > 0 (N/m)",
        )
        if len(k) == 0 or len(k) != len(tau):
            raise CaseError(
                "track.pad.tau_s",
                f"{len(tau)} values for {len(k)} stiffnesses",
                "one relaxation time per branch stiffness, at least one branch",
            )
        for i, (ki, ti) in enumerate(zip(k, tau, strict=True)):
            _check(f"track.pad.k_n_per_m[{i}]", ki, ki >= 0, "must be >= 0 (N/m)")
            _check(f"track.pad.tau_s[{i}]", ti, ti > 0, "must be > 0 (s)")

    def stiffness(self, f: ArrayLike, temperature: float | None = None) -> NDArray[np.complex128]:
        """``K_inf + sum_i K_i i omega tau_i / (1 + i omega tau_i)`` in N/m."""
        f = np.asarray(f, dtype=float)
        iwt = 2j * np.pi * f[..., None] * np.asarray(self.tau_s)
        branches = np.asarray(self.k_n_per_m) * iwt / (1.0 + iwt)
        return self.k_inf_n_per_m + branches.sum(axis=-1)
