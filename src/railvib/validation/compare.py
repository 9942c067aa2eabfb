"""Run one case three ways (symplectic + PEM, finite track, time-domain Monte Carlo) and compare.

Each frequency-domain route returns an :class:`~railvib.response.FRF`; its
acceleration PSDs come from the one result pipeline
(:func:`railvib.results.variables.compute_variables`), so PEM and the finite track
are turned into PSDs by the same code as every other railvib result. The three
datasets of a :class:`~railvib.validation.result.ValidationResult` carry real
units on every variable (those of ``VARIABLES["psd_acceleration"]`` for the PSDs).
The acceptance criteria are stated in :mod:`railvib.validation.result`.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any, TypeVar

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from railvib.coupling import CoupledSystem
from railvib.response import FRF
from railvib.results.variables import VARIABLES, compute_variables
from railvib.spectra.base import SpatialSpectrum
from railvib.track.slab import SlabTrack
from railvib.validation._legacy import bundle_form
from railvib.validation.causal import causal_system
from railvib.validation.coupled import FiniteCoupledSystem
from railvib.validation.monte_carlo import MonteCarloResult, monte_carlo
from railvib.validation.result import ValidationResult, ValidationSettings
from railvib.validation.scope import check_scope
from railvib.validation.statistics import welch_expectation

__all__ = ["validate_case"]

T = TypeVar("T")

#: the result variable every compared PSD is (units, note on pitch units)
_PSD = VARIABLES["psd_acceleration"]
_DIMS = ("frequency", "response")
_PsdFunction = Callable[[NDArray[np.float64]], NDArray[np.float64]]


def _validate_case_bundle(*bundle: Any, **options: Any) -> ValidationResult:
    """The deprecated form ``validate_case(vehicle, track, k_H, x0, v, spectrum, ...)``."""
    *system, spectrum = bundle
    return validate_case(CoupledSystem(*system), spectrum, **options)


@bundle_form(
    _validate_case_bundle,
    "validate_case(vehicle, track, contact_stiffness, leading_wheel_position, speed, "
    "spectrum, ...)",
    "validate_case(system, spectrum, ...) with system = CoupledSystem(vehicle, track, "
    "contact_stiffness, leading_wheel_position, speed)",
)
def validate_case(
    system: CoupledSystem,
    spectrum: SpatialSpectrum,
    *,
    settings: ValidationSettings | None = None,
    seed: int = 0,
    progress: Callable[[int], None] | None = None,
    frf_progress: Callable[[int], None] | None = None,
) -> ValidationResult:
    """Compare symplectic + PEM with the finite-track model and a time-domain Monte Carlo.

    The case is first checked against what the reference models can represent
    (:func:`railvib.validation.scope.check_scope`), before any computing. Hysteretic
    layers and a slab loss factor are then replaced by causal fits over the compared band
    (:func:`railvib.validation.causal.causal_system`), which all three routes solve: the
    result's ``approximations`` name them with their error against the originals.

    The deprecated form ``validate_case(vehicle, track, contact_stiffness,
    leading_wheel_position, speed, spectrum, ...)`` still works and warns.

    Parameters
    ----------
    system : CoupledSystem
        Vehicle on the periodic track: k_H in N/m, leading wheel position in m in
        ``[0, d)``, speed in m/s. The rail, pad, spacing and pad temperature of its
        track also build the finite tracks.
    spectrum : SpatialSpectrum
        One-sided irregularity spectrum, m^2/(rad/m).
    settings : ValidationSettings, optional
        Defaults to ``ValidationSettings()`` (a few minutes on 2 cores).
    seed : int
        Base seed of the Monte Carlo.
    progress : callable, optional
        Called with Newmark steps done (times realisations); the total is
        :func:`~railvib.validation.monte_carlo_work`.
    frf_progress : callable, optional
        Called with 1 after each frequency of the finite-track comparison; the total
        is ``settings.n_frf``.

    Returns
    -------
    ValidationResult
        Datasets with PSDs in (m/s^2)^2/Hz ((rad/s^2)^2/Hz for pitch), timings in s.

    Raises
    ------
    CaseError
        A case the reference models cannot check (a Timoshenko rail, a rail loss
        factor, a pad that is not viscous), at once.
    """
    check_scope(system)
    s = settings if settings is not None else ValidationSettings()
    # hysteretic layers have no causal time-domain form: all three routes take the same fits
    system, approximations = causal_system(system, s.f_min, s.f_max_frf)
    frf, frf_timings = _finite_track_comparison(system, spectrum, s, frf_progress)
    mc_result, mc_seconds = _timed(
        lambda: monte_carlo(system, spectrum, settings=s.monte_carlo, seed=seed, progress=progress)
    )
    mc = _monte_carlo_comparison(system, spectrum, s, mc_result, seed)
    table = _agreement_table(frf, mc, s.bands)
    timings = {**frf_timings, "monte_carlo_seconds": mc_seconds}
    return ValidationResult(
        frf=frf, mc=mc, table=table, timings=timings, approximations=approximations
    )


def _timed(func: Callable[[], T]) -> tuple[T, float]:
    """``func()`` and its wall-clock time in s."""
    t0 = time.perf_counter()
    out = func()
    return out, time.perf_counter() - t0


def _acceleration_psd(frf: FRF, spectrum: SpatialSpectrum, speed: float) -> NDArray[np.float64]:
    """Acceleration PSDs of `frf` under `spectrum` at `speed` (m/s), by the result pipeline."""
    s_r = spectrum.temporal(frf.f, speed)
    return np.asarray(compute_variables(frf, s_r, [_PSD.name])[_PSD.name], dtype=float)


def _pem_psd(system: CoupledSystem, spectrum: SpatialSpectrum) -> _PsdFunction:
    """``f -> `` symplectic + PEM acceleration PSDs ``(n_freq, n_resp)``."""

    def psd(f: NDArray[np.float64]) -> NDArray[np.float64]:
        return _acceleration_psd(system.frf(f), spectrum, system.speed)

    return psd


def _psd_attrs(long_name: str) -> dict[str, str]:
    """Attributes of a compared PSD: the units and note of ``psd_acceleration``."""
    return {**_PSD.attrs, "long_name": long_name}


def _coords(f: NDArray[np.float64], labels: tuple[str, ...], what: str) -> dict[str, Any]:
    return {
        "frequency": ("frequency", f, {"units": "Hz", "long_name": what}),
        "response": ("response", list(labels), {"long_name": "response"}),
    }


def _psd_units(labels: tuple[str, ...]) -> list[str]:
    """Unit of each response's acceleration PSD (pitch in rad-based units)."""
    return ["(rad/s^2)^2/Hz" if lab.endswith("pitch") else _PSD.units for lab in labels]


