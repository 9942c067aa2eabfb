"""The case-file schema: one pydantic model per section, units in the field metadata.

The schema drives validation (unknown keys, missing values, wrong types and
non-physical values are rejected with the field's dotted name), the commented
template (:mod:`railvib.case.template`) and the docs table. Values are SI unless
the key names another unit (``speed_kmh``, ``temperature_c``).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any, Literal

import tomli_w
from pydantic import Field, create_model, field_validator, model_validator

from railvib.case.moving import MovingSection
from railvib.case.profile import NonstationarySection, SpeedProfileSection, check_time_step
from railvib.case.sections import Section, section_model, table_section
from railvib.errors import CaseError
from railvib.outputs import ContactCheck
from railvib.registry import Parameter, Registry, declared_parameters
from railvib.spectra import SPECTRA
from railvib.track import DEFAULT_TRACK_MODEL, TRACKS, Rail
from railvib.vehicle import DEFAULT_VEHICLE_MODEL, VEHICLES

__all__ = [
    "FAMILY_TABLES",
    "Case",
    "ContactSection",
    "CriteriaSection",
    "FrequencySection",
    "OutputSection",
    "RailSection",
    "TrackSection",
    "TrainSection",
    "VehicleSection",
    "MAX_FREQUENCY_HZ",
    "MAX_RMS_BANDS",
    "MAX_SPEED_KMH",
    "check_label",
]

#: highest frequency of a grid, Hz: 20 times the 5 kHz top of railway vibration (the rail
#: is a beam on discrete pads; far above, its cross-section deforms)
MAX_FREQUENCY_HZ = 1.0e5
#: highest speed, km/h (trains in service run at up to 350 km/h, the record is 575 km/h)
MAX_SPEED_KMH = 1000.0
#: most RMS bands in a summary (third-octave bands from 0.1 Hz to 20 kHz are 54)
MAX_RMS_BANDS = 200
#: most characters of a title
MAX_TITLE_CHARS = 500


def check_label(field: str, value: Any, limit: int = MAX_TITLE_CHARS) -> str:
    """`value` if it is text fit for a title or label: no control characters, at most `limit`.

    Titles and labels go into netCDF attributes, Markdown, CSV and figure titles; a NUL
    or another control character breaks those writers (a line break, a table row).

    Parameters
    ----------
    field : str
        Dotted name of the field, for the error.
    value : object
        The text.
    limit : int
        Most characters allowed.

    Returns
    -------
    str
        `value`.

    Raises
    ------
    CaseError
        `value` is not text, holds a control character (one of U+0000-U+001F, U+007F-U+009F
        or a line or paragraph separator) or is longer than `limit`.
    """
    if not isinstance(value, str):
        raise CaseError(field, value, "text")
    bad = next((c for c in value if not c.isprintable() and c != " "), None)
    if bad is not None:
        raise CaseError(
            field,
            value,
            f"text without control characters (this one holds U+{ord(bad):04X} at position "
            f"{value.index(bad)}); write it on one line",
        )
    if len(value) > limit:
        raise CaseError(field, value, f"at most {limit} characters (this one has {len(value):,})")
    return value


def quantity(
    unit: str,
    doc: str,
    *,
    gt: float | None = 0.0,
    ge: float | None = None,
    le: float | None = None,
    plausible: tuple[float, float] | None = None,
    why: str = "",
    **kw: Any,
) -> Any:
    """A required physical field with its unit and one-line documentation.

    Parameters
    ----------
    unit : str
        Unit of the value.
    doc : str
        One line of documentation.
    gt, ge : float, optional
        Lower bound of a legal value (in `unit`); `ge` replaces `gt`.
    le : float, optional
        Upper bound of a legal value (in `unit`).
    plausible : (float, float), optional
        Legal values outside this range (in `unit`) load with a
        :class:`~railvib.errors.PlausibilityWarning` (see :mod:`railvib.case.plausibility`).
    why : str
        Why values outside `plausible` are suspicious, for the warning.
    **kw
        Passed to :func:`pydantic.Field`.

    Returns
    -------
    pydantic.fields.FieldInfo
        The field.
    """
    if ge is not None:
        gt = None
    extra: dict[str, Any] = {"unit": unit}
    if plausible is not None:
        extra.update(plausible=plausible, plausible_why=why)
    return Field(..., gt=gt, ge=ge, le=le, description=doc, json_schema_extra=extra, **kw)


#: the key of ``[vehicle]`` naming its model (omitted: the paper's 10-DOF car)
VEHICLE_MODEL_KEY = Parameter(
    "model",
    "",
    f"vehicle model, one of {', '.join(VEHICLES.names())} (omitted: {DEFAULT_VEHICLE_MODEL}; "
    "`railvib models vehicle`, docs/vehicles.md)",
    "text",
    default=None,
    choices=tuple(VEHICLES.names()),
)


def _vehicle_parameters() -> tuple[Parameter, ...]:
    """The keys of ``[vehicle]``: the model, then every model's own (checked against it)."""
    params = [VEHICLE_MODEL_KEY]
    for member in sorted(VEHICLES, key=lambda m: m.name != DEFAULT_VEHICLE_MODEL):
        for p in member.parameters:
            if p.key not in {q.key for q in params}:
                params.append(dataclasses.replace(p, default=None))
    return tuple(params)


