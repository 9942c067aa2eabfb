"""A harmonic point load moving along the finite track, integrated in time (issue 17).

The independent check of :mod:`railvib.track.moving`: the load travels through the
Hermite mesh of :class:`~railvib.validation.finite_track.FiniteTrack` (consistent nodal
forces from the cubic shape functions at its position, re-evaluated every step), the
track is integrated by Newmark's average-acceleration scheme (one factorisation, all
load frequencies as columns of one right-hand side, cosine and sine forcing apart), and
the rail displacement under the load (interpolated with the same shape functions) is
fitted, over an integer number of sleeper periods ``d / v`` after the start-up has died
out, by the harmonic series ``exp(i Omega t) sum_n A_n exp(i n 2 pi v t / d)``. Nothing
here uses the periodic track's waves, its lattice sums or a frequency-domain solve.

The finite track must be integrable in time: an Euler rail without loss factor and
spring-damper layers (pad, and for a ballasted track ballast, with explicit sleeper
DOFs). Newmark's scheme answers a harmonic at ``f`` as the continuous system does at
``tan(pi f dt) / (pi dt)`` (:func:`~railvib.validation.time_domain.newmark_frequency_warp`):
choose ``dt`` for the accuracy needed (``dt = 1e-5`` s: 5e-4 at 1.2 kHz).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray
from scipy.sparse.linalg import splu

from railvib.errors import CaseError
from railvib.validation.finite_track import FiniteTrack
from railvib.validation.scope import check_rail, viscous_pad

__all__ = ["MovingLoadFit", "hermite_shape_functions", "simulate_moving_load"]


@dataclass(frozen=True)
class MovingLoadFit:
    """Harmonics fitted to the simulated rail response under the moving load.

    Attributes
    ----------
    f : numpy.ndarray
        Load frequencies, Hz, ``(n_freq,)``.
    orders : numpy.ndarray
        Harmonic orders ``-N .. N``.
    amplitudes : numpy.ndarray
        ``A_n`` in m/N, complex, ``(n_freq, 2 N + 1)``; the load is on a sleeper at ``t = 0``.
    residual : numpy.ndarray
        RMS misfit of the series over the fit window relative to the RMS response
        (dimensionless), ``(n_freq,)``: what start-up transients and harmonics beyond N leave.
    """

    f: NDArray[np.float64]
    orders: NDArray[np.int64]
    amplitudes: NDArray[np.complex128]
    residual: NDArray[np.float64]

    @property
    def mean(self) -> NDArray[np.complex128]:
        """``A_0`` in m/N, ``(n_freq,)``."""
        return self.amplitudes[:, self.orders.size // 2]


def hermite_shape_functions(xi: ArrayLike, length: ArrayLike) -> NDArray[np.float64]:
    """Cubic Hermite shape functions of a beam element at local coordinates `xi`.

    Parameters
    ----------
    xi : array_like
        Position in the element divided by its length (dimensionless, 0..1).
    length : array_like
        Element length in m (broadcast with `xi`).

    Returns
    -------
    numpy.ndarray
        ``(..., 4)``: weights of ``(w_1, theta_1, w_2, theta_2)`` (theta in rad, times m).
    """
    x = np.asarray(xi, dtype=float)
    h = np.asarray(length, dtype=float)
    x2, x3 = x * x, x * x * x
    return np.stack(
        [1.0 - 3.0 * x2 + 2.0 * x3, h * (x - 2.0 * x2 + x3), 3.0 * x2 - 2.0 * x3, h * (x3 - x2)],
        axis=-1,
    )


def simulate_moving_load(
    track: FiniteTrack,
    f: ArrayLike,
    speed: float,
    *,
    dt: float,
    x_start: float,
    settle_periods: int,
    fit_periods: int,
    order: int = 2,
    ramp_periods: int = 2,
) -> MovingLoadFit:
    """Integrate the finite track under a unit harmonic load moving at `speed`.

    The load ``ramp(t) exp(i 2 pi f t)`` (N) is at ``x = v t``: it starts at rest at
    `x_start` (a sleeper), its amplitude rises over `ramp_periods` sleeper periods (half a
    cosine), and after `settle_periods` more the response under it is fitted over
    `fit_periods` periods.

    Parameters
    ----------
    track : FiniteTrack
        Finite track whose mesh covers the whole path with margins (absorbing ends).
    f : array_like
        Load frequencies in Hz (>= 0; 0 is a constant load), ``(n_freq,)``.
    speed : float
        v in m/s (> 0).
    dt : float
        Largest time step in s; rounded down to a whole number of steps per period.
    x_start : float
        Start position of the load, m: a sleeper position ``j d`` inside the mesh.
    settle_periods, fit_periods : int
        Sleeper periods ``d / v`` to wait after the ramp, and to fit over (counts >= 1).
    order : int
        Harmonics ``|n| <= order`` fitted (a count).
    ramp_periods : int
        Periods over which the load amplitude rises (a count >= 1).

    Returns
    -------
    MovingLoadFit
    """
    d = track.sleeper_spacing
    f = np.atleast_1d(np.asarray(f, dtype=float))
    if not (np.isfinite(speed) and speed > 0):
        raise CaseError("moving.speed_m_per_s", speed, "> 0 (m/s)")
    if abs(x_start / d - round(x_start / d)) > 1e-9:
        raise CaseError("x_start", x_start, f"a sleeper position, a multiple of {d} (m)")
    period = d / speed
    steps_per_period = int(np.ceil(period / dt))
    dt = period / steps_per_period
    n_periods = ramp_periods + settle_periods + fit_periods
    n_steps = n_periods * steps_per_period
    x_end = x_start + n_periods * d
    lo, hi = track.nodes[0], track.nodes[-1]
    if not (lo < x_start and x_end < hi):
        raise CaseError("x_start", x_start, f"a path [{x_start}, {x_end}] inside [{lo}, {hi}] (m)")

    m, c, k = _matrices(track)
    lu = splu((k + (2.0 / dt) * c + (4.0 / dt**2) * m).tocsc())
    history = sp.hstack([(4.0 / dt) * m + 2.0 * c, 2.0 * m], format="csr")
    n = m.shape[0]
    n_col = 2 * f.size  # cosine and sine forcing of every frequency
    state = np.zeros((2 * n, n_col))
    vel, acc = state[:n], state[n:]
    disp = np.zeros((n, n_col))

    t0 = x_start / speed
    t = np.asarray(t0 + np.arange(n_steps + 1) * dt, dtype=np.float64)
    ramp_end = t0 + ramp_periods * period
    envelope = np.where(t < ramp_end, 0.5 - 0.5 * np.cos(np.pi * (t - t0) / (ramp_end - t0)), 1.0)
    phase = 2.0 * np.pi * f[None, :] * t[:, None]
    load = envelope[:, None, None] * np.stack([np.cos(phase), np.sin(phase)], axis=2)
    load = load.reshape(n_steps + 1, n_col)  # columns (f0 cos, f0 sin, f1 cos, ...)
    rows, weights = _load_dofs(track, speed * t)

    fit_start = n_steps - fit_periods * steps_per_period
    under = np.zeros((fit_periods * steps_per_period, n_col))
    c_a, c_v, two_dt = 4.0 / dt**2, 4.0 / dt, 2.0 / dt
    for step in range(n_steps):
        rhs = history @ state
        np.add.at(rhs, rows[step + 1], weights[step + 1][:, None] * load[step + 1][None, :])
        np.subtract.at(rhs, rows[step], weights[step][:, None] * load[step][None, :])
        du = lu.solve(rhs)
        disp += du
        acc *= -1.0
        acc += c_a * du - c_v * vel
        vel *= -1.0
        vel += two_dt * du
        if step + 1 > fit_start:  # samples fit_start+1 .. n_steps: whole periods
            under[step - fit_start] = weights[step + 1] @ disp[rows[step + 1]]
    return _fit(f, speed / d, t[fit_start + 1 :], under, order)


def _matrices(track: FiniteTrack) -> tuple[sp.csc_matrix, sp.csc_matrix, sp.csc_matrix]:
    """Real ``(M, C, K)`` of the finite track, with explicit sleeper DOFs if ballasted."""
    if track.ballast is None:
        return track.time_domain_matrices()
    check_rail(track.rail, time_domain=True)
    layers = {"pad": track.pad, "ballast": track.ballast, "subgrade": track.subgrade}
    for name, model in layers.items():
        if model is not None and viscous_pad(model) is None:
            raise CaseError(f"track.{name}", type(model).__name__, "a spring_damper model")
    # the layers' matrix is K_l + i omega C_l - omega^2 M_l for viscous layers: read off at
    # two frequencies (exact, no fit)
    w1, w2 = 2.0 * np.pi, 4.0 * np.pi
    p1, p2 = track.pad_matrix(1.0), track.pad_matrix(2.0)
    m_layers = (p1.real - p2.real) / (w2**2 - w1**2)
    k_layers = p1.real + w1**2 * m_layers
    c_layers = p1.imag / w1
    m = (track.mass_matrix + m_layers).tocsc()
    c = sp.csc_matrix(c_layers)
    k = (track.rail_stiffness_matrix + k_layers).tocsc()
    return m, c, k


def _load_dofs(track: FiniteTrack, x: NDArray[np.float64]) -> tuple[NDArray, NDArray]:
    """DOFs ``(n_t, 4)`` and shape-function weights ``(n_t, 4)`` of the load at positions `x`."""
    nodes = track.nodes
    element = np.clip(np.searchsorted(nodes, x, side="right") - 1, 0, nodes.size - 2)
    length = nodes[element + 1] - nodes[element]
    xi = (x - nodes[element]) / length
    rows = 2 * element[:, None] + np.arange(4)[None, :]
    return rows, hermite_shape_functions(xi, length)


def _fit(
    f: NDArray[np.float64],
    passing_hz: float,
    t: NDArray[np.float64],
    under: NDArray[np.float64],
    order: int,
) -> MovingLoadFit:
    """Fourier coefficients of ``u exp(-i Omega t)`` over whole sleeper periods."""
    z = under[:, 0::2] + 1j * under[:, 1::2]  # response to exp(i Omega t), (n_t, n_freq)
    carrier = z * np.exp(-2j * np.pi * f[None, :] * t[:, None])
    orders = np.arange(-order, order + 1)
    basis = np.exp(-2j * np.pi * passing_hz * orders[None, :] * t[:, None])  # (n_t, n_harm)
    amplitudes = carrier.T @ basis / t.size  # exact for whole periods, uniform samples
    series = amplitudes @ basis.conj().T  # (n_freq, n_t)
    misfit = np.sqrt(np.mean(np.abs(carrier.T - series) ** 2, axis=1))
    scale = np.sqrt(np.mean(np.abs(carrier) ** 2, axis=0))
    return MovingLoadFit(f, orders, amplitudes, misfit / scale)
