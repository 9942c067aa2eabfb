"""The ``[speed_profile]`` and ``[nonstationary]`` sections of a non-stationary case.

A speed profile is a list of knots ``(t_i, x_i, v_i)`` joined by segments of
constant acceleration (``docs/nonstationary.md``): ``kind = "constant"`` (one speed
for a duration), ``"uniform"`` (from one speed to another at a constant acceleration
or in a given duration) or ``"table"`` (speeds against times, or against positions).
Every check that needs only the case's own numbers is made here, when the case is
loaded, with the field's name and the limits that would work; the one that needs the
vehicle's slowest mode is made when the run is built
(:func:`railvib.nonstationary.build.check_duration`).
"""

from __future__ import annotations

from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray
from pydantic import Field, model_validator

from railvib.case.sections import Section
from railvib.errors import CaseError

__all__ = [
    "MAX_ACCELERATION_MS2",
    "MAX_STEPS",
    "NonstationarySection",
    "SpeedProfileSection",
    "check_time_step",
    "knots",
    "nyquist_time_step",
]

#: largest acceleration or deceleration, m/s^2 (emergency braking is about 1.5-3 m/s^2)
MAX_ACCELERATION_MS2 = 20.0
#: most time steps of a run (10^6 steps of 10^3 wavenumbers are some minutes)
MAX_STEPS = 1_000_000
#: most knots of a table
MAX_KNOTS = 100_000
_KMH = 1.0 / 3.6
#: times (s), positions (m) and speeds (m/s) of the knots
_Knots = tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]


def _speed_field(doc: str) -> Any:
    """An optional speed in km/h (its sign is checked with the profile, see :func:`knots`)."""
    return Field(None, description=doc, json_schema_extra={"unit": "km/h"})


class SpeedProfileSection(Section):
    """Speed against time of a non-stationary run (mode = "nonstationary")."""

    kind: Literal["constant", "uniform", "table"] = Field(
        ..., description="constant speed, uniform acceleration/braking, or a table"
    )
    speed_kmh: float | None = _speed_field("constant: the speed (omitted: the case's speed_kmh)")
    duration_s: float | None = Field(
        None,
        gt=0.0,
        le=1e5,
        description="constant: length of the run; uniform: time from v_start to v_end "
        "(instead of acceleration_ms2)",
        json_schema_extra={"unit": "s"},
    )
    v_start_kmh: float | None = _speed_field("uniform: speed at the start")
    v_end_kmh: float | None = _speed_field("uniform: speed at the end")
    acceleration_ms2: float | None = Field(
        None,
        gt=0.0,
        le=MAX_ACCELERATION_MS2,
        description="uniform: magnitude of the acceleration (braking when v_end < v_start)",
        json_schema_extra={"unit": "m/s^2"},
    )
    time_s: list[float] | None = Field(
        None,
        max_length=MAX_KNOTS,
        description="table: times of the knots, increasing (or give position_m)",
        json_schema_extra={"unit": "s"},
    )
    position_m: list[float] | None = Field(
        None,
        max_length=MAX_KNOTS,
        description="table: positions of the leading wheel at the knots, increasing",
        json_schema_extra={"unit": "m"},
    )
    speeds_kmh: list[float] | None = Field(
        None,
        max_length=MAX_KNOTS,
        description="table: speed at each knot (constant acceleration between knots)",
        json_schema_extra={"unit": "km/h"},
    )
    time_step_s: float | None = Field(
        None,
        gt=0.0,
        description="integration and output time step (omitted: half the Nyquist limit "
        "wavelength_min / (2 v_max))",
        json_schema_extra={"unit": "s"},
    )


