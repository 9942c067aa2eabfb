"""Gauss-Kronrod-Filon rules of the moving-load wavenumber integrand on a list of panels.

:func:`panel_rules` is the kernel of :func:`railvib.track.moving.moving_load_receptance`:
for every panel ``[a, b]`` (each with its own load frequency) it integrates the integrand
``exp(i k r) G_n (delta_n0 - K w_0 / d)``: the smooth factor ``G_n (delta_n0 - K w_0 / d)``
at the 15 Kronrod nodes, interpolated by its polynomial of degree 14 there, times the
oscillating ``exp(i k r)`` integrated exactly (Filon's rule, :func:`filon_weights`: the
15-point Kronrod rule itself at ``r = 0``), and returns the difference of the Kronrod rule
to the embedded 7-point Gauss rule on the smooth factor (the ``r = 0`` integrand) as the
error estimate: the refinement resolves the integrand once for every observation point,
however far ahead (the gaps between the wheels of a vehicle, up to ~15 m, whose
``exp(i k r)`` would otherwise drive the bisection). Two implementations
give the same numbers (to rounding): NumPy, vectorised over all nodes (the reference and
the fallback), and the same algorithm written node by node (:func:`_panels`), which numba
compiles into one loop with every intermediate a scalar in registers (no arrays of nodes
x harmonics). numba is optional (``pip install railvib[fast]``) and is imported only
when a call asks for it; ``RAILVIB_COMPILED=0`` turns it off.
"""

from __future__ import annotations

import cmath
import math
import os
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.special import spherical_jn

from railvib.jit import numba_jit
from railvib.track.beam import _SERIES_TERMS, _SERIES_WAVENUMBER2, _odd_divided_difference, _over
from railvib.track.timoshenko import wavenumbers

__all__ = [
    "compiled_available",
    "filon_weights",
    "lattice_sum",
    "panel_rules",
    "timoshenko_lattice_sum",
]

#: Gauss-Kronrod 7-15 nodes on [0, 1] of the half panel and weights (QUADPACK qk15)
_XGK = np.array(
    [
        0.991455371120812639206854697526329,
        0.949107912342758524526189684047851,
        0.864864423359769072789712788640926,
        0.741531185599394439863864773280788,
        0.586087235467691130294144845693013,
        0.405845151377397166906606412076961,
        0.207784955007898467600689403773245,
        0.0,
    ]
)
_WGK = np.array(
    [
        0.022935322010529224963732008058970,
        0.063092092629978553290700663189204,
        0.104790010322250183839876322541518,
        0.140653259715525918745189590510238,
        0.169004726639267902826583426598550,
        0.190350578064785409913256402421014,
        0.204432940075298892414161999234649,
        0.209482141084727828012999174891714,
    ]
)
#: the embedded 7-point Gauss weights at the same nodes (0 at the Kronrod-only ones)
_WG = np.array(
    [
        0.0,
        0.129484966168869693270611432679082,
        0.0,
        0.279705391489276667901467771423780,
        0.0,
        0.381830050505118944950369775488975,
        0.0,
        0.417959183673469387755102040816327,
    ]
)
#: the 15 nodes on [-1, 1] and their Kronrod and Gauss weights
NODES = np.concatenate([-_XGK[:-1], _XGK[::-1]])
_KRONROD = np.concatenate([_WGK[:-1], _WGK[::-1]])
_GAUSS = np.concatenate([_WG[:-1], _WG[::-1]])

#: ``V^-1``, ``V[q, j] = P_j(t_q)`` the Legendre polynomials of degree 0..14 at the 15
#: nodes (condition number 6.4): the coefficients of the interpolating polynomial are
#: ``V^-1 f(t_q)``
_LEGENDRE_INVERSE = np.linalg.inv(np.polynomial.legendre.legvander(NODES, NODES.size - 1))

#: ``2 i^j``, j = 0..14: ``int_-1^1 P_j(t) exp(i w t) dt = 2 i^j j_j(w)`` (spherical Bessel)
_LEGENDRE_MOMENT = 2.0 * 1j ** np.arange(NODES.size)

#: panel half widths within this relative difference share their Filon weights (bisection
#: gives a few distinct widths a level, equal to rounding)
_SAME_WIDTH = 1e-13

#: ``1 / (4 j + 3)!``, j = 0..3: the series of ``(sinh z - sin z) / (2 z^3)`` in ``z^4``
_S3_SERIES = (1.0 / 6.0, 1.0 / 5040.0, 1.0 / 39916800.0, 1.0 / 1.307674368e12)