#: table name -> (the registry's members, the table's keys computed from them)
_KEYS: dict[str, tuple[tuple[Any, ...], tuple[Parameter, ...]]] = {}


def _keys_of(
    table: str, registry: Registry[Any], keys: Callable[[], tuple[Parameter, ...]]
) -> tuple[Parameter, ...]:
    """``keys()``, computed again only when `registry`'s (frozen) members have changed.

    Every case's validation checks its ``[vehicle]`` and ``[track]`` keys against them;
    computing them is most of that check's time.
    """
    members = tuple(registry)
    hit = _KEYS.get(table)
    if (
        hit is None
        or len(hit[0]) != len(members)
        or any(a is not b for a, b in zip(hit[0], members, strict=True))
    ):
        hit = (members, keys())
        _KEYS[table] = hit
    return hit[1]


def _check_vehicle(self: Section) -> Section:
    """Refuse keys of another vehicle model, require the model's own, and build it."""
    name = getattr(self, "model", None) or DEFAULT_VEHICLE_MODEL
    member = VEHICLES.get(name, "vehicle")
    own = {p.key: p for p in member.parameters}
    values = {}
    for p in _keys_of("vehicle", VEHICLES, _vehicle_parameters)[1:]:
        value = getattr(self, p.key)
        if p.key not in own and value is not None:
            raise CaseError(
                f"vehicle.{p.key}",
                value,
                f"not a key of vehicle model {name!r} (set vehicle.model)",
            )
        if p.key in own and value is None and own[p.key].required:
            unit = f" ({p.unit})" if p.unit not in ("", "-") else ""
            raise CaseError(f"vehicle.{p.key}", "<missing>", f"required{unit}")
        if p.key in own and value is not None:
            values[own[p.key].name] = value
    member.build(**values)
    return self


_VehicleBase: Any = section_model(
    "VehicleSection",
    _vehicle_parameters(),
    "The 10-DOF pitch-plane car (whole car; suspensions per wheelset / per bogie), or a "
    'vehicle of any topology (model = "multibody").',
)

#: ``[vehicle]``: the model and the parameters of every vehicle model, declared with them
VehicleSection: Any = create_model(
    "VehicleSection",
    __base__=_VehicleBase,
    __validators__={"_check_model": model_validator(mode="after")(_check_vehicle)},  # type: ignore[dict-item]
)
VehicleSection.__doc__ = _VehicleBase.__doc__

#: ``[track.rail]``: the rail beam, declared with :class:`~railvib.track.Rail`
RailSection: Any = table_section(Rail)

#: the key of ``[track]`` naming its model (omitted: the default rigid-base track)
TRACK_MODEL_KEY = Parameter(
    "model",
    "",
    f"track model, one of {', '.join(TRACKS.names())} (omitted: {DEFAULT_TRACK_MODEL}; "
    "`railvib models track`)",
    "text",
    default=None,
    choices=tuple(TRACKS.names()),
)


