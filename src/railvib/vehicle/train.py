"""Trains: several vehicles in a row, one multibody vehicle with every car's bodies and wheels.

The cars keep their topology; their bodies, suspensions and wheels are renamed
``car<i>.<name>`` (``car2.bogie1``, ``car3.wheel2``, cars numbered from the front, from 1)
and shifted along the train so that the leading wheel of car ``i + 1`` stands ``gap``
behind the trailing wheel of car ``i``. All wheels then ride the same track, each with its
delay, coupled through the track's receptance between them (:class:`railvib.coupling.
CoupledSystem` takes any number of wheels); optional couplers join neighbouring car bodies.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from railvib.errors import CaseError
from railvib.vehicle.assembly import Vehicle
from railvib.vehicle.parts import Attachment, Suspension

__all__ = ["car_prefix", "make_train"]


def car_prefix(car: int) -> str:
    """The prefix of car `car`'s names (1 = the leading car): ``car<i>.``."""
    return f"car{car}."


def make_train(
    cars: Sequence[Vehicle],
    gaps: float | Sequence[float],
    coupler_stiffness: float = 0.0,
    coupler_damping: float = 0.0,
    coupler_body: str = "carbody",
) -> Vehicle:
    """The train of `cars` (front to back), one vehicle with every car's bodies and wheels.

    Parameters
    ----------
    cars : sequence of Vehicle
        The cars, front to back (at least one).
    gaps : float or sequence of float
        Distance from the trailing wheel of each car to the leading wheel of the next, m
        (> 0): one value for every pair, or one per pair (``len(cars) - 1``).
    coupler_stiffness : float
        Vertical stiffness of the coupler between neighbouring car bodies, N/m (>= 0;
        0: no coupler).
    coupler_damping : float
        Viscous damping of the coupler, N s/m (>= 0; needs a coupler stiffness).
    coupler_body : str
        The body of each car the couplers join (default ``carbody``).

    Returns
    -------
    Vehicle
        Bodies ``car<i>.<body>``, suspensions ``car<i>.<name>`` and couplers
        ``coupler<i>`` (between car ``i`` and ``i + 1``, at the middle of the gap), wheels
        ``car<i>.wheel<j>`` front to back.

    Raises
    ------
    CaseError
        No car, a gap that is not > 0, the wrong number of gaps, a negative coupler value,
        or a car without `coupler_body` when there are couplers.
    """
    if not cars:
        raise CaseError("train.cars", 0, "at least one car")
    n = len(cars)
    if isinstance(gaps, int | float):
        gap_list = [float(gaps)] * (n - 1)
    else:
        gap_list = [float(g) for g in gaps]
    if len(gap_list) != n - 1:
        raise CaseError("train.gap_m", gap_list, f"one gap per pair of cars ({n - 1})")
    for g in gap_list:
        if not (np.isfinite(g) and g > 0):
            raise CaseError("train.gap_m", g, "must be > 0 (m)")
    for field, value, unit in (
        ("train.coupler_stiffness_n_per_m", coupler_stiffness, "N/m"),
        ("train.coupler_damping_ns_per_m", coupler_damping, "N s/m"),
    ):
        if not (np.isfinite(value) and value >= 0):
            raise CaseError(field, value, f"must be >= 0 ({unit})")
    coupled = coupler_stiffness > 0
    if coupler_damping > 0 and not coupled:
        raise CaseError(
            "train.coupler_stiffness_n_per_m",
            coupler_stiffness,
            "must be > 0 where a coupler damping is given (N/m)",
        )
    bodies, suspensions, wheels = [], [], []
    shift = 0.0
    previous_tail = 0.0
    for i, car in enumerate(cars, start=1):
        if i > 1:
            shift = previous_tail - gap_list[i - 2] - car.wheels[0].x
        p = car_prefix(i)
        bodies += [replace(b, name=p + b.name, x=b.x + shift) for b in car.bodies]
        suspensions += [
            replace(
                s,
                name=p + s.name,
                upper=Attachment(p + s.upper.body, s.upper.x + shift),
                lower=Attachment(p + s.lower.body, s.lower.x + shift),
            )
            for s in car.suspensions
        ]
        wheels += [
            replace(w, body=p + w.body, x=w.x + shift, name=p + name)
            for w, name in zip(car.wheels, car.wheel_names, strict=True)
        ]
        if coupled and coupler_body not in {b.name for b in car.bodies}:
            raise CaseError("train.coupler_body", coupler_body, f"a body of car {i}")
        if coupled and i > 1:
            x = previous_tail - gap_list[i - 2] / 2.0
            suspensions.append(
                Suspension(
                    f"coupler{i - 1}",
                    Attachment(car_prefix(i - 1) + coupler_body, x),
                    Attachment(p + coupler_body, x),
                    coupler_stiffness,
                    coupler_damping,
                )
            )
        previous_tail = car.wheels[-1].x + shift
    parts: tuple[tuple[Vehicle, int, int], ...] = ()
    if not coupled:  # the cars meet only through the track: condensed car by car
        starts = np.cumsum([0, *(len(c.dofs) for c in cars)])
        wheel_starts = np.cumsum([0, *(len(c.wheels) for c in cars)])
        parts = tuple(
            (car, int(d0), int(w0)) for car, d0, w0 in zip(cars, starts, wheel_starts, strict=False)
        )
    return Vehicle(tuple(bodies), tuple(suspensions), tuple(wheels), parts)
