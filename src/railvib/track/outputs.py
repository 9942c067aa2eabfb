"""The track alone: frequency responses, waves and the EN 15461 track decay rate.

Everything here works through the :class:`~railvib.track.base.TrackModel` interface
(``receptance``, ``period``, ``propagation_constants``, ``support_response``,
``sleeper_spacing``), so every registered track model gives these outputs.

* Transfer functions between rail points: receptance ``alpha`` (m/N), mobility
  ``i omega alpha`` (m/(N s)) and accelerance ``-omega^2 alpha`` (m/(N s^2)).
* Waves: the decay of each right-going wave, ``-20 log10 |mu| / period`` in dB/m, and
  whether it propagates (pass band) or not (stop band), :func:`wave_decay`.
* The track decay rate of EN 15461:2008+A1:2010 (Railway applications - Noise emission -
  Characterisation of the dynamic properties of track sections for pass by noise
  measurements), clause 7, Formula 1 and Annex A:
  ``DR = 4.343 / sum_n (|A(x_n)|^2 / |A(x_0)|^2) dx_n`` dB/m, on the excitation grid of
  its 6.7 and Figure 2, in one-third octave bands (:func:`track_decay_rate`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.track.base import TrackModel

__all__ = [
    "EN15461_GRID_BAYS",
    "FRF_QUANTITIES",
    "PASS_BAND_RATIO",
    "TrackDecay",
    "band_edges",
    "decay_rate",
    "en15461_positions",
    "en15461_weights",
    "frf",
    "third_octave_centres",
    "track_decay_rate",
    "wave_decay",
]

#: the excitation positions of EN 15461 6.7 and Figure 2, in sleeper bays from the
#: response point at mid-span: every quarter bay to 2.5, every half bay to 4, every bay
#: to 8, then 10 ... 66 (29 positions)
EN15461_GRID_BAYS = (
    *(0.25 * i for i in range(11)),
    3.0,
    3.5,
    4.0,
    5.0,
    6.0,
    7.0,
    8.0,
    10.0,
    12.0,
    16.0,
    20.0,
    24.0,
    30.0,
    36.0,
    42.0,
    48.0,
    54.0,
    66.0,
)

#: power of ``i omega`` and unit of each transfer function of :func:`frf`
FRF_QUANTITIES = {
    "receptance": (0, "m/N"),
    "mobility": (1, "m/(N s)"),
    "accelerance": (2, "m/(N s^2)"),
}

#: a wave propagates (pass band) where it decays over one period by less than this
#: fraction of its phase change measured from the nearer band edge (phase 0 or pi):
#: exactly the pass bands of an undamped structure (attenuation 0 there; phase 0 or pi
#: in its stop bands), and of a lightly damped one away from the band edges
PASS_BAND_RATIO = 0.1

#: default number of frequencies per one-third octave band of the band-averaged TDR
POINTS_PER_BAND = 12

#: 10 lg e: the decibels of one neper of |A|^2 (Formula 1's 4.343)
_DB_PER_NEPER_POWER = 10.0 / np.log(10.0)


def frf(
    track: TrackModel,
    f: ArrayLike,
    x_load: ArrayLike,
    x_obs: ArrayLike,
    quantity: str = "receptance",
) -> NDArray[np.complex128]:
    """Receptance, mobility or accelerance of the rail between points.

    Parameters
    ----------
    track : TrackModel
        The track.
    f : array_like
        Frequencies, Hz, ``(n_freq,)``.
    x_load, x_obs : array_like
        Positions of the unit loads and of the observation points along the rail, m.
    quantity : str
        ``"receptance"`` (m/N), ``"mobility"`` (``i omega alpha``, m/(N s)) or
        ``"accelerance"`` (``-omega^2 alpha``, m/(N s^2)).

    Returns
    -------
    numpy.ndarray
        ``(n_freq, n_obs, n_load)``, complex.
    """
    if quantity not in FRF_QUANTITIES:
        raise CaseError("quantity", quantity, f"one of {', '.join(FRF_QUANTITIES)}")
    f = np.atleast_1d(np.asarray(f, dtype=float))
    alpha = track.receptance(f, x_load, x_obs)
    power, _ = FRF_QUANTITIES[quantity]
    return np.asarray(alpha * ((2j * np.pi * f) ** power)[:, None, None], dtype=np.complex128)


def wave_decay(mu: ArrayLike, period: float) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Decay in dB/m of each wave and whether it propagates.

    Parameters
    ----------
    mu : array_like
        Propagation constants over one period (dimensionless), ``|mu| <= 1``, any shape.
    period : float
        The period, m.

    Returns
    -------
    decay : numpy.ndarray
        ``-20 log10 |mu| / period``, dB/m (amplitude; >= 0).
    propagates : numpy.ndarray of bool
        True in a pass band: attenuation per period ``-ln |mu|`` below
        :data:`PASS_BAND_RATIO` times the phase distance ``min(|arg mu|, pi - |arg mu|)``.
    """
    mu = np.asarray(mu, dtype=np.complex128)
    attenuation = -np.log(np.abs(mu))
    phase = np.abs(np.angle(mu))
    edge = np.minimum(phase, np.pi - phase)
    decay = np.asarray(20.0 / np.log(10.0) * attenuation / period, dtype=np.float64)
    return decay, np.asarray(attenuation < PASS_BAND_RATIO * edge)


