"""How each of the paper's numbers is read from our PSD curves.

Every function takes the study results (case key -> result dataset of
:func:`railvib.run`) and keyword arguments from :data:`railvib.reproduce.study.PAPER_NUMBERS`,
and returns one float. Bands are inclusive, in Hz; peaks are grid maxima (no
interpolation), so a frequency is exact to the grid step (0.1 Hz in the presets).
All PSDs are the ``psd_acceleration`` variable: one-sided, per Hz, in m^2/s^4/Hz.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

import numpy as np
import xarray as xr
from scipy.ndimage import uniform_filter1d
from scipy.signal import find_peaks

from railvib.docstrings import fill_doc
from railvib.pads import LogLinearFit, TabulatedPad, fit_log_linear
from railvib.results.stats import band_rms, dominant_frequency
from railvib.results.stats import peak as _peak

__all__ = [
    "METRICS",
    "Results",
    "comb_peaks",
    "comb_period_hz",
    "comb_spacing",
    "crossover",
    "envelope_peak_frequency",
    "frequency_shift",
    "headline_ratio",
    "headline_shift",
    "pad_k0",
    "pad_slope",
    "peak",
    "peak_difference",
    "peak_frequency",
    "peak_ratio",
    "psd",
    "rms_ratio",
    "rms_spread",
]

Results = Mapping[str, xr.Dataset]
Band = tuple[float, float]


#: parameter documentation shared by the reading functions (:func:`railvib.docstrings.fill_doc`)
_SHARED = {
    "results": """results : mapping of str to xarray.Dataset
    Study results: case key -> result dataset of :func:`railvib.run`.""",
    "case": """case : str
    Key of the case in `results`.""",
    "cases2": """cases : sequence of str
    The two case keys compared, ``(cases[0], cases[1])``.""",
    "response": """response : str
    Response label (a value of the ``response`` coordinate).""",
    "band": """band : (float, float)
    Frequency band ``(f_lo, f_hi)`` in Hz, inclusive.""",
}


@fill_doc(_SHARED)
def psd(results: Results, case: str, response: str) -> xr.DataArray:
    """Acceleration PSD of `response` in `case`, (m/s^2)^2/Hz against frequency (Hz).

    Parameters
    ----------
    {results}
    {case}
    {response}

    Returns
    -------
    xarray.DataArray
        One-sided acceleration PSD in (m/s^2)^2/Hz ((rad/s^2)^2/Hz for a pitch response),
        dimension ``frequency`` in Hz.
    """
    return results[case]["psd_acceleration"].sel(response=response)


@fill_doc(_SHARED)
def peak(results: Results, case: str, response: str, band: Band) -> float:
    """Largest PSD value in `band` (Hz), m^2/s^4/Hz.

    Parameters
    ----------
    {results}
    {case}
    {response}
    {band}

    Returns
    -------
    float
        The peak in m^2/s^4/Hz.
    """
    return float(_peak(psd(results, case, response), band))


@fill_doc(_SHARED)
def peak_frequency(results: Results, case: str, response: str, band: Band) -> float:
    """Frequency (Hz) of the largest PSD value in `band` (Hz).

    Parameters
    ----------
    {results}
    {case}
    {response}
    {band}

    Returns
    -------
    float
        Frequency of the peak in Hz (a grid frequency).
    """
    return float(dominant_frequency(psd(results, case, response), band))


@fill_doc(_SHARED)
def peak_ratio(
    results: Results, cases: Sequence[str], response: str, band: Band, percent: bool = False
) -> float:
    """Ratio of the maxima in `band` of ``cases[0]`` over ``cases[1]`` (x100 if `percent`).

    Parameters
    ----------
    {results}
    {cases2}
    {response}
    {band}
    percent : bool
        Return the ratio in percent.

    Returns
    -------
    float
        Peak ratio (dimensionless), or in % if `percent`.
    """
    num, den = (peak(results, c, response, band) for c in cases)
    return num / den * (100.0 if percent else 1.0)


@fill_doc(_SHARED)
def peak_difference(results: Results, cases: Sequence[str], response: str, band: Band) -> float:
    """Absolute difference of the maxima in `band` of the two cases, m^2/s^4/Hz.

    Parameters
    ----------
    {results}
    {cases2}
    {response}
    {band}

    Returns
    -------
    float
        ``|peak_0 - peak_1|`` in m^2/s^4/Hz.
    """
    a, b = (peak(results, c, response, band) for c in cases)
    return abs(a - b)


@fill_doc(_SHARED)
def frequency_shift(results: Results, cases: Sequence[str], response: str, band: Band) -> float:
    """Peak frequency of ``cases[0]`` minus that of ``cases[1]``, in `band`, Hz.

    Parameters
    ----------
    {results}
    {cases2}
    {response}
    {band}

    Returns
    -------
    float
        Frequency difference in Hz.
    """
    a, b = (peak_frequency(results, c, response, band) for c in cases)
    return a - b


def _rms(results: Results, case: str, response: str, band: Band) -> float:
    return float(band_rms(psd(results, case, response), band))


@fill_doc(_SHARED)
def rms_ratio(results: Results, cases: Sequence[str], response: str, band: Band) -> float:
    """RMS over `band` (Hz) of ``cases[0]`` divided by that of ``cases[1]``.

    Parameters
    ----------
    {results}
    {cases2}
    {response}
    {band}

    Returns
    -------
    float
        RMS ratio (dimensionless).
    """
    num, den = (_rms(results, c, response, band) for c in cases)
    return num / den


@fill_doc(_SHARED)
def rms_spread(results: Results, cases: Sequence[str], response: str, band: Band) -> float:
    """Spread of the RMS over `band` (Hz) among `cases`: ``100 (max / min - 1)``, in %.

    Parameters
    ----------
    {results}
    cases : sequence of str
        Keys of the cases compared.
    {response}
    {band}

    Returns
    -------
    float
        The spread in %.
    """
    values = [_rms(results, c, response, band) for c in cases]
    return 100.0 * (max(values) / min(values) - 1.0)


@fill_doc(_SHARED)
def crossover(results: Results, cases: Sequence[str], response: str, band: Band) -> float:
    """First frequency in `band` where ``cases[0]`` overtakes ``cases[1]``, Hz.

    The first sign change from negative to positive of ``log(PSD_0 / PSD_1)`` in
    `band`, linearly interpolated between grid points. NaN if there is none.

    Parameters
    ----------
    {results}
    {cases2}
    {response}
    {band}

    Returns
    -------
    float
        The crossover frequency in Hz, or NaN.
    """
    a, b = (psd(results, c, response).sel(frequency=slice(*band)) for c in cases)
    f = a["frequency"].values
    g = np.log(a.values / b.values)
    up = np.flatnonzero((g[:-1] < 0.0) & (g[1:] >= 0.0))
    if up.size == 0:
        return float("nan")
    i = int(up[0])
    return float(f[i] - g[i] * (f[i + 1] - f[i]) / (g[i + 1] - g[i]))


def comb_period_hz(ds: xr.Dataset) -> float:
    """The wheelbase comb period ``v / (2 l_t)`` of a result, Hz.

    From the dataset's speed (m/s) and the distance between the first two wheels (m).

    Parameters
    ----------
    ds : xarray.Dataset
        A result dataset of :func:`railvib.run` (attributes ``speed_m_per_s`` and
        ``wheel_positions_m``).

    Returns
    -------
    float
        The comb period in Hz.
    """
    x = np.asarray(ds.attrs["wheel_positions_m"], dtype=float)
    return float(ds.attrs["speed_m_per_s"]) / abs(float(x[0] - x[1]))


@fill_doc(_SHARED)
def comb_peaks(
    results: Results,
    case: str,
    response: str,
    band: Band,
    prominence_decades: float = 0.1,
    min_distance_hz: float = 5.0,
) -> np.ndarray:
    """Frequencies (Hz) of the comb teeth in `band`: the peaks :func:`comb_spacing` counts.

    Local maxima of ``log10 PSD`` with a prominence of at least `prominence_decades`
    and at least `min_distance_hz` apart.

    Parameters
    ----------
    {results}
    {case}
    {response}
    {band}
    prominence_decades : float
        Smallest prominence of a peak of ``log10 PSD``, in decades.
    min_distance_hz : float
        Smallest distance between two peaks in Hz.

    Returns
    -------
    numpy.ndarray
        Ascending grid frequencies of the peaks, Hz.
    """
    a = psd(results, case, response).sel(frequency=slice(*band))
    f = a["frequency"].values
    step = float(f[1] - f[0])
    idx, _ = find_peaks(
        np.log10(a.values),
        prominence=prominence_decades,
        distance=max(1, round(min_distance_hz / step)),
    )
    return np.asarray(f[idx], dtype=float)


@fill_doc(_SHARED)
def comb_spacing(
    results: Results,
    case: str,
    response: str,
    band: Band,
    prominence_decades: float = 0.1,
    min_distance_hz: float = 5.0,
) -> float:
    """Mean spacing of the PSD peaks in `band`, Hz.

    The peaks of :func:`comb_peaks`; the spacing is ``(f_last - f_first)/(n - 1)``.

    Parameters
    ----------
    {results}
    {case}
    {response}
    {band}
    prominence_decades : float
        Smallest prominence of a peak of ``log10 PSD``, in decades.
    min_distance_hz : float
        Smallest distance between two peaks in Hz.

    Returns
    -------
    float
        Mean peak spacing in Hz, or NaN if fewer than two peaks are found.
    """
    f = comb_peaks(results, case, response, band, prominence_decades, min_distance_hz)
    if f.size < 2:
        return float("nan")
    return float((f[-1] - f[0]) / (f.size - 1))


@fill_doc(_SHARED)
def envelope_peak_frequency(results: Results, case: str, response: str, band: Band) -> float:
    """Frequency (Hz) of the maximum of the PSD's overall trend in `band`.

    The trend is ``log10 PSD`` smoothed by a moving mean over one wheelbase comb
    period :func:`comb_period_hz`, which removes the comb's teeth.

    Parameters
    ----------
    {results}
    {case}
    {response}
    {band}

    Returns
    -------
    float
        Frequency of the trend's maximum in Hz (a grid frequency).
    """
    ds = results[case]
    a = psd(results, case, response).sel(frequency=slice(*band))
    f = a["frequency"].values
    window = max(1, round(comb_period_hz(ds) / float(f[1] - f[0])))
    trend = uniform_filter1d(np.log10(a.values), size=window, mode="nearest")
    return float(f[int(np.argmax(trend))])


@fill_doc(_SHARED)
def headline_ratio(results: Results, reference: str, cases: Sequence[str], response: str) -> float:
    """Largest whole-grid peak among `cases` divided by the `reference` case's peak.

    Parameters
    ----------
    {results}
    reference : str
        Key of the reference case.
    cases : sequence of str
        Keys of the cases compared.
    {response}

    Returns
    -------
    float
        Peak ratio (dimensionless).
    """
    whole = _whole(results[reference])
    return max(peak(results, c, response, whole) for c in cases) / peak(
        results, reference, response, whole
    )


@fill_doc(_SHARED)
def headline_shift(results: Results, reference: str, cases: Sequence[str], response: str) -> float:
    """Largest whole-grid dominant frequency among `cases` minus the `reference`'s, Hz.

    Parameters
    ----------
    {results}
    reference : str
        Key of the reference case.
    cases : sequence of str
        Keys of the cases compared.
    {response}

    Returns
    -------
    float
        Frequency difference in Hz.
    """
    whole = _whole(results[reference])
    return max(peak_frequency(results, c, response, whole) for c in cases) - peak_frequency(
        results, reference, response, whole
    )


def _pad_law(results: Results, case: str, band: Band, f0_hz: float) -> LogLinearFit:
    """The log-linear law fitted to the pad K' that drove `case`'s run, over `band`."""
    ds = results[case]
    k = np.asarray(ds["pad_stiffness"].values)
    f = ds["frequency"].values
    pad = TabulatedPad(tuple(f), tuple(k.real), tuple(k.imag))
    return fit_log_linear(pad, float("nan"), band, f0_hz=f0_hz)


@fill_doc(_SHARED)
def pad_k0(results: Results, case: str, band: Band, f0_hz: float = 5.0) -> float:
    """K0 of the paper's law ``K' = K0 (f/f0)^kappa`` fitted to the case's pad, kN/mm.

    The law is fitted (:func:`railvib.pads.fit_log_linear`, least squares in log-log at
    61 log-spaced frequencies over `band`) to the storage stiffness of the dataset's
    ``pad_stiffness``: the pad that drove the run, at the case's pad temperature.

    Parameters
    ----------
    {results}
    {case}
    {band}
    f0_hz : float
        Reference frequency f0 of the law, Hz.

    Returns
    -------
    float
        K0 in kN/mm.
    """
    return _pad_law(results, case, band, f0_hz).model.k0_n_per_m / 1e6


@fill_doc(_SHARED)
def pad_slope(results: Results, case: str, band: Band, f0_hz: float = 5.0) -> float:
    """Log-log slope kappa of the case's pad K' over `band` (see :func:`pad_k0`).

    Parameters
    ----------
    {results}
    {case}
    {band}
    f0_hz : float
        Reference frequency f0 of the law, Hz.

    Returns
    -------
    float
        kappa, dimensionless.
    """
    return _pad_law(results, case, band, f0_hz).model.exponent


def _whole(ds: xr.Dataset) -> Band:
    f = ds["frequency"].values
    return float(f[0]), float(f[-1])


#: reading functions by the name used in the study tables
METRICS: Mapping[str, Callable[..., float]] = {
    "peak": peak,
    "peak_frequency": peak_frequency,
    "peak_ratio": peak_ratio,
    "peak_difference": peak_difference,
    "frequency_shift": frequency_shift,
    "rms_ratio": rms_ratio,
    "rms_spread": rms_spread,
    "crossover": crossover,
    "comb_spacing": comb_spacing,
    "envelope_peak_frequency": envelope_peak_frequency,
    "headline_ratio": headline_ratio,
    "headline_shift": headline_shift,
    "pad_k0": pad_k0,
    "pad_slope": pad_slope,
}
