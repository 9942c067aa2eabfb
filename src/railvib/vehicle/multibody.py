"""Vehicles as data: a multibody vehicle read from tables of bodies, suspensions and wheels.

A vehicle file (or a case's ``[vehicle]`` table with ``model = "multibody"``) lists

* ``[[bodies]]``: ``name``, ``mass_kg``, ``pitch_inertia_kg_m2`` (omitted: no pitch DOF,
  a wheelset or a lumped mass), ``x_m`` (centre of mass, positive forward; default 0);
* ``[[suspensions]]``: ``name``, ``upper`` and ``lower`` (body names), ``x_m`` (where it
  acts; default the lower body's x), ``stiffness_n_per_m``, ``damping_ns_per_m``
  (default 0) and an optional frequency-dependent ``element`` in parallel (a pad-family
  table, e.g. ``{model = "generalized_maxwell", ...}`` for a Maxwell branch or an air
  spring with its reservoir);
* ``[[wheels]]``: ``body`` (a body without pitch DOF), ``x_m`` (default the body's x),
  optional ``name``; listed front to back.

The DOFs (``<body>.bounce``, ``<body>.pitch``), the matrices and the labels follow
from the tables (``docs/vehicles.md``). Errors name the field, e.g.
``vehicle.bodies[2].mass_kg``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

from railvib.errors import CaseError, did_you_mean
from railvib.pads import PADS
from railvib.registry import parameter
from railvib.vehicle.assembly import Vehicle
from railvib.vehicle.base import VEHICLES, VehicleModel
from railvib.vehicle.parts import Attachment, RigidBody, Suspension, Wheel

__all__ = ["MultibodyVehicle", "parse_vehicle"]

#: largest mass of one body, kg (100 times a 100 t locomotive body)
MAX_MASS_KG = 1e7
#: largest pitch inertia of one body, kg m^2
MAX_INERTIA_KG_M2 = 1e10
#: largest stiffness or damping of one element, N/m or N s/m
MAX_ELEMENT = 1e12
#: largest |x| of a point of a vehicle or train, m (a 20-car train is 500 m long)
MAX_X_M = 1e4

#: most bodies, suspensions and wheels of one vehicle file (a car has 7 bodies, 6 suspensions
#: and 4 wheels; trains are built from cars by make_train, not written as one file)
MAX_ITEMS = {"bodies": 200, "suspensions": 1000, "wheels": 100}

_BODY_KEYS = ("name", "mass_kg", "pitch_inertia_kg_m2", "x_m")
_SUSPENSION_KEYS = (
    "name",
    "upper",
    "lower",
    "x_m",
    "stiffness_n_per_m",
    "damping_ns_per_m",
    "element",
)
_WHEEL_KEYS = ("body", "x_m", "name")


@VEHICLES.register("multibody")
@dataclass(frozen=True)
class MultibodyVehicle(VehicleModel):
    """A pitch-plane vehicle of any topology, described by tables (a vehicle file).

    Parameters
    ----------
    bodies : tuple of dict
        ``[[bodies]]`` tables (``name``, ``mass_kg``, ``pitch_inertia_kg_m2``, ``x_m``).
    wheels : tuple of dict
        ``[[wheels]]`` tables (``body``, ``x_m``, ``name``), front to back.
    suspensions : tuple of dict
        ``[[suspensions]]`` tables (``name``, ``upper``, ``lower``, ``x_m``,
        ``stiffness_n_per_m``, ``damping_ns_per_m``, ``element``).
    name : str
        What the vehicle is (free text).
    source : str
        Where its values come from (paper, table), free text.
    basis : str
        What the values stand for: ``whole_car`` (every mass and suspension of the
        whole car, both rails' sides together) or ``half_car`` (one rail's side).
    """

    bodies: tuple[Mapping[str, Any], ...] = parameter(
        "", "the rigid bodies ([[bodies]]: name, mass_kg, pitch_inertia_kg_m2, x_m)", kind="tables"
    )
    wheels: tuple[Mapping[str, Any], ...] = parameter(
        "", "the wheel-rail contacts, front to back ([[wheels]]: body, x_m, name)", kind="tables"
    )
    suspensions: tuple[Mapping[str, Any], ...] = parameter(
        "",
        "the suspension elements ([[suspensions]]: name, upper, lower, x_m, "
        "stiffness_n_per_m, damping_ns_per_m, element)",
        kind="tables",
        default=(),
    )
    name: str = parameter("", "what the vehicle is", kind="text", default="")
    source: str = parameter(
        "", "where the values come from (paper, table)", kind="text", default=""
    )
    basis: str = parameter(
        "",
        "what the values stand for: the whole car or the side of one rail",
        kind="text",
        default="whole_car",
        choices=("whole_car", "half_car"),
    )

    def validate(self) -> None:
        """Parse the tables (every error names its field)."""
        _ = self._vehicle

    @cached_property
    def _vehicle(self) -> Vehicle:
        return parse_vehicle(self.bodies, self.suspensions, self.wheels)

    def vehicle(self) -> Vehicle:
        """The assembled vehicle, whole car (a ``half_car`` file is doubled)."""
        return self._vehicle if self.basis == "whole_car" else self._vehicle.scaled(2.0)


def parse_vehicle(
    bodies: Sequence[Mapping[str, Any]],
    suspensions: Sequence[Mapping[str, Any]],
    wheels: Sequence[Mapping[str, Any]],
) -> Vehicle:
    """The vehicle the tables describe, every error naming its field.

    Parameters
    ----------
    bodies, suspensions, wheels : sequence of mapping
        The ``[[bodies]]``, ``[[suspensions]]`` and ``[[wheels]]`` tables (module docstring).

    Returns
    -------
    Vehicle

    Raises
    ------
    CaseError
        Field ``bodies[i].<key>`` etc.: an unknown or missing key, a value out of range,
        duplicate names, a suspension or wheel naming no body, a wheel on a body with a
        pitch DOF, wheels not front to back, a body connected to no wheel, or a body
        whose pitch no suspension restrains.
    """
    for field, items in (("bodies", bodies), ("suspensions", suspensions), ("wheels", wheels)):
        if isinstance(items, Sequence) and len(items) > MAX_ITEMS[field]:
            raise CaseError(
                field,
                f"<{len(items):,} tables>",
                f"at most {MAX_ITEMS[field]} [[{field}]] tables in one vehicle (a train: [train])",
            )
    if not isinstance(bodies, Sequence) or isinstance(bodies, str) or not bodies:
        raise CaseError("bodies", _shown(bodies), "at least one [[bodies]] table")
    parsed_bodies = [_body(t, f"bodies[{i}]") for i, t in enumerate(bodies)]
    names = [b.name for b in parsed_bodies]
    for i, name in enumerate(names):
        if name in names[:i]:
            raise CaseError(f"bodies[{i}].name", name, "a name no other body has")
    by_name = {b.name: b for b in parsed_bodies}
    parsed_suspensions = [
        _suspension(t, f"suspensions[{i}]", by_name) for i, t in enumerate(suspensions)
    ]
    s_names = [s.name for s in parsed_suspensions]
    for i, name in enumerate(s_names):
        if name in s_names[:i]:
            raise CaseError(f"suspensions[{i}].name", name, "a name no other suspension has")
    if not isinstance(wheels, Sequence) or isinstance(wheels, str) or not wheels:
        raise CaseError(
            "wheels", _shown(wheels), "at least one [[wheels]] table (a wheel-rail contact)"
        )
    parsed_wheels = [_wheel(t, f"wheels[{i}]", by_name) for i, t in enumerate(wheels)]
    _check_wheels(parsed_wheels)
    _check_connected(parsed_bodies, parsed_suspensions, parsed_wheels)
    _check_pitch(parsed_bodies, parsed_suspensions)
    return Vehicle(tuple(parsed_bodies), tuple(parsed_suspensions), tuple(parsed_wheels))


def _shown(value: Any) -> Any:
    """A tuple of tables shown as the list the file wrote."""
    return list(value) if isinstance(value, tuple) else value


def _table(t: Any, where: str, keys: Sequence[str]) -> Mapping[str, Any]:
    """`t` if it is a table of known keys."""
    if not isinstance(t, Mapping):
        raise CaseError(where, t, "a table")
    for key in t:
        if key not in keys:
            raise CaseError(
                f"{where}.{key}",
                t[key],
                "unknown key; allowed here: " + ", ".join(keys) + did_you_mean(str(key), keys),
            )
    return t


def _text(t: Mapping[str, Any], key: str, where: str, default: str | None = None) -> str:
    if key not in t:
        if default is None:
            raise CaseError(f"{where}.{key}", "<missing>", "required (text)")
        return default
    value = t[key]
    if (
        not isinstance(value, str)
        or not value
        or not value.replace("_", "").replace(".", "").replace("-", "").isalnum()
    ):
        raise CaseError(
            f"{where}.{key}", value, "a name of letters, digits, '_', '-' and '.' (text)"
        )
    return value


def _number(
    t: Mapping[str, Any],
    key: str,
    where: str,
    unit: str,
    *,
    low: float,
    high: float,
    strict: bool = True,
    default: float | None = None,
) -> float:
    if key not in t:
        if default is None:
            raise CaseError(f"{where}.{key}", "<missing>", f"required ({unit})")
        return default
    value = t[key]
    ok = isinstance(value, int | float) and not isinstance(value, bool)
    x = float(value) if ok else float("nan")
    above = x > low if strict else x >= low
    if not (ok and np.isfinite(x) and above and x <= high):
        op = ">" if strict else ">="
        raise CaseError(f"{where}.{key}", value, f"must be {op} {low:g} and <= {high:g} ({unit})")
    return x


def _body(t: Any, where: str) -> RigidBody:
    t = _table(t, where, _BODY_KEYS)
    name = _text(t, "name", where)
    mass = _number(t, "mass_kg", where, "kg", low=0.0, high=MAX_MASS_KG)
    inertia = None
    if "pitch_inertia_kg_m2" in t:
        inertia = _number(
            t, "pitch_inertia_kg_m2", where, "kg m^2", low=0.0, high=MAX_INERTIA_KG_M2
        )
    x = _number(t, "x_m", where, "m", low=-MAX_X_M, high=MAX_X_M, strict=False, default=0.0)
    return RigidBody(name, mass, inertia, x)


def _body_name(t: Mapping[str, Any], key: str, where: str, bodies: Mapping[str, RigidBody]) -> str:
    name = _text(t, key, where)
    if name not in bodies:
        names = list(bodies)
        raise CaseError(f"{where}.{key}", name, f"a body among {names}{did_you_mean(name, names)}")
    return name


def _suspension(t: Any, where: str, bodies: Mapping[str, RigidBody]) -> Suspension:
    t = _table(t, where, _SUSPENSION_KEYS)
    upper = _body_name(t, "upper", where, bodies)
    lower = _body_name(t, "lower", where, bodies)
    if upper == lower:
        raise CaseError(f"{where}.lower", lower, f"a body other than upper = {upper!r}")
    name = _text(t, "name", where, default=f"{upper}-{lower}")
    x = _number(
        t, "x_m", where, "m", low=-MAX_X_M, high=MAX_X_M, strict=False, default=bodies[lower].x
    )
    element = None
    if "element" in t:
        element = PADS.from_dict(t["element"], f"{where}.element")
    k = _number(
        t,
        "stiffness_n_per_m",
        where,
        "N/m",
        low=0.0,
        high=MAX_ELEMENT,
        strict=element is None,
        default=0.0 if element is not None else None,
    )
    c = _number(
        t, "damping_ns_per_m", where, "N s/m", low=0.0, high=MAX_ELEMENT, strict=False, default=0.0
    )
    return Suspension(name, Attachment(upper, x), Attachment(lower, x), k, c, element)


def _wheel(t: Any, where: str, bodies: Mapping[str, RigidBody]) -> Wheel:
    t = _table(t, where, _WHEEL_KEYS)
    body = _body_name(t, "body", where, bodies)
    if bodies[body].pitch_inertia is not None:
        raise CaseError(
            f"{where}.body", body, "a body without a pitch DOF (a wheelset: no pitch_inertia_kg_m2)"
        )
    x = _number(
        t, "x_m", where, "m", low=-MAX_X_M, high=MAX_X_M, strict=False, default=bodies[body].x
    )
    name = _text(t, "name", where, default="")
    return Wheel(body, x, name)


def _check_wheels(wheels: Sequence[Wheel]) -> None:
    carriers: list[str] = []
    for i, w in enumerate(wheels):
        if w.body in carriers:
            raise CaseError(f"wheels[{i}].body", w.body, "one wheel per wheelset body")
        carriers.append(w.body)
        if i and w.x >= wheels[i - 1].x:
            raise CaseError(
                f"wheels[{i}].x_m", w.x, f"must be < {wheels[i - 1].x:g}: wheels front to back (m)"
            )
    names = [w.name for w in wheels if w.name]
    for i, w in enumerate(wheels):
        if w.name and names.count(w.name) > 1:
            raise CaseError(f"wheels[{i}].name", w.name, "a name no other wheel has")


def _check_connected(
    bodies: Sequence[RigidBody], suspensions: Sequence[Suspension], wheels: Sequence[Wheel]
) -> None:
    """Every body reaches a wheel contact through suspensions (else it floats free)."""
    reached = {w.body for w in wheels}
    grew = True
    while grew:
        grew = False
        for s in suspensions:
            ends = {s.upper.body, s.lower.body}
            if ends & reached and not ends <= reached:
                reached |= ends
                grew = True
    for i, b in enumerate(bodies):
        if b.name not in reached:
            raise CaseError(
                f"bodies[{i}]",
                b.name,
                "a body connected through suspensions to a wheel in contact "
                "(this one is unconnected: it floats free)",
            )


def _check_pitch(bodies: Sequence[RigidBody], suspensions: Sequence[Suspension]) -> None:
    """A body with a pitch DOF needs suspension points at two x positions at least."""
    for i, b in enumerate(bodies):
        if b.pitch_inertia is None:
            continue
        xs = {s.upper.x for s in suspensions if b.name in (s.upper.body, s.lower.body)}
        if len(xs) < 2:
            raise CaseError(
                f"bodies[{i}].pitch_inertia_kg_m2",
                b.pitch_inertia,
                "a pitch DOF restrained by suspensions at two x positions at least "
                "(or omit it: a body in bounce only)",
            )
