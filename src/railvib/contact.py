"""Linearised Hertz wheel-rail contact."""

from __future__ import annotations

import numpy as np

from railvib.errors import CaseError

__all__ = ["hertz_constant_conical", "hertz_stiffness"]


def hertz_stiffness(contact_constant: float, static_load: float) -> float:
    """Linearised Hertz contact stiffness ``k_H = 3 / (2 G) P0^(1/3)`` in N/m.

    From the Hertz law ``delta = G P^(2/3)`` linearised about the static load.

    Parameters
    ----------
    contact_constant : float
        G in m/N^(2/3) (> 0). Paper: 5.2e-8.
    static_load : float
        Static normal load P0 on the contact in N (> 0).

    Returns
    -------
    float
        k_H in N/m.

    Examples
    --------
    >>> round(hertz_stiffness(5.2e-8, 40.10e3) / 1e8, 3)
    9.873
    """
    if not (np.isfinite(contact_constant) and contact_constant > 0):
        raise CaseError("contact.contact_constant", contact_constant, "must be > 0 (m/N^(2/3))")
    if not (np.isfinite(static_load) and static_load > 0):
        raise CaseError("contact.static_load", static_load, "must be > 0 (N)")
    return 1.5 / contact_constant * static_load ** (1.0 / 3.0)


def hertz_constant_conical(wheel_radius: float) -> float:
    """Contact constant of a conical tread, ``G = 4.57e-8 R^-0.149`` in m/N^(2/3) (R in m).

    Parameters
    ----------
    wheel_radius : float
        Wheel rolling radius ``R`` in m (> 0).

    Returns
    -------
    float
        G in m/N^(2/3).

    Raises
    ------
    CaseError
        If `wheel_radius` is not a finite number > 0.
    """
    if not (np.isfinite(wheel_radius) and wheel_radius > 0):
        raise CaseError("contact.wheel_radius", wheel_radius, "must be > 0 (m)")
    return 4.57e-8 * wheel_radius**-0.149
