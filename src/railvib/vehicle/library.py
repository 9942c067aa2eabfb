"""Ready-made vehicles built from parts."""

from __future__ import annotations

from dataclasses import dataclass

from railvib.vehicle.assembly import Vehicle
from railvib.vehicle.parts import Attachment, RigidBody, Suspension, Wheel

__all__ = ["PitchPlaneParameters", "pitch_plane_10dof"]


@dataclass(frozen=True)
class PitchPlaneParameters:
    """Parameters of the 10-DOF pitch-plane car (paper Table 1, whole car).

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

    carbody_mass: float
    carbody_pitch_inertia: float
    bogie_mass: float
    bogie_pitch_inertia: float
    wheelset_mass: float
    primary_stiffness: float
    primary_damping: float
    secondary_stiffness: float
    secondary_damping: float
    bogie_half_spacing: float
    wheelset_half_spacing: float


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
