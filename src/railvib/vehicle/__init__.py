"""Pitch-plane vehicles assembled from bodies, suspensions and wheels."""

from railvib.vehicle.assembly import Vehicle
from railvib.vehicle.library import PitchPlaneParameters, pitch_plane_10dof
from railvib.vehicle.parts import Attachment, RigidBody, Suspension, Wheel

__all__ = [
    "Attachment",
    "PitchPlaneParameters",
    "RigidBody",
    "Suspension",
    "Vehicle",
    "Wheel",
    "pitch_plane_10dof",
]
