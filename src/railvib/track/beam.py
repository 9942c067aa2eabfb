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

from railvib.track.timoshenko import wavenumbers

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
    beta4: ArrayLike,
    shear_flexibility: complex,
    rotary: ArrayLike,
    length: float,
    rho_eps: ArrayLike | None = None,
) -> NDArray[np.complex128]:
    """Field transfer matrix of a Timoshenko span, ``(n_freq, 4, 4)``, in closed form.

    State ``y = (w, psi, psi', v)`` with ``psi`` the cross-section rotation and
    ``v = -S / EI`` (``S`` the shear force; ``v = w'''`` in the Euler limit), all
    with lengths scaled by ``L0``. The first-order system ``y' = A y`` has

    ``A = [[0, 1, 0, -eps], [0, 0, 1, 0], [0, -rho, 0, 1], [beta4, 0, 0, 0]]``,

    ``eps = EI / (kappa G A L0^2)`` and ``rho = rho_I omega^2 L0^2 / EI``; ``tr A = 0``
    so ``det exp(A L) = 1``. ``eps = rho = 0`` gives :func:`field_transfer`. ``A^2`` has
    the eigenvalues ``b^2`` and ``-a^2`` (:func:`railvib.track.timoshenko.wavenumbers`),
    so with ``N = A^2 + a^2 I`` (entries ``rho + b^2``, ``b^2 + eps beta4``, 1, ``beta4``)

    ``exp(A x) = cos(ax) I + sin(ax)/a A + D0 N + D1 A N``,

    ``D0 = (cosh bx - cos ax)/(a^2 + b^2) = 2 sin((a + ib)x/2) sin((a - ib)x/2)/(a^2 + b^2)``
    and ``D1 = (sinh(bx)/b - sin(ax)/a)/(a^2 + b^2)`` (:func:`_odd_divided_difference`).
    Every term is even in ``a`` and in ``b`` (no branch is chosen) and holds below, at
    and above the cut-off (``b = 0``); docs/design/0002-track-solver.md.

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
    rho_eps : array_like of complex, optional
        ``rho eps = rho_I omega^2 / kappa G A*`` formed directly (dimensionless, 1 at the
        cut-off), ``(n_freq,)``; by default ``rotary * shear_flexibility``.

    Returns
    -------
    numpy.ndarray
        Complex array ``(n_freq, 4, 4)``.
    """
    b4 = np.atleast_1d(np.asarray(beta4, dtype=complex))
    rho = np.broadcast_to(np.asarray(rotary, dtype=complex), b4.shape)
    eps = complex(shear_flexibility)
    rho_eps_ = rho * eps if rho_eps is None else np.asarray(rho_eps, dtype=complex)
    a2, b2, rho_b2, eb_b2, r = wavenumbers(b4, eps, rho, rho_eps_)
    x = float(length)
    a, b = np.sqrt(a2), np.sqrt(b2)
    cos_a = np.cos(a * x)
    sin_a, sinh_b = _over(np.sin(a * x), a, x), _over(np.sinh(b * x), b, x)
    d0 = 2.0 * np.sin(0.5 * x * (a + 1j * b)) * np.sin(0.5 * x * (a - 1j * b)) / r
    q, g = rho + eps * b4, b4 * (1.0 - rho_eps_)
    d1 = _odd_divided_difference(sin_a, sinh_b, a, b, r, q, g, x)
    diag_r, diag_e = cos_a + d0 * rho_b2, cos_a + d0 * eb_b2
    d0_b4, d1_b4 = d0 * b4, d1 * b4
    # 1 - eps (rho + b^2) = (1 - rho eps)(rho + b^2) / a^2 (vanishes at the cut-off)
    shear_03 = d1 * (1.0 - rho_eps_) * rho_b2 / a2 - eps * sin_a
    rows = (
        (diag_r, sin_a + d1 * b2, d0, shear_03),
        (d1_b4, diag_e, sin_a + d1 * eb_b2, d0),
        (d0_b4, d1 * eb_b2 * b2 - rho * sin_a, diag_e, sin_a + d1 * b2),
        (b4 * sin_a + d1_b4 * rho_b2, d0_b4, d1_b4, diag_r),
    )
    out = np.empty(b4.shape + (4, 4), dtype=complex)
    for i, row in enumerate(rows):
        for j, entry in enumerate(row):
            out[..., i, j] = entry
    return out


