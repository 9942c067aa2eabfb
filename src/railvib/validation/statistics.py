"""Welch PSD estimates pooled over realisations and their chi-square confidence bands.

A Welch estimate averaging ``K`` Hann-windowed segments with overlap is, for a
Gaussian process, ``S chi^2_nu / nu`` with the equivalent degrees of freedom
(Welch 1967; Percival & Walden 1993, Eq. 292b)

    nu = 2 K / (1 + 2 sum_{j=1}^{K-1} (1 - j/K) rho(j)^2),

``rho(j)`` the correlation of the window with itself shifted by ``j`` segment
steps. Averaging ``R`` independent realisations multiplies ``nu`` by ``R``. The
two-sided ``1 - alpha`` band around an estimate ``S_hat`` is then
``[nu S_hat / chi^2_{nu, 1 - alpha/2}, nu S_hat / chi^2_{nu, alpha/2}]``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import signal, stats

__all__ = [
    "WelchEstimate",
    "confidence_band",
    "welch_dof",
    "welch_expectation",
    "welch_psd",
]


def welch_dof(n_samples: int, nperseg: int, noverlap: int, window: str = "hann") -> float:
    """Equivalent chi-square degrees of freedom of one Welch estimate (dimensionless).

    Parameters
    ----------
    n_samples : int
        Length of the record, samples.
    nperseg : int
        Segment length, samples.
    noverlap : int
        Samples shared by neighbouring segments (< `nperseg`).
    window : str
        Window name understood by :func:`scipy.signal.get_window`.

    Returns
    -------
    float
        ``nu`` of the module docstring for one realisation (dimensionless).
    """
    step = nperseg - noverlap
    k = 1 + (n_samples - nperseg) // step
    w = signal.get_window(window, nperseg)
    norm = np.sum(w**2)
    total = 0.0
    for j in range(1, k):
        shift = j * step
        if shift >= nperseg:
            break
        rho = np.sum(w[: nperseg - shift] * w[shift:]) / norm
        total += (1.0 - j / k) * rho**2
    return 2.0 * k / (1.0 + 2.0 * total)


def confidence_band(
    estimate: ArrayLike, dof: float, confidence: float = 0.95
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Lower and upper chi-square confidence limits of a PSD estimate (same units).

    Parameters
    ----------
    estimate : array_like
        PSD estimate in any PSD unit (e.g. (m/s^2)^2/Hz), any shape.
    dof : float
        Equivalent degrees of freedom nu (dimensionless).
    confidence : float
        Two-sided confidence level in (0, 1).

    Returns
    -------
    lower, upper : numpy.ndarray
        The confidence limits, in the unit and shape of `estimate`.
    """
    s = np.asarray(estimate, dtype=float)
    alpha = 1.0 - confidence
    lower = dof * s / stats.chi2.ppf(1.0 - alpha / 2.0, dof)
    upper = dof * s / stats.chi2.ppf(alpha / 2.0, dof)
    return lower, upper


