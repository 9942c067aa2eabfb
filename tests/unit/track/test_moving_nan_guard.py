"""A NaN in the moving-load integrand is refused at once, not bisected to the last level.

Before this guard, one NaN panel rule (as scipy < 1.15's ``spherical_jn`` gave behind the
load) made the error test fail everywhere, and every panel was halved at each of the 30
levels: the CI's lower-bound workers grew past 4-10 GB. The guard must stop the
integral on the first level, with the library's one-line error.
"""

from __future__ import annotations

import numpy as np
import pytest

import railvib.track.moving as moving
from railvib.errors import NonFiniteResult
from railvib.pads import SpringDamper
from railvib.track import PeriodicTrack, Rail

PAPER = PeriodicTrack(Rail(6.62e6, 60.64), SpringDamper(5e7, 5e4), 0.6)


def test_a_nan_rule_stops_the_integral_on_its_first_level(monkeypatch):
    calls = []
    real_rules = moving.panel_rules

    def poisoned(*args, **kwargs):
        rule, error = real_rules(*args, **kwargs)
        calls.append(rule.shape[0])
        rule = np.array(rule, copy=True)
        rule[-1] = np.nan  # the last panel of the last frequency
        return rule, error

    monkeypatch.setattr(moving, "panel_rules", poisoned)
    with pytest.raises(
        NonFiniteResult, match=r"moving-load receptance: .* 1 load frequencies \(first 160 Hz\)"
    ):
        moving.moving_load_receptance(
            PAPER, [37.0, 160.0], 80 / 3.6, order=1, r=[0.0, -2.2], tolerance=0.5
        )
    assert len(calls) == 1  # refused before any bisection


def test_finite_rules_pass_the_guard():
    # the same call unpoisoned gives finite harmonics (the guard is not always raising)
    res = moving.moving_load_receptance(
        PAPER, [37.0, 160.0], 80 / 3.6, order=1, r=[0.0, -2.2], tolerance=0.5
    )
    assert np.all(np.isfinite(res.amplitudes))
