"""The batched multi-speed solver equals running the cases one by one."""

import numpy as np
import pytest

import railvib
from railvib.case import build_system
from railvib.case.load import merge_case_dicts
from railvib.results.stats import summary
from railvib.sweep import SweepLayout, compute_chunk, frf_many_speeds, sweep_from_dict
from railvib.sweep.spec import nested_override
from tests.unit.sweep.sweep_cases import small_sweep

# Reason for 1e-12: the batched solve (multi right-hand side, matmul instead of einsum)
# reorders floating-point operations only; on a well-conditioned 10x10 system that
# changes results by a few ulp times the condition number, far below 1e-12 relative
# to each response's largest value. Relative to the largest value because PSDs have
# deep notches where an elementwise relative error means nothing.
RTOL = 1e-12


def _max_rel(a, b):
    scale = np.max(np.abs(b), axis=0, keepdims=True)
    return float(np.max(np.abs(a - b) / scale))


def test_frf_many_speeds_equals_frf_at_each_speed():
    case = railvib.case_from_dict({"preset": "wang2017_metro"})
    system = build_system(case)
    f = np.geomspace(0.5, 1000.0, 200)
    speeds = np.array([11.1, 22.2, 44.4])
    batch = frf_many_speeds(system, f, speeds)
    for k, v in enumerate(speeds):
        one = build_system(case.model_copy(update={"speed_kmh": v * 3.6})).frf(f)
        assert _max_rel(batch.vehicle[k], one.vehicle) < RTOL
        assert _max_rel(batch.rail[k], one.rail) < RTOL
        assert _max_rel(batch.contact_force[k], one.contact_force) < RTOL


def _case_at(spec, index):
    d = spec.base_case_dict()
    for field, value in SweepLayout(spec).overrides(index):
        d = merge_case_dicts(d, nested_override(field, value))
    return railvib.case_from_dict(d)


@pytest.mark.parametrize(
    "axes",
    [
        [  # shared track, many speeds and irregularities
            {"field": "irregularity.long_wave.class_number", "values": [4, 6]},
            {"field": "speed_kmh", "values": [40.0, 90.0, 160.0]},
        ],
        [  # different pads and wheel positions (no shared structure), vehicle change
            {"field": "track.pad_temperature_c", "values": [-30.0, 25.0]},
            {"field": "contact.leading_wheel_position", "values": [0.0, 0.3]},
            {"field": "vehicle.wheelset_mass", "values": [1200.0, 1420.0]},
        ],
        [  # whole pad tables as values, zipped with speed
            {
                "field": "track.pad",
                "labels": ["stiff", "soft"],
                "zip": "pad",
                "values": [
                    {"model": "spring_damper", "stiffness_n_per_m": 1.2e8, "damping_ns_per_m": 6e4},
                    {"model": "hysteretic", "stiffness_n_per_m": 2.0e7, "loss_factor": 0.25},
                ],
            },
            {"field": "speed_kmh", "values": [60.0, 120.0], "zip": "pad"},
        ],
    ],
)
def test_chunk_equals_railvib_run_case_by_case(axes):
    spec = sweep_from_dict(
        small_sweep(
            axes=axes,
            chunk_size=100,
            variables=["psd_acceleration", "psd_force", "irregularity_psd"],
        )
    )
    lay = SweepLayout(spec)
    assert lay.n_chunks == 1
    out = compute_chunk(spec, 0)
    bands = spec.rms_bands
    for i, index in enumerate(lay.chunk_indices(0)):
        ds = railvib.run(_case_at(spec, index))
        assert _max_rel(out["psd_acceleration"][i], ds.psd_acceleration.values) < RTOL
        assert _max_rel(out["psd_force"][i], ds.psd_force.values) < RTOL
        # the same spectrum function evaluated on the same inputs: identical
        np.testing.assert_array_equal(out["irregularity_psd"][i], ds.irregularity_psd.values)
        ref = summary(ds, bands=[tuple(b) for b in bands])
        for name in ref.data_vars:
            np.testing.assert_allclose(
                out[f"summary/{name}"][i], ref[name].values, rtol=RTOL, atol=0, err_msg=name
            )


def test_layout_covers_every_case_once_and_fills_cheap_axes_first():
    spec = sweep_from_dict(
        small_sweep(
            chunk_size=5,
            axes=[
                {"field": "speed_kmh", "start": 40.0, "stop": 160.0, "num": 7},
                {"field": "track.pad_temperature_c", "values": [-30.0, 0.0, 30.0]},
            ],
        )
    )
    lay = SweepLayout(spec)
    assert lay.block == (5, 1)  # chunks run along speed, which shares the track
    seen = np.zeros(lay.shape, dtype=int)
    for cid in range(lay.n_chunks):
        idx = lay.chunk_indices(cid)
        assert len(idx) <= 5
        seen[tuple(idx.T)] += 1
    assert np.all(seen == 1)
