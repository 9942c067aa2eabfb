"""Exact Euler-Bernoulli beam kernels, stacked over frequency.

Two exact descriptions of a uniform beam span are provided:

* :func:`field_transfer` -- the field transfer matrix of the state
  ``y = (w, L0 w', L0^2 w'', L0^3 w''')`` over a length. It is an *entire*
  function of ``beta^4`` (no poles), evaluated by power series in ``beta^4 x^4``
  whose terms are all of one sign for an undamped beam, so no digits are lost
  at low frequency and no branch of a fourth root has to be chosen.
* :func:`dynamic_stiffness` -- the exact 4x4 dynamic stiffness of a span
  (docs/design/0002-track-solver.md), which has poles at the clamped-clamped natural frequencies.
  It is used to state the paper's symplectic formulation (cell stiffness ->
  transfer matrix, Eqs. 3-4) and in tests; the solver itself uses the pole-free
  transfer matrix.

All lengths here are dimensionless (divided by a reference length ``L0``, the
sleeper spacing) and ``beta4`` is ``m omega^2 L0^4 / EI*``.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["dynamic_stiffness", "field_transfer", "krylov_series", "timoshenko_transfer"]


def _n_terms(beta4: NDArray[np.complex128], length: float) -> int:
    """Number of series terms for |z|^n / n! to fall below 1e-17 of cosh|z|."""
    z = float(np.max(np.abs(beta4), initial=0.0)) ** 0.25 * abs(length)
    return max(6, math.ceil((2.72 * z + 34.0) / 4.0))


def krylov_series(beta4: ArrayLike, length: float) -> tuple[NDArray[np.complex128], ...]:
    """Scaled Krylov functions ``(S, T/b, U/b^2, V/b^3)`` and ``b^4`` at length `length`.

    With ``z = b x`` and ``zeta = z^4 = beta4 x^4``:
    ``S = sum zeta^k/(4k)!``, ``T/b = x sum zeta^k/(4k+1)!``,
    ``U/b^2 = x^2 sum zeta^k/(4k+2)!``, ``V/b^3 = x^3 sum zeta^k/(4k+3)!``.

    Parameters
    ----------
    beta4 : array_like of complex
        ``beta^4`` per frequency (dimensionless).
    length : float
        Signed dimensionless length x.

    Returns
    -------
    tuple of numpy.ndarray
        ``(s0, s1, s2, s3)`` with ``s_j = sum zeta^k / (4k+j)!`` times ``x^j``.
    """
    beta4 = np.asarray(beta4, dtype=complex)
    x = float(length)
    zeta = beta4 * x**4
    n = _n_terms(beta4, x)
    coeff = _inverse_factorials(n)  # (n, 4): 1 / (4k + j)!
    acc = np.zeros((4,) + zeta.shape, dtype=np.complex128)
    for k in range(n - 1, -1, -1):  # Horner in zeta for all four sums at once
        acc *= zeta
        acc += coeff[k].reshape((4,) + (1,) * zeta.ndim)
    return tuple(acc[j] * x**j for j in range(4))


@lru_cache(maxsize=8)
def _inverse_factorials(n: int) -> NDArray[np.float64]:
    """``1 / (4k + j)!`` for k < n, j < 4, shape ``(n, 4)``."""
    return np.array([[1.0 / math.factorial(4 * k + j) for j in range(4)] for k in range(n)])


def field_transfer(beta4: ArrayLike, length: float) -> NDArray[np.complex128]:
    """Field transfer matrix of a beam span, shape ``(n_freq, 4, 4)``.

    Maps the state ``y(x) = (w, w', w'', w''')`` (derivatives in dimensionless x)
    to ``y(x + length)`` for ``w'''' = beta4 w``. Negative `length` gives the inverse.

    Parameters
    ----------
    beta4 : array_like of complex
        ``m omega^2 L0^4 / EI*`` per frequency (dimensionless), shape ``(n_freq,)``.
    length : float
        Dimensionless span length (signed).

    Returns
    -------
    numpy.ndarray
        Complex array ``(n_freq, 4, 4)``.
    """
    b4 = np.atleast_1d(np.asarray(beta4, dtype=complex))
    s0, s1, s2, s3 = krylov_series(b4, length)
    out = np.empty(b4.shape + (4, 4), dtype=complex)
    # row r, column c: d^r/dx^r of the fundamental solution for y_c
    basis = (s0, s1, s2, s3)
    for r in range(4):
        for c in range(4):
            j = c - r
            out[..., r, c] = basis[j] if j >= 0 else b4 * basis[j + 4]
    return out


def dynamic_stiffness(beta4: ArrayLike, length: float) -> NDArray[np.complex128]:
    """Exact dynamic stiffness of a uniform beam span, ``(n_freq, 4, 4)``, units of EI* = 1.

    DOFs ``(w1, theta1, w2, theta2)`` with dimensionless lengths; end forces
    ``(V1, M1, V2, M2)`` acting on the span. Closed form (docs/design/0002-track-solver.md) with
    ``D = 1 - cos(bL) cosh(bL)``; singular where ``D = 0`` (clamped-clamped
    natural frequencies). Uses the closed form, so only for ``|b L| >~ 1e-2``.

    Parameters
    ----------
    beta4 : array_like of complex
        ``m omega^2 L0^4 / EI*`` per frequency (dimensionless), shape ``(n_freq,)``.
    length : float
        Dimensionless span length (> 0).

    Returns
    -------
    numpy.ndarray
        Complex array ``(n_freq, 4, 4)``.
    """
    b4 = np.atleast_1d(np.asarray(beta4, dtype=complex))
    b = b4**0.25
    lam = b * length
    c, s = np.cos(lam), np.sin(lam)
    ch, sh = np.cosh(lam), np.sinh(lam)
    d = 1.0 - c * ch
    k = np.empty(b4.shape + (4, 4), dtype=complex)
    k11 = b**3 * (c * sh + s * ch)
    k12 = b**2 * s * sh
    k13 = -(b**3) * (sh + s)
    k14 = b**2 * (ch - c)
    k22 = b * (s * ch - c * sh)
    k24 = b * (sh - s)
    rows = (
        (k11, k12, k13, k14),
        (k12, k22, -k14, k24),
        (k13, -k14, k11, -k12),
        (k14, k24, -k12, k22),
    )
    for i in range(4):
        for j in range(4):
            k[..., i, j] = rows[i][j] / d
    return k


def timoshenko_transfer(
    beta4: ArrayLike, shear_flexibility: complex, rotary: ArrayLike, length: float
) -> NDArray[np.complex128]:
    """Field transfer matrix of a Timoshenko span, ``(n_freq, 4, 4)``.

    State ``y = (w, psi, psi', v)`` with ``psi`` the cross-section rotation and
    ``v = -S / EI`` (``S`` the shear force; ``v = w'''`` in the Euler limit), all
    with lengths scaled by ``L0``. The first-order system ``y' = A y`` has

    ``A = [[0, 1, 0, -eps], [0, 0, 1, 0], [0, -rho, 0, 1], [beta4, 0, 0, 0]]``,

    ``eps = EI / (kappa G A L0^2)`` and ``rho = rho_I omega^2 L0^2 / EI``; ``tr A = 0``
    so ``det exp(A L) = 1``. ``eps = rho = 0`` gives :func:`field_transfer`. The
    matrix exponential is an entire function of the entries (no poles); it is
    evaluated by :func:`scipy.linalg.expm`, stacked over frequency.

    Parameters
    ----------
    beta4 : array_like of complex
        ``m omega^2 L0^4 / EI*`` per frequency (dimensionless), shape ``(n_freq,)``.
    shear_flexibility : complex
        ``eps = EI* / (kappa G A* L0^2)`` (dimensionless).
    rotary : array_like of complex
        ``rho = rho_I omega^2 L0^2 / EI*`` per frequency (dimensionless), shape ``(n_freq,)``.
    length : float
        Dimensionless span length (signed).

    Returns
    -------
    numpy.ndarray
        Complex array ``(n_freq, 4, 4)``.
    """
    from scipy.linalg import expm

    b4 = np.atleast_1d(np.asarray(beta4, dtype=complex))
    a = np.zeros(b4.shape + (4, 4), dtype=complex)
    a[..., 0, 1] = 1.0
    a[..., 0, 3] = -shear_flexibility
    a[..., 1, 2] = 1.0
    a[..., 2, 1] = -np.asarray(rotary, dtype=complex)
    a[..., 2, 3] = 1.0
    a[..., 3, 0] = b4
    return np.asarray(expm(a * length), dtype=np.complex128)
