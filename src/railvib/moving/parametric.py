"""Sleeper-passing (parametric) excitation: the vehicle's static loads moving over the supports.

On a smooth rail the only input is the vehicle's weight. Moving over the discrete
supports, each static wheel load meets a support stiffness that varies with the period
``d / v``; in steady state the contact forces, the wheels, the bodies and the rail under
the wheels are periodic, lines at ``n v / d``. Their harmonics follow from the harmonic
balance of :mod:`railvib.moving.harmonic` on the base frequency 0 with the static wheel
loads as the source (:meth:`~railvib.moving.harmonic.HarmonicSystem.solve`).

The **equivalent roughness** of a line is the irregularity at the wheels that gives the
same contact forces in the stationary model (the vehicle standing at its
``leading_wheel_position`` over the track): with that model's rail receptance ``R_s``
and ``P = -(S^-1 + R_s + I / k_H)^-1 r`` (paper Eq. 16), ``r_eq = -(S^-1 + R_s + I / k_H)
P_n``. Added at the line frequencies to a stationary analysis (per wheel, with its own
phase), it reproduces the parametric contact forces there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from railvib.coupling import CoupledSystem
from railvib.moving.harmonic import MovingSettings, check_moving, harmonic_blocks
from railvib.response import response_labels

__all__ = ["ParametricResponse", "parametric_response"]


@dataclass(frozen=True, eq=False)
class ParametricResponse:
    """The steady periodic response of the vehicle moving over a smooth rail.

    Every signal is ``y(t) = sum_n Y_n exp(i 2 pi n v t / d)`` (``t = 0``: the leading wheel
    at its ``leading_wheel_position``), ``n = -N .. N``, ``Y_-n = conj Y_n``.

    Attributes
    ----------
    passing_hz : float
        ``v / d``, Hz.
    orders : numpy.ndarray
        ``-N .. N``.
    vehicle : numpy.ndarray
        Vehicle DOF harmonics, m or rad, ``(2 N + 1, n_dof)`` (``n = 0``: the static
        displacement).
    rail : numpy.ndarray
        Rail under each wheel, m, ``(2 N + 1, n_wheel)``.
    contact_force : numpy.ndarray
        Contact force at each wheel (compressive positive), N, ``(2 N + 1, n_wheel)``
        (``n = 0``: the mean, the static wheel load).
    equivalent_roughness : numpy.ndarray
        Irregularity at each wheel that gives the lines' contact forces in the stationary
        model, m, ``(2 N + 1, n_wheel)`` (0 at ``n = 0``).
    dofs : tuple of str
        Vehicle DOF names.
    wheels : tuple of str
        Wheel names (a train's per car), or empty.
    """

    passing_hz: float
    orders: NDArray[np.int64]
    vehicle: NDArray[np.complex128]
    rail: NDArray[np.complex128]
    contact_force: NDArray[np.complex128]
    equivalent_roughness: NDArray[np.complex128]
    dofs: tuple[str, ...]
    wheels: tuple[str, ...] = ()

    @property
    def lines(self) -> NDArray[np.int64]:
        """The line orders ``1 .. N``."""
        return self.orders[self.orders > 0]

    @property
    def line_frequencies_hz(self) -> NDArray[np.float64]:
        """``n v / d`` of the lines ``n = 1 .. N``, Hz."""
        return np.asarray(self.lines * self.passing_hz, dtype=np.float64)

    @property
    def labels(self) -> tuple[str, ...]:
        """Displacement response labels: the vehicle DOFs, then ``rail@wheel<j>``."""
        return response_labels(self.dofs, self.rail.shape[1], self.wheels)

    def amplitude(self, which: str) -> NDArray[np.float64]:
        """Peak amplitude ``2 |Y_n|`` of the lines ``n = 1 .. N``.

        Parameters
        ----------
        which : str
            ``"contact_force"`` (N), ``"displacement"`` (vehicle DOFs then the rail, m or
            rad) or ``"equivalent_roughness"`` (m).

        Returns
        -------
        numpy.ndarray
            ``(N, n_wheel)`` or ``(N, n_resp)``.
        """
        if which == "displacement":
            y = np.concatenate([self.vehicle, self.rail], axis=1)
        else:
            y = getattr(self, which)
        return np.asarray(2.0 * np.abs(y[self.orders > 0]), dtype=np.float64)


def parametric_response(
    system: CoupledSystem, settings: MovingSettings | None = None, *, check: bool = True
) -> ParametricResponse:
    """Sleeper-passing lines of the vehicle moving at ``system.speed`` over a smooth rail.

    Parameters
    ----------
    system : CoupledSystem
        Vehicle, track, contact (N/m), leading wheel position (m) and speed (m/s).
    settings : MovingSettings, optional
        Harmonic order N (lines ``1 .. N``) and tolerance; default :class:`MovingSettings`.
    check : bool
        Run :func:`~railvib.moving.harmonic.check_moving` first (one-line errors).

    Returns
    -------
    ParametricResponse

    Examples
    --------
    >>> from railvib.case import build_system, load_preset_case
    >>> system = build_system(load_preset_case("wang2017_metro"))
    >>> res = parametric_response(system, MovingSettings(harmonic_order=2))
    >>> [round(float(f), 2) for f in res.line_frequencies_hz]
    [37.04, 74.07]
    """
    settings = MovingSettings() if settings is None else settings
    if check:
        top = settings.harmonic_order * system.speed / system.track.sleeper_spacing
        check_moving(system, top, settings)
    blocks = harmonic_blocks(system, [0.0], settings)
    n_w = blocks.stiffness.shape[2]
    h = blocks.orders.size
    loads = system.vehicle.static_wheel_loads()
    zero = np.zeros((1, h, n_w, 1), dtype=np.complex128)
    vehicle, force, rail = (a[0, :, :, 0] for a in blocks.solve(zero, loads))
    return ParametricResponse(
        blocks.passing_hz,
        blocks.orders,
        vehicle,
        rail,
        force,
        _equivalent_roughness(system, blocks.frequencies[0], force),
        system.vehicle.dofs,
        system.vehicle.wheel_names,
    )


def _equivalent_roughness(
    system: CoupledSystem, freqs: NDArray[np.float64], force: NDArray[np.complex128]
) -> NDArray[np.complex128]:
    """``r_eq = -(S^-1 + R_s + I / k_H) P_n`` at the lines ``n >= 1`` (conjugates below 0), m."""
    out = np.zeros_like(force)
    positive = freqs > 0.0
    f = freqs[positive]
    x = system.wheel_positions
    rec = system.track.receptance(f, x, x)
    s = system.vehicle.condensed_to_wheels(f).stiffness
    p = force[positive]
    r = -(np.linalg.solve(s, p[..., None])[..., 0] + np.einsum("fij,fj->fi", rec, p))
    r -= p / system.contact_stiffness
    out[positive] = r
    out[freqs < 0.0] = np.conj(r[::-1])
    return out