def third_octave_centres(f_low: float, f_high: float) -> tuple[NDArray[np.float64], list[str]]:
    """Exact base-10 one-third octave centre frequencies (IEC 61260-1) from `f_low` to `f_high`.

    ``f_m = 1000 x 10^(x / 10)`` Hz for integer ``x``; the bands whose nominal
    frequency lies in ``[f_low, f_high]`` (within 1 %).

    Parameters
    ----------
    f_low, f_high : float
        Nominal frequencies of the first and last band, Hz.

    Returns
    -------
    centres : numpy.ndarray
        Exact centre frequencies, Hz.
    nominal : list of str
        Their nominal names (``"100"``, ``"1250"``, ...).
    """
    x = np.arange(np.floor(10 * np.log10(f_low / 1000.0)) - 1, 10 * np.log10(f_high / 1000.0) + 2)
    centres = 1000.0 * 10.0 ** (x / 10.0)
    keep = (centres >= f_low / 1.01) & (centres <= f_high * 1.01)
    centres = centres[keep]
    return centres, [_nominal(c) for c in centres]


def _nominal(centre: float) -> str:
    """The nominal name of a one-third octave band (IEC 61260-1 Annex E: 1.25 -> 1.25, ...)."""
    mantissa = (1.0, 1.25, 1.6, 2.0, 2.5, 3.15, 4.0, 5.0, 6.3, 8.0, 10.0)
    exponent = np.floor(np.log10(centre))
    m = centre / 10.0**exponent
    best = min(mantissa, key=lambda v: abs(np.log(v / m)))
    value = best * 10.0**exponent
    return f"{value:g}"