#: numba's fast-math flags for the node loop: reassociation lets it vectorise the sums
#: over harmonics; NaN and infinity keep their meaning, and without contraction (fused
#: multiply-add) each node's omega = Omega - k v is the caller's to the last bit (the
#: sign at which K(omega) was conjugated)
_FASTMATH = {"nsz", "arcp", "afn", "reassoc"}

#: a node exactly at the fixed frame's omega = 0 is moved to this, rad/s (the lattice sum
#: and G_n, at a node where also k_n = 0, would give 0/0 there: the singularity is
#: removable, and K(omega) is evaluated at >= 1e-9 Hz anyway)
OMEGA_FLOOR = 2.0 * np.pi * 1e-9

#: ``(-1)^j / (2 j + 3)!``: the series of the Timoshenko span's ``D1`` (railvib.track.beam,
#: ``_odd_divided_difference``), summed by Clenshaw's recurrence where
#: ``max(|a|, |b|)^2 <= 4``
_D1_SERIES = np.array([(-1) ** j / math.factorial(2 * j + 3) for j in range(_SERIES_TERMS)])

#: where ``|G_0| > POLE_DOMINANCE |S - G_0|`` (next to the free Euler rail's poles: its
#: waves, and k = omega = 0 for a static load) the closed-form lattice sum minus G_0
#: would keep only ~eps x that ratio; the images m != 0 are summed directly there
POLE_DOMINANCE = 1e3

#: image pairs summed directly (:func:`_euler_images`), and the sum of those beyond
IMAGES = 64
_IMAGE_TAIL = (
    2.0
    * (np.pi**4 / 90.0 - float(np.sum(1.0 / np.arange(1, IMAGES + 1) ** 4.0)))
    / (2.0 * np.pi) ** 4
)

#: the Laurent series of ``1 / (4 sin^2(x/2)) - 1/x^2 - 1/12`` in ``x^2`` (that of csc^2)
_CSC2_SERIES = (1.0 / 240.0, 1.0 / 6048.0, 1.0 / 172800.0, 1.0 / 5322240.0, 691.0 / 118879488000.0)

_KERNEL: list[Any] = []


def compiled_available() -> bool:
    """Tell whether the compiled kernel can run (numba installed, ``RAILVIB_COMPILED`` not 0).

    The first call imports numba and loads the kernel (compiled once, then from numba's
    on-disk cache: 0.3-1 s).

    Returns
    -------
    bool
        True where :func:`panel_rules` may be called with ``compiled=True``.
    """
    if os.environ.get("RAILVIB_COMPILED", "1") == "0":
        return False
    return _kernel() is not None


def _kernel() -> Any:
    """The compiled node loop (numba, cached on disk), or None where numba is not installed."""
    if not _KERNEL:
        jit = numba_jit(fastmath=_FASTMATH)
        _KERNEL.append(None if jit is None else jit(_panels))
    return _KERNEL[0]


