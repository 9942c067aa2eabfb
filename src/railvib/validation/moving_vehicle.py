"""The vehicle moving along the finite track, integrated in time on a smooth rail (issue 17).

The independent check of :mod:`railvib.moving.parametric`: the wheels travel through the
Hermite mesh of :class:`~railvib.validation.finite_track.FiniteTrack` at constant speed
(each contact force applied, and the rail under each wheel read, by the cubic shape
functions at the wheel's position, re-evaluated every step, as
:mod:`railvib.validation.moving_load` does for one load), carrying the vehicle's static
loads through linear Hertz springs. Track (sparse, explicit sleeper DOFs) and vehicle
(dense) are integrated by Newmark's average-acceleration scheme; the contact forces of
each step are solved exactly from the two subsystems' step flexibilities (one sparse
solve per wheel and step), so the coupling is as implicit as a monolithic scheme.

The run starts from the static equilibrium at the start position with the quasi-static
velocity of the rolling deflection bowl (central difference of the static solutions a
small step either side), so the start-up transient is small; the contact forces are fitted
by ``sum_n P_n exp(i 2 pi n v t / d)`` over whole sleeper periods after `settle_periods`.
Nothing here uses the periodic track's waves, the moving-load receptance or a
frequency-domain solve.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.sparse.linalg import splu

from railvib.errors import CaseError
from railvib.validation.finite_track import FiniteTrack
from railvib.validation.moving_load import _load_dofs, _matrices
from railvib.vehicle.assembly import GRAVITY, Vehicle

__all__ = ["MovingVehicleFit", "simulate_moving_vehicle"]


@dataclass(frozen=True)
class MovingVehicleFit:
    """Harmonics fitted to the simulated contact forces and rail under the moving vehicle.

    Attributes
    ----------
    passing_hz : float
        ``v / d``, Hz.
    orders : numpy.ndarray
        ``-N .. N``.
    contact_force : numpy.ndarray
        ``P_n`` at each wheel, N, complex, ``(2 N + 1, n_wheel)``; ``t = 0`` at the start.
    rail : numpy.ndarray
        Rail under each wheel, m, ``(2 N + 1, n_wheel)``.
    residual : numpy.ndarray
        RMS misfit of the series over the fit window relative to the RMS of the dynamic
        contact force (dimensionless), ``(n_wheel,)``.
    history : numpy.ndarray
        The contact forces over the fit window, N, ``(n_samples, n_wheel)``.
    sample_rate : float
        Samples per second of `history`, Hz.
    """

    passing_hz: float
    orders: NDArray[np.int64]
    contact_force: NDArray[np.complex128]
    rail: NDArray[np.complex128]
    residual: NDArray[np.float64]
    history: NDArray[np.float64]
    sample_rate: float


def simulate_moving_vehicle(
    vehicle: Vehicle,
    track: FiniteTrack,
    contact_stiffness: float,
    speed: float,
    *,
    x_start: float,
    dt: float,
    settle_periods: int,
    fit_periods: int,
    order: int = 3,
    profile: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None,
) -> MovingVehicleFit:
    """Integrate the vehicle rolling at `speed` over the finite track, on a smooth rail or not.

    Parameters
    ----------
    vehicle : Vehicle
        Vehicle without frequency-dependent elements (springs and dampers only).
    track : FiniteTrack
        Finite track (spring-damper layers, Euler rail without loss factor) whose mesh holds
        the whole path of every wheel with margins (absorbing ends).
    contact_stiffness : float
        k_H per contact, N/m (> 0).
    speed : float
        v in m/s (> 0).
    x_start : float
        Position of the leading wheel at ``t = 0``, m.
    dt : float
        Largest time step, s; rounded down to a whole number of steps per sleeper period.
    settle_periods, fit_periods : int
        Sleeper periods ``d / v`` before the fit, and fitted (counts >= 1).
    order : int
        Harmonics ``|n| <= order`` fitted (a count).
    profile : (numpy.ndarray, numpy.ndarray), optional
        An irregularity ``(x, r)`` along the rail (m, m; positive a dip), read at each
        wheel's position (linear interpolation; it must cover every wheel's path). None:
        a smooth rail.

    Returns
    -------
    MovingVehicleFit
    """
    if not (np.isfinite(speed) and speed > 0):
        raise CaseError("speed", speed, "must be > 0 (m/s)")
    if vehicle.elements:
        raise CaseError("vehicle", "frequency-dependent elements", "springs and dampers only")
    d = track.sleeper_spacing
    period = d / speed
    steps_per_period = int(np.ceil(period / dt))
    dt = period / steps_per_period
    n_steps = (settle_periods + fit_periods) * steps_per_period
    offsets = vehicle.wheel_offsets
    lo, hi = track.nodes[0], track.nodes[-1]
    path = (x_start - offsets.max(), x_start + n_steps * dt * speed)
    if not (lo < path[0] and path[1] < hi):
        raise CaseError("x_start", x_start, f"a path {path} inside [{lo}, {hi}] (m)")
    if profile is not None and not (profile[0][0] <= path[0] and path[1] <= profile[0][-1]):
        raise CaseError("profile", "too short", f"covering the wheels' path {path} (m)")

    m_t, c_t, k_t = (a.tocsc() for a in _matrices(track))
    n_t = m_t.shape[0]
    m_v, c_v, k_v = vehicle.mass_matrix, vehicle.damping_matrix, vehicle.stiffness_matrix
    b = vehicle.wheel_matrix  # (n_dof, n_w)
    n_w = b.shape[1]
    weight = np.zeros(len(vehicle.dofs))
    for body in vehicle.bodies:
        weight[vehicle.dofs.index(f"{body.name}.bounce")] = body.mass * GRAVITY
    k_h = float(contact_stiffness)

    def positions(t: float) -> NDArray[np.float64]:
        return np.asarray(x_start - offsets + speed * t, dtype=np.float64)

    def shape(t: float) -> sp.csr_matrix:
        rows, weights = _load_dofs(track, positions(t))  # (n_w, 4) each
        cols = np.repeat(np.arange(n_w), 4)
        return sp.csr_matrix((weights.ravel(), (cols, rows.ravel())), shape=(n_w, n_t))

    def static(t: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        n = shape(t)
        full = sp.bmat(
            [
                [k_t + k_h * (n.T @ n), -k_h * (n.T @ sp.csr_matrix(b.T))],
                [-k_h * (sp.csr_matrix(b) @ n), sp.csr_matrix(k_v + k_h * (b @ b.T))],
            ],
            format="csc",
        )
        u = splu(full).solve(np.concatenate([np.zeros(n_t), weight]))
        return u[:n_t], u[n_t:]

    # start: static equilibrium, quasi-static velocity of the rolling bowl
    delta = 0.25 * dt
    u_t, u_v = static(0.0)
    ahead, behind = static(delta), static(-delta)
    v_t = (ahead[0] - behind[0]) / (2.0 * delta)
    v_v = (ahead[1] - behind[1]) / (2.0 * delta)
    a_t = -splu(m_t).solve(c_t @ v_t)  # K u = F at the start: M a = -C v
    a_v = -np.linalg.solve(m_v, c_v @ v_v)

    c_a, c_vel, c_d = 4.0 / dt**2, 4.0 / dt, 2.0 / dt
    lu_t = splu((k_t + c_d * c_t + c_a * m_t).tocsc())
    eff_v = k_v + c_d * c_v + c_a * m_v
    flex_v = b.T @ np.linalg.solve(eff_v, b)  # wheel displacement per wheel force, m/N
    fit_start = settle_periods * steps_per_period
    n_fit = fit_periods * steps_per_period
    force = np.zeros((n_fit, n_w))
    rail = np.zeros((n_fit, n_w))
    for step in range(n_steps):
        t1 = (step + 1) * dt
        n1 = shape(t1)
        hist_t = m_t @ (c_a * u_t + c_vel * v_t + a_t) + c_t @ (c_d * u_t + v_t)
        hist_v = m_v @ (c_a * u_v + c_vel * v_v + a_v) + c_v @ (c_d * u_v + v_v)
        cols = lu_t.solve(np.column_stack([hist_t, n1.T.toarray()]))
        free_t, unit_t = cols[:, 0], cols[:, 1:]
        free_v = np.linalg.solve(eff_v, hist_v + weight)
        # P = k_H (B^T u_v - N u_t), u_v = free_v - eff_v^-1 B P, u_t = free_t + unit_t P
        gap = b.T @ free_v - n1 @ free_t
        if profile is not None:
            gap -= np.interp(positions(t1), profile[0], profile[1])
        p = np.linalg.solve(np.eye(n_w) / k_h + flex_v + n1 @ unit_t, gap)
        u_t1 = free_t + unit_t @ p
        u_v1 = free_v - np.linalg.solve(eff_v, b @ p)
        a_t = c_a * (u_t1 - u_t) - c_vel * v_t - a_t
        v_t = c_d * (u_t1 - u_t) - v_t
        a_v = c_a * (u_v1 - u_v) - c_vel * v_v - a_v
        v_v = c_d * (u_v1 - u_v) - v_v
        u_t, u_v = u_t1, u_v1
        if step >= fit_start:
            force[step - fit_start] = p
            rail[step - fit_start] = n1 @ u_t
    t = (fit_start + 1 + np.arange(n_fit)) * dt
    orders = np.arange(-order, order + 1)
    basis = np.exp(-2j * np.pi * speed / d * orders[None, :] * t[:, None])  # (n_t, H)
    p_n = basis.T @ force / n_fit
    r_n = basis.T @ rail / n_fit
    series = (basis.conj() @ p_n).real
    dynamic = force - force.mean(axis=0)
    misfit = np.sqrt(np.mean((force - series) ** 2, axis=0))
    residual = misfit / np.maximum(np.sqrt(np.mean(dynamic**2, axis=0)), np.finfo(float).tiny)
    return MovingVehicleFit(speed / d, orders, p_n, r_n, residual, force, 1.0 / dt)