def _track_parameters() -> tuple[Parameter, ...]:
    """The keys of ``[track]``: the model, the default model's, then the other members' own.

    The other members' keys are optional here and checked against the chosen model.
    """
    params = [TRACK_MODEL_KEY, *TRACKS.get(DEFAULT_TRACK_MODEL).parameters]
    for member in TRACKS:
        for p in member.parameters:
            if p.key not in {q.key for q in params}:
                params.append(dataclasses.replace(p, default=None))
    return tuple(params)


def _check_track_keys(self: Section) -> Section:
    """Refuse keys of another track model, and require the chosen model's own keys."""
    name = getattr(self, "model", None) or DEFAULT_TRACK_MODEL
    member = TRACKS.get(name, "track")
    own = {p.key: p for p in member.parameters}
    for p in _keys_of("track", TRACKS, _track_parameters)[1:]:
        value = getattr(self, p.key)
        if p.key not in own and value is not None:
            raise CaseError(
                f"track.{p.key}", value, f"not a key of track model {name!r} (set track.model)"
            )
        if p.key in own and own[p.key].required and value is None:
            unit = f" ({p.unit})" if p.unit not in ("", "-") else ""
            raise CaseError(
                f"track.{p.key}", "<missing>", f"required by track model {name!r}{unit}"
            )
    return self


_TrackBase: Any = section_model(
    "TrackSection", _track_parameters(), "Rail on discrete supports at every sleeper."
)

#: ``[track]``: the model and the parameters of every track model, declared with them
TrackSection: Any = create_model(
    "TrackSection",
    __base__=_TrackBase,
    __validators__={"_check_keys": model_validator(mode="after")(_check_track_keys)},  # type: ignore[dict-item]
)
TrackSection.__doc__ = "Rail on discrete supports at every sleeper (rigid base, ballast, ...)."


class ContactSection(Section):
    """Linearised Hertz contact, one spring per wheelset."""

    contact_constant: float = quantity(
        "m/N^(2/3)", "Hertz contact constant G", le=1e-4
    )  # wheels are about 5e-8: 1e-4 is a contact stiffness of a few kN/m
    stiffness: float | None = Field(
        None,
        gt=0.0,
        le=1e15,
        description="contact stiffness per wheelset; if omitted, k_H = 3/(2G) P0^(1/3) from the "
        "static wheel load P0 (and twice that in rail_pair mode); per wheel in half_car mode",
        json_schema_extra={"unit": "N/m"},
    )
    leading_wheel_position: float = quantity(
        "m", "position of the leading wheel after a sleeper, in [0, d)", ge=0.0, le=3.0
    )  # d <= 3 m (track.sleeper_spacing)


#: most cars of a train (a 20-car train has 80 wheels; the track's receptance between all
#: wheels grows as the square of their number)
MAX_CARS = 50


class TrainSection(Section):
    """A train: the [vehicle] repeated car after car, all wheels on the one track."""

    cars: int = Field(1, ge=1, le=MAX_CARS, description="number of cars (1: a single vehicle)")
    gap_m: float = Field(
        5.0,
        gt=0.0,
        le=1.0e3,
        description="distance from the trailing wheel of a car to the leading wheel of the next",
        json_schema_extra={"unit": "m"},
    )
    coupler_stiffness_n_per_m: float = Field(
        0.0,
        ge=0.0,
        le=1.0e10,
        description="vertical stiffness of the coupler between neighbouring car bodies "
        "(0: no coupler)",
        json_schema_extra={"unit": "N/m"},
    )
    coupler_damping_ns_per_m: float = Field(
        0.0,
        ge=0.0,
        le=1.0e8,
        description="viscous damping of the coupler (needs a coupler stiffness)",
        json_schema_extra={"unit": "N s/m"},
    )

    @model_validator(mode="after")
    def _coupler(self) -> TrainSection:
        if self.coupler_damping_ns_per_m > 0 and self.coupler_stiffness_n_per_m == 0:
            raise CaseError(
                "train.coupler_stiffness_n_per_m",
                0.0,
                "must be > 0 where a coupler damping is given (N/m)",
            )
        return self


