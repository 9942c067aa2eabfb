"""Build the physics objects a validated case describes (the one place SI conversion happens)."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

from railvib.case.schema import Case
from railvib.contact import hertz_stiffness
from railvib.coupling import CoupledSystem
from railvib.grid import FrequencyGrid
from railvib.pads import PADS, PadModel
from railvib.pads.scaled import ScaledPad
from railvib.spectra import SPECTRA, SpatialSpectrum
from railvib.track import DEFAULT_TRACK_MODEL, TRACKS, PeriodicTrack, Rail
from railvib.units import kmh_to_ms
from railvib.vehicle import DEFAULT_VEHICLE_MODEL, VEHICLES, Vehicle, make_train

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
    """The vehicle of the case (its ``[vehicle]`` model assembled).

    Parameters
    ----------
    case : Case
        A validated case.

    Returns
    -------
    Vehicle
        The whole car (a ``[train]`` of them, :func:`railvib.vehicle.make_train`); in
        ``half_car`` mode half of it (every mass, inertia, stiffness and
        damping halved: the side of one rail).
    """
    name = case.vehicle.model or DEFAULT_VEHICLE_MODEL
    member = VEHICLES.get(name, "vehicle")
    given = case.vehicle.model_dump()
    values = {p.name: given[p.key] for p in member.parameters if given.get(p.key) is not None}
    vehicle = member.build(**values).vehicle()
    train = case.train
    if train is not None and train.cars > 1:
        vehicle = make_train(
            [vehicle] * train.cars,
            train.gap_m,
            train.coupler_stiffness_n_per_m,
            train.coupler_damping_ns_per_m,
        )
    return vehicle.scaled(0.5) if case.rail_model == "half_car" else vehicle


def build_pad(case: Case) -> PadModel:
    """The railpad model of one rail seat (before any rail_pair doubling).

    Parameters
    ----------
    case : Case
        A validated case.

    Returns
    -------
    PadModel
        The ``[track.pad]`` model, complex stiffness per rail seat in N/m.
    """
    return PADS.from_dict(dict(case.track.pad), "track.pad")


def build_spectrum(case: Case) -> SpatialSpectrum:
    """The irregularity spectrum of the case."""
    return SPECTRA.from_dict(dict(case.irregularity), "irregularity")


#: units of the ``[track]`` numbers given per rail (masses per rail seat, a slab's share of
#: one rail): doubled in ``rail_pair`` mode with the rail; lengths, counts, loss factors and
#: temperatures are not
PER_RAIL_UNITS = ("kg", "kg/m", "N m^2", "N/m", "N m/rad")


def _rail_multiplier(case: Case) -> float:
    return 2.0 if case.rail_model == "rail_pair" else 1.0


def build_track(case: Case) -> PeriodicTrack:
    """The periodic track; in ``rail_pair`` mode the beam and pads stand for both rails.

    Parameters
    ----------
    case : Case
        A validated case.

    Returns
    -------
    PeriodicTrack
        The periodic track of the case's ``track.model`` in SI units; in ``rail_pair``
        mode EI, m, kappa G A, rho I, the pad (and ballast, subgrade, foundation, bearing)
        stiffness and the quantities per rail (:data:`PER_RAIL_UNITS`: masses per rail
        seat, a slab's EI, mass and joint stiffnesses) are doubled.
    """
    n = _rail_multiplier(case)
    rail = Rail(**case.track.rail.model_dump())
    pad = build_pad(case)
    if n != 1.0:
        shear = None if rail.shear_stiffness is None else n * rail.shear_stiffness
        rail = replace(
            rail,
            bending_stiffness=n * rail.bending_stiffness,
            mass_per_length=n * rail.mass_per_length,
            shear_stiffness=shear,
            rotary_inertia=n * rail.rotary_inertia,
        )
        pad = ScaledPad(pad, n)
    member = TRACKS.get(case.track.model or DEFAULT_TRACK_MODEL, "track")
    given = case.track.model_dump()
    values: dict[str, Any] = {
        p.name: given[p.key]
        for p in member.parameters
        if given.get(p.key) is not None and p.kind not in ("member", "table")
    }
    values.update(rail=rail, pad=pad)
    for p in member.parameters:
        if p.kind == "member" and p.key != "pad" and given.get(p.key) is not None:
            layer = PADS.from_dict(dict(given[p.key]), f"track.{p.key}")
            values[p.name] = layer if n == 1.0 else ScaledPad(layer, n)
        elif p.kind == "number" and p.unit in PER_RAIL_UNITS and p.name in values:
            values[p.name] = n * values[p.name]  # a quantity per rail: both rails' share
    track = member.build(**values)
    assert isinstance(track, PeriodicTrack), "every track model is a periodic track"
    return track


def contact_stiffness(case: Case, vehicle: Vehicle | None = None) -> float:
    """Contact stiffness per wheelset, N/m.

    Given explicitly, or the linearised Hertz stiffness at the static load of
    one wheel (half the wheelset load), doubled in ``rail_pair`` mode where the
    two wheels of a wheelset act in parallel on the one beam. In ``half_car`` mode
    the vehicle is half the car, so its contact loads are those of one wheel.

    Parameters
    ----------
    case : Case
        A validated case.
    vehicle : Vehicle, optional
        The case's vehicle if already built (its static wheel loads in N are used);
        None builds it.

    Returns
    -------
    float
        Contact stiffness k_H in N/m.
    """
    if case.contact.stiffness is not None:
        return case.contact.stiffness
    vehicle = build_vehicle(case) if vehicle is None else vehicle
    per_contact = float(vehicle.static_wheel_loads().mean())
    wheel_load = per_contact if case.rail_model == "half_car" else per_contact / 2.0
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