#: largest ``max(|a|^2, |b|^2) x^2`` where :func:`_odd_divided_difference` sums its series
#: (no term above 1/6 and the sum above 0.1, so a few ulp at most); above it the closed
#: form loses about ``max(|a|^2, |b|^2) / |a^2 + b^2|`` ulp (at most 1.3 for the rails of
#: tests/unit/track/test_timoshenko_span.py up to 5 kHz)
_SERIES_WAVENUMBER2 = 4.0

#: terms of that series: the first left out is below ``13 4^12 / 27! = 2e-20``, and the sum
#: above 0.1
_SERIES_TERMS = 12


def _over(
    value: NDArray[np.complex128], k: NDArray[np.complex128], x: float
) -> NDArray[np.complex128]:
    """``sin(kx) / k`` or ``sinh(kx) / k`` from its numerator `value`: ``x`` where ``k = 0``.

    No digits are lost for small ``k`` (numerator and ``k`` each hold theirs); only ``k = 0``
    exactly (``b`` at the cut-off) is taken apart.
    """
    zero = k == 0
    return np.asarray(np.where(zero, x, value / np.where(zero, 1.0, k)), dtype=complex)


def _odd_divided_difference(
    sin_a: NDArray[np.complex128],
    sinh_b: NDArray[np.complex128],
    a: NDArray[np.complex128],
    b: NDArray[np.complex128],
    r: NDArray[np.complex128],
    q: NDArray[np.complex128],
    g: NDArray[np.complex128],
    x: float,
) -> NDArray[np.complex128]:
    """``D1 = (sinh(bx)/b - sin(ax)/a) / (a^2 + b^2)``, ``(n_freq,)``.

    ``-x^3`` times the divided difference of ``sinc(sqrt z)`` at ``z = a^2 x^2`` and
    ``-b^2 x^2``. Where both are small it is the series
    ``x^3 sum_k (-1)^k h_k / (2k + 3)!`` with ``h_k`` the complete symmetric polynomials
    of the two points, ``h_k = s h_(k-1) - p h_(k-2)``, ``s = q x^2 = (a^2 - b^2) x^2`` and
    ``p = -g x^4 = -a^2 b^2 x^4`` (``q = rho + eps beta4`` and ``g = beta4 (1 - rho eps)``
    given without cancellation); elsewhere the closed form from ``sin_a = sin(ax)/a``,
    ``sinh_b = sinh(bx)/b`` and ``r = a^2 + b^2`` (formed without cancellation).
    """
    x2 = x * x
    series = np.maximum(np.abs(a), np.abs(b)) ** 2 * x2 <= _SERIES_WAVENUMBER2
    out = np.empty(a.shape, dtype=complex)
    if np.any(series):
        whole = bool(np.all(series))
        s = (q if whole else q[series]) * x2
        p = (g if whole else g[series]) * (-x2 * x2)
        # Clenshaw's recurrence for sum c_k h_k: b_k = c_k + s b_(k+1) - p b_(k+2), sum b_0
        b_next, b_next2 = np.zeros_like(s), np.zeros_like(s)
        for k in range(_SERIES_TERMS - 1, -1, -1):
            b_k = s * b_next
            b_k -= p * b_next2
            b_k += (-1) ** k / math.factorial(2 * k + 3)
            b_next, b_next2 = b_k, b_next
        out[series] = b_next * x**3
    closed = ~series
    if np.any(closed):
        out[closed] = (sinh_b[closed] - sin_a[closed]) / r[closed]
    return out