class FrequencySection(Section):
    """The frequency grid of the analysis."""

    f_min: float = quantity("Hz", "lowest frequency", le=MAX_FREQUENCY_HZ)
    f_max: float = quantity("Hz", "highest frequency", le=MAX_FREQUENCY_HZ)
    spacing: Literal["linear", "log"] = Field("linear", description="grid spacing")
    step: float | None = Field(
        None,
        gt=0.0,
        le=MAX_FREQUENCY_HZ,
        description="step of a linear grid",
        json_schema_extra={"unit": "Hz"},
    )
    n: int | None = Field(None, ge=2, description="number of points of a log grid")

    @model_validator(mode="after")
    def _band(self) -> FrequencySection:
        if self.f_max <= self.f_min:
            raise CaseError("frequency.f_max", self.f_max, f"must be > f_min = {self.f_min} (Hz)")
        if self.spacing == "linear" and self.step is None:
            raise CaseError("frequency.step", None, "required for a linear grid (Hz)")
        if self.spacing == "log" and self.n is None:
            raise CaseError("frequency.n", None, "required for a log grid (number of points)")
        return self


#: the threshold of the contact check, declared once with :class:`~railvib.outputs.ContactCheck`
_THRESHOLD = {p.key: p for p in declared_parameters(ContactCheck)}["loss_of_contact_threshold"]


class OutputSection(Section):
    """What the summary reports."""

    rms_bands: list[tuple[float, float]] = Field(
        default_factory=lambda: [(0.5, 20.0), (20.0, 100.0), (100.0, 1000.0)],
        max_length=MAX_RMS_BANDS,
        description="frequency bands [f_lo, f_hi] for the RMS in the summary",
        json_schema_extra={"unit": "Hz"},
    )
    loss_of_contact_threshold: float = Field(
        default=float(_THRESHOLD.default),
        gt=_THRESHOLD.gt,
        lt=_THRESHOLD.lt,
        description=_THRESHOLD.doc.split(";")[0] + "; above it the case is flagged "
        "linear_model_valid = false (railvib run --strict exits with code 3)",
        json_schema_extra={"unit": _THRESHOLD.unit},
    )

    @field_validator("rms_bands", mode="before")
    @classmethod
    def _count(cls, value: Any) -> Any:
        """Refuse too many bands before each is validated (10^5 bands took 10 s)."""
        if isinstance(value, list | tuple) and len(value) > MAX_RMS_BANDS:
            raise CaseError(
                "output.rms_bands", f"<{len(value):,} bands>", f"at most {MAX_RMS_BANDS} bands"
            )
        return value

    @model_validator(mode="after")
    def _bands(self) -> OutputSection:
        for i, (lo, hi) in enumerate(self.rms_bands):
            if not (0 <= lo < hi):
                raise CaseError(f"output.rms_bands[{i}]", [lo, hi], "need 0 <= f_lo < f_hi (Hz)")
        return self


class CriteriaSection(Section):
    """Settings of the engineering criteria (docs/criteria.md); every key is optional."""

    floor_positions_m: list[float] | None = Field(
        None,
        max_length=20,
        description="floor points of the car body for ride comfort, m from its centre, "
        "positive forward (default: over the bogies and at the centre)",
        json_schema_extra={"unit": "m"},
    )
    comfort_body: str = Field(
        "carbody",
        description="the body whose floor is evaluated (a body with bounce and pitch; in a "
        "train the default is the leading car's, car1.carbody)",
    )
    comfort_weighting: Literal["Wb", "Wk"] = Field(
        "Wb",
        description="frequency weighting of a_w: Wb (ISO 2631-4, EN 12299: rail vehicles) "
        "or Wk (ISO 2631-1)",
    )
    comfort_band_hz: tuple[float, float] | None = Field(
        None,
        description="band of a_w, N_MV and Wz within 0.5-80 Hz (default: 0.5-80 Hz where the "
        "grid reaches)",
        json_schema_extra={"unit": "Hz"},
    )
    octave_band_hz: tuple[float, float] | None = Field(
        None,
        description="range of the one-third-octave bands (default: the whole grid)",
        json_schema_extra={"unit": "Hz"},
    )


