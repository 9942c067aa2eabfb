"""Build the physics objects a validated case describes (the one place SI conversion happens)."""

from __future__ import annotations

from railvib.case.schema import Case
from railvib.contact import hertz_stiffness
from railvib.coupling import CoupledSystem
from railvib.grid import FrequencyGrid
from railvib.pads.base import PadModel
from railvib.spectra.base import SpatialSpectrum
from railvib.track.periodic import PeriodicTrack, Rail
from railvib.units import kmh_to_ms
from railvib.vehicle import PitchPlaneParameters, Vehicle, pitch_plane_10dof

__all__ = [
    "build_grid",
    "build_pad",
    "build_spectrum",
    "build_system",
    "build_track",
    "build_vehicle",
    "contact_stiffness",
]


def build_vehicle(case: Case) -> Vehicle:
    """The 10-DOF pitch-plane vehicle of the case."""
    return pitch_plane_10dof(PitchPlaneParameters(**case.vehicle.model_dump()))


def build_pad(case: Case) -> PadModel:
    """The railpad model of one rail seat (before any rail_pair doubling)."""
    from railvib.pads import pad_from_dict

    return pad_from_dict(dict(case.track.pad), field="track.pad")


def build_spectrum(case: Case) -> SpatialSpectrum:
    """The irregularity spectrum of the case."""
    from railvib.spectra import spectrum_from_dict

    return spectrum_from_dict(dict(case.irregularity), field="irregularity")


def _rail_multiplier(case: Case) -> float:
    return 2.0 if case.rail_model == "rail_pair" else 1.0


def build_track(case: Case) -> PeriodicTrack:
    """The periodic track; in ``rail_pair`` mode the beam and pads stand for both rails."""
    from railvib.pads.scaled import ScaledPad

    n = _rail_multiplier(case)
    r = case.track.rail
    rail = Rail(
        n * r.bending_stiffness,
        n * r.mass_per_length,
        r.loss_factor,
        shear_stiffness=None if r.shear_stiffness is None else n * r.shear_stiffness,
        rotary_inertia=n * r.rotary_inertia,
    )
    pad = build_pad(case)
    if n != 1.0:
        pad = ScaledPad(pad, n)
    return PeriodicTrack(rail, pad, case.track.sleeper_spacing, case.track.pad_temperature_c)


def contact_stiffness(case: Case, vehicle: Vehicle | None = None) -> float:
    """Contact stiffness per wheelset, N/m.

    Given explicitly, or the linearised Hertz stiffness at the static load of
    one wheel (half the wheelset load), doubled in ``rail_pair`` mode where the
    two wheels of a wheelset act in parallel on the one beam.
    """
    if case.contact.stiffness is not None:
        return case.contact.stiffness
    vehicle = build_vehicle(case) if vehicle is None else vehicle
    wheel_load = float(vehicle.static_wheel_loads().mean()) / 2.0
    return _rail_multiplier(case) * hertz_stiffness(case.contact.contact_constant, wheel_load)


def build_system(case: Case) -> CoupledSystem:
    """The coupled vehicle-track system of the case."""
    vehicle = build_vehicle(case)
    return CoupledSystem(
        vehicle=vehicle,
        track=build_track(case),
        contact_stiffness=contact_stiffness(case, vehicle),
        leading_wheel_position=case.contact.leading_wheel_position,
        speed=kmh_to_ms(case.speed_kmh),
    )


def build_grid(case: Case) -> FrequencyGrid:
    """The frequency grid of the case."""
    fr = case.frequency
    if fr.spacing == "log":
        assert fr.n is not None
        return FrequencyGrid.logarithmic(fr.f_min, fr.f_max, fr.n)
    assert fr.step is not None
    return FrequencyGrid.linear(fr.f_min, fr.f_max, fr.step)
