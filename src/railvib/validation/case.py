"""Run one case three ways (symplectic + PEM, finite track, time-domain Monte Carlo) and compare.

Acceptance (issue 5):

* the finite-track frequency-domain acceleration PSDs agree with PEM within 2 %
  (``| S_finite / S_pem - 1 |``) at every frequency from 1 Hz to 1 kHz;
* the PEM PSDs lie inside the Monte Carlo 95 % chi-square band in at least 90 % of
  the Welch bins from 1 to 500 Hz, for each response. PEM is compared as the Welch
  estimator sees it (:func:`~railvib.validation.statistics.welch_expectation`:
  the PEM PSD convolved with the spectral window of one segment), which is the
  expectation of the Monte Carlo estimate; the raw point values are reported too.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from railvib.coupling import CoupledSystem
from railvib.pem import acceleration_psd
from railvib.spectra.base import SpatialSpectrum
from railvib.track.periodic import PeriodicTrack
from railvib.validation.coupled import FiniteCoupledSystem
from railvib.validation.monte_carlo import MonteCarloSettings, monte_carlo
from railvib.validation.statistics import welch_expectation
from railvib.vehicle.assembly import Vehicle

__all__ = ["ValidationResult", "ValidationSettings", "monte_carlo_work", "validate_case"]

FRF_TOLERANCE = 0.02  # issue 5: finite track vs PEM within 2 %
BAND_FRACTION = 0.90  # issue 5: PEM inside the MC band in >= 90 % of bins


@dataclass(frozen=True)
class ValidationSettings:
    """Settings of :func:`validate_case`.

    Parameters
    ----------
    f_min : float
        Lowest compared frequency, Hz.
    f_max_frf : float
        Highest frequency of the finite-track comparison, Hz.
    f_max_mc : float
        Highest frequency of the Monte Carlo comparison, Hz.
    n_frf : int
        Number of log-spaced frequencies of the finite-track comparison.
    frf_margin_spans : int
        Bays of finite track beyond the outer wheels (frequency domain).
    frf_elements_per_span : int
        Hermite elements per bay (frequency domain).
    confidence : float
        Confidence level of the Monte Carlo band.
    bands : tuple of (float, float)
        Frequency bands of the agreement table, Hz.
    monte_carlo : MonteCarloSettings
        Time-domain settings.
    """

    f_min: float = 1.0
    f_max_frf: float = 1000.0
    f_max_mc: float = 500.0
    n_frf: int = 600
    frf_margin_spans: int = 60
    frf_elements_per_span: int = 8
    confidence: float = 0.95
    bands: tuple[tuple[float, float], ...] = ((1.0, 10.0), (10.0, 100.0), (100.0, 1000.0))
    monte_carlo: MonteCarloSettings = field(default_factory=MonteCarloSettings)

    @classmethod
    def quick(cls, realisations: int | None = None) -> ValidationSettings:
        """Settings for the test suite: 150 FRF points, short Monte Carlo (about 20 s a case)."""
        mc = MonteCarloSettings.quick()
        if realisations is not None:
            mc = replace(mc, realisations=int(realisations))
        return cls(n_frf=150, frf_margin_spans=40, monte_carlo=mc)


@dataclass(frozen=True, eq=False)
class ValidationResult:
    """Outcome of :func:`validate_case`.

    Attributes
    ----------
    frf : xarray.Dataset
        Finite track vs PEM on a log grid: ``pem_psd``, ``finite_psd``, ``relative_error``.
    mc : xarray.Dataset
        Monte Carlo on the Welch bins: ``pem_psd``, ``pem_expected``, ``mc_psd``,
        ``mc_lower``, ``mc_upper``, ``inside``, ``inside_raw``.
    table : xarray.Dataset
        Per band and response: ``max_relative_error`` (finite track),
        ``fraction_inside`` and ``fraction_inside_raw`` (Monte Carlo).
    timings : dict
        Wall-clock seconds of each route.
    """

    frf: xr.Dataset
    mc: xr.Dataset
    table: xr.Dataset
    timings: dict[str, float]

    @property
    def max_relative_error(self) -> xr.DataArray:
        """Finite track vs PEM, max over the whole FRF band, per response."""
        return self.frf["relative_error"].max("frequency")

    @property
    def fraction_inside(self) -> xr.DataArray:
        """Fraction of Welch bins with PEM inside the band, over the MC range, per response."""
        return self.mc["inside"].mean("frequency")

    @property
    def passed(self) -> bool:
        """Both acceptance criteria of issue 5 hold for every response."""
        return bool(
            (self.max_relative_error <= FRF_TOLERANCE).all()
            and (self.fraction_inside >= BAND_FRACTION).all()
        )

    def summary_markdown(self) -> str:
        """Markdown table: per response, finite-track max error and fraction inside the MC band."""
        lines = [
            "| response | finite track max rel. error | PEM inside MC band | raw PEM inside |",
            "|---|---|---|---|",
        ]
        raw = self.mc["inside_raw"].mean("frequency")
        for resp in self.frf["response"].values:
            lines.append(
                f"| {resp} | {float(self.max_relative_error.sel(response=resp)):.2e} "
                f"| {float(self.fraction_inside.sel(response=resp)):.1%} "
                f"| {float(raw.sel(response=resp)):.1%} |"
            )
        return "\n".join(lines)

    def table_markdown(self) -> str:
        """Markdown table of agreement per frequency band and response."""
        bands = list(self.table["band"].values)
        head = "| response | " + " | ".join(f"{b} Hz: FE err / MC in" for b in bands) + " |"
        lines = [head, "|---" * (len(bands) + 1) + "|"]
        for resp in self.table["response"].values:
            cells = []
            for b in bands:
                err = float(self.table["max_relative_error"].sel(band=b, response=resp))
                frac = float(self.table["fraction_inside"].sel(band=b, response=resp))
                frac_s = "-" if np.isnan(frac) else f"{frac:.0%}"
                cells.append(f"{err:.1e} / {frac_s}")
            lines.append(f"| {resp} | " + " | ".join(cells) + " |")
        return "\n".join(lines)


def _pem_psd(system: CoupledSystem, spectrum: SpatialSpectrum) -> Callable:
    def psd(f: NDArray[np.float64]) -> NDArray[np.float64]:
        h = system.frf(f)
        frf = np.concatenate([h.vehicle, h.rail], axis=1)
        return acceleration_psd(f, np.abs(frf) ** 2 * spectrum.temporal(f, system.speed)[:, None])

    return psd


def _units(labels: tuple[str, ...]) -> list[str]:
    return ["(rad/s^2)^2/Hz" if lab.endswith("pitch") else "(m/s^2)^2/Hz" for lab in labels]


def validate_case(
    vehicle: Vehicle,
    track: PeriodicTrack,
    contact_stiffness: float,
    leading_wheel_position: float,
    speed: float,
    spectrum: SpatialSpectrum,
    *,
    settings: ValidationSettings | None = None,
    seed: int = 0,
    progress: Callable[[int], None] | None = None,
) -> ValidationResult:
    """Compare symplectic + PEM with the finite-track model and a time-domain Monte Carlo.

    Parameters
    ----------
    vehicle : Vehicle
        Pitch-plane vehicle.
    track : PeriodicTrack
        The periodic track (its rail, pad and spacing also build the finite track).
    contact_stiffness : float
        k_H in N/m.
    leading_wheel_position : float
        Leading wheel position from a sleeper, m, in ``[0, d)``.
    speed : float
        m/s.
    spectrum : SpatialSpectrum
        One-sided irregularity spectrum, m^2/(rad/m).
    settings : ValidationSettings, optional
        Defaults to ``ValidationSettings()`` (a few minutes on 2 cores).
    seed : int
        Base seed of the Monte Carlo.
    progress : callable, optional
        Called with Newmark steps done (times realisations); total is
        :func:`monte_carlo_work`.

    Returns
    -------
    ValidationResult
    """
    s = settings if settings is not None else ValidationSettings()
    pem_system = CoupledSystem(vehicle, track, contact_stiffness, leading_wheel_position, speed)
    pem = _pem_psd(pem_system, spectrum)
    timings: dict[str, float] = {}

    # 1. finite track, frequency domain
    f = np.geomspace(s.f_min, s.f_max_frf, s.n_frf)
    t0 = time.perf_counter()
    s_pem = pem(f)
    timings["pem_seconds"] = time.perf_counter() - t0
    finite = FiniteCoupledSystem.build(
        vehicle,
        track.rail,
        track.pad,
        track.sleeper_spacing,
        contact_stiffness,
        leading_wheel_position,
        speed,
        margin_spans=s.frf_margin_spans,
        elements_per_span=s.frf_elements_per_span,
        pad_temperature=track.pad_temperature,
    )
    t0 = time.perf_counter()
    h = finite.frf(f)
    frf = np.concatenate([h.vehicle, h.rail], axis=1)
    s_fin = acceleration_psd(f, np.abs(frf) ** 2 * spectrum.temporal(f, speed)[:, None])
    timings["finite_track_seconds"] = time.perf_counter() - t0
    labels = h.labels
    rel = np.abs(s_fin / s_pem - 1.0)
    coords: dict[str, tuple[str, object, dict[str, str]]] = {
        "frequency": ("frequency", f, {"units": "Hz", "long_name": "frequency"}),
        "response": ("response", list(labels), {"long_name": "response"}),
    }
    units = _units(labels)
    ds_frf = xr.Dataset(
        {
            "pem_psd": (
                ("frequency", "response"),
                s_pem,
                {"units": "see attrs", "long_name": "PEM acceleration PSD, one-sided"},
            ),
            "finite_psd": (
                ("frequency", "response"),
                s_fin,
                {"units": "see attrs", "long_name": "finite-track acceleration PSD, one-sided"},
            ),
            "relative_error": (
                ("frequency", "response"),
                rel,
                {"units": "1", "long_name": "|finite / PEM - 1|"},
            ),
        },
        coords=coords,
        attrs={"psd_units": units, "elements_per_span": s.frf_elements_per_span},
    )

    # 2. time-domain Monte Carlo
    mc_s = s.monte_carlo
    t0 = time.perf_counter()
    mc = monte_carlo(
        vehicle,
        track.rail,
        track.pad,
        track.sleeper_spacing,
        contact_stiffness,
        leading_wheel_position,
        speed,
        spectrum,
        settings=mc_s,
        seed=seed,
        progress=progress,
    )
    timings["monte_carlo_seconds"] = time.perf_counter() - t0
    est = mc.estimate
    sel = (est.f >= s.f_min) & (est.f <= s.f_max_mc)
    fb = est.f[sel]
    lower, upper = est.band(s.confidence)
    lower, upper, s_mc = lower[sel], upper[sel], est.psd[sel]
    fs = 1.0 / (mc_s.dt * mc_s.decimation)
    s_exp = welch_expectation(pem, fb, fs, mc_s.segment_seconds, mc_s.input_band)
    s_raw = pem(fb)
    inside = (s_exp >= lower) & (s_exp <= upper)
    inside_raw = (s_raw >= lower) & (s_raw <= upper)
    coords_mc = {
        "frequency": ("frequency", fb, {"units": "Hz", "long_name": "Welch bin"}),
        "response": coords["response"],
    }
    dims = ("frequency", "response")
    ds_mc = xr.Dataset(
        {
            "pem_psd": (dims, s_raw, {"units": "see attrs", "long_name": "PEM PSD at the bin"}),
            "pem_expected": (
                dims,
                s_exp,
                {"units": "see attrs", "long_name": "PEM PSD through the Welch window"},
            ),
            "mc_psd": (dims, s_mc, {"units": "see attrs", "long_name": "Monte Carlo Welch PSD"}),
            "mc_lower": (
                dims,
                lower,
                {"units": "see attrs", "long_name": "lower confidence limit"},
            ),
            "mc_upper": (
                dims,
                upper,
                {"units": "see attrs", "long_name": "upper confidence limit"},
            ),
            "inside": (dims, inside, {"units": "1", "long_name": "PEM (windowed) inside band"}),
            "inside_raw": (dims, inside_raw, {"units": "1", "long_name": "PEM (raw) inside band"}),
        },
        coords=coords_mc,
        attrs={
            "psd_units": units,
            "dof": est.dof,
            "confidence": s.confidence,
            "realisations": mc_s.realisations,
            "record_seconds": mc_s.record_seconds,
            "dt": mc_s.dt,
            "seed": seed,
            "band_method": "chi-square with Welch equivalent degrees of freedom",
        },
    )

    # 3. agreement per band
    names = [f"{lo:g}-{hi:g}" for lo, hi in s.bands]
    err_tab = np.full((len(names), len(labels)), np.nan)
    in_tab = np.full_like(err_tab, np.nan)
    raw_tab = np.full_like(err_tab, np.nan)
    for i, (lo, hi) in enumerate(s.bands):
        m = (f >= lo) & (f <= hi)
        if m.any():
            err_tab[i] = rel[m].max(axis=0)
        m = (fb >= lo) & (fb <= hi)
        if m.any():
            in_tab[i] = inside[m].mean(axis=0)
            raw_tab[i] = inside_raw[m].mean(axis=0)
    table = xr.Dataset(
        {
            "max_relative_error": (
                ("band", "response"),
                err_tab,
                {"units": "1", "long_name": "finite track vs PEM, max |S_fe/S_pem - 1|"},
            ),
            "fraction_inside": (
                ("band", "response"),
                in_tab,
                {"units": "1", "long_name": "fraction of bins with windowed PEM inside MC band"},
            ),
            "fraction_inside_raw": (
                ("band", "response"),
                raw_tab,
                {"units": "1", "long_name": "fraction of bins with raw PEM inside MC band"},
            ),
        },
        coords={
            "band": ("band", names, {"units": "Hz", "long_name": "frequency band"}),
            "response": coords["response"],
        },
    )
    return ValidationResult(frf=ds_frf, mc=ds_mc, table=table, timings=timings)


def monte_carlo_work(settings: ValidationSettings) -> int:
    """Total Newmark steps times realisations of one case (for a progress bar)."""
    mc = settings.monte_carlo
    steps = int(round((mc.discard_seconds + mc.record_seconds) / mc.dt))
    return steps * mc.realisations