class Case(Section):
    """A complete railvib case: vehicle, track, contact, operation, irregularity, grid.

    Attributes
    ----------
    vehicle : VehicleSection
        The ``[vehicle]`` section (`railvib models vehicle`).
    track : TrackSection
        The ``[track]`` section (`railvib models track`).
    contact : ContactSection
        The ``[contact]`` section: Hertz contact.
    frequency : FrequencySection
        The ``[frequency]`` grid, Hz.
    output : OutputSection
        The ``[output]`` section: RMS bands and the loss-of-contact threshold.
    """

    title: str = Field("railvib case", description="free text shown in outputs")
    rail_model: Literal["single_rail", "rail_pair", "half_car"] = Field(
        ...,
        description="single_rail: the beam is ONE rail carrying the whole vehicle (the paper's "
        "reading); rail_pair: the beam is both rails (2 EI, 2 m, 2 pads, 2 k_H per wheelset); "
        "half_car: the beam is one rail under half the vehicle (its masses, inertias and "
        "suspensions halved, k_H of one wheel) - the same physics as rail_pair "
        "(docs/vehicles.md)",
    )
    speed_kmh: float = quantity(
        "km/h",
        "vehicle speed",
        le=MAX_SPEED_KMH,
        plausible=(10.0, 450.0),
        why="the range of railway running speeds (trains in service run at up to 350 km/h): "
        "likely a typo or a value in another unit",
    )
    vehicle: VehicleSection
    train: TrainSection | None = Field(
        None, description="a train of [vehicle] cars (omitted: one vehicle; docs/vehicles.md)"
    )
    track: TrackSection
    contact: ContactSection
    irregularity: dict[str, Any] = Field(
        ..., description="irregularity spectrum (type = <name>: `railvib models spectrum`)"
    )
    frequency: FrequencySection
    output: OutputSection = Field(default_factory=OutputSection)
    criteria: CriteriaSection | None = Field(
        None, description="settings of the engineering criteria (docs/criteria.md)"
    )
    mode: Literal["stationary", "nonstationary", "moving"] = Field(
        "stationary",
        description="stationary: one speed (speed_kmh); nonstationary: the speed of "
        "[speed_profile] (docs/nonstationary.md); moving: the vehicle moving over the "
        "sleepers at speed_kmh, sleeper-passing lines and cyclostationary PSDs "
        "(docs/moving-vehicle.md)",
    )
    speed_profile: SpeedProfileSection | None = Field(
        None, description='speed against time, for mode = "nonstationary"'
    )
    nonstationary: NonstationarySection | None = Field(
        None, description="settings of a non-stationary run (omitted: the defaults)"
    )
    moving: MovingSection | None = Field(
        None, description='settings of a mode = "moving" run (omitted: the defaults)'
    )

    @model_validator(mode="after")
    def _profile(self) -> Case:
        if self.mode == "nonstationary":
            if self.speed_profile is None:
                raise CaseError("speed_profile", "<missing>", 'required by mode = "nonstationary"')
            check_time_step(
                self.speed_profile,
                self.nonstationary or NonstationarySection.model_validate({}),
                self.speed_kmh,
            )
        elif self.speed_profile is not None or self.nonstationary is not None:
            field = "speed_profile" if self.speed_profile is not None else "nonstationary"
            raise CaseError(
                field, "<table>", 'used by mode = "nonstationary" only: set mode, or remove it'
            )
        if self.moving is not None and self.mode != "moving":
            raise CaseError(
                "moving", "<table>", 'used by mode = "moving" only: set mode, or remove it'
            )
        return self

    @field_validator("title")
    @classmethod
    def _title(cls, value: str) -> str:
        return check_label("title", value)

    def to_toml(self) -> str:
        """The full, resolved case as TOML text (stored with every result)."""
        return tomli_w.dumps(self.model_dump(mode="json", exclude_none=True))


#: the family tables of a case (location -> family): free tables naming a member
FAMILY_TABLES: dict[tuple[str, ...], Registry[Any]] = {
    **{
        ("track", p.key): p.family
        for p in _track_parameters()
        if p.kind == "member" and p.family is not None
    },
    ("irregularity",): SPECTRA,
}
