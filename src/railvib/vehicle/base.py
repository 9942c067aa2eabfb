"""The vehicle-model family: parameter sets that assemble a :class:`~railvib.vehicle.Vehicle`.

A vehicle model is a frozen dataclass whose fields are declared with
:func:`railvib.registry.parameter` and registers itself in :data:`VEHICLES`;
its parameters are checked on construction (errors name ``vehicle.<key>``),
conditions between them in :meth:`VehicleModel.validate`.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import ClassVar

from railvib.errors import CaseError
from railvib.registry import Registry, check_parameters
from railvib.vehicle.assembly import Vehicle

__all__ = ["DEFAULT_VEHICLE_MODEL", "VEHICLES", "VehicleModel"]


class VehicleModel(ABC):
    """Parameters of one kind of vehicle, and how they assemble the multibody vehicle."""

    #: name in case files, set on registration
    model_name: ClassVar[str] = ""

    def __post_init__(self) -> None:
        try:
            check_parameters(self, "must")
            self.validate()
        except CaseError as err:
            raise CaseError(f"vehicle.{err.field}", err.value, err.allowed) from None

    def validate(self) -> None:  # noqa: B027 (a hook: most models need no extra check)
        """Check conditions between parameters (each parameter alone is checked already)."""

    @abstractmethod
    def vehicle(self) -> Vehicle:
        """The assembled vehicle: bodies, suspensions and wheels (front to back)."""


#: every vehicle model a case file can describe
VEHICLES: Registry[VehicleModel] = Registry(
    "vehicle model", VehicleModel, "model", where="[vehicle]", tagged=False
)

#: the model of a case's ``[vehicle]`` table (the paper's 10-DOF car)
DEFAULT_VEHICLE_MODEL = "pitch_plane_10dof"
