"""The rule that names responses: written once, used by every solver, dataset and plot.

Response labels (``CONVENTIONS.md``): vehicle DOFs ``<body>.bounce`` /
``<body>.pitch``, then the rail under wheel ``j`` (numbered from the front, from
1) ``rail@wheel<j>``; a train's bodies and wheels carry their car (``car2.bogie1.bounce``,
``rail@car3.wheel2``). This module needs nothing but Python, so the command line
can show the labels without loading the numerical stack.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

__all__ = [
    "displacement_unit",
    "leading_car_label",
    "rail_label",
    "response_labels",
    "wheel_name",
]


def rail_label(wheel: int | str) -> str:
    """Label of the rail under wheel `wheel`.

    Parameters
    ----------
    wheel : int or str
        The wheel's number (1 = the leading wheel): ``rail_label(2)`` is ``rail@wheel2``;
        or its name: ``rail_label("car3.wheel2")`` is ``rail@car3.wheel2`` (a train's
        wheels are named per car).

    Returns
    -------
    str
        The response label.
    """
    return f"rail@wheel{wheel}" if isinstance(wheel, int) else f"rail@{wheel}"


def response_labels(
    vehicle_dofs: Sequence[str], n_wheel: int, wheel_names: Sequence[str] = ()
) -> tuple[str, ...]:
    """Labels of a run's responses: the vehicle DOFs, then the rail under each wheel.

    Parameters
    ----------
    vehicle_dofs : sequence of str
        Names of the vehicle DOFs, e.g. ``"carbody.bounce"``.
    n_wheel : int
        Number of wheels.
    wheel_names : sequence of str, optional
        Names of the wheels front to back (a train's ``car<i>.wheel<j>``); empty: numbered.

    Returns
    -------
    tuple of str
        `vehicle_dofs` followed by ``rail@wheel1`` ... ``rail@wheel<n_wheel>`` (or
        ``rail@<name>`` for named wheels).
    """
    if wheel_names:
        return (*vehicle_dofs, *(rail_label(str(w)) for w in wheel_names))
    return (*vehicle_dofs, *(rail_label(j + 1) for j in range(n_wheel)))


def displacement_unit(label: str) -> str:
    """Unit of the displacement of response `label`: ``"rad"`` for a pitch DOF, else ``"m"``."""
    return "rad" if label.endswith(".pitch") else "m"


def leading_car_label(label: str) -> str:
    """`label` of a single vehicle as it reads for a train's leading car.

    ``carbody.bounce`` becomes ``car1.carbody.bounce`` and ``rail@wheel2`` becomes
    ``rail@car1.wheel2`` (figures of a single car's responses show a train's first car).

    Parameters
    ----------
    label : str
        A response label of a single vehicle.

    Returns
    -------
    str
        The label of the same response of car 1.
    """
    return f"rail@car1.{label[5:]}" if label.startswith("rail@") else f"car1.{label}"


def wheel_name(responses: Iterable[object], index: int) -> str:
    """How summaries name wheel `index` (0-based): ``wheel 3``, or a train's ``car2.wheel1``.

    Parameters
    ----------
    responses : iterable of str
        The response labels of a result; its ``rail@...`` labels follow the wheels.
    index : int
        Position of the wheel along the ``wheel`` axis.

    Returns
    -------
    str
        The wheel's name in a train (``car2.wheel1``), else ``wheel <number>``.
    """
    rails = [str(r).removeprefix("rail@") for r in responses if str(r).startswith("rail@")]
    if index < len(rails) and "." in rails[index]:
        return rails[index]
    return f"wheel {index + 1}"
