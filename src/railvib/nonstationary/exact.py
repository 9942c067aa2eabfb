"""The exact non-stationary pseudo-excitation method on a rigid track.

For each wavenumber ``Omega_k`` the pseudo irregularity ``a_k exp(i Omega_k x)``
(``a_k = sqrt(S(Omega_k) dOmega_k)``) is met by wheel j at ``x_j(t) = s(t) - o_j``
(``s`` the leading wheel's position from the profile, ``o_j`` the wheel's offset
behind it), so the input is ``a_k exp(i Omega_k (s(t) - o_j))``. The vehicle's modes
``eta' = lambda eta + V^-1 B r(t)`` are stepped exactly for an input whose phase is
linear over the step (``Omega_k`` times the chord of ``s``):

    eta_{n+1} = e^{lambda h} eta_n + beta_n (e^{i w h} - e^{lambda h}) / (i w - lambda),

``w = Omega_k (s_{n+1} - s_n) / h``, all wavenumbers and modes at once, plus the
first-order term of the phase's departure from its chord, ``Omega a u (u - h) / 2``
(:func:`_curvature`, in closed form). The chord alone is off by at most
``delta = Omega_max |a_max| h^2 / 8`` rad (:func:`phase_error_bound`), and its
frequency steps at each step boundary ring the lightly damped fast modes (the wheelsets
on their contact springs): for the paper's car braking at 1 m/s^2 with wavelengths
down to 1 m that was 2.4 % of the largest RMS at the Nyquist step; with the
correction the error is of order ``delta^2``: 3e-7 at the Nyquist step, 1e-7 at the
default step (half of it; docs/nonstationary.md). Then ``sigma_y^2(t) = sum_k
|y_k(t)|^2`` and ``S_y(Omega; t) = |y_k(t)|^2 / dOmega_k`` (Lin's non-stationary
PEM; Lin, Zhang, Zhao and Williams, J. Sound Vib. 1997; Zhang, Lin et al.,
Vehicle Syst. Dyn. 2010), and the spectral moments of the crossing rates from the
pseudo velocities.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from railvib.errors import CaseError
from railvib.nonstationary.band import SpatialBand
from railvib.nonstationary.profile import SpeedProfile
from railvib.nonstationary.statespace import RigidTrackVehicle

__all__ = ["MomentHistory", "exact_response", "phase_error_bound", "time_axis"]

#: steps whose outputs are formed together (one matrix product per block): 4 steps of 10^3
#: wavenumbers keep the block's temporaries (3 MB) in cache; 64 took 1.5 times as long
STEP_BLOCK = 4
#: below this ``|z| = |(i w - lambda) h|`` the step's integral is summed as a series (the
#: quotient loses about 1e-16 / |z| of its digits: 1e-14 here)
_SERIES = 1e-2


@dataclass(frozen=True, eq=False)
class MomentHistory:
    """Second moments of the outputs against time, and the PSD snapshots.

    Attributes
    ----------
    t : numpy.ndarray
        Times, s, ``(n_t,)``.
    variance : numpy.ndarray
        ``E[y^2]``, ``(n_t, n_out)`` (output unit^2).
    velocity_variance : numpy.ndarray
        ``E[y'^2]``, ``(n_t, n_out)`` ((output unit / s)^2).
    cross : numpy.ndarray
        ``E[y y'] = d(E[y^2])/dt / 2``, ``(n_t, n_out)``.
    first_moment : numpy.ndarray
        ``lambda_1 = sum_k Im(conj(y_k) y'_k)`` (the non-stationary first spectral moment),
        ``(n_t, n_out)``.
    map_index : numpy.ndarray
        Indices into `t` of the snapshots, ``(n_map,)``.
    psd_wavenumber : numpy.ndarray
        ``S_y(Omega_k; t) = |y_k|^2 / dOmega_k`` at the snapshots, ``(n_map, n_wavenumber,
        n_out)``, output unit^2/(rad/m).
    """

    t: NDArray[np.float64]
    variance: NDArray[np.float64]
    velocity_variance: NDArray[np.float64]
    cross: NDArray[np.float64]
    first_moment: NDArray[np.float64]
    map_index: NDArray[np.intp]
    psd_wavenumber: NDArray[np.float64]


def time_axis(duration: float, dt: float) -> NDArray[np.float64]:
    """Step times from 0 to `duration` (s) with the largest equal step <= `dt` (s)."""
    n = max(1, int(np.ceil(duration / dt - 1e-9)))
    return np.linspace(0.0, duration, n + 1)


def phase_error_bound(band: SpatialBand, profile: SpeedProfile, dt: float) -> float:
    """Largest phase error of the input's chord over a step, ``Omega_max |a|_max h^2 / 8``, rad.

    The integrator takes the first-order term of that error exactly; what is left of the
    response's relative error is of the order of the square of this bound.

    Parameters
    ----------
    band : SpatialBand
        The wavenumbers (rad/m).
    profile : SpeedProfile
        The speed profile (its largest acceleration, m/s^2).
    dt : float
        Time step, s.

    Returns
    -------
    float
        The bound in rad.
    """
    return float(band.wavenumber.max() * profile.acceleration_max * dt**2 / 8.0)


def exact_response(
    model: RigidTrackVehicle,
    profile: SpeedProfile,
    band: SpatialBand,
    dt: float,
    *,
    initial: str = "steady",
    map_times: int = 101,
    progress: Callable[[int], None] | None = None,
) -> MomentHistory:
    """Integrate the pseudo responses of every wavenumber through the speed profile.

    Parameters
    ----------
    model : RigidTrackVehicle
        The vehicle on its contact springs over a rigid rail.
    profile : SpeedProfile
        Position and speed against time.
    band : SpatialBand
        Wavenumbers and pseudo-excitation amplitudes.
    dt : float
        Largest time step, s (the steps are equal; see :func:`time_axis`).
    initial : {"steady", "rest"}
        steady: the stationary response at the start speed (at rest on the irregularity
        when it is 0); rest: all states zero (a start-up transient follows).
    map_times : int
        Snapshots of the PSD, spread evenly over the steps.
    progress : callable, optional
        Called with the number of steps just done.

    Returns
    -------
    MomentHistory
        Outputs in the order of :attr:`RigidTrackVehicle.matrices` (DOF displacements,
        DOF accelerations, contact forces).
    """
    if initial not in ("steady", "rest"):
        raise CaseError("nonstationary.initial_state", initial, "one of 'steady', 'rest'")
    lam, bm, cm = model.modes
    _, _, _, d = model.matrices
    t = time_axis(profile.duration, dt)
    s = profile.position(t)
    v = profile.speed(t)
    om, amp = band.wavenumber, band.amplitude
    offsets = model.vehicle.wheel_offsets
    back = np.exp(-1j * om[:, None] * offsets[None, :])  # (n_om, n_wheel)
    q = amp[:, None] * (back @ bm.T)  # modal input per unit phase, (n_om, n_mode)
    dr = amp[:, None] * (back @ d.T)  # direct feed-through, (n_om, n_out)
    cmt = np.ascontiguousarray(cm.T)  # (n_mode, n_out)
    both = np.hstack([cmt, lam[:, None] * cmt])  # outputs and their rates from the modes
    qc = q @ cmt  # the rate's term of the input through the modes, (n_om, n_out)
    n_t, n_out = t.size, cm.shape[0]
    map_index = np.unique(np.linspace(0, n_t - 1, max(2, int(map_times))).round().astype(np.intp))
    out = {k: np.empty((n_t, n_out)) for k in ("var", "dvar", "cross", "l1")}
    psd = np.empty((map_index.size, om.size, n_out))
    phase0 = np.exp(1j * om * s[0])
    if initial == "steady":
        eta = phase0[:, None] * q / (1j * om[:, None] * v[0] - lam[None, :])
    else:
        eta = np.zeros_like(q)
    block_eta = np.empty((STEP_BLOCK,) + q.shape, dtype=complex)
    block_phase = np.empty((STEP_BLOCK, om.size), dtype=complex)
    filled, start = 0, 0
    h_last, e_lam, series = -1.0, np.ones_like(lam), np.zeros(lam.shape, dtype=bool)
    work = np.empty_like(q)
    prev_phase = phase0
    for n in range(n_t):
        phase = np.exp(1j * om * s[n])
        if n > 0:
            h = t[n] - t[n - 1]
            if h != h_last:  # |z| >= |Re(lambda)| h: only lightly damped modes may need the series
                h_last, e_lam, series = h, np.exp(lam * h), np.abs(lam.real) * h <= _SERIES
            w = om * (s[n] - s[n - 1]) / h
            e_iw = phase * np.conj(prev_phase)  # exp(i w h), exact
            np.subtract(1j * w[:, None], lam[None, :], out=work)  # i w - lambda
            integral = e_iw[:, None] - e_lam[None, :]
            with np.errstate(divide="ignore", invalid="ignore"):  # the series covers z ~ 0
                integral /= work
            accel = (v[n] - v[n - 1]) / h
            if accel != 0.0:  # the phase's parabola off its chord, to first order
                integral += (0.5j * accel * om)[:, None] * _curvature(integral, e_iw, work, h)
            if series.any():
                _series_fix(integral, work, e_lam, h, series, 0.5j * accel * om)
            eta *= e_lam[None, :]
            integral *= q
            integral *= prev_phase[:, None]
            eta += integral
        prev_phase = phase
        block_eta[filled] = eta
        block_phase[filled] = phase
        filled += 1
        if filled == STEP_BLOCK or n == n_t - 1:
            _moments(
                block_eta[:filled],
                block_phase[:filled],
                qc,
                both,
                dr,
                om,
                v[start : n + 1],
                out,
                start,
            )
            if progress is not None:
                progress(filled)
            start, filled = n + 1, 0
        if n in map_index:
            y = eta @ cmt + phase[:, None] * dr
            psd[np.searchsorted(map_index, n)] = np.abs(y) ** 2 / band.width[:, None]
    return MomentHistory(t, out["var"], out["dvar"], out["cross"], out["l1"], map_index, psd)


def _curvature(
    integral: NDArray[np.complex128],
    e_iw: NDArray[np.complex128],
    iw_lam: NDArray[np.complex128],
    h: float,
) -> NDArray[np.complex128]:
    """``int_0^h e^{lambda (h - u)} e^{i w u} u (u - h) du`` from the step's integral.

    With ``e^{lambda h} I_k = int_0^h e^{lambda (h - u)} e^{i w u} u^k du``, ``I_1 = (h e^{i w
    h} - I_0) / z`` and ``I_2 = (h^2 e^{i w h} - 2 I_1) / z`` (``z = i w - lambda``; the
    recursion loses ``1e-16 / |z h|^2`` of its digits, 1e-12 at the series' threshold).
    The true phase over a step is the chord plus ``Omega a u (u - h) / 2``; this is the
    first-order term of its exponential, so the frequency's step at a step boundary does
    not ring the lightly damped modes.
    """
    with np.errstate(divide="ignore", invalid="ignore"):  # the series covers z ~ 0
        i1 = (h * e_iw[:, None] - integral) / iw_lam
        return (h * h * e_iw[:, None] - 2.0 * i1) / iw_lam - h * i1


def _series_fix(
    integral: NDArray[np.complex128],
    iw_lam: NDArray[np.complex128],
    e_lam: NDArray[np.complex128],
    h: float,
    modes: NDArray[np.bool_],
    curve: NDArray[np.complex128],
) -> None:
    """The step integrals of the lightly damped `modes` where ``|z| <= _SERIES``, as a series.

    ``(e^{i w h} - e^{lambda h}) / (i w - lambda) = h e^{lambda h} (e^z - 1) / z`` with
    ``z = (i w - lambda) h``, the series to ``z^4`` exact to ``|z|^5 / 720 < 2e-13``; and
    `curve` (``i Omega a / 2``, per wavenumber) times :func:`_curvature`, ``-h^3
    e^{lambda h} sum_k z^k / (k! (k + 2)(k + 3))``, to ``z^3``.
    """
    cols = np.flatnonzero(modes)
    z = iw_lam[:, cols] * h
    small = np.abs(z) <= _SERIES
    if small.any():
        zs = z[small]
        series = h * (1 + zs / 2 * (1 + zs / 3 * (1 + zs / 4 * (1 + zs / 5))))
        bend = -(h**3) * (1 / 6 + zs * (1 / 12 + zs * (1 / 40 + zs / 180)))
        rows = np.broadcast_to(curve[:, None], z.shape)[small]
        block = integral[:, cols]
        block[small] = (series + rows * bend) * np.broadcast_to(e_lam[cols], z.shape)[small]
        integral[:, cols] = block


def _moments(
    eta: NDArray[np.complex128],
    phase: NDArray[np.complex128],
    qc: NDArray[np.complex128],
    cmt: NDArray[np.complex128],
    dr: NDArray[np.complex128],
    om: NDArray[np.float64],
    v: NDArray[np.float64],
    out: dict[str, NDArray[np.float64]],
    start: int,
) -> None:
    """Second moments of a block of steps into `out` from row `start` (in place).

    `cmt` is ``[(C V)^T, diag(lambda) (C V)^T]``: one product gives the outputs and the
    modal part of their rates.
    """
    n_b, n_om, n_mode = eta.shape
    n_out = dr.shape[1]
    both = (eta.reshape(n_b * n_om, n_mode) @ cmt).reshape(n_b, n_om, 2 * n_out)
    y, dy = both[..., :n_out], both[..., n_out:]
    y += phase[..., None] * dr[None]
    # y' = C V (lambda eta + V^-1 B r) + D r', r' = i Omega v r
    dy += phase[..., None] * (qc[None] + (1j * om[None, :] * v[:, None])[..., None] * dr[None])
    yr, yi, dr_, di = y.real, y.imag, dy.real, dy.imag
    rows = slice(start, start + n_b)
    out["var"][rows] = np.sum(yr * yr + yi * yi, axis=1)
    out["dvar"][rows] = np.sum(dr_ * dr_ + di * di, axis=1)
    out["cross"][rows] = np.sum(yr * dr_ + yi * di, axis=1)  # Re(conj(y) y')
    out["l1"][rows] = np.sum(yr * di - yi * dr_, axis=1)  # Im(conj(y) y')
