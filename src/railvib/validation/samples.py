"""Irregularity sample functions by the spectral representation (random phases).

A profile is the sum of cosines at the spatial frequencies ``n_k = k / L`` (cycle/m)
of a record of length ``L``,

    r(x) = sum_k sqrt(2 S_n(n_k) dn) cos(2 pi n_k x + phi_k),   dn = 1 / L,

with ``S_n = 2 pi S(Omega = 2 pi n_k)`` the one-sided PSD per cycle/m and independent
phases ``phi_k`` uniform on ``[0, 2 pi)``; the sum is evaluated by one inverse real
FFT. The sample is periodic with period ``L``; its variance is exactly the
integral of the spectrum over the retained band, and it tends to a Gaussian process.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.spectra.base import SpatialSpectrum

__all__ = ["sample_profile", "wheel_irregularities"]


def _check_positive(name: str, value: float, unit: str) -> float:
    if not (np.isfinite(value) and value > 0):
        raise CaseError(name, value, f"must be > 0 ({unit})")
    return float(value)


def _line_amplitudes(
    spectrum: SpatialSpectrum,
    n_points: int,
    dx: float,
    band: tuple[float, float] | None,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Spatial frequencies (cycle/m) and cosine amplitudes (m) of lines 1 .. n_points//2 - 1."""
    length = n_points * dx
    k = np.arange(1, n_points // 2)
    n = k / length
    amp = np.zeros(n.size)
    keep = np.ones(n.size, dtype=bool)
    if band is not None:
        keep = (n >= band[0]) & (n <= band[1])
    s_cycles = 2.0 * np.pi * np.asarray(spectrum.psd(2.0 * np.pi * n[keep]), dtype=float)
    amp[keep] = np.sqrt(2.0 * s_cycles / length)
    return n, amp


def sample_profile(
    spectrum: SpatialSpectrum,
    length: float,
    dx: float,
    seed: int | np.random.Generator | None,
    *,
    wavelength_range: tuple[float, float] | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """One irregularity profile sampled from a one-sided spatial spectrum.

    Parameters
    ----------
    spectrum : SpatialSpectrum
        One-sided spatial PSD in m^2/(rad/m).
    length : float
        Record length L in m (> 0); the profile is periodic with this period.
    dx : float
        Sample spacing in m (> 0); lines up to the Nyquist number ``1 / (2 dx)`` are used.
    seed : int, numpy.random.Generator or None
        Seed for ``numpy.random.default_rng`` (or a generator); same seed, same profile.
    wavelength_range : (float, float), optional
        Shortest and longest wavelength kept, m. Default: everything from ``2 dx`` to L.

    Returns
    -------
    x : numpy.ndarray
        Positions in m, ``j dx`` for ``j = 0 .. N - 1``, ``N = round(L / dx)``.
    r : numpy.ndarray
        Irregularity in m, positive a dip.

    Examples
    --------
    >>> from railvib.spectra import FRAClass
    >>> x, r = sample_profile(FRAClass(5), 100.0, 0.25, seed=1)
    >>> x.shape == r.shape == (400,)
    True
    """
    length = _check_positive("length", length, "m")
    dx = _check_positive("dx", dx, "m")
    n_points = int(round(length / dx))
    if n_points < 4:
        raise CaseError("length", length, f"at least 4 samples of dx = {dx} (m)")
    band = None
    if wavelength_range is not None:
        lo, hi = (float(v) for v in wavelength_range)
        if not (0 < lo < hi):
            raise CaseError("wavelength_range", wavelength_range, "0 < shortest < longest (m)")
        band = (1.0 / hi, 1.0 / lo)
    rng = np.random.default_rng(seed)
    _, amp = _line_amplitudes(spectrum, n_points, dx, band)
    phases = rng.uniform(0.0, 2.0 * np.pi, amp.size)
    coeff = np.zeros(n_points // 2 + 1, dtype=complex)
    coeff[1 : n_points // 2] = 0.5 * n_points * amp * np.exp(1j * phases)
    x = np.arange(n_points, dtype=np.float64) * dx
    return x, np.asarray(np.fft.irfft(coeff, n=n_points), dtype=np.float64)


def wheel_irregularities(
    spectrum: SpatialSpectrum,
    speed: float,
    wheel_offsets: ArrayLike,
    duration: float,
    dt: float,
    seed: int,
    *,
    realisations: ArrayLike = (0,),
    frequency_band: tuple[float, float] | None = None,
    ramp: float = 0.0,
) -> NDArray[np.float64]:
    """Irregularity under each wheel in time, ``r_j(t) = r(v t - s_j)``, for several realisations.

    The profile of realisation ``i`` uses the phases of
    ``default_rng(SeedSequence(seed).spawn(i + 1)[i])``, so any subset of realisations
    is reproducible on its own. The shift ``s_j`` is applied exactly in the spectral
    domain (circularly over the period ``v duration``).

    Parameters
    ----------
    spectrum : SpatialSpectrum
        One-sided spatial PSD in m^2/(rad/m).
    speed : float
        v in m/s (> 0).
    wheel_offsets : array_like
        Distance of each wheel behind the leading wheel, m.
    duration : float
        Record length in s (> 0); the sample is periodic with this period.
    dt : float
        Time step in s (> 0).
    seed : int
        Base seed.
    realisations : array_like of int
        Indices of the realisations to generate.
    frequency_band : (float, float), optional
        Lowest and highest temporal frequency kept, Hz (lines outside are zero).
    ramp : float
        Length in s of a half-cosine fade-in applied to every wheel (>= 0), so that a
        simulation starting at rest is not kicked.

    Returns
    -------
    numpy.ndarray
        ``(n_steps + 1, n_wheel, n_realisations)`` in m at ``t = k dt``, ``k = 0 .. n_steps``,
        ``n_steps = round(duration / dt)``.
    """
    speed = _check_positive("speed", speed, "m/s")
    duration = _check_positive("duration", duration, "s")
    dt = _check_positive("dt", dt, "s")
    offsets = np.atleast_1d(np.asarray(wheel_offsets, dtype=float))
    idx = np.atleast_1d(np.asarray(realisations, dtype=int))
    n_points = int(round(duration / dt))
    dx = speed * dt
    band = None
    if frequency_band is not None:
        band = (frequency_band[0] / speed, frequency_band[1] / speed)
    n, amp = _line_amplitudes(spectrum, n_points, dx, band)
    children = np.random.SeedSequence(seed).spawn(int(idx.max()) + 1 if idx.size else 0)
    shift = np.exp(-2j * np.pi * n[:, None] * offsets[None, :])  # (n_line, n_wheel)
    out = np.empty((n_points + 1, offsets.size, idx.size))
    t = np.arange(n_points + 1) * dt
    taper = np.ones_like(t)
    if ramp > 0:
        inside = t < ramp
        taper[inside] = 0.5 - 0.5 * np.cos(np.pi * t[inside] / ramp)
    for col, i in enumerate(idx):
        phases = np.random.default_rng(children[i]).uniform(0.0, 2.0 * np.pi, amp.size)
        coeff = np.zeros((n_points // 2 + 1, offsets.size), dtype=complex)
        coeff[1 : n_points // 2] = (0.5 * n_points * amp * np.exp(1j * phases))[:, None] * shift
        series = np.fft.irfft(coeff, n=n_points, axis=0)
        out[:n_points, :, col] = series
        out[n_points, :, col] = series[0]
    return out * taper[:, None, None]