def panel_rules(
    mid: NDArray[np.float64],
    half: NDArray[np.float64],
    omega_load: NDArray[np.float64],
    support: NDArray[np.complex128],
    speed: float,
    rail: tuple[float, ...],
    shift: NDArray[np.float64],
    r: NDArray[np.float64],
    *,
    compiled: bool = False,
) -> tuple[NDArray[np.complex128], NDArray[np.float64]]:
    """Kronrod rule and its error estimate of the moving-load integrand on every panel.

    Parameters
    ----------
    mid, half : numpy.ndarray
        Centre and half width of each panel, rad/m, ``(n_panel,)``.
    omega_load : numpy.ndarray
        The load's circular frequency ``Omega`` of each panel, rad/s, ``(n_panel,)``.
    support : numpy.ndarray
        ``K(omega)`` at the panel's 15 nodes ``mid + half x NODES``, at the fixed frame's
        frequency ``omega = Omega - k v`` (``conj K(|omega|)`` where ``omega < 0``), N/m,
        ``(n_panel, 15)``.
    speed : float
        Load speed v, m/s.
    rail : tuple of float
        ``(EI, m, eta, d)``: bending stiffness (N m^2), mass per length (kg/m), loss factor
        (> 0, dimensionless) and sleeper spacing (m) of an Euler rail; a Timoshenko rail
        adds ``(kappa G A, rho I)`` (N, kg m).
    shift : numpy.ndarray
        ``2 pi n / d`` of each harmonic, rad/m, ``(n_harm,)``.
    r : numpy.ndarray
        Observation points ahead of the load, m, ``(n_obs,)``.
    compiled : bool
        Run the numba kernel (:func:`compiled_available` must be True) instead of NumPy.

    Returns
    -------
    rule : numpy.ndarray
        ``int exp(i k r) G_n (delta_n0 - K w_0 / d) dk`` over each panel by the Filon rule
        on the Kronrod nodes (:func:`filon_weights`; the Kronrod rule at ``r = 0``), m/N,
        ``(n_panel, n_obs, n_harm)`` (the phase ``exp(i 2 pi n r / d)`` and the ``1 / 2 pi``
        are left to the caller).
    error : numpy.ndarray
        ``max |Kronrod - Gauss|`` of ``int G_n (delta_n0 - K w_0 / d) dk`` (the ``r = 0``
        integrand) over the harmonics, m/N, ``(n_panel,)``.
    """
    n_panel = mid.size
    rule = np.empty((n_panel, r.size, shift.size), dtype=np.complex128)
    error = np.empty(n_panel)
    oscillating = bool(np.any(r != 0.0))
    if compiled:
        group, table = _filon_table(half, r)
        _kernel()(
            np.ascontiguousarray(mid, dtype=np.float64),
            np.ascontiguousarray(half, dtype=np.float64),
            np.ascontiguousarray(omega_load, dtype=np.float64),
            np.ascontiguousarray(support, dtype=np.complex128),
            float(speed),
            *(float(x) for x in rail),
            *((0.0, 0.0) if len(rail) == 4 else ()),  # shear 0: an Euler rail
            np.ascontiguousarray(shift, dtype=np.float64),
            group,
            table,
            np.ascontiguousarray(r, dtype=np.float64),
            oscillating,
            NODES,
            _KRONROD,
            _GAUSS,
            OMEGA_FLOOR,
            _D1_SERIES,
            _CSC2_SERIES,
            rule,
            error,
        )
        return rule, error
    k = mid[:, None] + half[:, None] * NODES[None, :]  # (n_panel, 15)
    values = integrand(k, omega_load[:, None] - k * speed, support, rail, shift)
    weights = filon_weights(mid, half, r)
    rule[...] = np.einsum("pqn,poq->pon", values, weights, optimize=True)
    difference = (_KRONROD - _GAUSS) * np.stack([np.ones(NODES.size), NODES])[: 1 + oscillating]
    smooth = np.einsum("pqn,sq->psn", values, difference) * half[:, None, None]
    error[...] = np.abs(smooth).max(axis=(1, 2), initial=0.0)
    return rule, error


def filon_weights(
    mid: NDArray[np.float64], half: NDArray[np.float64], r: NDArray[np.float64]
) -> NDArray[np.complex128]:
    """Weights of ``int exp(i k r) g(k) dk`` over each panel from ``g`` at its 15 nodes, m^-1.

    ``g`` is replaced by its interpolating polynomial at the nodes ``mid + half t_q``
    (degree 14, in the Legendre basis: ``V^-1``), whose product with ``exp(i k r)`` is
    integrated exactly (Filon's rule)::

        int exp(i k r) g dk = half exp(i mid r) sum_q w_q(half r) g(k_q),
        w_q(w) = sum_j (V^-1)_jq 2 i^j j_j(w),

    ``j_j`` the spherical Bessel functions; at ``r = 0`` they are the Kronrod weights (the
    Kronrod rule is interpolatory), taken as such. Exact for a polynomial ``g`` of degree
    14 whatever ``half r``, so the oscillation costs no nodes: the error is that of the
    interpolation of ``g``, which the Kronrod-Gauss estimate of ``int g dk`` measures.

    Parameters
    ----------
    mid, half : numpy.ndarray
        Centre and half width of each panel, rad/m, ``(n_panel,)``.
    r : numpy.ndarray
        Observation points ahead of the load, m, ``(n_obs,)``.

    Returns
    -------
    numpy.ndarray
        ``half exp(i mid r) w_q(half r)``, rad/m, ``(n_panel, n_obs, 15)``.
    """
    group, table = _filon_table(half, r)
    phase = np.exp(1j * mid[:, None] * r[None, :]) * half[:, None]  # (n_panel, n_obs)
    return np.asarray(table[group] * phase[:, :, None], dtype=np.complex128)


