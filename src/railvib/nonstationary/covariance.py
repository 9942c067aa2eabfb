"""The independent reference: the covariance (Lyapunov) differential equation.

An irregularity that is filtered white noise in space, ``dz/dx = F z + G w(x)``,
``r = H z``, with ``E[w(x) w(x')] = q delta(x - x')``, has the one-sided spatial PSD
``S(Omega) = (q / pi) |H (i Omega - F)^-1 G|^2`` m^2/(rad/m). Seen from a vehicle at
position ``s(t)`` the filter runs in time, ``z' = v F z + v G w(s(t))``, and
``w(s(t))`` is white in time with intensity ``q / v``, so the noise enters with
intensity ``q v(t)`` (Hammond and Harrison, J. Dyn. Syst. Meas. Control 1981). With
the vehicle's state ``x' = A x + B r`` the joint state ``X = [x; z]`` has the
covariance equation

    P' = A(t) P + P A(t)^T + q v(t) Gamma Gamma^T,   A(t) = [[A, B H], [0, v(t) F]],

integrated here with an explicit Runge-Kutta method of order 8 (``scipy``'s DOP853)
at a tolerance far below the 1 % compared. A single wheel only: the delayed copies
of the profile under trailing wheels have no finite-dimensional state.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import solve_ivp

from railvib.errors import CaseError
from railvib.nonstationary.profile import SpeedProfile
from railvib.nonstationary.statespace import RigidTrackVehicle
from railvib.spectra.base import SpatialSpectrum

__all__ = ["ShapingFilter", "covariance_response"]


@dataclass(frozen=True, eq=False)
class ShapingFilter(SpatialSpectrum):
    """A rational irregularity spectrum as a filter of spatial white noise (a reference model).

    Parameters
    ----------
    f : numpy.ndarray
        ``F``, 1/m, ``(m, m)``, stable (eigenvalues with negative real parts).
    g : numpy.ndarray
        ``G``, ``(m,)``.
    h : numpy.ndarray
        ``H``, ``(m,)``: ``r = H z``.
    intensity : float
        ``q``, m^2/m (white noise ``E[w(x) w(x')] = q delta(x - x')``).
    """

    f: NDArray[np.float64]
    g: NDArray[np.float64]
    h: NDArray[np.float64]
    intensity: float

    @classmethod
    def first_order(cls, variance: float, corner: float) -> ShapingFilter:
        """First-order filter ``dr/dx = -alpha r + w``: ``S = (q / pi) / (Omega^2 + alpha^2)``.

        Its variance is ``q / (2 alpha)``.

        Parameters
        ----------
        variance : float
            Variance of r, m^2.
        corner : float
            ``alpha``, rad/m.
        """
        return cls(np.array([[-corner]]), np.array([1.0]), np.array([1.0]), 2.0 * corner * variance)

    def psd(self, wavenumber: ArrayLike) -> NDArray[np.float64]:
        """One-sided PSD in m^2/(rad/m) at `wavenumber` (rad/m)."""
        om = np.atleast_1d(np.asarray(wavenumber, dtype=float))
        m = self.f.shape[0]
        resolvent = np.linalg.solve(1j * om[:, None, None] * np.eye(m) - self.f, self.g)
        return self.intensity / np.pi * np.abs(resolvent @ self.h) ** 2

    @property
    def covariance(self) -> NDArray[np.float64]:
        """Stationary covariance of z: ``F P + P F^T + q G G^T = 0``."""
        return _lyapunov(self.f, self.intensity * np.outer(self.g, self.g))


def _lyapunov(a: NDArray[np.float64], qq: NDArray[np.float64]) -> NDArray[np.float64]:
    """``P`` with ``A P + P A^T + Q = 0`` (Kronecker form; small systems)."""
    n = a.shape[0]
    eye = np.eye(n)
    p = np.linalg.solve(np.kron(eye, a) + np.kron(a, eye), -qq.reshape(-1))
    p = p.reshape(n, n)
    return 0.5 * (p + p.T)


def _system(
    a: NDArray[np.float64], bh: NDArray[np.float64], f: NDArray[np.float64], v: float
) -> NDArray[np.float64]:
    """The joint state matrix ``[[A, B H], [0, v F]]`` at speed `v` (m/s)."""
    return np.block([[a, bh], [np.zeros((f.shape[0], a.shape[0])), v * f]])


def covariance_response(
    model: RigidTrackVehicle, shaping: ShapingFilter, profile: SpeedProfile, t: ArrayLike
) -> NDArray[np.float64]:
    """Variances of the outputs of a one-wheel vehicle from the covariance equation.

    Starts from the stationary covariance at the start speed (at rest on the
    irregularity when it is 0), as the exact PEM's ``initial = "steady"``.

    Parameters
    ----------
    model : RigidTrackVehicle
        A vehicle with one wheel on its contact spring over a rigid rail.
    shaping : ShapingFilter
        The irregularity.
    profile : SpeedProfile
        The speed profile.
    t : array_like
        Output times, s, increasing, within the profile.

    Returns
    -------
    numpy.ndarray
        ``(n_t, n_out)``: variances of the outputs of :attr:`RigidTrackVehicle.matrices`.
    """
    if model.n_wheel != 1:
        raise CaseError("vehicle.wheels", model.n_wheel, "one wheel (the covariance reference)")
    a, b, c, d = model.matrices
    n, m = a.shape[0], shaping.f.shape[0]
    bh = b @ shaping.h[None, :]
    gamma = np.concatenate([np.zeros(n), shaping.g])
    noise = shaping.intensity * np.outer(gamma, gamma)
    c_aug = np.hstack([c, d @ shaping.h[None, :]])

    def system(time: float) -> NDArray[np.float64]:
        return _system(a, bh, shaping.f, float(profile.speed(time)))

    v0 = float(profile.speed(0.0))
    if v0 > 0:
        p0 = _lyapunov(system(0.0), v0 * noise)
    else:  # frozen filter: z stationary in space, the vehicle in static equilibrium on it
        tr = np.vstack([-np.linalg.solve(a, bh), np.eye(m)])
        p0 = tr @ shaping.covariance @ tr.T

    def rhs(time: float, flat: NDArray[np.float64]) -> NDArray[np.float64]:
        p = flat.reshape(n + m, n + m)
        ap = system(time) @ p
        return (ap + ap.T + float(profile.speed(time)) * noise).reshape(-1)

    t = np.asarray(t, dtype=float)
    # absolute tolerance per entry from the stationary covariance at the top speed, where
    # every state moves (at a start from rest the velocities are 0 at first)
    v_top = float(profile.v_max)
    d = np.diag(_lyapunov(_system(a, bh, shaping.f, v_top), v_top * noise))
    scale = np.sqrt(np.outer(d, d)).reshape(-1)
    sol = solve_ivp(
        rhs,
        (float(t[0]), float(t[-1])),
        p0.reshape(-1),
        method="DOP853",
        t_eval=t,
        rtol=1e-10,
        atol=1e-12 * scale,
    )
    if not sol.success:
        raise RuntimeError(f"covariance equation: {sol.message}")
    p_t = sol.y.T.reshape(t.size, n + m, n + m)
    return np.einsum("oi,tij,oj->to", c_aug, p_t, c_aug)