def _finite_track_comparison(
    system: CoupledSystem,
    spectrum: SpatialSpectrum,
    s: ValidationSettings,
    progress: Callable[[int], None] | None = None,
) -> tuple[xr.Dataset, dict[str, float]]:
    """PEM vs the finite track on the log grid: the ``frf`` dataset and the two timings."""
    f = np.geomspace(s.f_min, s.f_max_frf, s.n_frf)
    s_pem, pem_seconds = _timed(lambda: _pem_psd(system, spectrum)(f))
    # graded absorbers (the Monte Carlo's damping) in the outer half of the margins: waves
    # of an undamped rail above the pad resonance travel past the margins of a ballasted
    # track (quick settings, thompson_ballasted with viscous layers: car-body pitch 2.9e-2
    # without them, 3.1e-3 with them); a slab track's further still (its own margin, the
    # outer 5/6 of it absorbing)
    margin, absorber = s.frf_margin_spans, s.frf_margin_spans // 2
    if isinstance(system.track, SlabTrack):
        margin = s.frf_slab_margin_spans
        absorber = margin * 5 // 6
    finite = FiniteCoupledSystem.from_system(
        system,
        margin_spans=margin,
        elements_per_span=s.frf_elements_per_span,
        absorber_spans=absorber,
        absorber_damping=s.monte_carlo.absorber_damping,
    )
    h, fin_seconds = _timed(lambda: finite.frf(f, progress))
    s_fin, psd_seconds = _timed(lambda: _acceleration_psd(h, spectrum, system.speed))
    ds = xr.Dataset(
        {
            "pem_psd": (_DIMS, s_pem, _psd_attrs("PEM acceleration PSD, one-sided")),
            "finite_psd": (_DIMS, s_fin, _psd_attrs("finite-track acceleration PSD, one-sided")),
            "relative_error": (
                _DIMS,
                np.abs(s_fin / s_pem - 1.0),
                {"units": "1", "long_name": "|finite / PEM - 1|"},
            ),
        },
        coords=_coords(f, h.labels, "frequency"),
        attrs={"psd_units": _psd_units(h.labels), "elements_per_span": s.frf_elements_per_span},
    )
    timings = {"pem_seconds": pem_seconds, "finite_track_seconds": fin_seconds + psd_seconds}
    return ds, timings