class NonstationarySection(Section):
    """Settings of the non-stationary pseudo-excitation run."""

    method: Literal["exact", "quasi_stationary", "both"] = Field(
        "both", description="exact time integration, the quasi-stationary estimate, or both"
    )
    wavelength_min_m: float = Field(
        1.0,
        gt=0.0,
        le=1e4,
        description="shortest irregularity wavelength of the spatial band",
        json_schema_extra={"unit": "m"},
    )
    wavelength_max_m: float = Field(
        100.0,
        gt=0.0,
        le=1e5,
        description="longest irregularity wavelength of the spatial band",
        json_schema_extra={"unit": "m"},
    )
    n_wavenumbers: int = Field(
        1000, ge=16, le=100_000, description="spatial frequencies (log-spaced) of the band"
    )
    initial_state: Literal["steady", "rest"] = Field(
        "steady",
        description="steady: stationary response at the start speed; rest: the vehicle at rest "
        "(a start-up transient)",
    )
    map_times: int = Field(
        101, ge=2, le=5000, description="instants of the time-frequency map of the PSDs"
    )
    map_frequencies: int = Field(
        200,
        ge=2,
        le=5000,
        description="frequencies (log-spaced over the case's [frequency] band) of the map",
    )
    first_passage_levels: list[float] = Field(
        default_factory=lambda: [3.0, 4.0],
        max_length=20,
        description="levels of the first-passage probability, in multiples of each "
        "response's largest RMS over the run",
    )

    @model_validator(mode="after")
    def _band(self) -> NonstationarySection:
        if self.wavelength_max_m <= self.wavelength_min_m:
            raise CaseError(
                "nonstationary.wavelength_max_m",
                self.wavelength_max_m,
                f"must be > wavelength_min_m = {self.wavelength_min_m} (m)",
            )
        for i, level in enumerate(self.first_passage_levels):
            if not (np.isfinite(level) and level > 0):
                raise CaseError(f"nonstationary.first_passage_levels[{i}]", level, "must be > 0")
        return self


def knots(profile: SpeedProfileSection, case_speed_kmh: float) -> _Knots:
    """Times (s), positions (m) and speeds (m/s) of the profile's knots, after checking it.

    Between knots the acceleration is constant: ``x`` follows from ``t`` and ``v`` by
    ``dx = (v_a + v_b) dt / 2`` (and ``t`` from ``x`` and ``v`` the same way).

    Parameters
    ----------
    profile : SpeedProfileSection
        The ``[speed_profile]`` section.
    case_speed_kmh : float
        The case's ``speed_kmh`` (the speed of a constant profile that names none).

    Returns
    -------
    t, x, v : numpy.ndarray
        ``(n_knot,)`` each: s, m (the leading wheel starts at 0), m/s.

    Raises
    ------
    CaseError
        A key of another kind, a missing key, a negative speed, a profile that stops and
        starts again, one that does not move, or a table whose times or positions do not
        increase.
    """
    given = {k for k, v in profile.model_dump().items() if v is not None} - {"kind", "time_step_s"}
    own = {
        "constant": ({"duration_s"}, {"speed_kmh"}),
        "uniform": ({"v_start_kmh", "v_end_kmh"}, {"acceleration_ms2", "duration_s"}),
        "table": ({"speeds_kmh"}, {"time_s", "position_m"}),
    }[profile.kind]
    for key in sorted(given - own[0] - own[1]):
        raise CaseError(
            f"speed_profile.{key}",
            getattr(profile, key),
            f"not a key of kind {profile.kind!r} (its keys: {', '.join(sorted(own[0] | own[1]))})",
        )
    for key in sorted(own[0] - given):
        raise CaseError(f"speed_profile.{key}", "<missing>", f"required by kind {profile.kind!r}")
    if profile.kind == "constant":
        v_kmh = case_speed_kmh if profile.speed_kmh is None else profile.speed_kmh
        _check_speed("speed_profile.speed_kmh", v_kmh)
        if v_kmh == 0:
            raise CaseError(
                "speed_profile.speed_kmh", v_kmh, "must be > 0 (km/h): a profile that moves"
            )
        assert profile.duration_s is not None
        v = v_kmh * _KMH
        return (
            np.array([0.0, profile.duration_s]),
            np.array([0.0, v * profile.duration_s]),
            np.array([v, v]),
        )
    if profile.kind == "uniform":
        return _uniform(profile)
    return _table(profile)


