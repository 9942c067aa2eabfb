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

One case's block (:meth:`railvib.coupling.CoupledSystem.frf_blocks`) goes further on
:func:`fused_points`: the vehicle's condensation onto its wheels is executed per point
too (in batches of points, a point a vector lane), from the integer tables of its
minimum-degree elimination
(:attr:`railvib.vehicle.Vehicle.elimination_program`, any tree of bodies, a train's cars
included), and the bodies are recovered by back-substitution through the elimination's
multipliers, so neither ``S`` nor ``R_v`` is formed as an array; the receptance is scaled
from the wave solver's dimensionless one and the wheels' inputs ``exp(-i omega t_j)`` are
formed in the same pass.

Loaded only where the compiled wave kernel is (:mod:`railvib.track.compiled` decides:
a sweep's large stacks, a process that has loaded it); numba is imported on first use.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from railvib.jit import numba_jit

if TYPE_CHECKING:  # the vehicle's layer is above this kernel's: the type only
    from railvib.vehicle.assembly import EliminationProgram

__all__ = ["coupled_points", "fused_kernel", "fused_points", "kernel"]

_KERNEL: list[Any] = []
_FUSED: list[Any] = []
_B = 64  # points a batch of the fused kernel (structure of arrays)
# cos and sin of the wheels' input phases: pi/2 in two parts (33 + 53 bits: n pi/2 exact for
# |n| < 2^20), and the minimax kernels of fdlibm (k_sin.c, k_cos.c) on [-pi/4, pi/4]
_TWO_OVER_PI = 6.36619772367581382433e-01
_PIO2_1 = 1.57079632673412561417e00
_PIO2_1T = 6.07710050650619224932e-11
_SINCOS_MAX = 2.0**19 * np.pi  # |phase| above: the library's cos and sin
_S1, _S2, _S3 = -1.66666666666666324348e-01, 8.33333333332248946124e-03, -1.98412698298579493134e-04
_S4, _S5, _S6 = 2.75573137070700676789e-06, -2.50507602534068634195e-08, 1.58969099521155010221e-10
_C1, _C2, _C3 = 4.16666666666666019037e-02, -1.38888888888741095749e-03, 2.48015872894767294178e-05
_C4, _C5, _C6 = -2.75573143513906633035e-07, 2.08757232129817482790e-09, -1.13596475577881948265e-11


def kernel() -> Any:
    """The compiled point kernel (numba, cached on disk), or None where numba is not installed."""
    if not _KERNEL:
        jit = numba_jit(error_model="numpy")
        _KERNEL.append(None if jit is None else jit(_points))
    return _KERNEL[0]


def fused_kernel() -> Any:
    """The compiled fused kernel of :func:`fused_points`, or None where numba is not installed."""
    if not _FUSED:
        # as the wave kernel's (railvib.track.compiled): divisions without a zero test, and
        # a * b + c as one FMA (no reassociation), so that each stage is one vector loop
        jit = numba_jit(error_model="numpy", fastmath={"contract"})
        _FUSED.append(None if jit is None else jit(_fused))
    return _FUSED[0]


def fused_points(
    program: EliminationProgram,
    f: NDArray[np.float64],
    element_stiffness: NDArray[np.complex128],
    receptance: NDArray[np.complex128],
    scale: complex,
    contact_stiffness: float,
    delays: NDArray[np.float64],
    run: Any = None,
    out: tuple[NDArray[Any], ...] | None = None,
) -> tuple[NDArray[Any], ...]:
    """One case's vehicle condensation, coupled solve and body recovery, point by point.

    At each frequency the vehicle's dynamic stiffness is formed and its body DOFs
    eliminated by `program` (:attr:`railvib.vehicle.Vehicle.elimination_program`, the
    elimination of :meth:`~railvib.vehicle.Vehicle.condensed_to_wheels`), the coupled
    system of :func:`coupled_points` is solved with partial pivoting, and the bodies are
    recovered by back-substitution through the elimination's multipliers: no condensed
    entry, recovery matrix or excitation array is formed.

    Parameters
    ----------
    program : EliminationProgram
        The vehicle's elimination.
    f : numpy.ndarray
        Frequencies in Hz, ``(n_freq,)``.
    element_stiffness : numpy.ndarray
        ``K*_e(f)`` of the vehicle's frequency-dependent elements, ``(n_freq, n_element)``,
        N/m (:meth:`~railvib.vehicle.Vehicle.element_stiffness`).
    receptance : numpy.ndarray
        The rail receptance from the wheels to the wheels and then to further observed
        points, divided by `scale` (m/N over the unit of `scale`: dimensionless from the
        wave solver), ``(n_freq, n_obs, n_wheel)`` (``n_obs >= n_wheel``).
    scale : complex
        Its scale, m/N (``d^3 / EI*`` of the wave solver's dimensionless receptance; 1
        where `receptance` is in m/N).
    contact_stiffness : float
        k_H per contact, N/m.
    delays : numpy.ndarray
        Each wheel's input delay, s, ``(n_wheel,)``: its input ``exp(-i 2 pi f t_j)``
        (:func:`railvib.pem.excitation_vector`).
    run : callable, optional
        The point kernel (default: the compiled one; the plain Python function ``_fused``
        gives the same numbers, slowly).
    out : tuple of numpy.ndarray, optional
        The arrays to write the vehicle, contact-force, rail and observed responses into
        (the shapes of those returned; views, e.g. a run's result arrays' rows and
        columns, so that no block's response is copied into place); new ones by default.

    Returns
    -------
    vehicle, contact_force, rail, wheel_receptance, observed : numpy.ndarray
        ``(n_freq, n_dof)``, ``(n_freq, n_wheel)``, ``(n_freq, n_wheel)``, the receptance
        between the wheels ``(n_freq, n_wheel, n_wheel)`` in m/N, and the displacement of
        the further points ``(n_freq, n_obs - n_wheel)``, m per m of irregularity.
    bad : numpy.ndarray of bool
        ``(n_freq,)``: frequencies where a pivot of the vehicle's elimination failed the
        test of ``program.pivot_threshold``; their responses are not set (the
        caller solves them densely).
    """
    n, n_obs, n_w = receptance.shape
    shapes = ((n, program.n_dof), (n, n_w), (n, n_w), (n, n_obs - n_w))
    if out is None:
        out = tuple(np.empty(shape, dtype=np.complex128) for shape in shapes)
    for array, shape in zip(out, shapes, strict=True):
        if array.shape != shape or array.dtype != np.complex128:
            raise ValueError(f"out: {array.shape} {array.dtype}, not {shape} complex128")
    u_v, force, rail, observed = out
    rec = np.empty((n, n_w, n_w), dtype=np.complex128)
    bad = np.zeros(n, dtype=np.bool_)
    (fused_kernel() if run is None else run)(
        np.ascontiguousarray(f, dtype=float),
        np.ascontiguousarray(element_stiffness, dtype=np.complex128),
        np.ascontiguousarray(receptance, dtype=np.complex128),
        complex(scale),
        1.0 / float(contact_stiffness),
        np.ascontiguousarray(delays, dtype=float),
        program.base,
        program.term_slot,
        program.term_element,
        program.term_factor,
        program.pivot_slot,
        program.pivot_dof,
        program.nb_ptr,
        program.nb_dof,
        program.nb_slot,
        program.update_ptr,
        program.update,
        program.wheel_dof,
        program.wheel_slot,
        program.column_ptr,
        program.column_wheel,
        program.pivot_threshold,
        u_v,
        force,
        rail,
        rec,
        observed,
        bad,
    )
    return u_v, force, rail, rec, observed, bad


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


def _fused(  # noqa: C901, PLR0912, PLR0913, PLR0915 - the stages of one batch, written out
    f: Any,
    element_stiffness: Any,
    receptance: Any,
    scale: complex,
    h: float,
    delays: Any,
    base: Any,
    term_slot: Any,
    term_element: Any,
    term_factor: Any,
    pivot_slot: Any,
    pivot_dof: Any,
    nb_ptr: Any,
    nb_dof: Any,
    nb_slot: Any,
    update_ptr: Any,
    update: Any,
    wheel_dof: Any,
    wheel_slot: Any,
    column_ptr: Any,
    column_wheel: Any,
    threshold: float,
    u_v: Any,
    force: Any,
    rail: Any,
    rec: Any,
    observed: Any,
    bad: Any,
) -> None:
    """The fused kernel: each point's condensation, solve and recovery (:func:`fused_points`).

    The points go in batches of `_B`, structure of arrays: each complex quantity is a row
    of real parts and a row of imaginary parts, a point a lane, and every operation of the
    elimination program, of the coupled solve and of the recovery is one loop over the
    batch without branches (the pivot test flags the point in `bad`; the partial pivoting
    is a compare-and-swap of rows by select), which LLVM turns into vector instructions.
    Each point's operations are those of the point-by-point solve, in the same order.
    """
    n_freq, n_obs, n = receptance.shape
    n_slot, n_dof = base.shape[1], u_v.shape[1]
    n_nb, n_term, n_step = nb_dof.shape[0], term_slot.shape[0], pivot_slot.shape[0]
    dr, di = np.zeros((n_slot, _B)), np.zeros((n_slot, _B))  # the elimination's entries
    lr, li = np.zeros((n_nb, _B)), np.zeros((n_nb, _B))  # and its multipliers
    rr, ri = np.zeros((n_obs * n, _B)), np.zeros((n_obs * n, _B))  # receptance, m/N
    sr, si = np.zeros((n * n, _B)), np.zeros((n * n, _B))  # S
    ar, ai = np.zeros((n * n, _B)), np.zeros((n * n, _B))  # the coupled system
    xr, xi = np.zeros((n, _B)), np.zeros((n, _B))  # input, then u_w
    vr, vi = np.zeros((n, _B)), np.zeros((n, _B))  # inverse pivots
    pr, pi = np.zeros((n, _B)), np.zeros((n, _B))  # contact forces
    ur, ui = np.zeros((n_dof, _B)), np.zeros((n_dof, _B))  # the bodies
    om, om2, weak = np.zeros(_B), np.zeros(_B), np.zeros(_B)
    c0, c1, swap = np.zeros(_B), np.zeros(_B), np.zeros(_B)
    two_pi = 2.0 * np.pi
    minus_two_pi = -2.0 * np.pi
    threshold2 = threshold * threshold
    sc_r, sc_i = scale.real, scale.imag
    full = column_wheel.shape[0] == n * n  # no structural zero in S (one car)
    for start in range(0, n_freq, _B):
        nb = min(_B, n_freq - start)
        # the dynamic stiffness's entries K - omega^2 M + i omega C, and the elements
        for b in range(nb):
            om[b] = two_pi * f[start + b]
            om2[b] = om[b] * om[b]
            weak[b] = 0.0
        for k in range(n_slot):
            b0, b1, b2 = base[0, k], base[1, k], base[2, k]
            for b in range(nb):
                dr[k, b] = b0 - om2[b] * b1
                di[k, b] = om[b] * b2
        for t in range(n_term):
            k, e, fac = term_slot[t], term_element[t], term_factor[t]
            for b in range(nb):
                k_e = element_stiffness[start + b, e]
                dr[k, b] = dr[k, b] + k_e.real * fac
                di[k, b] = di[k, b] + k_e.imag * fac
        # the body DOFs eliminated (the pivot test of the stacked elimination, as a flag)
        for st in range(n_step):
            ps = pivot_slot[st]
            for b in range(nb):
                c0[b] = dr[ps, b] * dr[ps, b] + di[ps, b] * di[ps, b]
            for k in range(nb_ptr[st], nb_ptr[st + 1]):
                ns = nb_slot[k]
                for b in range(nb):
                    e2 = dr[ns, b] * dr[ns, b] + di[ns, b] * di[ns, b]
                    weak[b] = weak[b] if c0[b] >= threshold2 * e2 else 1.0
            for b in range(nb):
                c1[b] = 1.0 / c0[b]
            for k in range(nb_ptr[st], nb_ptr[st + 1]):
                ns = nb_slot[k]
                for b in range(nb):
                    inv_r, inv_i = dr[ps, b] * c1[b], -di[ps, b] * c1[b]
                    er, ei = dr[ns, b], di[ns, b]
                    lr[k, b] = er * inv_r - ei * inv_i
                    li[k, b] = er * inv_i + ei * inv_r
            for k in range(update_ptr[st], update_ptr[st + 1]):
                tg, m, src = update[k, 0], update[k, 1], update[k, 2]
                for b in range(nb):
                    mr, mi, sr_, si_ = lr[m, b], li[m, b], dr[src, b], di[src, b]
                    dr[tg, b] = dr[tg, b] - (mr * sr_ - mi * si_)
                    di[tg, b] = di[tg, b] - (mr * si_ + mi * sr_)
        # the receptance in m/N, also where the caller solves the point
        for b in range(nb):
            for i in range(n_obs):
                for j in range(n):
                    value = receptance[start + b, i, j]
                    vr_ = value.real * sc_r - value.imag * sc_i
                    vi_ = value.real * sc_i + value.imag * sc_r
                    rr[i * n + j, b], ri[i * n + j, b] = vr_, vi_
                    if i < n:
                        rec[start + b, i, j] = complex(vr_, vi_)
        for i in range(n):
            for j in range(n):
                slot = wheel_slot[i, j]
                if slot >= 0:
                    for b in range(nb):
                        sr[i * n + j, b], si[i * n + j, b] = dr[slot, b], di[slot, b]
        # (R + h I) S + I, and the input exp(-i 2 pi f t_j)
        for i in range(n):
            for j in range(n):
                ij = i * n + j
                for b in range(nb):
                    ar[ij, b], ai[ij, b] = h * sr[ij, b], h * si[ij, b]
                if full:
                    for m in range(n):
                        im, mj = i * n + m, m * n + j
                        for b in range(nb):
                            ar[ij, b] = ar[ij, b] + (rr[im, b] * sr[mj, b] - ri[im, b] * si[mj, b])
                            ai[ij, b] = ai[ij, b] + (rr[im, b] * si[mj, b] + ri[im, b] * sr[mj, b])
                else:
                    for k in range(column_ptr[j], column_ptr[j + 1]):
                        im, mj = i * n + column_wheel[k], column_wheel[k] * n + j
                        for b in range(nb):
                            ar[ij, b] = ar[ij, b] + (rr[im, b] * sr[mj, b] - ri[im, b] * si[mj, b])
                            ai[ij, b] = ai[ij, b] + (rr[im, b] * si[mj, b] + ri[im, b] * sr[mj, b])
            for b in range(nb):
                ar[i * n + i, b] = ar[i * n + i, b] + 1.0
        for i in range(n):
            large = False
            for b in range(nb):
                phase = minus_two_pi * f[start + b] * delays[i]
                xr[i, b] = phase
                large = large or abs(phase) > _SINCOS_MAX
            if large:  # beyond the reduction's range: the library's, point by point
                for b in range(nb):
                    phase = xr[i, b]
                    xr[i, b], xi[i, b] = np.cos(phase), np.sin(phase)
                continue
            for b in range(nb):
                # cos and sin as fdlibm's kernels after a Cody-Waite reduction by pi/2
                phase = xr[i, b]
                turns = np.floor(phase * _TWO_OVER_PI + 0.5)
                y = (phase - turns * _PIO2_1) - turns * _PIO2_1T
                z = y * y
                z2 = z * z
                sin_r = _S2 + z * (_S3 + z * _S4) + z * z2 * (_S5 + z * _S6)
                sin_y = y + z * y * (_S1 + z * sin_r)
                cos_r = z * (_C1 + z * (_C2 + z * _C3)) + z2 * z2 * (_C4 + z * (_C5 + z * _C6))
                half = 0.5 * z
                one = 1.0 - half
                cos_y = one + (((1.0 - one) - half) + z * cos_r)
                quadrant = turns - 4.0 * np.floor(turns * 0.25)
                c = cos_y if quadrant == 0.0 else -sin_y if quadrant == 1.0 else sin_y
                c = -cos_y if quadrant == 2.0 else c
                sn = sin_y if quadrant == 0.0 else cos_y if quadrant == 1.0 else -cos_y
                sn = -sin_y if quadrant == 2.0 else sn
                xr[i, b], xi[i, b] = c, sn
        # elimination with partial pivoting: the largest pivot swapped up by selects
        for k in range(n):
            kk = k * n + k
            for i in range(k + 1, n):
                ik = i * n + k
                for b in range(nb):
                    size2 = ar[kk, b] ** 2 + ai[kk, b] ** 2
                    swap[b] = 1.0 if ar[ik, b] ** 2 + ai[ik, b] ** 2 > size2 else 0.0
                for j in range(k, n):
                    kj, ij = k * n + j, i * n + j
                    for b in range(nb):
                        up_r, up_i, lo_r, lo_i = ar[kj, b], ai[kj, b], ar[ij, b], ai[ij, b]
                        yes = swap[b] > 0.0
                        ar[kj, b] = lo_r if yes else up_r
                        ar[ij, b] = up_r if yes else lo_r
                        ai[kj, b] = lo_i if yes else up_i
                        ai[ij, b] = up_i if yes else lo_i
                for b in range(nb):
                    up_r, up_i, lo_r, lo_i = xr[k, b], xi[k, b], xr[i, b], xi[i, b]
                    yes = swap[b] > 0.0
                    xr[k, b] = lo_r if yes else up_r
                    xr[i, b] = up_r if yes else lo_r
                    xi[k, b] = lo_i if yes else up_i
                    xi[i, b] = up_i if yes else lo_i
            for b in range(nb):
                inv = 1.0 / (ar[kk, b] ** 2 + ai[kk, b] ** 2)
                vr[k, b], vi[k, b] = ar[kk, b] * inv, -ai[kk, b] * inv
            for i in range(k + 1, n):
                ik = i * n + k
                for b in range(nb):
                    c0[b] = ar[ik, b] * vr[k, b] - ai[ik, b] * vi[k, b]
                    c1[b] = ar[ik, b] * vi[k, b] + ai[ik, b] * vr[k, b]
                for j in range(k + 1, n):
                    kj, ij = k * n + j, i * n + j
                    for b in range(nb):
                        ar[ij, b] = ar[ij, b] - (c0[b] * ar[kj, b] - c1[b] * ai[kj, b])
                        ai[ij, b] = ai[ij, b] - (c0[b] * ai[kj, b] + c1[b] * ar[kj, b])
                for b in range(nb):
                    xr[i, b] = xr[i, b] - (c0[b] * xr[k, b] - c1[b] * xi[k, b])
                    xi[i, b] = xi[i, b] - (c0[b] * xi[k, b] + c1[b] * xr[k, b])
        for k in range(n - 1, -1, -1):
            for j in range(k + 1, n):
                kj = k * n + j
                for b in range(nb):
                    xr[k, b] = xr[k, b] - (ar[kj, b] * xr[j, b] - ai[kj, b] * xi[j, b])
                    xi[k, b] = xi[k, b] - (ar[kj, b] * xi[j, b] + ai[kj, b] * xr[j, b])
            for b in range(nb):
                acc_r, acc_i = xr[k, b], xi[k, b]
                xr[k, b] = acc_r * vr[k, b] - acc_i * vi[k, b]
                xi[k, b] = acc_r * vi[k, b] + acc_i * vr[k, b]
        # P = -S u_w, u_rail = R P and the further points, the bodies back-substituted
        for i in range(n):
            for b in range(nb):
                c0[b], c1[b] = 0.0, 0.0
            lo, hi = (0, n) if full else (column_ptr[i], column_ptr[i + 1])
            for k in range(lo, hi):
                j = k if full else column_wheel[k]
                for b in range(nb):
                    c0[b] = c0[b] + (sr[i * n + j, b] * xr[j, b] - si[i * n + j, b] * xi[j, b])
                    c1[b] = c1[b] + (sr[i * n + j, b] * xi[j, b] + si[i * n + j, b] * xr[j, b])
            for b in range(nb):
                pr[i, b], pi[i, b] = -c0[b], -c1[b]
        for i in range(n_obs):
            for b in range(nb):
                c0[b] = rr[i * n, b] * pr[0, b] - ri[i * n, b] * pi[0, b]
                c1[b] = rr[i * n, b] * pi[0, b] + ri[i * n, b] * pr[0, b]
            for j in range(1, n):
                for b in range(nb):
                    c0[b] = c0[b] + (rr[i * n + j, b] * pr[j, b] - ri[i * n + j, b] * pi[j, b])
                    c1[b] = c1[b] + (rr[i * n + j, b] * pi[j, b] + ri[i * n + j, b] * pr[j, b])
            for b in range(nb):
                if i < n:
                    rail[start + b, i] = complex(c0[b], c1[b])
                else:
                    observed[start + b, i - n] = complex(c0[b], c1[b])
        for i in range(n):
            w = wheel_dof[i]
            for b in range(nb):
                ur[w, b], ui[w, b] = xr[i, b], xi[i, b]
        for st in range(n_step - 1, -1, -1):
            pd = pivot_dof[st]
            for b in range(nb):
                c0[b], c1[b] = 0.0, 0.0
            for k in range(nb_ptr[st], nb_ptr[st + 1]):
                nd = nb_dof[k]
                for b in range(nb):
                    c0[b] = c0[b] + (lr[k, b] * ur[nd, b] - li[k, b] * ui[nd, b])
                    c1[b] = c1[b] + (lr[k, b] * ui[nd, b] + li[k, b] * ur[nd, b])
            for b in range(nb):
                ur[pd, b], ui[pd, b] = -c0[b], -c1[b]
        for b in range(nb):
            q = start + b
            bad[q] = weak[b] > 0.0
            for i in range(n):
                force[q, i] = complex(pr[i, b], pi[i, b])
            for i in range(n_dof):
                u_v[q, i] = complex(ur[i, b], ui[i, b])
