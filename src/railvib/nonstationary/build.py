"""The physics of a non-stationary case: vehicle on a rigid track, profile, band, step."""

from __future__ import annotations

from dataclasses import dataclass

from railvib.case import Case, build_spectrum, build_vehicle, contact_stiffness
from railvib.case.profile import NonstationarySection, check_time_step, knots
from railvib.errors import CaseError
from railvib.grid import FrequencyGrid
from railvib.nonstationary.band import SpatialBand
from railvib.nonstationary.profile import SpeedProfile
from railvib.nonstationary.statespace import RigidTrackVehicle

__all__ = ["NonstationaryRun", "build_run", "check_duration"]


@dataclass(frozen=True, eq=False)
class NonstationaryRun:
    """Everything a non-stationary run computes with.

    Attributes
    ----------
    model : RigidTrackVehicle
        The case's vehicle on its contact springs over a rigid rail.
    profile : SpeedProfile
        The ``[speed_profile]``.
    band : SpatialBand
        The wavenumbers of ``[nonstationary]`` with the case's irregularity.
    dt : float
        Time step, s.
    grid : FrequencyGrid
        The frequencies of the time-frequency map: ``map_frequencies`` log-spaced over
        the case's ``[frequency]`` band.
    settings : NonstationarySection
        The ``[nonstationary]`` section (defaults where omitted).
    """

    model: RigidTrackVehicle
    profile: SpeedProfile
    band: SpatialBand
    dt: float
    grid: FrequencyGrid
    settings: NonstationarySection


def check_duration(
    profile: SpeedProfile, slowest_mode_hz: float, field: str, value: object
) -> None:
    """Refuse a run shorter than one period of the slowest mode (it would show no response).

    Parameters
    ----------
    profile : SpeedProfile
        The profile.
    slowest_mode_hz : float
        Natural frequency of the slowest mode, Hz.
    field : str
        The case key that sets the duration, for the error.
    value : object
        Its value, for the error.

    Raises
    ------
    CaseError
        Naming `field`, the duration and the shortest one that works.
    """
    period = 1.0 / slowest_mode_hz
    if profile.duration < period:
        v = profile.v
        change = abs(float(v[-1] - v[0]))
        hint = (
            f"; an acceleration_ms2 <= {change / period:.4g} m/s^2 lasts that long"
            if field.endswith("acceleration_ms2")
            else ""
        )
        raise CaseError(
            field,
            value,
            f"a run of {profile.duration:.4g} s: it must last >= {period:.4g} s, one period "
            f"of the slowest mode ({slowest_mode_hz:.3g} Hz){hint}",
        )


def _duration_field(case: Case) -> str:
    p = case.speed_profile
    assert p is not None
    if p.kind == "table":
        return "speed_profile.time_s" if p.time_s is not None else "speed_profile.position_m"
    if p.kind == "uniform" and p.acceleration_ms2 is not None:
        return "speed_profile.acceleration_ms2"
    return "speed_profile.duration_s"


def build_run(case: Case) -> NonstationaryRun:
    """The non-stationary run of `case` (``mode = "nonstationary"``), checked before computing.

    Parameters
    ----------
    case : Case
        A validated case with a ``[speed_profile]``.

    Returns
    -------
    NonstationaryRun

    Raises
    ------
    CaseError
        No speed profile, or a run shorter than one period of the slowest mode.
    """
    if case.speed_profile is None:
        raise CaseError("speed_profile", "<missing>", 'required by mode = "nonstationary"')
    settings = case.nonstationary or NonstationarySection.model_validate({})
    t, x, v = knots(case.speed_profile, case.speed_kmh)
    profile = SpeedProfile(t, x, v)
    vehicle = build_vehicle(case)
    model = RigidTrackVehicle(vehicle, contact_stiffness(case, vehicle))
    field = _duration_field(case)
    value = getattr(case.speed_profile, field.split(".")[-1])
    check_duration(profile, model.slowest_mode_hz, field, value)
    dt = check_time_step(case.speed_profile, settings, case.speed_kmh)
    band = SpatialBand.log_spaced(
        build_spectrum(case),
        settings.wavelength_min_m,
        settings.wavelength_max_m,
        settings.n_wavenumbers,
    )
    fr = case.frequency
    grid = FrequencyGrid.logarithmic(fr.f_min, fr.f_max, settings.map_frequencies)
    return NonstationaryRun(model, profile, band, dt, grid, settings)
