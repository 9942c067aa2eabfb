"""Every structural sweep axis on the stacked path against each case solved alone (issue 13).

The reference is :meth:`railvib.coupling.CoupledSystem.frf` of each case's own system
(the run path, one case at a time); the stacked solve lays the cases' points on one
axis, so the two differ only in the order of floating-point operations and in the
number of Krylov-series terms (set by the largest ``|beta4|`` of a stack).
"""

import numpy as np
import pytest

import railvib
from railvib.case import build_system, case_from_dict
from railvib.case.load import load_preset_case, merge_case_dicts
from railvib.sweep import sweep_from_dict
from railvib.sweep.batch import compute_chunk
from railvib.sweep.layout import SweepLayout
from railvib.sweep.spec import nested_override
from railvib.sweep.stacked import frf_case_stack
from railvib.track.periodic import PeriodicTrack

#: reason: rounding only (the same algorithm on each point); 1e-10 of each response's
#: peak is the agreement issue 13 asks of a stacked axis
RTOL = 1e-10

F = np.geomspace(0.5, 1000.0, 90)

#: a temperature-dependent pad (fractional Zener with a WLF shift), for the temperature axis
TTS_PAD = {
    "track": {
        "pad": {
            "model": "fractional_zener",
            "k0_n_per_m": 4.0e7,
            "k_inf_n_per_m": 2.0e8,
            "tau_s": 1.0e-3,
            "alpha": 0.4,
            "tts": {"reference_temperature_c": 20.0, "glass_transition_c": -50.0},
        }
    }
}

#: (field, three values) of every structural parameter a sweep may vary
AXES = [
    ("track.rail.bending_stiffness", [4.0e6, 6.62e6, 9.0e6]),
    ("track.rail.mass_per_length", [50.0, 60.64, 75.0]),
    ("track.rail.loss_factor", [0.0, 0.01, 0.05]),
    ("track.sleeper_spacing", [0.55, 0.6, 0.65]),
    ("track.pad.stiffness_n_per_m", [2.0e7, 5.0e7, 1.5e8]),
    ("track.pad_temperature_c", [-20.0, 20.0, 40.0]),
    ("vehicle.carbody_mass", [15000.0, 21920.0, 30000.0]),
    ("vehicle.bogie_mass", [2000.0, 2550.0, 3200.0]),
    ("vehicle.wheelset_mass", [1200.0, 1420.0, 1800.0]),
    ("vehicle.primary_stiffness", [1.0e6, 1.7e6, 3.0e6]),
    ("vehicle.primary_damping", [2.0e3, 5.0e3, 2.0e4]),
    ("vehicle.secondary_stiffness", [2.0e5, 2.75e5, 4.0e5]),
    ("vehicle.secondary_damping", [1.0e4, 3.0e4, 6.0e4]),
    ("vehicle.wheelset_half_spacing", [1.0, 1.1, 1.25]),
    ("contact.stiffness", [8.0e8, 1.4e9, 2.5e9]),
    ("contact.contact_constant", [4.0e-8, 5.2e-8, 6.5e-8]),
    ("contact.leading_wheel_position", [0.0, 0.3, 0.45]),
    ("speed_kmh", [40.0, 80.0, 160.0]),
]


def _max_rel(a, b):
    """Largest difference relative to the largest value of each response."""
    return float(np.max(np.abs(a - b) / np.abs(b).max(axis=0, keepdims=True)))


def _systems(field, values, base=None):
    base = load_preset_case().model_dump(exclude_none=True) if base is None else base
    if field == "track.pad_temperature_c":
        base = merge_case_dicts(base, TTS_PAD)
    return [
        build_system(case_from_dict(merge_case_dicts(base, nested_override(field, v))))
        for v in values
    ]


def _assert_each_case_alone(batch, systems):
    for i, system in enumerate(systems):
        one = system.frf(F)
        assert _max_rel(batch.vehicle[i], one.vehicle) < RTOL
        assert _max_rel(batch.rail[i], one.rail) < RTOL
        assert _max_rel(batch.contact_force[i], one.contact_force) < RTOL


@pytest.mark.parametrize(("field", "values"), AXES, ids=[a[0] for a in AXES])
def test_each_stacked_axis_equals_the_cases_solved_alone(field, values):
    systems = _systems(field, values)
    _assert_each_case_alone(frf_case_stack(F, systems), systems)


def test_cases_differing_in_everything_at_once_are_one_stack(monkeypatch):
    base = load_preset_case().model_dump(exclude_none=True)
    over = [
        {"track": {"rail": {"bending_stiffness": 5.0e6}, "sleeper_spacing": 0.62}},
        {"vehicle": {"carbody_mass": 25000.0}, "contact": {"leading_wheel_position": 0.1}},
        {"speed_kmh": 120.0, "track": {"rail": {"loss_factor": 0.02}}},
        {"contact": {"stiffness": 1.0e9}, "vehicle": {"primary_damping": 9.0e3}},
    ]
    systems = [build_system(case_from_dict(merge_case_dicts(base, o), warn=False)) for o in over]
    refs = [s.frf(F) for s in systems]

    def refused(*args, **kwargs):
        raise AssertionError("an Euler rail's track is solved on the stack, not case by case")

    monkeypatch.setattr(PeriodicTrack, "receptance", refused)
    batch = frf_case_stack(F, systems)
    for i, one in enumerate(refs):
        assert _max_rel(batch.vehicle[i], one.vehicle) < RTOL
        assert _max_rel(batch.rail[i], one.rail) < RTOL
        assert _max_rel(batch.contact_force[i], one.contact_force) < RTOL


@pytest.mark.slow
def test_timoshenko_and_ballasted_tracks_in_a_stack_with_euler_ones():
    base = load_preset_case().model_dump(exclude_none=True)
    euler = _systems("track.rail.bending_stiffness", [6.0e6], base)
    timoshenko = _systems("track.rail.shear_stiffness", [2.45e8], base)  # its own solver
    ballasted = _systems(
        "track.ballast.stiffness_n_per_m",
        [5.0e7, 1.0e8],
        load_preset_case("thompson_ballasted").model_dump(exclude_none=True),
    )
    systems = euler + timoshenko + ballasted
    _assert_each_case_alone(frf_case_stack(F, systems), systems)


@pytest.mark.slow
def test_a_chunk_of_rail_and_vehicle_axes_equals_railvib_run_case_by_case():
    base = load_preset_case().model_dump(exclude_none=True)
    base["frequency"] = {"spacing": "log", "f_min": 0.5, "f_max": 1000.0, "n": 60}
    spec = sweep_from_dict(
        {
            "title": "rail x vehicle",
            "chunk_size": 100,
            "variables": ["psd_acceleration", "psd_force"],
            "case": base,
            "axes": [
                {"field": "track.rail.bending_stiffness", "values": [5.0e6, 8.0e6]},
                {"field": "track.sleeper_spacing", "values": [0.58, 0.63]},
                {"field": "vehicle.secondary_stiffness", "values": [2.0e5, 4.0e5]},
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
        assert _max_rel(out["psd_acceleration"][i], ds.psd_acceleration.values) < RTOL
        assert _max_rel(out["psd_force"][i], ds.psd_force.values) < RTOL