def band_edges(centres: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Lower and upper edges of base-10 one-third octave bands, ``f_m 10^(-+1/20)``, Hz.

    Parameters
    ----------
    centres : array_like
        Exact centre frequencies, Hz.

    Returns
    -------
    lower, upper : numpy.ndarray
        Edges, Hz.
    """
    centres = np.asarray(centres, dtype=float)
    return centres * 10.0 ** (-1.0 / 20.0), centres * 10.0 ** (1.0 / 20.0)


def en15461_positions(sleeper_spacing: float) -> NDArray[np.float64]:
    """The 29 excitation positions of EN 15461 6.7 / Figure 2, m from the response point.

    Parameters
    ----------
    sleeper_spacing : float
        Sleeper (fastener) spacing d, m.

    Returns
    -------
    numpy.ndarray
        :data:`EN15461_GRID_BAYS` times `sleeper_spacing`.
    """
    return np.asarray(EN15461_GRID_BAYS, dtype=float) * sleeper_spacing


def en15461_weights(x: ArrayLike) -> NDArray[np.float64]:
    """The length of rail each position stands for, ``dx_n`` of EN 15461 Annex A (A.2), m.

    From halfway to the position before to halfway to the one after; from 0 to halfway
    for the first (the response point itself); symmetric about the last one.

    Parameters
    ----------
    x : array_like
        Positions from the response point, m, starting at 0, increasing.

    Returns
    -------
    numpy.ndarray
        ``dx_n``, m.
    """
    x = np.asarray(x, dtype=float)
    if x.ndim != 1 or x.size < 2 or x[0] != 0.0 or np.any(np.diff(x) <= 0):
        raise CaseError("positions", list(x), "at least two, from 0 m, increasing (m)")
    mid = 0.5 * (x[1:] + x[:-1])
    lower = np.concatenate([[0.0], mid])
    upper = np.concatenate([mid, [x[-1] + 0.5 * (x[-1] - x[-2])]])
    return np.asarray(upper - lower, dtype=np.float64)


def decay_rate(ratio: ArrayLike, x: ArrayLike) -> NDArray[np.float64]:
    """EN 15461 Formula 1: ``4.343 / sum_n ratio_n dx_n``, dB/m.

    Parameters
    ----------
    ratio : array_like
        ``|A(x_n)|^2 / |A(x_0)|^2`` (dimensionless), ``(..., n_positions)``.
    x : array_like
        The positions, m (:func:`en15461_weights`).

    Returns
    -------
    numpy.ndarray
        The decay rate, dB/m, ``(...)``.
    """
    weights = en15461_weights(x)
    total = np.sum(np.asarray(ratio, dtype=float) * weights, axis=-1)
    return np.asarray(_DB_PER_NEPER_POWER / total, dtype=np.float64)


@dataclass(frozen=True, eq=False)
class TrackDecay:
    """Track decay rates in one-third octave bands (:func:`track_decay_rate`).

    Attributes
    ----------
    centres : numpy.ndarray
        Exact band centre frequencies, Hz, ``(n_band,)``.
    nominal : list of str
        Nominal band names.
    rate : numpy.ndarray
        EN 15461 decay rate, dB/m, ``(n_band,)``.
    wave : numpy.ndarray
        Decay of the least-attenuated wave (``propagation_constants[:, 0]``) over the same
        frequencies (band mean), dB/m, ``(n_band,)``.
    positions : numpy.ndarray
        Excitation positions from the response point, m, ``(n_positions,)``.
    ratio : numpy.ndarray
        ``|A(x_n)|^2 / |A(x_0)|^2`` per band, ``(n_band, n_positions)``.
    method : str
        ``"band"`` (band-averaged accelerance) or ``"centre"`` (at the centres).
    x_response : float
        The response (accelerometer) position, m.
    """

    centres: NDArray[np.float64]
    nominal: list[str]
    rate: NDArray[np.float64]
    wave: NDArray[np.float64]
    positions: NDArray[np.float64]
    ratio: NDArray[np.float64]
    method: str
    x_response: float

    @property
    def minimum_measurable(self) -> float:
        """EN 15461 Formula 2: ``DR_min = 4.343 / x_max``, dB/m."""
        return float(_DB_PER_NEPER_POWER / self.positions[-1])

    @property
    def suitable(self) -> NDArray[np.bool_]:
        """Per band: ``DR >= 2 DR_min`` (clause 7); elsewhere the rate is an upper bound."""
        return np.asarray(self.rate >= 2.0 * self.minimum_measurable)

    @property
    def far_drop_db(self) -> NDArray[np.float64]:
        """How far the farthest response lies below the direct one per band, dB (6.7: >= 10)."""
        return np.asarray(-10.0 * np.log10(self.ratio[:, -1]), dtype=np.float64)


def track_decay_rate(
    track: TrackModel,
    f_low: float = 100.0,
    f_high: float = 5000.0,
    *,
    method: Literal["band", "centre"] = "band",
    x_response: float | None = None,
    points_per_band: int = POINTS_PER_BAND,
) -> TrackDecay:
    """The EN 15461 track decay rate of `track` in one-third octave bands.

    The response point is at mid-span (EN 15461 6.7) unless `x_response` is given; the
    unit force is applied at each position of :func:`en15461_positions` from it (by
    reciprocity the same as the response there to a force at the point). The standard
    reduces each measured frequency response to its one-third octave band magnitude
    (6.7, clause 7): ``method="band"`` averages ``|accelerance|^2`` over
    `points_per_band` equally spaced frequencies of each band (the mean over the lines
    of a narrow-band analyser); ``"centre"`` evaluates the receptance at the exact centre
    frequencies only (the ratio is then the same for receptance, mobility, accelerance).

    Parameters
    ----------
    track : TrackModel
        The track.
    f_low, f_high : float
        Nominal frequencies of the first and last band, Hz (EN 15461 6.6: at least
        100 Hz - 5 kHz).
    method : {"band", "centre"}
        Band-averaged (the standard's) or at the band centres.
    x_response : float, optional
        Response position, m; default mid-span of the first bay, ``d / 2``.
    points_per_band : int
        Frequencies per band of ``method="band"`` (>= 1).

    Returns
    -------
    TrackDecay

    Raises
    ------
    CaseError
        Bad bands, method or positions, named.
    """
    if method not in ("band", "centre"):
        raise CaseError("method", method, "'band' or 'centre'")
    if not (np.isfinite(f_low) and np.isfinite(f_high) and 0 < f_low <= f_high):
        raise CaseError("tdr bands", f"{f_low} - {f_high}", "0 < f_low <= f_high (Hz)")
    if int(points_per_band) != points_per_band or points_per_band < 1:
        raise CaseError("points_per_band", points_per_band, "an integer >= 1")
    d = track.sleeper_spacing
    x0 = 0.5 * d if x_response is None else float(x_response)
    centres, nominal = third_octave_centres(f_low, f_high)
    if centres.size == 0:
        raise CaseError("tdr bands", f"{f_low} - {f_high}", "at least one band (Hz)")
    positions = en15461_positions(d)
    if method == "centre":
        f = centres
        n = 1
    else:
        n = int(points_per_band)
        lower, upper = band_edges(centres)
        step = (upper - lower) / n
        f = (lower[:, None] + (np.arange(n) + 0.5)[None, :] * step[:, None]).ravel()
    a = frf(track, f, [x0], x0 + positions, "accelerance")[:, :, 0]
    power = (np.abs(a) ** 2).reshape(centres.size, n, positions.size).mean(axis=1)
    ratio = power / power[:, :1]
    wave, _ = wave_decay(track.propagation_constants(f)[:, 0], track.period)
    return TrackDecay(
        centres=centres,
        nominal=nominal,
        rate=decay_rate(ratio, positions),
        wave=wave.reshape(centres.size, n).mean(axis=1),
        positions=positions,
        ratio=np.asarray(ratio, dtype=np.float64),
        method=method,
        x_response=x0,
    )
