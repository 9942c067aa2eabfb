"""Building blocks of a pitch-plane vehicle: rigid bodies, suspensions, wheels."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

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
    """A vertical spring, a viscous damper and a frequency-dependent element in parallel.

    Parameters
    ----------
    name : str
        Label, e.g. ``"primary.1"``.
    upper, lower : Attachment
        The two points it connects.
    stiffness : float
        Spring stiffness in N/m (> 0; >= 0 when an `element` is given).
    damping : float
        Viscous damping in N s/m (>= 0).
    element : object, optional
        A frequency-dependent element in parallel: any object with a method
        ``stiffness(f)`` returning the complex stiffness ``K*(f)`` in N/m (a member of
        the pad family, :data:`railvib.pads.PADS`, e.g. a Maxwell branch or an air
        spring with its reservoir as a ``generalized_maxwell`` element).
    """

    name: str
    upper: Attachment
    lower: Attachment
    stiffness: float
    damping: float = 0.0
    element: Any = None

    def __post_init__(self) -> None:
        if self.element is None:
            _check_positive(f"vehicle.{self.name}.stiffness", self.stiffness, "N/m")
        elif not (np.isfinite(self.stiffness) and self.stiffness >= 0):
            raise CaseError(f"vehicle.{self.name}.stiffness", self.stiffness, "must be >= 0 (N/m)")
        if not (np.isfinite(self.damping) and self.damping >= 0):
            raise CaseError(f"vehicle.{self.name}.damping", self.damping, "must be >= 0 (N s/m)")


@dataclass(frozen=True)
class Wheel:
    """A wheel-rail contact: the body that carries it (a wheelset), its x (m) and its name.

    The name labels the rail under it (``rail@<name>``); empty: ``wheel<j>``, ``j`` its
    place from the front (from 1).

    Attributes
    ----------
    body : str
        The body that carries the wheel (a wheelset).
    x : float
        Position of the contact in the vehicle frame, m.
    name : str
        The wheel's label; empty: numbered from the front.
    """

    body: str
    x: float
    name: str = ""
