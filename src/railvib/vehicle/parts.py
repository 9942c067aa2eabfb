"""Building blocks of a pitch-plane vehicle: rigid bodies, suspensions, wheels."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from railvib.errors import CaseError

__all__ = ["Attachment", "RigidBody", "Suspension", "Wheel"]


def _check_positive(field: str, value: float, unit: str) -> None:
    if not (np.isfinite(value) and value > 0):
        raise CaseError(field, value, f"must be > 0 ({unit})")


@dataclass(frozen=True)
class RigidBody:
    """A rigid body moving vertically (bounce) and, optionally, in pitch.

    Parameters
    ----------
    name : str
        Label, e.g. ``"carbody"``; DOFs are named ``"<name>.bounce"`` and ``"<name>.pitch"``.
    mass : float
        Mass in kg (> 0).
    pitch_inertia : float or None
        Pitch moment of inertia about the centre of mass in kg m^2 (> 0), or None
        for a body without a pitch DOF (a wheelset in the pitch-plane model).
    x : float
        Longitudinal position of the centre of mass in the vehicle frame, m
        (positive forward).
    """

    name: str
    mass: float
    pitch_inertia: float | None = None
    x: float = 0.0

    def __post_init__(self) -> None:
        _check_positive(f"vehicle.{self.name}.mass", self.mass, "kg")
        if self.pitch_inertia is not None:
            _check_positive(f"vehicle.{self.name}.pitch_inertia", self.pitch_inertia, "kg m^2")

    @property
    def dofs(self) -> tuple[str, ...]:
        """DOF labels of this body."""
        if self.pitch_inertia is None:
            return (f"{self.name}.bounce",)
        return (f"{self.name}.bounce", f"{self.name}.pitch")


@dataclass(frozen=True)
class Attachment:
    """A point of a body: the body's name and the point's x in the vehicle frame (m)."""

    body: str
    x: float


@dataclass(frozen=True)
class Suspension:
    """A vertical spring and viscous damper in parallel between two body points.

    Parameters
    ----------
    name : str
        Label, e.g. ``"primary.1"``.
    upper, lower : Attachment
        The two points it connects.
    stiffness : float
        Spring stiffness in N/m (> 0).
    damping : float
        Viscous damping in N s/m (>= 0).
    """

    name: str
    upper: Attachment
    lower: Attachment
    stiffness: float
    damping: float = 0.0

    def __post_init__(self) -> None:
        _check_positive(f"vehicle.{self.name}.stiffness", self.stiffness, "N/m")
        if not (np.isfinite(self.damping) and self.damping >= 0):
            raise CaseError(f"vehicle.{self.name}.damping", self.damping, "must be >= 0 (N s/m)")


@dataclass(frozen=True)
class Wheel:
    """A wheel-rail contact: the body that carries it (a wheelset) and its x (m)."""

    body: str
    x: float
