"""Random response of the moving vehicle: harmonic transfer functions and cyclostationary PSDs.

A pseudo irregularity ``exp(i omega t)`` at the leading wheel (delayed by ``s_j / v`` at
wheel ``j``, as in :mod:`railvib.pem`) drives every response at ``omega + n Omega_s``:
``y(t) = exp(i omega t) sum_n H_n(omega) exp(i n Omega_s t)`` (``Omega_s = 2 pi v / d``),
the harmonic transfer functions of the linear periodically time-varying system. One
harmonic-balance solve per frequency (:class:`~railvib.moving.harmonic.HarmonicSystem`,
``(2 N + 1) n_wheel`` unknowns, vectorised over frequency) with the pseudo input in every
harmonic slot at once gives both:

* the input in slot 0: ``H_n(f)`` for ``n = -N .. N`` (:attr:`MovingFRF.harmonics`), whose
  phase-resolved (evolutionary) PSD ``|sum_n H_n(f) exp(i n Omega_s tau)|^2 S_r(f)`` shows
  the variation over the sleeper period (``tau`` in ``[0, d / v)``, input frequency ``f``);
* the input in slot ``-n``, the response in slot 0: ``H_n(f - n v / d)``
  (:attr:`MovingFRF.arriving`), so the time-averaged PSD on the grid itself is::

      S_y(f) = sum_n |H_n(f - n v / d)|^2 S_r(|f - n v / d|),

  one-sided (``H_n(-f) = conj H_{-n}(f)`` of the real system folds the negative input
  frequencies onto the positive ones). Inputs below the grid's lowest frequency are left
  out, as a stationary run on that grid leaves them out.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.coupling import CoupledSystem
from railvib.errors import SolverWarning
from railvib.moving.harmonic import (
    MovingSettings,
    check_moving,
    harmonic_blocks,
    load_receptances,
)
from railvib.pem import wheel_delays
from railvib.response import response_labels
from railvib.spectra.base import SpatialSpectrum

__all__ = ["FREQUENCY_BLOCK", "MovingFRF", "moving_frf"]

#: base frequencies solved at once (each holds (2N+1)^2 n_w^2 blocks)
FREQUENCY_BLOCK = 256


@dataclass(frozen=True, eq=False)
class MovingFRF:
    """Harmonic transfer functions of the moving vehicle, per metre of irregularity.

    Responses are stacked as in :class:`railvib.response.FRF`: displacements (the vehicle
    DOFs, then the rail under each wheel, m/m or rad/m) and contact forces (N/m).

    Attributes
    ----------
    f : numpy.ndarray
        Grid frequencies, Hz, ``(n_freq,)``.
    passing_hz : float
        ``v / d``, Hz.
    speed : float
        v, m/s.
    orders : numpy.ndarray
        ``-N .. N``.
    harmonics : tuple of numpy.ndarray
        ``H_n(f)``: (displacement ``(n_freq, H, n_resp)``, contact force ``(n_freq, H,
        n_wheel)``); harmonic ``n`` at ``f + n v / d``.
    arriving : tuple of numpy.ndarray
        ``H_n(f - n v / d)``: the response at ``f`` to the input at ``f - n v / d``, same
        shapes (index ``n + N``).
    dofs : tuple of str
        Vehicle DOF names.
    wheels : tuple of str
        Wheel names.
    """

    f: NDArray[np.float64]
    passing_hz: float
    speed: float
    orders: NDArray[np.int64]
    harmonics: tuple[NDArray[np.complex128], NDArray[np.complex128]]
    arriving: tuple[NDArray[np.complex128], NDArray[np.complex128]]
    dofs: tuple[str, ...]
    wheels: tuple[str, ...]

    @property
    def labels(self) -> tuple[str, ...]:
        """Displacement response labels."""
        return response_labels(self.dofs, self.harmonics[1].shape[2], self.wheels)

    @property
    def tail(self) -> float:
        """Largest ``|H_{+-N}| / max_n |H_n|`` of the contact forces over the grid (dimensionless).

        What the outermost harmonics kept carry, relative to the largest, in the coupled
        system: an estimate of what the order leaves out (the order check before the run
        bounds the moving-load receptance's harmonics, this the coupled ones).
        """
        size = np.abs(self.harmonics[1]).max(axis=2)  # (n_freq, H)
        edge = np.maximum(size[:, 0], size[:, -1])
        return float((edge / np.maximum(size.max(axis=1), np.finfo(float).tiny)).max())

    def input_psd(self, spectrum: SpatialSpectrum, f: ArrayLike) -> NDArray[np.float64]:
        """``S_r(|f|)`` in m^2/Hz, 0 below the grid's lowest frequency (left out).

        Parameters
        ----------
        spectrum : SpatialSpectrum
            Irregularity spectrum.
        f : array_like
            Input frequencies, Hz (any sign).

        Returns
        -------
        numpy.ndarray
            m^2/Hz, shape of `f`.
        """
        g = np.abs(np.asarray(f, dtype=float))
        inside = g >= self.f.min() * (1.0 - 1e-12)
        out = np.zeros_like(g)
        out[inside] = spectrum.temporal(g[inside], self.speed)
        return out

    def averaged_psd(
        self, spectrum: SpatialSpectrum
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Time-averaged one-sided PSDs ``sum_n |H_n(f - n v/d)|^2 S_r(|f - n v/d|)``.

        Parameters
        ----------
        spectrum : SpatialSpectrum
            Irregularity spectrum (spatial; temporal at this speed).

        Returns
        -------
        displacement, contact_force : numpy.ndarray
            ``(n_freq, n_resp)`` in m^2/Hz (rad^2/Hz for pitch), ``(n_freq, n_wheel)`` N^2/Hz.
        """
        s = self.input_psd(spectrum, self.f[:, None] - self.orders[None, :] * self.passing_hz)
        disp, force = (np.einsum("fnr,fn->fr", np.abs(a) ** 2, s) for a in self.arriving)
        return disp, force

    def phase_psd(
        self, spectrum: SpatialSpectrum, n_phase: int = 8
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """The PSD's variation over the sleeper period (evolutionary, by input frequency).

        ``|sum_n H_n(f) exp(i 2 pi n tau v / d)|^2 S_r(f)`` at ``tau = j d / (v n_phase)``:
        its integral over ``f`` is the variance at that instant of the period.

        Parameters
        ----------
        spectrum : SpatialSpectrum
            Irregularity spectrum.
        n_phase : int
            Instants per sleeper period (a count >= 1).

        Returns
        -------
        phase, displacement, contact_force : numpy.ndarray
            ``tau v / d`` (fraction of the period, ``(n_phase,)``), ``(n_phase, n_freq,
            n_resp)`` in m^2/Hz and ``(n_phase, n_freq, n_wheel)`` in N^2/Hz.
        """
        phase = np.arange(int(n_phase)) / int(n_phase)
        rot = np.exp(2j * np.pi * np.outer(phase, self.orders))  # (n_phase, H)
        s = self.input_psd(spectrum, self.f)
        disp, force = (
            np.abs(np.einsum("pn,fnr->pfr", rot, a)) ** 2 * s[None, :, None] for a in self.harmonics
        )
        return phase, disp, force


def moving_frf(
    system: CoupledSystem,
    f: ArrayLike,
    settings: MovingSettings | None = None,
    *,
    check: bool = True,
) -> MovingFRF:
    """Harmonic transfer functions of the vehicle moving along the periodic track.

    Parameters
    ----------
    system : CoupledSystem
        Vehicle, track, contact (N/m), leading wheel position (m; the phase of the sleeper
        period at ``t = 0``) and speed (m/s).
    f : array_like
        Grid frequencies, Hz (> 0), ``(n_freq,)``.
    settings : MovingSettings, optional
        Harmonic order and tolerance; default :class:`MovingSettings`.
    check : bool
        Run :func:`~railvib.moving.harmonic.check_moving` first (one-line errors).

    Returns
    -------
    MovingFRF
    """
    settings = MovingSettings() if settings is None else settings
    f = np.atleast_1d(np.asarray(f, dtype=float))
    if check:
        check_moving(system, float(f.max()), settings, float(f.min()))
    delays = wheel_delays(system.vehicle.wheel_offsets, system.speed)
    n = settings.harmonic_order
    h = 2 * n + 1
    parts: list[list[NDArray[np.complex128]]] = [[], [], [], []]
    passing = system.speed / system.track.sleeper_spacing
    table = load_receptances(system, f, settings)  # one call, every distinct |f + m v/d|
    for start in range(0, f.size, FREQUENCY_BLOCK):
        fb = f[start : start + FREQUENCY_BLOCK]
        blocks = harmonic_blocks(system, fb, settings, table)
        inputs = blocks.frequencies  # (n_f, H): slot c holds the input at f + c v / d
        rhs = np.zeros((fb.size, h, delays.size, h), dtype=np.complex128)
        for c in range(h):
            rhs[:, c, :, c] = np.exp(-2j * np.pi * inputs[:, c, None] * delays[None, :])
        vehicle, force, rail = blocks.solve(rhs)
        disp = np.concatenate([vehicle, rail], axis=2)  # (n_f, H slot, n_resp, H input)
        parts[0].append(disp[:, :, :, n])
        parts[1].append(force[:, :, :, n])
        # response in slot 0 to the input in slot -n: index n + N <- input column N - n
        parts[2].append(np.moveaxis(disp[:, n, :, ::-1], 2, 1))
        parts[3].append(np.moveaxis(force[:, n, :, ::-1], 2, 1))
    d_h, f_h, d_a, f_a = (np.concatenate(p) for p in parts)
    out = MovingFRF(
        f,
        passing,
        system.speed,
        np.arange(-n, n + 1),
        (d_h, f_h),
        (d_a, f_a),
        system.vehicle.dofs,
        system.vehicle.wheel_names,
    )
    if out.tail > settings.tolerance:
        warnings.warn(
            f"the coupled contact-force harmonics |n| = {n} reach {out.tail:.2g} of the largest "
            f"(above moving.tolerance = {settings.tolerance:g}): what the order leaves out is "
            "not negligible there (near the split pinned-pinned peaks f_pp +- v/(2d), or v/d "
            "near the wheel-track resonance); raise moving.harmonic_order",
            SolverWarning,
            stacklevel=2,
        )
    return out
