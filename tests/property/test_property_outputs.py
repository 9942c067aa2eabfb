"""Property-based: all outputs finite and non-negative from 0.1 Hz to 5 kHz."""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings

import railvib
from railvib.testing.strategies import case_overrides

F = np.geomspace(0.1, 5000.0, 300)


@pytest.mark.property
@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(overrides=case_overrides())
def test_outputs_finite_and_non_negative(overrides):
    case = railvib.case_from_dict({"preset": "wang2017_metro", **overrides})
    system = railvib.build_system(case)
    from railvib.case import build_spectrum

    ds = railvib.run_system(system, railvib.FrequencyGrid.from_array(F), build_spectrum(case))
    for name in ("psd_acceleration", "psd_displacement", "psd_force", "irregularity_psd"):
        values = ds[name].values
        assert np.all(np.isfinite(values)), name
        assert np.all(values >= 0), name
    assert np.all(np.isfinite(ds.frf_displacement.values))
    # a passive track: the rail's driving-point receptance under each wheel absorbs power
    rec = system.track.receptance(F, system.wheel_positions, system.wheel_positions)
    assert np.all(np.isfinite(rec))
    assert np.all(np.diagonal(rec, axis1=1, axis2=2).imag < 0)
