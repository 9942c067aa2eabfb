"""Pitch-plane vehicles assembled from bodies, suspensions and wheels (or read as data)."""

from railvib.vehicle.assembly import Vehicle
from railvib.vehicle.base import DEFAULT_VEHICLE_MODEL, VEHICLES, VehicleModel
from railvib.vehicle.library import PitchPlaneParameters, pitch_plane_10dof
from railvib.vehicle.multibody import MultibodyVehicle, parse_vehicle
from railvib.vehicle.parts import Attachment, RigidBody, Suspension, Wheel
from railvib.vehicle.train import car_prefix, make_train

__all__ = [
    "DEFAULT_VEHICLE_MODEL",
    "VEHICLES",
    "Attachment",
    "MultibodyVehicle",
    "PitchPlaneParameters",
    "RigidBody",
    "Suspension",
    "Vehicle",
    "VehicleModel",
    "Wheel",
    "car_prefix",
    "make_train",
    "parse_vehicle",
    "pitch_plane_10dof",
]
