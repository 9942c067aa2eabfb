"""The readings of rail and car: rail_pair and half_car are one physical system.

``rail_pair`` doubles the beam, the pads and k_H under the whole car; ``half_car`` keeps
one rail and halves the car. Every dynamic stiffness of the second is half that of the
first, so the displacements are equal and the contact forces half. ``single_rail`` (the
paper's reading: the whole car on one rail, k_H of one wheel) is another system.
"""

from __future__ import annotations

import numpy as np
import pytest

from railvib.case import case_from_dict
from railvib.case.build import build_system

F = np.linspace(20.0, 200.0, 361)  # 0.5 Hz steps through the wheel-rail resonance


def _frf(rail_model, vehicle=None):
    data = {"preset": "wang2017_metro", "rail_model": rail_model}
    if vehicle is not None:
        data["vehicle"] = {"preset": vehicle}
    return build_system(case_from_dict(data, warn=False)).frf(F)


def _resonance(frf):
    """Frequency of the largest wheelset bounce response per metre of irregularity, Hz."""
    wheel = frf.dofs.index("wheelset1.bounce")
    return F[np.argmax(np.abs(frf.vehicle[:, wheel]))]


@pytest.mark.parametrize("vehicle", [None, "iwnicki1998_manchester_coach"])
def test_rail_pair_and_half_car_are_the_same_system(vehicle):
    pair, half = _frf("rail_pair", vehicle), _frf("half_car", vehicle)
    # the two systems' matrices differ by the factor 2 exactly (a power of two): the
    # solves agree to rounding, 1e-12 of each response's peak
    for a, b in ((pair.vehicle, half.vehicle), (pair.rail, half.rail)):
        assert np.abs(a - b).max() <= 1e-12 * np.abs(a).max()
    assert (
        np.abs(pair.contact_force - 2 * half.contact_force).max()
        <= 1e-12 * np.abs(pair.contact_force).max()
    )
    assert _resonance(pair) == _resonance(half)


def test_single_rail_is_the_papers_other_reading():
    # the whole wheelset on one rail's beam resonates lower than on both rails: near the
    # paper's 47.9 Hz PSD peak (docs/paper-interpretation.md; a peak per metre of
    # irregularity sits up to half a comb spacing, 5 Hz at 80 km/h, from it) against
    # 61-64 Hz for half a wheelset on one rail (the same note)
    single, pair = _resonance(_frf("single_rail")), _resonance(_frf("rail_pair"))
    assert 42.9 < single < 52.9
    assert 56.0 < pair < 69.0
