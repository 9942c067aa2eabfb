"""The rule that names responses: written once, used by every solver, dataset and plot.

Response labels (``CONVENTIONS.md``): vehicle DOFs ``<body>.bounce`` /
``<body>.pitch``, then the rail under wheel ``j`` (numbered from the front, from
1) ``rail@wheel<j>``. This module needs nothing but Python, so the command line
can show the labels without loading the numerical stack.
"""

from __future__ import annotations

from collections.abc import Sequence

__all__ = ["displacement_unit", "rail_label", "response_labels"]


def rail_label(wheel: int) -> str:
    """Label of the rail displacement under wheel `wheel` (1 = the leading wheel)."""
    return f"rail@wheel{wheel}"


def response_labels(vehicle_dofs: Sequence[str], n_wheel: int) -> tuple[str, ...]:
    """Labels of a run's responses: the vehicle DOFs, then the rail under each wheel.

    Parameters
    ----------
    vehicle_dofs : sequence of str
        Names of the vehicle DOFs, e.g. ``"carbody.bounce"``.
    n_wheel : int
        Number of wheels.

    Returns
    -------
    tuple of str
        `vehicle_dofs` followed by ``rail@wheel1`` ... ``rail@wheel<n_wheel>``.
    """
    return (*vehicle_dofs, *(rail_label(j + 1) for j in range(n_wheel)))


def displacement_unit(label: str) -> str:
    """Unit of the displacement of response `label`: ``"rad"`` for a pitch DOF, else ``"m"``."""
    return "rad" if label.endswith(".pitch") else "m"
