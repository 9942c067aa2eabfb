"""``railvib explore`` of a moving case shows its stationary response, said so in a note.

``railvib.run`` refuses a moving case (it is the stationary pipeline); the explorer, which
solves the stationary case only, runs the case with its mode set back to stationary, and
its frame must be that of the same case written as stationary.
"""

from __future__ import annotations

import numpy as np
import pytest

from railvib.case import case_from_dict
from railvib.explore import Explorer

GRID = {"spacing": "log", "f_min": 5.0, "f_max": 200.0, "n": 12}


@pytest.mark.slow  # two runs of the explorer
def test_a_moving_case_is_shown_stationary_with_a_note():
    moving = case_from_dict(
        {
            "preset": "wang2017_metro",
            "mode": "moving",
            "moving": {"harmonic_order": 2},
            "frequency": GRID,
        }
    )
    still = case_from_dict({"preset": "wang2017_metro", "frequency": GRID})
    shown = Explorer(moving).frame(Explorer(moving).initial())
    reference = Explorer(still).frame(Explorer(still).initial())
    assert shown.notes[0].startswith("note: mode = 'moving' in the case: shown is the stationary")
    # the same stationary case: the same numbers, to round-off
    assert shown.psd.keys() == reference.psd.keys()
    for name, values in reference.psd.items():
        np.testing.assert_allclose(shown.psd[name], values, rtol=1e-12)