def _filon_table(
    half: NDArray[np.float64], r: NDArray[np.float64]
) -> tuple[NDArray[np.intp], NDArray[np.complex128]]:
    """``w_q(half r)`` of :func:`filon_weights` once per distinct half width.

    Returns each panel's index into the table ``(n_panel,)`` and the table ``(n_width,
    n_obs, 15)`` (bisection gives a few distinct widths a level: the spherical Bessel
    functions, ~3 us each, are evaluated for those only).
    """
    group = np.zeros(half.size, dtype=np.intp)
    if half.size == 0:
        return group, np.zeros((1, r.size, NODES.size), dtype=np.complex128)
    order = np.argsort(half, kind="stable")
    sorted_half = half[order]
    new = np.concatenate([[True], np.diff(sorted_half) > _SAME_WIDTH * sorted_half[1:]])
    group[order] = np.cumsum(new) - 1
    width = sorted_half[new]  # (n_width,)
    degree = np.arange(NODES.size)
    argument = width[:, None, None] * np.abs(r)[None, :, None]  # (n_width, n_obs, 1)
    # j_j(-x) = (-1)^j j_j(x) (DLMF 10.47.14): scipy < 1.15 gives NaN for x < 0, j >= 1
    parity = np.where(r < 0.0, -1.0, 1.0)[None, :, None] ** degree
    moments = _LEGENDRE_MOMENT * parity * spherical_jn(degree, argument)
    table = np.asarray(moments @ _LEGENDRE_INVERSE, dtype=np.complex128)
    table[:, r == 0.0, :] = _KRONROD
    return group, table


def integrand(
    k: NDArray[np.float64],
    omega: NDArray[np.float64],
    support: NDArray[np.complex128],
    rail: tuple[float, ...],
    shift: NDArray[np.float64],
) -> NDArray[np.complex128]:
    """``G_n (delta_n0 - K w_0 / d)`` at wavenumbers `k` and fixed-frame `omega`, m^2/N.

    Parameters
    ----------
    k, omega : numpy.ndarray
        Wavenumbers (rad/m) and the fixed frame's circular frequencies (rad/s), same shape.
    support : numpy.ndarray
        ``K(omega)``, N/m, same shape.
    rail : tuple of float
        ``(EI, m, eta, d)`` or ``(EI, m, eta, d, kappa G A, rho I)`` as in
        :func:`panel_rules`.
    shift : numpy.ndarray
        ``2 pi n / d``, rad/m, ``(n_harm,)``.

    Returns
    -------
    numpy.ndarray
        Shape ``k.shape + (n_harm,)``, complex.
    """
    ei, m, eta, d = rail[:4]
    omega = np.where(omega == 0.0, OMEGA_FLOOR, omega)
    sign = np.where(omega < 0.0, -1.0, 1.0)
    loss = 1.0 + 1j * eta * sign  # hysteretic: EI (1 - i eta) at omega < 0
    ei_c = ei * loss
    beta4 = m * omega**2 * d**4 / ei_c
    if len(rail) == 4:  # Euler: G(k) = d^4 / EI* / ((kd)^4 - beta4)
        lattice = lattice_sum(k * d, beta4)
        kn = (k[..., None] + shift) * d
        gn = 1.0 / (kn**4 - beta4[..., None])
        g0 = 1.0 / ((k * d) ** 4 - beta4)
    else:  # Timoshenko: G(k) = d^4 / EI* (eps (kd)^2 + 1 - rho eps) / ((kd)^4 - q (kd)^2 - g)
        shear, rotary = rail[4], rail[5]
        eps = ei / (shear * d**2)  # EI* / kGA*: both carry the same loss
        rho_eps = rotary * omega**2 / (shear * loss)
        rho = rotary * omega**2 * d**2 / ei_c
        lattice = timoshenko_lattice_sum(k * d, beta4, eps, rho, rho_eps)
        q, g = rho + eps * beta4, beta4 * (1.0 - rho_eps)
        kn = (k[..., None] + shift) * d
        gn = (eps * kn**2 + (1.0 - rho_eps)[..., None]) / (
            kn**4 - q[..., None] * kn**2 - g[..., None]
        )
        g0 = (eps * (k * d) ** 2 + 1.0 - rho_eps) / ((k * d) ** 4 - q * (k * d) ** 2 - g)
    rest = lattice - g0  # the images m != 0: digits lost where G_0 dominates ...
    near = np.abs(g0) > POLE_DOMINANCE * np.abs(rest)
    if np.any(near) and len(rail) == 4:  # ... so summed directly there
        rest[near] = _euler_images(k[near] * d, beta4[near])
    elif np.any(near):
        rest[near] = _timoshenko_images(k[near] * d, eps, q[near], g[near], 1.0 - rho_eps[near])
    scale = d**4 / ei_c  # m/N per unit of the dimensionless sums and G
    kk = support * scale
    base = d + kk * rest
    total = base + kk * g0  # d + K S
    # K w_0 / d = K G_0 / (d + K S), and 1 - K w_0 / d = (d + K (S - G_0)) / (d + K S)
    factor = np.where(shift == 0, (base / total)[..., None], -(kk * g0 / total)[..., None])
    return np.asarray(gn * scale[..., None] * factor, dtype=np.complex128)


