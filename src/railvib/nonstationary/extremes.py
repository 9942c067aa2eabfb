"""Level crossings and first passage of a non-stationary Gaussian response.

With ``y`` zero-mean Gaussian and ``E[y^2] = l0``, ``E[y'^2] = l2``, ``E[y y'] = c`` at
time t, the rate of up-crossings of a level b is Rice's (the speed conditional on
``y = b`` is Gaussian with mean ``mu = c b / l0`` and variance ``s^2 = l2 - c^2 / l0``):

    nu+(b, t) = phi(b / sqrt(l0)) / sqrt(l0) * (s phi(mu / s) + mu Phi(mu / s)),

and crossings of ``|y| = b`` happen at ``2 nu+``. The first-passage probability over
``[0, T]`` is ``1 - (1 - p_0) exp(-int h dt)``, ``p_0 = P(|y(0)| > b)``, with the hazard
``h = 2 nu+`` (Poisson: independent crossings) or Vanmarcke's clumping correction
``h = 2 nu+ (1 - exp(-sqrt(pi/2) q^1.2 b / sqrt(l0))) / (1 - exp(-b^2 / (2 l0)))``, with
the bandwidth ``q = sqrt(1 - l1^2 / (l0 l2))`` from the first moment ``l1``
(Vanmarcke, J. Appl. Mech. 1975; for a non-stationary process with the moments of its
evolutionary spectrum: Corotis, Vanmarcke and Cornell, J. Eng. Mech. Div. 1972).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import erfc, ndtr

__all__ = ["CROSSING_MODELS", "first_passage_probability", "upcrossing_rate"]

#: the hazard models of :func:`first_passage_probability`
CROSSING_MODELS = ("poisson", "vanmarcke")


def _phi(x: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.exp(-0.5 * x * x) / np.sqrt(2.0 * np.pi)


def upcrossing_rate(
    level: ArrayLike, variance: ArrayLike, velocity_variance: ArrayLike, cross: ArrayLike
) -> NDArray[np.float64]:
    """Rice's rate of up-crossings of `level` by a non-stationary Gaussian process, 1/s.

    Parameters
    ----------
    level : array_like
        Level b (output unit), broadcast with the moments.
    variance, velocity_variance, cross : array_like
        ``E[y^2]``, ``E[y'^2]`` and ``E[y y']`` at each time (output unit^2, per s^2,
        per s).

    Returns
    -------
    numpy.ndarray
        ``nu+(b, t)`` in 1/s (0 where the variance is 0).
    """
    b = np.asarray(level, dtype=float)
    l0 = np.asarray(variance, dtype=float)
    l2 = np.asarray(velocity_variance, dtype=float)
    c = np.asarray(cross, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        sd = np.sqrt(l0)
        mu = c * b / l0
        s = np.sqrt(np.maximum(l2 - c * c / l0, 0.0))
        ratio = np.where(s > 0, mu / s, np.sign(mu) * np.inf)
        tail = np.where(s > 0, s * _phi(ratio) + mu * ndtr(ratio), np.maximum(mu, 0.0))
        rate = _phi(b / sd) / sd * tail
    return np.where(l0 > 0, rate, 0.0)


def first_passage_probability(
    t: ArrayLike,
    level: ArrayLike,
    variance: ArrayLike,
    velocity_variance: ArrayLike,
    cross: ArrayLike,
    first_moment: ArrayLike,
    model: str = "poisson",
) -> NDArray[np.float64]:
    """Probability that ``|y|`` exceeds `level` at least once over the times `t`.

    Parameters
    ----------
    t : array_like
        Times, s, ``(n_t,)``.
    level : array_like
        Level b per output, ``(n_out,)`` (output unit).
    variance, velocity_variance, cross, first_moment : array_like
        ``E[y^2]``, ``E[y'^2]``, ``E[y y']`` and ``l1``, ``(n_t, n_out)``, in output unit^2,
        per s^2, per s, per s.
    model : {"poisson", "vanmarcke"}
        The hazard (module docstring).

    Returns
    -------
    numpy.ndarray
        ``(n_out,)``, between 0 and 1.
    """
    t = np.asarray(t, dtype=float)
    b = np.asarray(level, dtype=float)[None, :]
    l0 = np.asarray(variance, dtype=float)
    nu = 2.0 * upcrossing_rate(b, l0, velocity_variance, cross)
    if model == "vanmarcke":
        l1 = np.asarray(first_moment, dtype=float)
        l2 = np.asarray(velocity_variance, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            q = np.sqrt(np.clip(1.0 - l1 * l1 / (l0 * l2), 0.0, 1.0))
            r = b / np.sqrt(l0)
            factor = -np.expm1(-np.sqrt(np.pi / 2.0) * q**1.2 * r) / -np.expm1(-0.5 * r * r)
        nu = nu * np.where(np.isfinite(factor), np.minimum(factor, 1.0), 0.0)
    elif model != "poisson":
        raise ValueError(f"model must be one of {CROSSING_MODELS}")
    hazard = np.sum(0.5 * (nu[1:] + nu[:-1]) * np.diff(t)[:, None], axis=0)
    with np.errstate(divide="ignore", invalid="ignore"):
        p0 = np.where(l0[0] > 0, erfc(b[0] / np.sqrt(2.0 * l0[0])), 0.0)
    return 1.0 - (1.0 - p0) * np.exp(-hazard)
