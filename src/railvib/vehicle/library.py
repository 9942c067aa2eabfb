"""Ready-made vehicles built from parts."""

from __future__ import annotations

from dataclasses import dataclass

from railvib.errors import CaseError
from railvib.registry import parameter
from railvib.vehicle.assembly import Vehicle
from railvib.vehicle.base import VEHICLES, VehicleModel
from railvib.vehicle.parts import Attachment, RigidBody, Suspension, Wheel

__all__ = ["PitchPlaneParameters", "pitch_plane_10dof"]


def _positive(unit: str, doc: str, typical: tuple[float, float], le: float) -> float:
    """A parameter that must be > 0 and <= `le`, plausible over `typical` (log-uniform)."""
    return parameter(unit, doc, gt=0.0, le=le, typical=typical, log=True)


@VEHICLES.register("pitch_plane_10dof")
@dataclass(frozen=True)
class PitchPlaneParameters(VehicleModel):
    """The 10-DOF pitch-plane car: body and two bogies in bounce and pitch, four wheelsets.

    Paper Table 1 values are for the whole car; suspensions are per wheelset
    (primary) and per bogie (secondary).

    Parameters
    ----------
    carbody_mass : float
        M_c, kg.
    carbody_pitch_inertia : float
        J_c, kg m^2.
    bogie_mass : float
        M_t (each bogie), kg.
    bogie_pitch_inertia : float
        J_t (each bogie), kg m^2.
    wheelset_mass : float
        M_w (each wheelset), kg.
    primary_stiffness : float
        K_s1 per wheelset (both sides together), N/m.
    primary_damping : float
        C_s1 per wheelset, N s/m.
    secondary_stiffness : float
        K_s2 per bogie, N/m.
    secondary_damping : float
        C_s2 per bogie, N s/m.
    bogie_half_spacing : float
        l_c, half the distance between bogie centres, m.
    wheelset_half_spacing : float
        l_t, half the wheelbase of a bogie, m.
    """

    # upper bounds: some 10-100 times any rail vehicle's value (a 100 t car, a 27 m car
    # body), so that no real car is refused and every product of them stays finite
    carbody_mass: float = _positive("kg", "car body mass M_c", (1e4, 6e4), 1e6)
    carbody_pitch_inertia: float = _positive(
        "kg m^2", "car body pitch inertia J_c", (2e5, 3e6), 1e9
    )
    bogie_mass: float = _positive("kg", "mass of one bogie frame M_t", (1e3, 4e3), 1e5)
    bogie_pitch_inertia: float = _positive(
        "kg m^2", "pitch inertia of one bogie J_t", (1e3, 5e3), 1e6
    )
    wheelset_mass: float = _positive("kg", "mass of one wheelset M_w", (8e2, 2.5e3), 1e5)
    primary_stiffness: float = _positive(
        "N/m", "primary suspension stiffness per wheelset K_s1", (3e5, 5e6), 1e10
    )
    primary_damping: float = parameter(
        "N s/m", "primary damping per wheelset C_s1", ge=0.0, le=1e8, typical=(1e2, 5e4), log=True
    )
    secondary_stiffness: float = _positive(
        "N/m", "secondary suspension stiffness per bogie K_s2", (1e5, 1e6), 1e10
    )
    secondary_damping: float = parameter(
        "N s/m", "secondary damping per bogie C_s2", ge=0.0, le=1e8, typical=(1e3, 1e5), log=True
    )
    bogie_half_spacing: float = parameter(
        "m", "half the distance between bogie centres l_c", gt=0.0, le=50.0, typical=(4.0, 10.0)
    )
    wheelset_half_spacing: float = parameter(
        "m", "half the wheelbase of a bogie l_t", gt=0.0, le=10.0, typical=(0.9, 1.5)
    )

    def validate(self) -> None:
        """The wheelsets of a bogie lie between the bogie centres: ``l_t < l_c``."""
        if self.wheelset_half_spacing >= self.bogie_half_spacing:
            raise CaseError(
                "wheelset_half_spacing",
                self.wheelset_half_spacing,
                f"must be < bogie_half_spacing = {self.bogie_half_spacing} (m)",
            )

    def vehicle(self) -> Vehicle:
        """The assembled 10-DOF car (see :func:`pitch_plane_10dof`)."""
        return pitch_plane_10dof(self)


def pitch_plane_10dof(p: PitchPlaneParameters) -> Vehicle:
    """Car body and two bogies in bounce and pitch, four wheelsets in bounce.

    Wheelsets are numbered 1-4 from the front; the vehicle frame has x forward
    with the car body's centre at 0, the bogies at ``+-l_c`` and the wheelsets
    at ``+-l_c +- l_t``.

    Parameters
    ----------
    p : PitchPlaneParameters
        Masses, inertias, suspension and geometry.

    Returns
    -------
    Vehicle
        DOFs ``carbody.bounce, carbody.pitch, bogie1.bounce, bogie1.pitch,
        bogie2.bounce, bogie2.pitch, wheelset1.bounce ... wheelset4.bounce``.
    """
    lc, lt = p.bogie_half_spacing, p.wheelset_half_spacing
    bodies = [RigidBody("carbody", p.carbody_mass, p.carbody_pitch_inertia, 0.0)]
    suspensions = []
    wheels = []
    for i, xb in enumerate((lc, -lc), start=1):
        bogie = f"bogie{i}"
        bodies.append(RigidBody(bogie, p.bogie_mass, p.bogie_pitch_inertia, xb))
        suspensions.append(
            Suspension(
                f"secondary.{i}",
                Attachment("carbody", xb),
                Attachment(bogie, xb),
                p.secondary_stiffness,
                p.secondary_damping,
            )
        )
    for i, xw in enumerate((lc + lt, lc - lt, -lc + lt, -lc - lt), start=1):
        wheelset = f"wheelset{i}"
        bogie = "bogie1" if i <= 2 else "bogie2"
        bodies.append(RigidBody(wheelset, p.wheelset_mass, None, xw))
        suspensions.append(
            Suspension(
                f"primary.{i}",
                Attachment(bogie, xw),
                Attachment(wheelset, xw),
                p.primary_stiffness,
                p.primary_damping,
            )
        )
        wheels.append(Wheel(wheelset, xw))
    return Vehicle(tuple(bodies), tuple(suspensions), tuple(wheels))