def _check_speed(field: str, value: float) -> None:
    if not np.isfinite(value) or value < 0:
        raise CaseError(
            field, value, "must be >= 0 (km/h); a train running backwards is another run"
        )
    if value > 1000.0:
        raise CaseError(field, value, "must be <= 1000 (km/h)")


def _uniform(p: SpeedProfileSection) -> _Knots:
    assert p.v_start_kmh is not None
    assert p.v_end_kmh is not None
    _check_speed("speed_profile.v_start_kmh", p.v_start_kmh)
    _check_speed("speed_profile.v_end_kmh", p.v_end_kmh)
    v0, v1 = p.v_start_kmh * _KMH, p.v_end_kmh * _KMH
    if v0 == v1:
        raise CaseError(
            "speed_profile.v_end_kmh",
            p.v_end_kmh,
            f'must differ from v_start_kmh = {p.v_start_kmh} (km/h); use kind = "constant"',
        )
    if (p.acceleration_ms2 is None) == (p.duration_s is None):
        raise CaseError(
            "speed_profile.acceleration_ms2",
            "<missing>" if p.acceleration_ms2 is None else p.acceleration_ms2,
            "give exactly one of acceleration_ms2 (m/s^2) and duration_s (s)",
        )
    duration = abs(v1 - v0) / p.acceleration_ms2 if p.acceleration_ms2 is not None else p.duration_s
    assert duration is not None
    if p.duration_s is not None and abs(v1 - v0) / duration > MAX_ACCELERATION_MS2:
        raise CaseError(
            "speed_profile.duration_s",
            p.duration_s,
            f"must be >= {abs(v1 - v0) / MAX_ACCELERATION_MS2:.4g} s (an acceleration <= "
            f"{MAX_ACCELERATION_MS2} m/s^2)",
        )
    return (
        np.array([0.0, duration]),
        np.array([0.0, 0.5 * (v0 + v1) * duration]),
        np.array([v0, v1]),
    )


def _table(p: SpeedProfileSection) -> _Knots:
    assert p.speeds_kmh is not None
    if (p.time_s is None) == (p.position_m is None):
        raise CaseError(
            "speed_profile.time_s",
            "<missing>" if p.time_s is None else p.time_s,
            "give exactly one of time_s (s) and position_m (m)",
        )
    axis_name = "time_s" if p.time_s is not None else "position_m"
    axis = np.asarray(p.time_s if p.time_s is not None else p.position_m, dtype=float)
    kmh = np.asarray(p.speeds_kmh, dtype=float)
    if axis.size < 2 or axis.size != kmh.size:
        raise CaseError(
            f"speed_profile.{axis_name}",
            f"<{axis.size} values>",
            f"at least 2 values, one per speed (speeds_kmh has {kmh.size})",
        )
    for i, value in enumerate(kmh):
        _check_speed(f"speed_profile.speeds_kmh[{i}]", float(value))
    bad = np.flatnonzero(~np.isfinite(axis[1:]) | ~(np.diff(axis) > 0))
    if bad.size or not np.isfinite(axis[0]):
        i = int(bad[0]) + 1 if bad.size else 0
        raise CaseError(
            f"speed_profile.{axis_name}[{i}]",
            float(axis[i]),
            f"must be finite and > {axis_name}[{i - 1}] = {axis[i - 1]:g} (values increase)"
            if i
            else "must be finite",
        )
    moving = np.flatnonzero(kmh > 0)
    if moving.size == 0:
        raise CaseError(
            "speed_profile.speeds_kmh", p.speeds_kmh, "a profile that moves: some speed > 0 (km/h)"
        )
    stops = np.flatnonzero(kmh[1:] == 0) + 1
    restart = [i for i in stops if np.any(kmh[i + 1 :] > 0)]
    if restart:
        i = int(restart[0])
        j = i + 1 + int(np.flatnonzero(kmh[i + 1 :] > 0)[0])
        raise CaseError(
            f"speed_profile.speeds_kmh[{i}]",
            float(kmh[i]),
            f"a profile that stops ({axis_name}[{i}] = {axis[i]:g}) does not start again "
            f"(speeds_kmh[{j}] = {kmh[j]:g}): split it into two runs, or keep the speed > 0",
        )
    v = kmh * _KMH
    if axis_name == "time_s":
        t = axis - axis[0]
        x = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])
    else:
        x = axis - axis[0]
        pair = v[1:] + v[:-1]
        if np.any(pair == 0):  # two zero speeds in a row cannot cover a distance
            i = int(np.flatnonzero(pair == 0)[0])
            raise CaseError(
                f"speed_profile.speeds_kmh[{i + 1}]",
                0.0,
                "must be > 0 when position increases (km/h)",
            )
        t = np.concatenate([[0.0], np.cumsum(2.0 * np.diff(x) / pair)])
    acc = np.abs(np.diff(v) / np.diff(t))
    if np.any(acc > MAX_ACCELERATION_MS2):
        i = int(np.argmax(acc > MAX_ACCELERATION_MS2))
        raise CaseError(
            f"speed_profile.speeds_kmh[{i + 1}]",
            float(kmh[i + 1]),
            f"an acceleration of {acc[i]:.3g} m/s^2 from the knot before: at most "
            f"{MAX_ACCELERATION_MS2} m/s^2",
        )
    return t, x, v


