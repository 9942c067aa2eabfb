"""Sweeps of cases whose vehicle is data (a vehicle preset) or a train equal railvib.run.

The sweep's stacked solve keys its track solutions by the wheel positions as built and
its condensations by the vehicle table with its train; a key read from the pitch-plane
car's own fields would not exist for these vehicles (issue 15 met issue 13 here).
"""

import numpy as np
import pytest

import railvib
from railvib.case.load import merge_case_dicts
from railvib.sweep import sweep_from_dict
from railvib.sweep.batch import compute_chunk
from railvib.sweep.layout import SweepLayout
from railvib.sweep.spec import nested_override

#: the stacked solve and the case-by-case solver differ by rounding only (measured 1e-14)
RTOL = 1e-10

GRID = {"spacing": "log", "f_min": 0.5, "f_max": 500.0, "n": 40}
VEHICLES = {
    "vehicle preset": {
        "preset": "wang2017_metro",
        "vehicle": {"preset": "iwnicki1998_manchester_coach"},
    },
    "two-car train": {"preset": "wang2017_metro", "train": {"cars": 2, "gap_m": 4.7}},
}


@pytest.mark.parametrize("kind", list(VEHICLES))
def test_a_sweep_over_speed_and_pad_equals_railvib_run(kind):
    base = {**VEHICLES[kind], "frequency": GRID}
    spec = sweep_from_dict(
        {
            "title": kind,
            "chunk_size": 10,
            "variables": ["psd_acceleration", "psd_force"],
            "case": base,
            "axes": [
                {"field": "speed_kmh", "values": [60.0, 100.0]},
                {"field": "track.pad.stiffness_n_per_m", "values": [4.0e7, 9.0e7]},
            ],
        }
    )
    lay = SweepLayout(spec)
    out = compute_chunk(spec, 0)
    for i, index in enumerate(lay.chunk_indices(0)):
        d = spec.base_case_dict()
        for field, value in lay.overrides(index):
            d = merge_case_dicts(d, nested_override(field, value))
        ds = railvib.run(railvib.case_from_dict(d))
        for name in ("psd_acceleration", "psd_force"):
            want = ds[name].values
            scale = np.abs(want).max(axis=0, keepdims=True)  # each response's peak
            assert np.max(np.abs(out[name][i] - want) / scale) < RTOL, (kind, name, i)