def _monte_carlo_comparison(
    system: CoupledSystem,
    spectrum: SpatialSpectrum,
    s: ValidationSettings,
    mc: MonteCarloResult,
    seed: int,
) -> xr.Dataset:
    """PEM (raw and through the Welch window) against the Monte Carlo band: the ``mc`` dataset."""
    mc_s = s.monte_carlo
    est = mc.estimate
    sel = (est.f >= s.f_min) & (est.f <= s.f_max_mc)
    fb = est.f[sel]
    lower, upper = (limit[sel] for limit in est.band(s.confidence))
    pem = _pem_psd(system, spectrum)
    fs = 1.0 / (mc_s.dt * mc_s.decimation)
    s_exp = welch_expectation(pem, fb, fs, mc_s.segment_seconds, mc_s.input_band)
    s_raw = pem(fb)
    inside = {"units": "1", "long_name": "PEM (windowed) inside band"}
    inside_raw = {"units": "1", "long_name": "PEM (raw) inside band"}
    return xr.Dataset(
        {
            "pem_psd": (_DIMS, s_raw, _psd_attrs("PEM PSD at the bin")),
            "pem_expected": (_DIMS, s_exp, _psd_attrs("PEM PSD through the Welch window")),
            "mc_psd": (_DIMS, est.psd[sel], _psd_attrs("Monte Carlo Welch PSD")),
            "mc_lower": (_DIMS, lower, _psd_attrs("lower confidence limit")),
            "mc_upper": (_DIMS, upper, _psd_attrs("upper confidence limit")),
            "inside": (_DIMS, (s_exp >= lower) & (s_exp <= upper), inside),
            "inside_raw": (_DIMS, (s_raw >= lower) & (s_raw <= upper), inside_raw),
        },
        coords=_coords(fb, mc.labels, "Welch bin"),
        attrs={
            "psd_units": _psd_units(mc.labels),
            "dof": est.dof,
            "confidence": s.confidence,
            "realisations": mc_s.realisations,
            "record_seconds": mc_s.record_seconds,
            "dt": mc_s.dt,
            "seed": seed,
            "band_method": "chi-square with Welch equivalent degrees of freedom",
        },
    )


def _band_extremes(
    frf: xr.Dataset, mc: xr.Dataset, bands: tuple[tuple[float, float], ...]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Per band: max relative error, fraction inside, fraction inside (raw); NaN if empty."""
    f, fb = frf["frequency"].values, mc["frequency"].values
    rel = frf["relative_error"].values
    inside, inside_raw = mc["inside"].values, mc["inside_raw"].values
    err_tab = np.full((len(bands), rel.shape[1]), np.nan)
    in_tab = np.full_like(err_tab, np.nan)
    raw_tab = np.full_like(err_tab, np.nan)
    for i, (lo, hi) in enumerate(bands):
        m = (f >= lo) & (f <= hi)
        if m.any():
            err_tab[i] = rel[m].max(axis=0)
        m = (fb >= lo) & (fb <= hi)
        if m.any():
            in_tab[i] = inside[m].mean(axis=0)
            raw_tab[i] = inside_raw[m].mean(axis=0)
    return err_tab, in_tab, raw_tab


def _agreement_table(
    frf: xr.Dataset, mc: xr.Dataset, bands: tuple[tuple[float, float], ...]
) -> xr.Dataset:
    """Agreement per frequency band (Hz) and response: the ``table`` dataset."""
    err_tab, in_tab, raw_tab = _band_extremes(frf, mc, bands)
    dims = ("band", "response")
    return xr.Dataset(
        {
            "max_relative_error": (
                dims,
                err_tab,
                {"units": "1", "long_name": "finite track vs PEM, max |S_fe/S_pem - 1|"},
            ),
            "fraction_inside": (
                dims,
                in_tab,
                {"units": "1", "long_name": "fraction of bins with windowed PEM inside MC band"},
            ),
            "fraction_inside_raw": (
                dims,
                raw_tab,
                {"units": "1", "long_name": "fraction of bins with raw PEM inside MC band"},
            ),
        },
        coords={
            "band": (
                "band",
                [f"{lo:g}-{hi:g}" for lo, hi in bands],
                {"units": "Hz", "long_name": "frequency band"},
            ),
            "response": ("response", frf["response"].values.tolist(), {"long_name": "response"}),
        },
    )
