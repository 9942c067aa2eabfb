"""The dataset of a non-stationary run: RMS against time, PSD maps, first passage."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from railvib.io import railvib_version
from railvib.nonstationary.build import NonstationaryRun
from railvib.nonstationary.exact import MomentHistory, exact_response, phase_error_bound
from railvib.nonstationary.extremes import CROSSING_MODELS, first_passage_probability
from railvib.nonstationary.quasi import QS_LIMIT, quasi_stationary_psd, validity_parameter
from railvib.results.units import with_unit_coordinates

__all__ = ["frequency_map", "nonstationary_dataset"]

#: the per-response quantity of each variable (units per response: m or rad)
#: a variable: (dims, values, attrs)
_Var = tuple[tuple[str, ...], NDArray[np.generic], dict[str, str]]

_QUANTITIES = {
    "rms_displacement": "displacement",
    "rms_acceleration": "acceleration",
    "rms_acceleration_qs": "acceleration",
    "rms_displacement_qs": "displacement",
    "psd_acceleration": "psd_acceleration",
    "psd_acceleration_qs": "psd_acceleration",
    "first_passage_level_acceleration": "acceleration",
}


def frequency_map(
    psd_wavenumber: NDArray[np.float64],
    wavenumber: NDArray[np.float64],
    speed: NDArray[np.float64],
    f: NDArray[np.float64],
) -> NDArray[np.float64]:
    """``S_y(f; t)`` per Hz on the frequencies `f` from ``S_y(Omega; t)`` per rad/m.

    Wavenumber ``Omega`` is met at ``f = v Omega / (2 pi)``, so ``S_f = S_Omega 2 pi / v``;
    the values are interpolated (linear in log f) onto `f`, and 0 outside the band
    ``v [Omega_min, Omega_max] / (2 pi)`` and at rest (everything at 0 Hz).

    Parameters
    ----------
    psd_wavenumber : numpy.ndarray
        ``(n_t, n_wavenumber, n_out)``, unit^2/(rad/m).
    wavenumber : numpy.ndarray
        ``(n_wavenumber,)``, rad/m, increasing.
    speed : numpy.ndarray
        ``(n_t,)``, m/s.
    f : numpy.ndarray
        ``(n_freq,)``, Hz, > 0.

    Returns
    -------
    numpy.ndarray
        ``(n_t, n_freq, n_out)``, unit^2/Hz.
    """
    out = np.zeros((speed.size, f.size, psd_wavenumber.shape[2]))
    logf = np.log(f)
    for i, v in enumerate(speed):
        if v <= 0:
            continue
        fk = np.log(v * wavenumber / (2.0 * np.pi))
        per_hz = psd_wavenumber[i] * (2.0 * np.pi / v)
        for o in range(per_hz.shape[1]):
            out[i, :, o] = np.interp(logf, fk, per_hz[:, o], left=0.0, right=0.0)
    return out


def nonstationary_dataset(
    run: NonstationaryRun,
    attrs: dict[str, str] | None = None,
    progress: Callable[[int], None] | None = None,
) -> xr.Dataset:
    """Compute the run and gather it: see ``docs/nonstationary.md`` for every variable.

    Parameters
    ----------
    run : NonstationaryRun
        The built run (:func:`railvib.nonstationary.build.build_run`).
    attrs : dict, optional
        Extra global attributes (title, case TOML).
    progress : callable, optional
        Called with the number of time steps just integrated.

    Returns
    -------
    xarray.Dataset
        Over ``time`` (s), ``map_time`` (s), ``frequency`` (Hz), ``response``, ``wheel``,
        ``level`` and ``crossing_model``.
    """
    model, profile, band, s = run.model, run.profile, run.band, run.settings
    n_dof, n_wheel = model.n_dof, model.n_wheel
    labels = list(model.vehicle.dofs)
    f = run.grid.f
    exact = s.method in ("exact", "both")
    qs = s.method in ("quasi_stationary", "both")
    if exact:
        hist = exact_response(
            model,
            profile,
            band,
            run.dt,
            initial=s.initial_state,
            map_times=s.map_times,
            progress=progress,
        )
        t = hist.t
        map_t = hist.t[hist.map_index]
    else:
        from_steps = np.linspace(0.0, profile.duration, s.map_times)
        t = map_t = from_steps
    speed = profile.speed(t)
    eps = validity_parameter(profile, t, model.slowest_mode_hz)
    disp, acc, force = slice(0, n_dof), slice(n_dof, 2 * n_dof), slice(2 * n_dof, None)
    time_attrs = {"units": "s", "long_name": "time from the start of the profile"}
    coords = {
        "time": ("time", t, time_attrs),
        "map_time": ("map_time", map_t, {**time_attrs, "long_name": "time of the PSD map"}),
        "frequency": ("frequency", f, {"units": "Hz", "long_name": "frequency"}),
        "response": ("response", labels, {"long_name": "vehicle DOF"}),
        "wheel": ("wheel", np.arange(1, n_wheel + 1), {"long_name": "wheel (from the front)"}),
        "position": (
            "time",
            profile.position(t),
            {"units": "m", "long_name": "leading wheel position"},
        ),
    }
    data: dict[str, _Var] = {
        "speed": (("time",), speed, {"units": "m/s", "long_name": "speed"}),
        "quasi_stationary_parameter": (
            ("time",),
            eps,
            {
                "units": "1",
                "long_name": "speed change over one period of the slowest mode, |dv/dt| / (v f_1)",
                "note": f"the quasi-stationary estimate holds where it is small (< {QS_LIMIT})",
            },
        ),
    }
    psd_units = {"psd_acceleration": "(m/s^2)^2/Hz", "psd_force": "N^2/Hz"}
    if exact:
        rms = np.sqrt(np.maximum(hist.variance, 0.0))
        data["rms_displacement"] = (
            ("time", "response"),
            rms[:, disp],
            _a("m", "RMS displacement (exact PEM)"),
        )
        data["rms_acceleration"] = (
            ("time", "response"),
            rms[:, acc],
            _a("m/s^2", "RMS acceleration (exact PEM)"),
        )
        data["rms_force"] = (
            ("time", "wheel"),
            rms[:, force],
            _a("N", "RMS dynamic contact force (exact PEM)"),
        )
        fmap = frequency_map(hist.psd_wavenumber, band.wavenumber, profile.speed(map_t), f)
        data["psd_acceleration"] = (
            ("map_time", "frequency", "response"),
            fmap[..., acc],
            _a(psd_units["psd_acceleration"], "evolutionary PSD of the acceleration (exact PEM)"),
        )
        data["psd_force"] = (
            ("map_time", "frequency", "wheel"),
            fmap[..., force],
            _a(psd_units["psd_force"], "evolutionary PSD of the contact force (exact PEM)"),
        )
        data.update(_first_passage(hist, s.first_passage_levels, acc, force))
    if qs:
        sq = quasi_stationary_psd(model, profile, band, map_t)
        rms_qs = np.sqrt(sq.sum(axis=1))
        data["rms_displacement_qs"] = (
            ("map_time", "response"),
            rms_qs[:, disp],
            _a("m", "RMS displacement (quasi-stationary)"),
        )
        data["rms_acceleration_qs"] = (
            ("map_time", "response"),
            rms_qs[:, acc],
            _a("m/s^2", "RMS acceleration (quasi-stationary)"),
        )
        data["rms_force_qs"] = (
            ("map_time", "wheel"),
            rms_qs[:, force],
            _a("N", "RMS dynamic contact force (quasi-stationary)"),
        )
        qmap = frequency_map(
            sq / band.width[None, :, None], band.wavenumber, profile.speed(map_t), f
        )
        data["psd_acceleration_qs"] = (
            ("map_time", "frequency", "response"),
            qmap[..., acc],
            _a(
                psd_units["psd_acceleration"],
                "PSD of the acceleration at the instantaneous speed (quasi-stationary)",
            ),
        )
    meta = {
        "railvib_version": railvib_version(),
        "analysis": "non-stationary pseudo-excitation method, rigid track",
        "method": s.method,
        "initial_state": s.initial_state,
        "time_step_s": run.dt,
        "integrator": "exact modal exponential with the input phase linear over a step",
        "phase_error_bound_rad": phase_error_bound(band, profile, run.dt),
        "contact_stiffness_n_per_m": model.contact_stiffness,
        "slowest_mode_hz": model.slowest_mode_hz,
        "wavelength_min_m": s.wavelength_min_m,
        "wavelength_max_m": s.wavelength_max_m,
        "n_wavenumbers": band.wavenumber.size,
        "irregularity_variance_in_band_m2": band.variance,
        "quasi_stationary_parameter_max": float(np.max(eps)),
        "quasi_stationary_valid_fraction": float(np.mean(eps <= QS_LIMIT)),
        "time_dependence": "exp(+i omega t)",
        "sign_convention": "displacements positive downward; irregularity > 0 is a dip",
        **(attrs or {}),
    }
    if exact:
        coords["level"] = (
            "level",
            np.asarray(s.first_passage_levels, dtype=float),
            {"units": "1", "long_name": "first-passage level in multiples of the largest RMS"},
        )
        coords["crossing_model"] = ("crossing_model", list(CROSSING_MODELS), {})
    ds = xr.Dataset(
        {k: xr.DataArray(v[1], dims=v[0], attrs=v[2]) for k, v in data.items()},
        coords=coords,
        attrs=meta,
    )
    return with_unit_coordinates(ds, _QUANTITIES)


def _a(units: str, long_name: str) -> dict[str, str]:
    return {"units": units, "long_name": long_name}


def _first_passage(
    hist: MomentHistory, levels: list[float], acc: slice, force: slice
) -> dict[str, _Var]:
    """First-passage probabilities of the accelerations and contact forces over the run."""
    out: dict[str, _Var] = {}
    k = np.asarray(levels, dtype=float)
    for name, sl, dim, unit in (
        ("acceleration", acc, "response", "m/s^2"),
        ("force", force, "wheel", "N"),
    ):
        var = hist.variance[:, sl]
        moments = (var, hist.velocity_variance[:, sl], hist.cross[:, sl], hist.first_moment[:, sl])
        b = k[:, None] * np.sqrt(var.max(axis=0))[None, :]  # (n_level, n_out)
        p = np.array(
            [
                [first_passage_probability(hist.t, level, *moments, model) for level in b]
                for model in CROSSING_MODELS
            ]
        )
        out[f"first_passage_level_{name}"] = (
            ("level", dim),
            b,
            _a(unit, f"level b of the first passage of the {name} (k times its largest RMS)"),
        )
        out[f"first_passage_probability_{name}"] = (
            ("crossing_model", "level", dim),
            p,
            _a("1", f"probability that |{name}| exceeds b at least once over the run"),
        )
    return out
