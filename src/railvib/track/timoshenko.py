"""Closed forms of the Timoshenko rail's bay: characteristic coefficients and Bloch waves.

The bay is the span ``exp(A)`` of :func:`railvib.track.beam.timoshenko_transfer` followed
by the pad's shear jump ``P`` (``v -> v - pad w``), in the dimensionless state
``(w, psi, psi', v)``. The span's exponents ``s`` solve
``s^4 + (rho + eps beta4) s^2 - beta4 (1 - rho eps) = 0``: ``s^2 = b^2`` (``b`` evanescent
below the cut-off frequency, imaginary above it) and ``s^2 = -a^2`` (``a`` propagating).
Every quantity here is even in ``a`` and in ``b`` (``cos a``, ``sin a / a``, ``cosh b``,
``sinh b / b``), so no branch of a root is chosen and the forms hold on both sides of the
cut-off and at it (``b = 0``). Each Bloch quantity that can be small is formed from its
own shifted quadratic, so that it keeps its relative digits where the waves nearly
coincide: band edges (``mu = +-1``) and the cut-off meeting a pinned-pinned frequency
(four roots near ``mu = 1``). The derivation is in docs/design/0002-track-solver.md.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["Span", "bay_characteristic", "bay_waves", "span_terms", "wavenumbers"]

#: below this ``|b|^2``, ``sinh(b) / b`` is taken from its series (error ``|b|^6 / 5040``)
_SERIES_B2 = 1e-8


class Span(NamedTuple):
    """The Timoshenko span's wave terms per frequency (dimensionless), each ``(n_freq,)``.

    Attributes
    ----------
    a2, b2 : numpy.ndarray
        ``a^2`` and ``b^2``.
    rho_b2, eb_b2 : numpy.ndarray
        ``rho + b^2 = a^2 - eps beta4`` and ``b^2 + eps beta4`` (their product is
        ``beta4``), the middle components of the span's waves.
    r : numpy.ndarray
        ``a^2 + b^2 = sqrt((rho - eps beta4)^2 + 4 beta4)`` (no cancellation).
    eb : numpy.ndarray
        ``eps beta4``.
    beta4 : numpy.ndarray
        ``m omega^2 d^4 / EI*``.
    x, y : numpy.ndarray
        ``X = 2 cos a`` and ``Y = 2 cosh b``, the span waves' ``mu + 1/mu``.
    x_m, y_m, x_p, y_p : numpy.ndarray
        ``X - 2 = -4 sin^2(a/2)``, ``Y - 2 = 4 sinh^2(b/2)``, ``X + 2 = 4 cos^2(a/2)``,
        ``Y + 2 = 4 cosh^2(b/2)``.
    y_x : numpy.ndarray
        ``Y - X = 4 sin((a + ib)/2) sin((a - ib)/2)``.
    a_sin, b_sinh : numpy.ndarray
        ``a sin a = a^2 sinc(a)`` and ``b sinh b = b^2 sinhc(b)``.
    alpha_sin, gamma_sinh : numpy.ndarray
        The two parts of the span's displacement per unit ``v``, ``B14(1) = alpha sin a +
        gamma sinh b``.
    """

    a2: NDArray[np.complex128]
    b2: NDArray[np.complex128]
    rho_b2: NDArray[np.complex128]
    eb_b2: NDArray[np.complex128]
    r: NDArray[np.complex128]
    eb: NDArray[np.complex128]
    beta4: NDArray[np.complex128]
    x: NDArray[np.complex128]
    y: NDArray[np.complex128]
    x_m: NDArray[np.complex128]
    y_m: NDArray[np.complex128]
    x_p: NDArray[np.complex128]
    y_p: NDArray[np.complex128]
    y_x: NDArray[np.complex128]
    a_sin: NDArray[np.complex128]
    b_sinh: NDArray[np.complex128]
    alpha_sin: NDArray[np.complex128]
    gamma_sinh: NDArray[np.complex128]


def _complex(values: ArrayLike) -> NDArray[np.complex128]:
    """`values` as a complex array."""
    return np.asarray(values, dtype=np.complex128)


def wavenumbers(
    beta4: NDArray[np.complex128],
    eps: complex,
    rho: NDArray[np.complex128],
    rho_eps: NDArray[np.complex128],
) -> tuple[NDArray[np.complex128], ...]:
    """The span's squared wavenumbers ``a^2``, ``b^2`` and the terms formed from them.

    Each is formed without cancellation: ``a^2 + b^2 = sqrt((rho - eps beta4)^2 + 4 beta4)``,
    ``b^2`` as the product of the roots over the larger one, and of ``rho + b^2`` and
    ``b^2 + eps beta4`` (product ``beta4``) the larger directly, the smaller as ``beta4``
    over it.

    Parameters
    ----------
    beta4 : numpy.ndarray
        ``m omega^2 d^4 / EI*`` (dimensionless), ``(n_freq,)``.
    eps : complex
        ``EI* / (kappa G A* d^2)`` (dimensionless).
    rho : numpy.ndarray
        ``rho_I omega^2 d^2 / EI*`` (dimensionless), ``(n_freq,)``.
    rho_eps : numpy.ndarray
        ``rho eps`` (dimensionless, 1 at the cut-off), ``(n_freq,)``.

    Returns
    -------
    a2, b2, rho_b2, eb_b2, r : numpy.ndarray
        ``a^2``, ``b^2``, ``rho + b^2``, ``b^2 + eps beta4`` and ``a^2 + b^2``, each
        ``(n_freq,)`` (dimensionless).
    """
    eb = eps * beta4
    q = rho + eb
    r = np.sqrt((rho - eb) ** 2 + 4.0 * beta4)
    r = np.where(np.real(np.conj(q) * r) >= 0, r, -r)  # so that q + r does not cancel
    a2 = 0.5 * (q + r)
    b2 = 2.0 * beta4 * (1.0 - rho_eps) / (q + r)  # the small root as product / large
    # rho + b^2 = (r + u) / 2 and b^2 + eps beta4 = (r - u) / 2, u = rho - eps beta4, their
    # product beta4: the larger formed directly, the smaller as beta4 over it
    u = rho - eb
    plus_big = np.abs(r + u) >= np.abs(r - u)
    big = 0.5 * np.where(plus_big, r + u, r - u)
    other = beta4 / np.where(big == 0, 1.0, big)
    rho_b2, eb_b2 = np.where(plus_big, big, other), np.where(plus_big, other, big)
    return tuple(_complex(t) for t in (a2, b2, rho_b2, eb_b2, r))


def span_terms(
    beta4: NDArray[np.complex128],
    eps: complex,
    rho: NDArray[np.complex128],
    rho_eps: NDArray[np.complex128],
) -> Span:
    """The span's wave terms (:class:`Span`) from the dimensionless rail parameters.

    Parameters
    ----------
    beta4 : numpy.ndarray
        ``m omega^2 d^4 / EI*`` (dimensionless), ``(n_freq,)``.
    eps : complex
        ``EI* / (kappa G A* d^2)`` (dimensionless).
    rho : numpy.ndarray
        ``rho_I omega^2 d^2 / EI*`` (dimensionless), ``(n_freq,)``.
    rho_eps : numpy.ndarray
        ``rho eps = rho_I omega^2 / kappa G A*`` (dimensionless, 1 at the cut-off),
        ``(n_freq,)``.

    Returns
    -------
    Span
    """
    eb = eps * beta4
    a2, b2, rho_b2, eb_b2, r = wavenumbers(beta4, eps, rho, rho_eps)
    a, b = np.sqrt(a2), np.sqrt(b2)
    sinc = np.sin(a) / a
    series = np.abs(b2) < _SERIES_B2
    sinhc = np.where(
        series, 1.0 + b2 / 6.0 + b2 * b2 / 120.0, np.sinh(b) / np.where(series, 1.0, b)
    )
    sin_h, sinh_h = np.sin(0.5 * a), np.sinh(0.5 * b)
    cos_h, cosh_h = np.cos(0.5 * a), np.cosh(0.5 * b)
    return Span(
        a2=_complex(a2),
        b2=_complex(b2),
        rho_b2=_complex(rho_b2),
        eb_b2=_complex(eb_b2),
        r=_complex(r),
        eb=_complex(eb),
        beta4=_complex(beta4),
        x=_complex(2.0 * np.cos(a)),
        y=_complex(2.0 * np.cosh(b)),
        x_m=_complex(-4.0 * sin_h * sin_h),
        y_m=_complex(4.0 * sinh_h * sinh_h),
        x_p=_complex(4.0 * cos_h * cos_h),
        y_p=_complex(4.0 * cosh_h * cosh_h),
        y_x=_complex(4.0 * np.sin(0.5 * (a + 1j * b)) * np.sin(0.5 * (a - 1j * b))),
        a_sin=_complex(a2 * sinc),
        b_sinh=_complex(b2 * sinhc),
        # alpha a r = -(1 + eps^2 beta4 + eps b^2) = -(1 + eps (b^2 + eps beta4)), and
        # gamma b r = 1 + eps^2 beta4 - eps a^2 = (1 - rho eps)(rho + b^2) / a^2, which
        # vanishes at the cut-off (so formed as a product)
        alpha_sin=_complex(-(1.0 + eps * eb_b2) * sinc / r),
        gamma_sinh=_complex((1.0 - rho_eps) * rho_b2 * sinhc / (a2 * r)),
    )


def bay_characteristic(
    span: Span, pad: NDArray[np.complex128]
) -> tuple[NDArray[np.complex128], NDArray[np.complex128], NDArray[np.complex128]]:
    """``c1 = tr T``, ``c2 - 2`` and the discriminant ``c1^2 - 4 (c2 - 2)`` of the bay.

    ``T = P exp(A)``: the pad's jump is a rank-one change of the span, so
    ``det(mu - T) = Q_a Q_b + pad mu (alpha sin a Q_b + gamma sinh b Q_a)`` with
    ``Q_a = mu^2 - X mu + 1``, ``Q_b = mu^2 - Y mu + 1``; in ``lambda = mu + 1/mu`` that is
    ``(lambda - X)(lambda - Y) + pad (alpha sin a (lambda - Y) + gamma sinh b (lambda - X))``.
    Hence ``c1 = X + Y - pad B14(1)``,
    ``c2 - 2 = X Y - 2 pad (alpha sin a cosh b + gamma sinh b cos a)`` and the discriminant
    ``(X - Y + pad (gamma sinh b - alpha sin a))^2 + 4 pad^2 alpha sin a gamma sinh b``,
    which keeps its digits where the two ``lambda`` nearly coincide.

    Parameters
    ----------
    span : Span
        The span's wave terms (dimensionless).
    pad : numpy.ndarray
        Dimensionless pad stiffness ``K* d^3 / EI*``, ``(n_freq,)``.

    Returns
    -------
    c1, c2m2, disc : numpy.ndarray
        Each ``(n_freq,)``.
    """
    al, ga = pad * span.alpha_sin, pad * span.gamma_sinh
    c1 = span.x + span.y - al - ga
    c2m2 = span.x * span.y - al * span.y - ga * span.x
    split = ga - al - span.y_x
    return c1, c2m2, split * split + 4.0 * al * ga


def _shifted_roots(
    hx: NDArray[np.complex128],
    hy: NDArray[np.complex128],
    al: NDArray[np.complex128],
    ga: NDArray[np.complex128],
    delta: NDArray[np.complex128],
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """``lambda_+ - c`` and ``lambda_- - c``, ``lambda_+- = (c1 +- delta) / 2``, from the shift.

    ``hx = X - c`` and ``hy = Y - c`` (each given with its relative digits); the roots of
    ``(w - hx)(w - hy) + al (w - hy) + ga (w - hx) = 0`` are ``(s +- delta) / 2`` with
    ``s = hx + hy - al - ga``: the larger formed directly, the smaller as the product of
    the roots over it.
    """
    s = hx + hy - al - ga
    product = hx * hy - al * hy - ga * hx
    plus_big = np.abs(s + delta) >= np.abs(s - delta)
    big = 0.5 * np.where(plus_big, s + delta, s - delta)
    small = product / np.where(big == 0, 1.0, big)
    return np.where(plus_big, big, small), np.where(plus_big, small, big)


def bay_waves(
    span: Span, pad: NDArray[np.complex128]
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """Propagation constants ``|mu| <= 1`` of the bay and their Bloch vectors, closed form.

    For each root ``lambda`` of the characteristic quadratic (:func:`bay_characteristic`)
    the shifts ``lambda - 2``, ``lambda + 2``, ``lambda - X`` and ``lambda - Y`` come from
    their own quadratics (:func:`_shifted_roots`). ``mu = (lambda - sqrt(lambda^2 - 4)) / 2``
    with ``lambda^2 - 4 = (lambda - 2)(lambda + 2)``, and ``mu - 1`` (or ``mu + 1``) without
    cancellation. The Bloch vector (state just right of a sleeper) is
    ``(exp(A) - mu)^-1 e4`` times ``(lambda - X)(lambda - Y)``: with the span's waves
    ``y_s = (s, s^2 + eps beta4, s (s^2 + eps beta4), beta4)``,
    ``k_b [(cosh b - mu) E_b - b sinh b O_b] + k_a [(cos a - mu) E_a + a sin a O_a]``,
    ``E_s = (0, s^2 + eps beta4, 0, beta4)``, ``O_s = (1, 0, s^2 + eps beta4, 0)``,
    ``k_b = (eps beta4 - a^2)(lambda - X)``, ``k_a = -(b^2 + eps beta4)(lambda - Y)``. It has
    no pole (at a pinned-pinned frequency it is the span's own mode) and depends on ``mu``
    only through quantities formed with their relative digits.

    Parameters
    ----------
    span : Span
        The span's wave terms (dimensionless).
    pad : numpy.ndarray
        Dimensionless pad stiffness ``K* d^3 / EI*``, ``(n_freq,)``.

    Returns
    -------
    mu : numpy.ndarray
        ``(n_freq, 2)``.
    vec : numpy.ndarray
        Bloch vectors ``(n_freq, 4, 2)``, unit norm (all zero where the closed form
        vanishes, for the caller to replace).
    """
    c1, _, disc = bay_characteristic(span, pad)
    delta = np.sqrt(disc)
    al, ga = pad * span.alpha_sin, pad * span.gamma_sinh
    zero = np.zeros_like(span.x)
    u = np.stack(_shifted_roots(span.x_m, span.y_m, al, ga, delta), axis=1)  # lambda - 2
    v = np.stack(_shifted_roots(span.x_p, span.y_p, al, ga, delta), axis=1)  # lambda + 2
    ux = np.stack(_shifted_roots(zero, span.y_x, al, ga, delta), axis=1)  # lambda - X
    uy = np.stack(_shifted_roots(-span.y_x, zero, al, ga, delta), axis=1)  # lambda - Y
    near_one = np.abs(u) <= np.abs(v)
    lam = np.where(near_one, u + 2.0, v - 2.0)
    root = np.sqrt(u * v)
    root = np.where(np.real(np.conj(lam) * root) >= 0, root, -root)  # |lambda + root| large
    offset = 0.5 * np.where(near_one, u - root, v - root)  # mu - 1 or mu + 1
    mu = np.where(near_one, 1.0 + offset, offset - 1.0)
    # cosh b - mu and cos a - mu, from the same side (+1 or -1) as mu's offset
    b_mu = np.where(near_one, 0.5 * span.y_m[:, None], 0.5 * span.y_p[:, None]) - offset
    a_mu = np.where(near_one, 0.5 * span.x_m[:, None], 0.5 * span.x_p[:, None]) - offset
    beta4 = span.beta4[:, None]
    e_a, e_b = -span.rho_b2[:, None], span.eb_b2[:, None]  # s^2 + eps beta4, s = ia and b
    k_b = e_a * ux
    k_a = -e_b * uy
    b_sinh, a_sin = span.b_sinh[:, None], span.a_sin[:, None]
    vec = np.stack(
        [
            k_a * a_sin - k_b * b_sinh,
            k_b * b_mu * e_b + k_a * a_mu * e_a,
            k_a * a_sin * e_a - k_b * b_sinh * e_b,
            (k_b * b_mu + k_a * a_mu) * beta4,
        ],
        axis=1,
    )
    norm = np.linalg.norm(vec, axis=1, keepdims=True)
    vec = vec / np.where(norm > 0, norm, 1.0)
    return np.asarray(mu, dtype=np.complex128), np.asarray(vec, dtype=np.complex128)
