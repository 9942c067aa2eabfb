"""The moving-load receptance at many load frequencies, by adaptive interpolation in frequency.

``A_n(Omega, r)`` (:func:`railvib.track.moving.moving_load_receptance`) is a smooth function
of the load frequency wherever the Doppler line ``omega = Omega - k v`` meets no wave of
the track tangentially (a wave whose group velocity is the load's): on a damped track it
varies on scales of hertz, and a run on a fine grid asks for it at ``(2 N + 1) n_freq``
frequencies (70 000 for a 0.1 Hz grid to 1 kHz), every one a wavenumber integral of ~10^3
nodes. Here the band is cut into intervals, the integral is computed directly at the
``P + 1`` Chebyshev-Lobatto points of each, and the degree-``P`` interpolant serves every
frequency inside. An interval is accepted when the degree-``P/2`` interpolant on every
other point reproduces the computed values at the points it leaves out to within
``interpolation_tolerance`` of the largest harmonic there (a measured error of the coarser
rule, which bounds the finer one's on an analytic function); otherwise it is halved. Where
halving reaches intervals holding no more asked-for frequencies than the points of their
two halves, those frequencies are computed directly: near a tangency (the moving load's
resonances, ``A_n`` singular in ``Omega``) the answer is the direct integral.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.track.moving import (
    _EXTRA,
    _WARN_ERROR,
    MovingLoadResponse,
    _checked,
    _checked_method,
    check_harmonic_sizes,
    integrated_harmonics,
    warn_unresolved,
)
from railvib.track.periodic import PeriodicTrack

__all__ = ["DEGREE", "INTERPOLATION_FACTOR", "interpolated_receptance"]

#: degree of the interpolant on each interval (its ``DEGREE + 1`` Chebyshev-Lobatto points;
#: the estimate is the degree ``DEGREE / 2`` one on every other point)
DEGREE = 16

#: default interpolation tolerance, in units of the quadrature tolerance
INTERPOLATION_FACTOR = 10.0

#: width of the starting intervals, Hz
_START_WIDTH = 80.0

#: intervals narrower than this fraction of the highest frequency are computed directly
_NARROWEST = 1e-12

#: frequencies whose harmonics' sizes are taken at once (the order check)
_CHUNK = 2048

#: Chebyshev-Lobatto points on [-1, 1], ascending
_LOBATTO = -np.cos(np.pi * np.arange(DEGREE + 1) / DEGREE)


def _barycentric(nodes: NDArray[np.float64], t: NDArray[np.float64]) -> NDArray[np.float64]:
    """Interpolation matrix ``(t.size, nodes.size)`` of the Chebyshev-Lobatto `nodes` at `t`."""
    p = nodes.size - 1
    w = (-1.0) ** np.arange(p + 1)
    w[0] *= 0.5
    w[-1] *= 0.5
    diff = t[:, None] - nodes[None, :]
    exact = diff == 0.0
    diff[exact] = 1.0
    terms = w / diff
    matrix = terms / terms.sum(axis=1, keepdims=True)
    hit = exact.any(axis=1)
    matrix[hit] = exact[hit].astype(float)
    return matrix


#: the degree DEGREE / 2 interpolant on the even points, at the odd ones
_CHECK = _barycentric(_LOBATTO[::2], _LOBATTO[1::2])


def interpolated_receptance(
    track: PeriodicTrack,
    f: ArrayLike,
    speed: float,
    *,
    order: int = 5,
    r: ArrayLike = (0.0,),
    tolerance: float = 1e-2,
    compiled: bool | None = None,
    quadrature_tolerance: float | None = None,
    interpolation_tolerance: float | None = None,
) -> MovingLoadResponse:
    """:func:`~railvib.track.moving.moving_load_receptance` by adaptive interpolation in `f`.

    Parameters
    ----------
    track, f, speed, order, r, tolerance, compiled, quadrature_tolerance
        As for :func:`~railvib.track.moving.moving_load_receptance` (Hz, m/s, m, -).
    interpolation_tolerance : float, optional
        Error of the interpolation, measured on every interval, relative to the largest
        harmonic at each of its points (dimensionless, in (0, 1e-2]); default
        :data:`INTERPOLATION_FACTOR` times the quadrature tolerance (the nested check
        overstates the error: on the default case 3e-8 left 2.2e-9).

    Returns
    -------
    MovingLoadResponse
        The harmonics at `f`, as from the direct integral.

    Raises
    ------
    CaseError
        As :func:`~railvib.track.moving.moving_load_receptance` (the same checks), and
        ``moving.interpolation_tolerance`` out of range.
    """
    f_arr, v, r_arr = _checked(track, f, speed, order, r, tolerance)
    compiled, quadrature_tolerance = _checked_method(f_arr.size, compiled, quadrature_tolerance)
    if interpolation_tolerance is None:
        interpolation_tolerance = INTERPOLATION_FACTOR * quadrature_tolerance
    if not (np.isfinite(interpolation_tolerance) and 0.0 < interpolation_tolerance <= 1e-2):
        raise CaseError(
            "moving.interpolation_tolerance", interpolation_tolerance, "in (0, 1e-2] (-)"
        )
    n_orders = np.arange(-order - _EXTRA, order + _EXTRA + 1)
    method = (bool(compiled), float(quadrature_tolerance))

    integrated: list[NDArray[np.float64]] = []
    left: list[NDArray[np.float64]] = []

    def direct(freqs: NDArray[np.float64]) -> tuple[NDArray[np.complex128], NDArray[np.bool_]]:
        values, error = integrated_harmonics(track, freqs, v, n_orders, r_arr, method)
        integrated.append(freqs)
        left.append(error)
        return values, error <= _WARN_ERROR

    ascending = np.argsort(f_arr, kind="stable")
    amplitudes = _adaptive(direct, f_arr[ascending], float(interpolation_tolerance))
    # one warning for all the rounds' integrals
    warn_unresolved(np.concatenate(integrated), np.concatenate(left), stacklevel=3)
    if np.any(ascending != np.arange(f_arr.size)):
        amplitudes[ascending] = amplitudes.copy()
    if order >= 1:
        check_harmonic_sizes(f_arr, v, _sizes(amplitudes), order, tolerance)
    kept = amplitudes[:, :, _EXTRA : amplitudes.shape[2] - _EXTRA]
    return MovingLoadResponse(
        f_arr, v, track.sleeper_spacing, r_arr, n_orders[_EXTRA:-_EXTRA], kept
    )


def _sizes(amplitudes: NDArray[np.complex128]) -> NDArray[np.float64]:
    """``max_r |A_n|``, ``(n_freq, n_harm)``, in chunks that stay in cache."""
    size = np.empty((amplitudes.shape[0], amplitudes.shape[2]))
    for start in range(0, amplitudes.shape[0], _CHUNK):
        part = amplitudes[start : start + _CHUNK]
        size[start : start + _CHUNK] = np.abs(part).max(axis=1)
    return size


def _adaptive(
    direct: Callable[[NDArray[np.float64]], tuple[NDArray[np.complex128], NDArray[np.bool_]]],
    f: NDArray[np.float64],
    tol: float,
) -> NDArray[np.complex128]:
    """Values of `direct` at the sorted frequencies `f`, interpolated where that is accurate.

    `direct` returns the values at the frequencies it is given and whether each is trusted
    (the quadrature reached its tolerance there). Each round computes, in one call of
    `direct`, the Chebyshev-Lobatto points of every pending interval and the asked-for
    frequencies of the intervals too sparse to interpolate; an interval whose points are
    all trusted and whose check keeps the tolerance fills its frequencies from the
    interpolant, the others are halved for the next round (so where the quadrature is not
    resolved, the frequencies asked for are computed directly, and warned of).
    """
    lo, hi = float(f[0]), float(f[-1])
    edges = np.linspace(lo, hi, max(1, int(np.ceil((hi - lo) / _START_WIDTH))) + 1)
    pending = np.stack([edges[:-1], edges[1:]], axis=1)  # (n_interval, 2)
    out: NDArray[np.complex128] | None = None
    while pending.size:
        first = np.searchsorted(f, pending[:, 0], "left")
        last = np.searchsorted(f, pending[:, 1], "right")
        # no more asked for than the points of its two halves (or no width left to halve)
        few = last - first <= 2 * (DEGREE + 1)
        few |= pending[:, 1] - pending[:, 0] <= _NARROWEST * hi
        ranges = zip(first[few], last[few], strict=True)
        asked = np.concatenate([np.arange(a, b) for a, b in ranges] + [np.empty(0, np.intp)])
        fit, first, last = pending[~few], first[~few], last[~few]
        centre, half = fit.mean(axis=1), 0.5 * (fit[:, 1] - fit[:, 0])
        points = (centre[:, None] + half[:, None] * _LOBATTO).ravel()
        batch, where = np.unique(np.concatenate([points, f[asked]]), return_inverse=True)
        values, trusted = direct(batch)
        if out is None:
            out = np.empty((f.size,) + values.shape[1:], dtype=np.complex128)
        out[asked] = values[where[points.size :]]
        width = int(np.prod(values.shape[1:]))
        nodes = values[where[: points.size]].reshape(centre.size, DEGREE + 1, width)
        scale = np.maximum(np.abs(nodes).max(axis=2), np.finfo(float).tiny)
        check = np.einsum("oe,iec->ioc", _CHECK, nodes[:, ::2]) - nodes[:, 1::2]
        good = (np.abs(check).max(axis=2) / scale[:, 1::2]).max(axis=1) <= tol
        good &= trusted[where[: points.size]].reshape(centre.size, DEGREE + 1).all(axis=1)
        # real matrices on the real and imaginary parts side by side: one real product
        flat = out.reshape(f.size, -1).view(np.float64)
        for i in np.flatnonzero(good):
            a, b = first[i], last[i]
            matrix = _barycentric(_LOBATTO, np.clip((f[a:b] - centre[i]) / half[i], -1.0, 1.0))
            np.matmul(matrix, nodes[i].view(np.float64), out=flat[a:b])
        split = fit[~good]
        middle = split.mean(axis=1)
        halves = np.concatenate(
            [np.stack([split[:, 0], middle], axis=1), np.stack([middle, split[:, 1]], axis=1)]
        )
        pending = halves[np.argsort(halves[:, 0], kind="stable")]
    assert out is not None
    return out
