"""The case-file schema: one pydantic model per section, units in the field metadata.

The schema drives validation (unknown keys, missing values, wrong types and
non-physical values are rejected with the field's dotted name), the commented
template (:mod:`railvib.case.template`) and the docs table. Values are SI unless
the key names another unit (``speed_kmh``, ``temperature_c``).
"""

from __future__ import annotations

from typing import Any, Literal

import tomli_w
from pydantic import BaseModel, ConfigDict, Field, model_validator

__all__ = [
    "Case",
    "ContactSection",
    "FrequencySection",
    "OutputSection",
    "RailSection",
    "TrackSection",
    "VehicleSection",
]


def quantity(
    unit: str, doc: str, *, gt: float | None = 0.0, ge: float | None = None, **kw: Any
) -> Any:
    """A required physical field with its unit and one-line documentation."""
    if ge is not None:
        gt = None
    return Field(..., gt=gt, ge=ge, description=doc, json_schema_extra={"unit": unit}, **kw)


class _Section(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, strict=False)


class VehicleSection(_Section):
    """The 10-DOF pitch-plane car (whole car; suspensions per wheelset / per bogie)."""

    carbody_mass: float = quantity("kg", "car body mass M_c")
    carbody_pitch_inertia: float = quantity("kg m^2", "car body pitch inertia J_c")
    bogie_mass: float = quantity("kg", "mass of one bogie frame M_t")
    bogie_pitch_inertia: float = quantity("kg m^2", "pitch inertia of one bogie J_t")
    wheelset_mass: float = quantity("kg", "mass of one wheelset M_w")
    primary_stiffness: float = quantity("N/m", "primary suspension stiffness per wheelset K_s1")
    primary_damping: float = quantity("N s/m", "primary damping per wheelset C_s1", ge=0.0)
    secondary_stiffness: float = quantity("N/m", "secondary suspension stiffness per bogie K_s2")
    secondary_damping: float = quantity("N s/m", "secondary damping per bogie C_s2", ge=0.0)
    bogie_half_spacing: float = quantity("m", "half the distance between bogie centres l_c")
    wheelset_half_spacing: float = quantity("m", "half the wheelbase of a bogie l_t")

    @model_validator(mode="after")
    def _geometry(self) -> VehicleSection:
        if self.wheelset_half_spacing >= self.bogie_half_spacing:
            from railvib.errors import CaseError

            raise CaseError(
                "vehicle.wheelset_half_spacing",
                self.wheelset_half_spacing,
                f"must be < bogie_half_spacing = {self.bogie_half_spacing} (m)",
            )
        return self


class RailSection(_Section):
    """Euler-Bernoulli rail."""

    bending_stiffness: float = quantity("N m^2", "bending stiffness EI of the rail beam")
    mass_per_length: float = quantity("kg/m", "mass per unit length of the rail beam")
    loss_factor: float = quantity("-", "rail loss factor eta_r (EI -> EI (1 + i eta_r))", ge=0.0)
    shear_stiffness: float | None = Field(
        None,
        gt=0.0,
        description="kappa G A; given, the rail is a Timoshenko beam (CHN60: 2.45e8), "
        "omitted, an Euler-Bernoulli beam as in the paper",
        json_schema_extra={"unit": "N"},
    )
    rotary_inertia: float = Field(
        0.0,
        ge=0.0,
        description="rho I, rotary inertia per length of a Timoshenko rail (CHN60: 0.2525)",
        json_schema_extra={"unit": "kg m"},
    )


class TrackSection(_Section):
    """Rail on discrete railpads at every sleeper, rigid below."""

    sleeper_spacing: float = quantity("m", "sleeper spacing d")
    rail: RailSection
    pad: dict[str, Any] = Field(
        ...,
        description="railpad model: model = spring_damper | hysteretic | log_linear | tabulated | "
        "constant_phase | zener | fractional_zener | prony | ..., plus its parameters",
    )
    pad_temperature_c: float | None = Field(
        None,
        gt=-273.15,
        description="pad temperature used by temperature-dependent pad models",
        json_schema_extra={"unit": "degC"},
    )


class ContactSection(_Section):
    """Linearised Hertz contact, one spring per wheelset."""

    contact_constant: float = quantity("m/N^(2/3)", "Hertz contact constant G")
    stiffness: float | None = Field(
        None,
        gt=0.0,
        description="contact stiffness per wheelset; if omitted, k_H = 3/(2G) P0^(1/3) from the "
        "static wheel load P0 (and twice that in rail_pair mode)",
        json_schema_extra={"unit": "N/m"},
    )
    leading_wheel_position: float = quantity(
        "m", "position of the leading wheel after a sleeper, in [0, d)", ge=0.0
    )


class FrequencySection(_Section):
    """The frequency grid of the analysis."""

    f_min: float = quantity("Hz", "lowest frequency")
    f_max: float = quantity("Hz", "highest frequency")
    spacing: Literal["linear", "log"] = Field("linear", description="grid spacing")
    step: float | None = Field(
        None, gt=0.0, description="step of a linear grid", json_schema_extra={"unit": "Hz"}
    )
    n: int | None = Field(None, ge=2, description="number of points of a log grid")

    @model_validator(mode="after")
    def _band(self) -> FrequencySection:
        from railvib.errors import CaseError

        if self.f_max <= self.f_min:
            raise CaseError("frequency.f_max", self.f_max, f"must be > f_min = {self.f_min} (Hz)")
        if self.spacing == "linear" and self.step is None:
            raise CaseError("frequency.step", None, "required for a linear grid (Hz)")
        if self.spacing == "log" and self.n is None:
            raise CaseError("frequency.n", None, "required for a log grid (number of points)")
        return self


class OutputSection(_Section):
    """What the summary reports."""

    rms_bands: list[tuple[float, float]] = Field(
        default_factory=lambda: [(0.5, 20.0), (20.0, 100.0), (100.0, 1000.0)],
        description="frequency bands [f_lo, f_hi] for the RMS in the summary",
        json_schema_extra={"unit": "Hz"},
    )

    @model_validator(mode="after")
    def _bands(self) -> OutputSection:
        from railvib.errors import CaseError

        for i, (lo, hi) in enumerate(self.rms_bands):
            if not (0 <= lo < hi):
                raise CaseError(f"output.rms_bands[{i}]", [lo, hi], "need 0 <= f_lo < f_hi (Hz)")
        return self


class Case(_Section):
    """A complete railvib case: vehicle, track, contact, operation, irregularity, grid."""

    title: str = Field("railvib case", description="free text shown in outputs")
    rail_model: Literal["single_rail", "rail_pair"] = Field(
        ...,
        description="single_rail: the beam is ONE rail carrying the whole vehicle (the paper's "
        "reading); rail_pair: the beam is both rails (2 EI, 2 m, 2 pads, 2 k_H per wheelset)",
    )
    speed_kmh: float = quantity("km/h", "vehicle speed")
    vehicle: VehicleSection
    track: TrackSection
    contact: ContactSection
    irregularity: dict[str, Any] = Field(
        ..., description="irregularity spectrum (type = fra | shitai | combined | tabulated | ...)"
    )
    frequency: FrequencySection
    output: OutputSection = Field(default_factory=OutputSection)

    def to_toml(self) -> str:
        """The full, resolved case as TOML text (stored with every result)."""
        return tomli_w.dumps(self.model_dump(mode="json", exclude_none=True))
