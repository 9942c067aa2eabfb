"""The coupled vehicle-track solve compiled (numba), one pass over the (case, frequency) points.

The same equations as :func:`railvib.coupling.coupled_response` (the reference, and the
fallback): at each point, with the rail receptance ``R`` between the wheels, the vehicle
condensed on its wheels ``S`` (with its body recovery ``R_v``) and the contact compliance
``h = 1/k_H``,

    ((R + h I) S + I) u_w = r,   P = -S u_w,   u = R_v u_w,   u_rail = R P,

written point by point so that the system is formed, solved (Gaussian elimination with
partial pivoting: no point is left to LAPACK) and back-substituted in registers, and the
responses go straight into their result arrays: no entry array of the stack is formed
and no result is copied into place.

Loaded only where the compiled wave kernel is (:mod:`railvib.track.compiled` decides:
a sweep's large stacks, a process that has loaded it); numba is imported on first use.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from railvib.jit import numba_jit

__all__ = ["coupled_points", "kernel"]

_KERNEL: list[Any] = []


def kernel() -> Any:
    """The compiled point kernel (numba, cached on disk), or None where numba is not installed."""
    if not _KERNEL:
        jit = numba_jit(error_model="numpy")
        _KERNEL.append(None if jit is None else jit(_points))
    return _KERNEL[0]


def coupled_points(
    receptance: NDArray[np.complex128],
    track_of: NDArray[np.int64],
    stiffness: NDArray[np.complex128],
    recovery: NDArray[np.complex128],
    vehicle_of: NDArray[np.int64],
    contact_stiffness: NDArray[np.float64],
    excitation: NDArray[np.complex128],
    delay_of: NDArray[np.int64],
    run: Any = None,
) -> tuple[NDArray[np.complex128], NDArray[np.complex128], NDArray[np.complex128]]:
    """Vehicle, contact-force and rail responses of every (case, frequency) point.

    Parameters
    ----------
    receptance : numpy.ndarray
        Rail receptance between the wheels of each distinct track,
        ``(n_track, n_freq, n_w, n_w)``, m/N.
    track_of : numpy.ndarray
        Each case's track (row of `receptance`), ``(n_case,)``.
    stiffness, recovery : numpy.ndarray
        Each distinct vehicle condensed on its wheels: ``S`` ``(n_vehicle, n_freq, n_w,
        n_w)``, N/m, and ``R_v`` ``(n_vehicle, n_freq, n_dof, n_w)``.
    vehicle_of : numpy.ndarray
        Each case's vehicle, ``(n_case,)``.
    contact_stiffness : numpy.ndarray
        k_H of each case, N/m, ``(n_case,)``.
    excitation : numpy.ndarray
        Each distinct irregularity input at the wheels, ``(n_delay, n_freq, n_w)``, m.
    delay_of : numpy.ndarray
        Each case's input (row of `excitation`), ``(n_case,)``.
    run : callable, optional
        The point kernel (default: the compiled one; the plain Python function
        ``_points`` gives the same numbers, slowly).

    Returns
    -------
    vehicle, contact_force, rail : numpy.ndarray
        ``(n_case, n_freq, n_dof)``, ``(n_case, n_freq, n_w)``, ``(n_case, n_freq, n_w)``
        (the order of :func:`railvib.coupling.coupled_response`).
    """
    n_case, n_freq, n_w = track_of.size, receptance.shape[1], receptance.shape[2]
    u_v = np.empty((n_case, n_freq, recovery.shape[2]), dtype=np.complex128)
    rail = np.empty((n_case, n_freq, n_w), dtype=np.complex128)
    force = np.empty((n_case, n_freq, n_w), dtype=np.complex128)
    (kernel() if run is None else run)(
        np.ascontiguousarray(receptance, dtype=np.complex128),
        np.ascontiguousarray(track_of, dtype=np.int64),
        np.ascontiguousarray(stiffness, dtype=np.complex128),
        np.ascontiguousarray(recovery, dtype=np.complex128),
        np.ascontiguousarray(vehicle_of, dtype=np.int64),
        1.0 / np.asarray(contact_stiffness, dtype=float),
        np.ascontiguousarray(excitation, dtype=np.complex128),
        np.ascontiguousarray(delay_of, dtype=np.int64),
        u_v,
        rail,
        force,
    )
    return u_v, force, rail


def _points(  # noqa: PLR0913 - the kernel's arrays, as numba takes them
    receptance: Any,
    track_of: Any,
    stiffness: Any,
    recovery: Any,
    vehicle_of: Any,
    compliance: Any,
    excitation: Any,
    delay_of: Any,
    u_v: Any,
    rail: Any,
    force: Any,
) -> None:
    """The kernel: each point's system formed, solved and back-substituted (see module doc)."""
    n_freq, n = receptance.shape[1], receptance.shape[2]
    n_dof = recovery.shape[2]
    a = np.empty((n, n), dtype=np.complex128)
    x = np.empty(n, dtype=np.complex128)
    inv_diag = np.empty(n, dtype=np.complex128)
    for c in range(track_of.shape[0]):
        t, v, e, h = track_of[c], vehicle_of[c], delay_of[c], compliance[c]
        for q in range(n_freq):
            # (R + h I) S + I, and the input
            for i in range(n):
                for j in range(n):
                    acc = h * stiffness[v, q, i, j]
                    for m in range(n):
                        acc = acc + receptance[t, q, i, m] * stiffness[v, q, m, j]
                    a[i, j] = acc
                a[i, i] = a[i, i] + 1.0
                x[i] = excitation[e, q, i]
            # elimination with partial pivoting
            for k in range(n):
                piv = k
                size = a[k, k].real ** 2 + a[k, k].imag ** 2
                for i in range(k + 1, n):
                    s_i = a[i, k].real ** 2 + a[i, k].imag ** 2
                    if s_i > size:
                        piv, size = i, s_i
                if piv != k:
                    for j in range(k, n):
                        a[k, j], a[piv, j] = a[piv, j], a[k, j]
                    x[k], x[piv] = x[piv], x[k]
                inv_diag[k] = 1.0 / a[k, k]
                for i in range(k + 1, n):
                    ell = a[i, k] * inv_diag[k]
                    for j in range(k + 1, n):
                        a[i, j] = a[i, j] - ell * a[k, j]
                    x[i] = x[i] - ell * x[k]
            for k in range(n - 1, -1, -1):
                acc = x[k]
                for j in range(k + 1, n):
                    acc = acc - a[k, j] * x[j]
                x[k] = acc * inv_diag[k]
            # P = -S u_w, u = R_v u_w, u_rail = R P
            for i in range(n):
                acc = stiffness[v, q, i, 0] * x[0]
                for j in range(1, n):
                    acc = acc + stiffness[v, q, i, j] * x[j]
                force[c, q, i] = -acc
            for i in range(n_dof):
                acc = recovery[v, q, i, 0] * x[0]
                for j in range(1, n):
                    acc = acc + recovery[v, q, i, j] * x[j]
                u_v[c, q, i] = acc
            for i in range(n):
                acc = receptance[t, q, i, 0] * force[c, q, 0]
                for j in range(1, n):
                    acc = acc + receptance[t, q, i, j] * force[c, q, j]
                rail[c, q, i] = acc
