"""Structural sweeps are stacked: a chunk of pad cases is one group, solved as one stack."""

import copy

import pytest

from railvib.case.load import merge_case_dicts
from railvib.sweep import SweepLayout, sweep_from_dict
from railvib.sweep.batch import _chunk_cases, _with_field
from railvib.sweep.spec import nested_override
from tests.unit.sweep.sweep_cases import small_sweep


def test_a_chunk_of_pad_and_speed_cases_is_one_stacked_group():
    spec = sweep_from_dict(
        small_sweep(
            chunk_size=12,
            axes=[
                {"field": "track.pad_temperature_c", "values": [-30.0, 0.0, 30.0]},
                {"field": "track.pad.k0_n_per_m", "values": [3.0e7, 5.0e7]},
                {"field": "speed_kmh", "values": [60.0, 120.0]},
            ],
        )
    )
    cases, groups = _chunk_cases(spec, SweepLayout(spec), 0)
    assert len(cases) == 12
    assert groups == [list(range(12))]  # nothing but the pad and speed differ


def test_a_vehicle_axis_still_splits_the_groups():
    spec = sweep_from_dict(
        small_sweep(
            chunk_size=4,
            axes=[
                {"field": "vehicle.wheelset_mass", "values": [1200.0, 1420.0]},
                {"field": "track.pad_temperature_c", "values": [-30.0, 30.0]},
            ],
        )
    )
    _, groups = _chunk_cases(spec, SweepLayout(spec), 0)
    assert sorted(map(len, groups)) == [2, 2]


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("speed_kmh", 95.0),
        ("track.pad_temperature_c", -12.5),
        ("track.pad.k0_n_per_m", 3.3e7),
        ("track.pad", {"model": "spring_damper", "stiffness_n_per_m": 9e7}),  # replaces
        ("track.pad.tts", {"reference_temperature_c": 10.0}),  # merges into the table
        ("irregularity.long_wave.class_number", 4),
        ("new_table.key", [1, 2]),
    ],
)
def test_overriding_one_path_equals_merging_the_case_dicts(field, value):
    base = sweep_from_dict(small_sweep()).base_case_dict()
    before = copy.deepcopy(base)
    assert _with_field(base, field.split("."), value) == merge_case_dicts(
        base, nested_override(field, value)
    )
    assert base == before  # the base is shared, never modified