def lattice_sum(kd: NDArray[np.float64], beta4: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """``sum_m 1 / ((kd + 2 pi m)^4 - beta4)`` in closed form, without cancellation.

    With ``z^4 = beta4``, ``a = sin^2(kd/2)``: the partial fractions of ``1/(x^4 - z^4)``
    and ``sum_m 1/((kd + 2 pi m)^2 - b^2) = sin b / (2 b (cos b - cos kd))`` give
    ``[ -2 a s3 + (sinhc^2(z/2) sinc z + sinc^2(z/2) sinhc z) / 4 ] / (8 D)``, ``s3 = (sinh z
    - sin z) / (2 z^3)``, ``D = (a - sin^2(z/2)) (a + sinh^2(z/2))``. Every term is even in
    ``z`` and in ``i z``, so no fourth root has to be chosen, and ``z -> 0`` loses no digits
    (``s3`` by its series below ``|z| = 1``).

    Parameters
    ----------
    kd : numpy.ndarray
        Wavenumber times sleeper spacing (rad).
    beta4 : numpy.ndarray
        ``m omega^2 d^4 / EI*`` (dimensionless), broadcast with `kd`.

    Returns
    -------
    numpy.ndarray
        The sum (dimensionless), complex.
    """
    z = beta4**0.25
    sin_h, sinh_h = np.sin(0.5 * z), np.sinh(0.5 * z)
    small = np.abs(beta4) < 1.0
    zeta = np.where(small, beta4, 0.0)  # the series: sum zeta^j / (4j+3)!, |zeta| < 1
    c0, c1, c2, c3 = _S3_SERIES
    series = c0 + zeta * (c1 + zeta * (c2 + zeta * c3))
    cube = np.where(small, 1.0, z * z * z)
    s3 = np.where(small, series, (np.sinh(z) - np.sin(z)) / (2.0 * cube))
    a = np.sin(0.5 * kd) ** 2
    p, q = sin_h * sin_h, sinh_h * sinh_h
    # (q sin z + p sinh z) / z^3 as products of sin x / x and sinh x / x: exact at z = 0
    mixed = 0.25 * (_sinc(1j * 0.5 * z) ** 2 * _sinc(z) + _sinc(0.5 * z) ** 2 * _sinc(1j * z))
    numerator = -2.0 * a * s3 + mixed
    return np.asarray(numerator / (8.0 * (a - p) * (a + q)), dtype=np.complex128)


def _euler_images(kd: NDArray[np.float64], beta4: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """``sum_(m != 0) 1 / ((kd + 2 pi m)^4 - beta4)`` summed directly (:data:`IMAGES` pairs).

    The images beyond are ``(2 pi m)^-4`` to ``O(kd^2 / m^6)`` (the odd terms cancel in
    pairs): their sum ``2 (zeta(4) - H_M^(4)) / (2 pi)^4`` leaves < 1e-12 of the result.
    """
    m = 2.0 * np.pi * np.arange(1, IMAGES + 1)
    x = kd[..., None]
    b = beta4[..., None]
    pairs = 1.0 / ((x + m) ** 4 - b) + 1.0 / ((x - m) ** 4 - b)
    return np.asarray(pairs.sum(axis=-1) + _IMAGE_TAIL, dtype=np.complex128)


def _timoshenko_images(
    kd: NDArray[np.float64],
    eps: float,
    q: NDArray[np.complex128],
    g: NDArray[np.complex128],
    n0: NDArray[np.complex128],
) -> NDArray[np.complex128]:
    """``sum_(m != 0) g(kd + 2 pi m)`` of :func:`timoshenko_lattice_sum`, summed directly.

    ``g(x) = eps / x^2 + h(x)``, ``h(x) = ((n0 + eps q) x^2 + eps g) / (x^2 (x^4 - q x^2 -
    g))``: the images of ``eps / x^2`` in closed form (:func:`_inverse_square_images`), those
    of ``h`` as :func:`_euler_images` (:data:`IMAGES` pairs, the rest as ``(n0 + eps q) / x^4``).
    """
    m = 2.0 * np.pi * np.arange(1, IMAGES + 1)
    c2, c0 = (n0 + eps * q)[..., None], (eps * g)[..., None]
    qq, gg = q[..., None], g[..., None]
    total = np.zeros(np.shape(kd), dtype=np.complex128)
    for x in (kd[..., None] + m, kd[..., None] - m):
        x2 = x * x
        total += ((c2 * x2 + c0) / (x2 * (x2 * x2 - qq * x2 - gg))).sum(axis=-1)
    tail = (n0 + eps * q) * _IMAGE_TAIL
    return np.asarray(eps * _inverse_square_images(kd) + total + tail, dtype=np.complex128)


def _inverse_square_images(kd: NDArray[np.float64]) -> NDArray[np.float64]:
    """``sum_(m != 0) 1 / (kd + 2 pi m)^2 = 1 / (4 sin^2(kd / 2)) - 1 / kd^2`` (1/12 at 0).

    By its Laurent series below ``|kd| = 1/2`` (the next term leaves < 1e-13 there),
    without the cancellation of the closed form.
    """
    t2 = kd * kd
    c1, c2, c3, c4, c5 = _CSC2_SERIES
    series = 1.0 / 12.0 + t2 * (c1 + t2 * (c2 + t2 * (c3 + t2 * (c4 + t2 * c5))))
    small = np.abs(kd) < 0.5
    safe = np.where(small, 1.0, kd)
    closed = 0.25 / np.sin(0.5 * safe) ** 2 - 1.0 / (safe * safe)
    return np.asarray(np.where(small, series, closed), dtype=np.float64)


def timoshenko_lattice_sum(
    kd: NDArray[np.float64],
    beta4: NDArray[np.complex128],
    eps: float,
    rho: NDArray[np.complex128],
    rho_eps: NDArray[np.complex128],
) -> NDArray[np.complex128]:
    """``sum_m g(kd + 2 pi m)``, ``g(x) = (eps x^2 + n0) / (x^4 - q x^2 - g)``: a Timoshenko rail.

    ``q = rho + eps beta4``, ``g = beta4 (1 - rho eps)``, ``n0 = 1 - rho eps``; the roots
    in ``x^2`` are ``a^2`` and ``-b^2`` (:func:`railvib.track.timoshenko.wavenumbers`).
    With ``F(y) = sum_m 1 / ((kd + 2 pi m)^2 - y) = sinc(sqrt y) / (2 (cos sqrt y - cos kd))``
    the partial fractions give ``eps F(a^2) + (n0 - eps b^2) DF``, ``DF`` the divided
    difference of ``F`` at ``a^2`` and ``-b^2``:
    ``DF = (D0 sin(a)/a - D1 (cos a - cos kd)) / (2 (cos a - cos kd)(cosh b - cos kd))``,
    with ``D0 = (cosh b - cos a) / (a^2 + b^2)`` and ``D1 = (sinh(b)/b - sin(a)/a) / (a^2 +
    b^2)`` formed without cancellation as for the Timoshenko span
    (:func:`railvib.track.beam.timoshenko_transfer`). ``eps = rho = 0`` is the Euler
    rail's :func:`lattice_sum`.

    Parameters
    ----------
    kd : numpy.ndarray
        Wavenumber times sleeper spacing (rad).
    beta4, rho, rho_eps : numpy.ndarray
        ``m omega^2 d^4 / EI*``, ``rho_I omega^2 d^2 / EI*`` and ``rho_I omega^2 / kGA*``
        (dimensionless), the shape of `kd`.
    eps : float
        ``EI / (kappa G A d^2)`` (dimensionless).

    Returns
    -------
    numpy.ndarray
        The sum (dimensionless), complex, the shape of `kd`.
    """
    shape = np.shape(kd)
    b4, rh, re = (np.asarray(x, dtype=np.complex128).ravel() for x in (beta4, rho, rho_eps))
    a2, b2, _, _, r = wavenumbers(b4, complex(eps), rh, re)
    a, b = np.sqrt(a2), np.sqrt(b2)
    sin_a, sinh_b = _over(np.sin(a), a, 1.0), _over(np.sinh(b), b, 1.0)
    d0 = 2.0 * np.sin(0.5 * (a + 1j * b)) * np.sin(0.5 * (a - 1j * b)) / r
    q, g = rh + eps * b4, b4 * (1.0 - re)
    d1 = _odd_divided_difference(sin_a, sinh_b, a, b, r, q, g, 1.0)
    t = np.ravel(kd)
    # cos a - cos kd and cosh b - cos kd as products: no cancellation at small kd
    v1 = 2.0 * np.sin(0.5 * (t + a)) * np.sin(0.5 * (t - a))
    v2 = 2.0 * np.sin(0.5 * (t + 1j * b)) * np.sin(0.5 * (t - 1j * b))
    divided = (d0 * sin_a - d1 * v1) / (2.0 * v1 * v2)
    out = eps * sin_a / (2.0 * v1) + (1.0 - re - eps * b2) * divided
    return np.asarray(out.reshape(shape), dtype=np.complex128)


def _sinc(z: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """``sin z / z`` (1 at 0; no cancellation anywhere); ``_sinc(i z) = sinh z / z``."""
    zero = z == 0
    safe = np.where(zero, 1.0, z)
    return np.asarray(np.where(zero, 1.0, np.sin(safe) / safe), dtype=np.complex128)


def _panels(  # noqa: C901, PLR0912, PLR0913, PLR0915 - one loop body the compiler fuses
    mid: Any,
    half: Any,
    omega_load: Any,
    support: Any,
    speed: float,
    ei: float,
    m: float,
    eta: float,
    d: float,
    shear: float,
    rotary: float,
    shift: Any,
    group: Any,
    table: Any,
    r: Any,
    oscillating: bool,
    nodes: Any,
    w_kronrod: Any,
    w_gauss: Any,
    omega_floor: float,
    series: Any,
    csc2: Any,
    rule: Any,
    error: Any,
) -> None:
    """:func:`panel_rules` node by node, written for numba (fills `rule` and `error`).

    ``shear = 0``: an Euler rail; else a Timoshenko rail (:func:`timoshenko_lattice_sum`,
    with the coefficients `series` of its divided difference ``D1``; `csc2`: those of
    :func:`_inverse_square_images`). `table[group[p]]`: the Filon weights ``w_q(half r)``
    of panel ``p`` (:func:`_filon_table`), ``(n_obs, 15)``; `oscillating`: some ``r != 0``
    (the error estimate then also takes the first moment, whose odd part ``r = 0`` hides).
    """
    n_harm, n_obs = shift.size, r.size
    d4 = d**4
    values = np.empty((nodes.size, n_harm), dtype=np.complex128)
    smooth = np.empty(n_harm, dtype=np.complex128)
    moment = np.empty(n_harm, dtype=np.complex128)
    value = np.empty(n_harm, dtype=np.complex128)
    ei_pos = ei * complex(1.0, eta)  # hysteretic: EI (1 - i eta) at omega < 0
    inv_pos = 1.0 / ei_pos
    timoshenko = shear > 0.0
    eps = ei / (shear * d * d) if timoshenko else 0.0  # EI* / kGA* d^2: the loss cancels
    for p in range(mid.size):
        smooth[:] = 0.0
        moment[:] = 0.0
        for q in range(nodes.size):
            k = mid[p] + half[p] * nodes[q]
            omega = omega_load[p] - k * speed
            if omega == 0.0:
                omega = omega_floor
            inv_ei = inv_pos.conjugate() if omega < 0.0 else inv_pos
            beta4 = m * omega * omega * d4 * inv_ei
            theta = k * d
            if timoshenko:  # timoshenko_lattice_sum, scalar
                rho = rotary * omega * omega * d * d * inv_ei
                rho_eps = rho * eps
                eb = eps * beta4
                qq = rho + eb
                rr = cmath.sqrt((rho - eb) ** 2 + 4.0 * beta4)
                if (qq.conjugate() * rr).real < 0.0:
                    rr = -rr
                gg = beta4 * (1.0 - rho_eps)
                b2 = 2.0 * gg / (qq + rr)
                a = cmath.sqrt(0.5 * (qq + rr))
                b = cmath.sqrt(b2)
                sin_a = cmath.sin(a) / a if a != 0 else 1.0 + 0j
                sinh_b = cmath.sinh(b) / b if b != 0 else 1.0 + 0j
                d0 = 2.0 * cmath.sin(0.5 * (a + 1j * b)) * cmath.sin(0.5 * (a - 1j * b)) / rr
                if max(abs(a), abs(b)) ** 2 <= _SERIES_WAVENUMBER2:
                    b_next, b_next2 = 0.0 + 0j, 0.0 + 0j
                    for j in range(series.size - 1, -1, -1):
                        b_j = qq * b_next + gg * b_next2 + series[j]
                        b_next, b_next2 = b_j, b_next
                    d1 = b_next
                else:
                    d1 = (sinh_b - sin_a) / rr
                # cos a - cos kd and cosh b - cos kd as products: no cancellation at small kd
                v1 = 2.0 * cmath.sin(0.5 * (theta + a)) * cmath.sin(0.5 * (theta - a))
                v2 = 2.0 * cmath.sin(0.5 * (theta + 1j * b)) * cmath.sin(0.5 * (theta - 1j * b))
                divided = (d0 * sin_a - d1 * v1) / (2.0 * v1 * v2)
                n0 = 1.0 - rho_eps
                lattice = eps * sin_a / (2.0 * v1) + (n0 - eps * b2) * divided
                t2 = theta * theta
                g0 = (eps * t2 + n0) / (t2 * t2 - qq * t2 - gg)
            else:
                # lattice_sum, scalar: sin and sinh of z/2 and z from the real functions
                # of z's real and imaginary parts
                z = cmath.sqrt(cmath.sqrt(beta4))
                hx, hy = 0.5 * z.real, 0.5 * z.imag
                sx, cx, sy, cy = math.sin(hx), math.cos(hx), math.sin(hy), math.cos(hy)
                shx, chx = math.sinh(hx), math.cosh(hx)
                shy, chy = math.sinh(hy), math.cosh(hy)
                sin_h = complex(sx * chy, cx * shy)
                cos_h = complex(cx * chy, -sx * shy)
                sinh_h = complex(shx * cy, chx * sy)
                cosh_h = complex(chx * cy, shx * sy)
                sin_z, sinh_z = 2.0 * sin_h * cos_h, 2.0 * sinh_h * cosh_h
                pp, qp = sin_h * sin_h, sinh_h * sinh_h
                a_k = math.sin(0.5 * theta) ** 2
                if abs(beta4) < 1.0:
                    s3 = 1.0 / 6.0 + beta4 * (
                        1.0 / 5040.0 + beta4 * (1.0 / 39916800.0 + beta4 / 1.307674368e12)
                    )
                    # (qp sin z + pp sinh z) / z^3 as in lattice_sum: 1/2 at z = 0
                    mixed = 0.5 + 0j if z == 0 else (qp * sin_z + pp * sinh_z) / (z * z * z)
                    numerator = -2.0 * a_k * s3 + mixed
                else:
                    numerator = (-a_k * (sinh_z - sin_z) + qp * sin_z + pp * sinh_z) / (z * z * z)
                lattice = numerator / (8.0 * (a_k - pp) * (a_k + qp))
                t2 = theta * theta
                g0 = 1.0 / (t2 * t2 - beta4)
            rest = lattice - g0  # the images m != 0 (summed directly where G_0 dominates)
            if abs(g0) > POLE_DOMINANCE * abs(rest) and not timoshenko:  # _euler_images
                rest = _IMAGE_TAIL + 0j
                for j in range(IMAGES, 0, -1):
                    xp, xm = theta + 2.0 * math.pi * j, theta - 2.0 * math.pi * j
                    rest += 1.0 / (xp**4 - beta4) + 1.0 / (xm**4 - beta4)
            elif abs(g0) > POLE_DOMINANCE * abs(rest):  # _timoshenko_images
                c2, c0 = n0 + eps * qq, eps * gg
                rest = c2 * _IMAGE_TAIL + 0j
                for j in range(IMAGES, 0, -1):
                    for x in (theta + 2.0 * math.pi * j, theta - 2.0 * math.pi * j):
                        x2 = x * x
                        rest += (c2 * x2 + c0) / (x2 * (x2 * x2 - qq * x2 - gg))
                if abs(theta) < 0.5:  # _inverse_square_images
                    t2 = theta * theta
                    c_1, c_2, c_3, c_4, c_5 = csc2
                    images2 = 1.0 / 12.0 + t2 * (
                        c_1 + t2 * (c_2 + t2 * (c_3 + t2 * (c_4 + t2 * c_5)))
                    )
                else:
                    images2 = 0.25 / math.sin(0.5 * theta) ** 2 - 1.0 / (theta * theta)
                rest += eps * images2
            # K w_0 / d = K G_0 / (d + K S), G_0 and S in units of d^4 / EI*, and
            # 1 - K w_0 / d = (d + K (S - G_0)) / (d + K S)
            scale = d4 * inv_ei
            kk = support[p, q] * scale
            base = d + kk * rest
            total = base + kk * g0
            reaction = kk * g0 / total
            for n in range(n_harm):
                tn = theta + shift[n] * d
                tn2 = tn * tn
                numerator_n = base / total if shift[n] == 0.0 else -reaction
                if timoshenko:
                    den = tn2 * tn2 - qq * tn2 - gg
                    numerator_n *= eps * tn2 + n0
                else:
                    den = tn2 * tn2 - beta4
                value[n] = scale * numerator_n * den.conjugate() / (den.real**2 + den.imag**2)
            for n in range(n_harm):
                values[q, n] = value[n]
            w_diff = (w_kronrod[q] - w_gauss[q]) * half[p]  # Kronrod - Gauss, r = 0
            w_odd = w_diff * nodes[q]  # ... and of the first moment
            for n in range(n_harm):
                smooth[n] += w_diff * value[n]
                moment[n] += w_odd * value[n]
        weights = table[group[p]]
        for o in range(n_obs):
            kr = mid[p] * r[o]
            phase = half[p] * (1.0 + 0j if r[o] == 0.0 else complex(math.cos(kr), math.sin(kr)))
            for n in range(n_harm):
                acc = 0.0 + 0j
                for q in range(nodes.size):
                    acc += weights[o, q] * values[q, n]
                rule[p, o, n] = phase * acc
        worst = 0.0
        for n in range(n_harm):
            worst = max(worst, abs(smooth[n]))
            if oscillating:
                worst = max(worst, abs(moment[n]))
        error[p] = worst