def nyquist_time_step(wavelength_min_m: float, v_max: float) -> float:
    """Largest time step, s, that samples the highest excitation frequency twice a period.

    The highest excitation frequency of the run is ``f_top = v_max / wavelength_min``
    (Hz); a step ``dt <= 1 / (2 f_top)`` resolves it (to resolve a temporal band up to
    ``f_max`` down to the speed ``v_min`` needs ``wavelength_min = v_min / f_max``, so
    ``f_top = f_max v_max / v_min``).

    Parameters
    ----------
    wavelength_min_m : float
        Shortest wavelength of the spatial band, m.
    v_max : float
        Highest speed of the profile, m/s (> 0).

    Returns
    -------
    float
        ``wavelength_min / (2 v_max)`` in s.
    """
    return wavelength_min_m / (2.0 * v_max)


def check_time_step(
    profile: SpeedProfileSection, settings: NonstationarySection, case_speed_kmh: float
) -> float:
    """The run's time step, s: the one given, checked, or half the Nyquist limit.

    Parameters
    ----------
    profile : SpeedProfileSection
        The ``[speed_profile]`` section.
    settings : NonstationarySection
        The ``[nonstationary]`` section (its shortest wavelength).
    case_speed_kmh : float
        The case's ``speed_kmh``.

    Returns
    -------
    float
        Time step in s.

    Raises
    ------
    CaseError
        ``speed_profile.time_step_s`` above the Nyquist limit (the message gives the
        largest step that works, and the shortest wavelength that would work with this
        step), or a run of more than :data:`MAX_STEPS` steps.
    """
    t, _, v = knots(profile, case_speed_kmh)
    v_max = float(v.max())
    limit = nyquist_time_step(settings.wavelength_min_m, v_max)
    dt = profile.time_step_s if profile.time_step_s is not None else 0.5 * limit
    if dt > limit:
        raise CaseError(
            "speed_profile.time_step_s",
            dt,
            f"must be <= {limit:.4g} s: two steps per period of the highest excitation "
            f"frequency v_max / wavelength_min = {v_max:.4g} m/s / {settings.wavelength_min_m:g} m "
            f"= {v_max / settings.wavelength_min_m:.4g} Hz (or set nonstationary.wavelength_min_m "
            f">= {2.0 * dt * v_max:.4g} m)",
        )
    duration = float(t[-1])
    if duration / dt > MAX_STEPS:
        raise CaseError(
            "speed_profile.time_step_s",
            dt,
            f"a run of {duration:.4g} s needs a step >= {duration / MAX_STEPS:.3g} s "
            f"(at most {MAX_STEPS:,} steps)",
        )
    return dt
