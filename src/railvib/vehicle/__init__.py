"""Pitch-plane vehicles assembled from bodies, suspensions and wheels."""

from railvib.vehicle.assembly import Vehicle
from railvib.vehicle.base import DEFAULT_VEHICLE_MODEL, VEHICLES, VehicleModel
from railvib.vehicle.library import PitchPlaneParameters, pitch_plane_10dof
from railvib.vehicle.parts import Attachment, RigidBody, Suspension, Wheel

__all__ = [
    "DEFAULT_VEHICLE_MODEL",
    "VEHICLES",
    "Attachment",
    "PitchPlaneParameters",
    "RigidBody",
    "Suspension",
    "Vehicle",
    "VehicleModel",
    "Wheel",
    "pitch_plane_10dof",
]