@dataclass(frozen=True, eq=False)
class WelchEstimate:
    """Welch PSD averaged over realisations.

    Attributes
    ----------
    f : numpy.ndarray
        Frequencies, Hz.
    psd : numpy.ndarray
        One-sided PSD per Hz, ``(n_freq, n_output)`` (units of the signal squared per Hz).
    per_realisation : numpy.ndarray
        ``(n_freq, n_output, n_realisations)``.
    dof : float
        Equivalent degrees of freedom of `psd`.
    """

    f: NDArray[np.float64]
    psd: NDArray[np.float64]
    per_realisation: NDArray[np.float64]
    dof: float

    def band(self, confidence: float = 0.95) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Chi-square confidence band of :attr:`psd`."""
        return confidence_band(self.psd, self.dof, confidence)


def welch_psd(
    x: ArrayLike, sample_rate: float, segment_seconds: float, overlap: float = 0.5
) -> WelchEstimate:
    """One-sided Welch PSD (Hann window) of records ``(n_samples, n_output, n_realisations)``.

    Parameters
    ----------
    x : array_like
        Records in the signal's unit (e.g. m/s^2), time first, shape
        ``(n_samples, n_output, n_realisations)`` or ``(n_samples, n_output)`` (one realisation).
    sample_rate : float
        Sample rate in Hz.
    segment_seconds : float
        Segment length in s; the frequency resolution is ``1 / segment_seconds``.
    overlap : float
        Fraction of a segment shared by neighbours, in [0, 1) (dimensionless).

    Returns
    -------
    WelchEstimate
        One-sided PSD per Hz in the signal's unit squared per Hz, averaged over realisations.
    """
    x = np.asarray(x, dtype=float)
    if x.ndim == 2:
        x = x[:, :, None]
    nperseg = int(round(segment_seconds * sample_rate))
    noverlap = int(round(overlap * nperseg))
    f, p = signal.welch(
        x,
        fs=sample_rate,
        window="hann",
        nperseg=nperseg,
        noverlap=noverlap,
        detrend="constant",
        scaling="density",
        return_onesided=True,
        axis=0,
    )
    dof = welch_dof(x.shape[0], nperseg, noverlap) * x.shape[2]
    return WelchEstimate(f=f, psd=p.mean(axis=2), per_realisation=p, dof=dof)


def welch_expectation(
    psd: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    f_bins: ArrayLike,
    sample_rate: float,
    segment_seconds: float,
    band: tuple[float, float],
    oversampling: int = 8,
) -> NDArray[np.float64]:
    """Compute the expected value of a Hann-window Welch estimate of a process with a known PSD.

    ``E[S_hat(f)] = int S(|f'|) |W(f - f')|^2 df' / (f_s sum w^2)``: the true one-sided
    PSD seen through the spectral window of one segment (this is what the Monte Carlo
    estimates, whatever the number of segments; it blurs nulls narrower than two bins).

    Parameters
    ----------
    psd : callable
        ``psd(f)`` one-sided PSD at frequencies ``f`` in Hz, ``(n_f,)`` or ``(n_f, n_out)``.
    f_bins : array_like
        Welch bin frequencies in Hz (multiples of ``1 / segment_seconds``).
    sample_rate : float
        Sample rate of the records, Hz.
    segment_seconds : float
        Welch segment length, s.
    band : (float, float)
        The PSD is taken as zero outside this band (the band of the sampled input), Hz.
    oversampling : int
        Fine-grid points per Welch bin.

    Returns
    -------
    numpy.ndarray
        ``(n_bins,)`` or ``(n_bins, n_out)``, units of `psd`.
    """
    nperseg = int(round(segment_seconds * sample_rate))
    df = sample_rate / nperseg
    delta = df / oversampling
    n_fft = oversampling * nperseg
    w = signal.get_window("hann", nperseg)
    kernel = np.abs(np.fft.fft(w, n_fft)) ** 2 / (n_fft * np.sum(w**2))  # sums to 1
    half = n_fft // 2 - 1
    kern = np.concatenate([kernel[-half:], kernel[: half + 1]])  # offsets -half .. half
    m_hi = int(np.floor(band[1] / delta))
    g = np.arange(0, m_hi + 1) * delta
    values = np.asarray(psd(np.where(g > 0, g, delta)), dtype=float)
    values = values.reshape(g.size, -1) * ((g >= band[0]) & (g <= band[1]))[:, None]
    two_sided = np.concatenate([values[:0:-1], values], axis=0)  # grid -m_hi .. m_hi
    full = signal.fftconvolve(two_sided, kern[:, None], mode="full", axes=0)
    # full[i] = sum_m two_sided[m] kern[i - m]; offset (i - m) - half, frequency (m - m_hi) delta
    f_bins = np.asarray(f_bins, dtype=float)
    idx = np.rint(f_bins / delta).astype(int) + m_hi + half
    out = full[idx]
    return out[:, 0] if np.asarray(psd(np.array([band[0]]))).ndim == 1 else out
