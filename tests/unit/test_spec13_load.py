"""Issue 13: a sweep file's axis values are checked against the validated base case.

`case_with_table` validates only the table an axis value changes; it must refuse,
accept and warn exactly as validating the whole case with the value merged on does
(`case_from_dict`), which is what every axis value was checked with before.
"""

import copy
import warnings

import pytest

from railvib.case import case_from_dict, merge_case_dicts
from railvib.case.load import case_with_table
from railvib.case.schema import TRACKS, VEHICLES, _keys_of, _track_parameters, _vehicle_parameters
from railvib.errors import CaseError
from railvib.sweep import sweep_from_dict
from railvib.sweep.spec import nested_override
from tests.unit.sweep.sweep_cases import small_sweep


def _base():
    d = small_sweep()
    d["case"]["frequency"]["n"] = 20
    return sweep_from_dict(d).base_case_dict()


def _outcome(check):
    """What a check gives: the error's three parts, or the case and its warnings."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            case = check()
        except CaseError as exc:
            return ("refused", exc.field, repr(exc.value), exc.allowed)
    return ("accepted", case.model_dump(mode="json"), [str(w.message) for w in caught])


#: good, bad and suspicious values of fields in every table an axis can vary
VALUES = [
    ("track.pad.k0_n_per_m", 3.0e7),
    ("track.pad.k0_n_per_m", -1.0),
    ("track.pad.k0_n_per_m", 3.0e8),  # above k_inf: not a Zener pad
    ("track.pad.k0_n_per_m", 1.0e3),
    ("track.pad.k0_n_per_m", "stiff"),
    ("track.pad.alpha", 1.5),
    ("track.pad.tts.glass_transition_c", 30.0),
    ("track.pad_temperature_c", -45.0),
    ("track.pad_temperature_c", -300.0),
    ("track.pad", {"model": "no_such_pad"}),
    ("track.pad", {"model": "fractional_zener", "k0_n_per_m": 4.0e7}),
    ("track.rail.bending_stiffness", 0.0),
    ("track.rail.bending_stiffness", 7.0e6),
    ("track.sleeper_spacing", 0.65),
    ("track.no_such_key", 1.0),
    ("track.model", "no_such_track"),
    ("speed_kmh", 5.0),  # legal, implausibly slow: warns
    ("speed_kmh", -1.0),
    ("vehicle.carbody_mass", 30000.0),
    ("vehicle.carbody_mass", -5.0),
    ("vehicle", {"preset": "no_such_vehicle"}),
    ("contact.contact_constant", 1.0),
    ("irregularity.type", "no_such_spectrum"),
    ("rail_model", "rail_pair"),
    ("mode", "nonstationary"),
]


@pytest.mark.parametrize(("field", "value"), VALUES)
def test_one_table_check_equals_the_whole_case_check(field, value, tmp_path):
    base = _base()
    base_case = case_from_dict(base, base_dir=tmp_path, warn=False)
    key = field.split(".")[0]
    whole = _outcome(
        lambda: case_from_dict(
            merge_case_dicts(base, nested_override(field, value)), base_dir=tmp_path
        )
    )
    one = _outcome(
        lambda: case_with_table(base, base_case, key, nested_override(field, value)[key], tmp_path)
    )
    assert one == whole


def test_the_list_of_values_covers_refusals_acceptances_and_warnings(tmp_path):
    # so the comparison above cannot pass by comparing only one kind of outcome
    base = _base()
    outcomes = [
        _outcome(
            lambda f=f, v=v: case_from_dict(
                merge_case_dicts(base, nested_override(f, v)), base_dir=tmp_path
            )
        )
        for f, v in VALUES
    ]
    assert any(o[0] == "refused" for o in outcomes)
    assert any(o[0] == "accepted" and not o[2] for o in outcomes)
    assert any(o[0] == "accepted" and o[2] for o in outcomes)


def test_a_bad_value_at_position_537_of_1000_is_named():
    values = [2.0e7 + 1.0e4 * i for i in range(1000)]
    values[537] = -1.0
    d = small_sweep(
        axes=[
            {"field": "track.pad_temperature_c", "values": [-30.0, 0.0]},
            {"field": "track.pad.k0_n_per_m", "values": values},
        ]
    )
    d["case"]["frequency"]["n"] = 20
    with pytest.raises(CaseError) as info:
        sweep_from_dict(d)
    assert info.value.field == "track.pad.k0_n_per_m"
    assert info.value.value == -1.0
    assert "[sweep axes[1].values[537], field track.pad.k0_n_per_m]" in info.value.allowed


def test_an_implausible_axis_value_still_warns_naming_it():
    d = small_sweep(axes=[{"field": "speed_kmh", "values": [80.0, 5.0]}])
    d["case"]["frequency"]["n"] = 20
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sweep_from_dict(d)
    messages = [str(w.message) for w in caught]
    assert [m for m in messages if m.startswith("speed_kmh = 5.0: below")], messages


def test_the_base_case_is_not_changed_by_the_checks(tmp_path):
    base = _base()
    before = copy.deepcopy(base)
    base_case = case_from_dict(base, base_dir=tmp_path, warn=False)
    case_with_table(base, base_case, "track", {"pad": {"k0_n_per_m": 3.0e7}}, tmp_path)
    assert base == before


def test_a_base_with_a_preset_is_refused():
    with pytest.raises(ValueError, match="resolved base case"):
        case_with_table({"preset": "wang2017_metro"}, None, "speed_kmh", 80.0)


@pytest.mark.parametrize(
    ("table", "registry", "keys"),
    [("track", TRACKS, _track_parameters), ("vehicle", VEHICLES, _vehicle_parameters)],
)
def test_the_cached_table_keys_are_those_computed_afresh(table, registry, keys):
    assert _keys_of(table, registry, keys) == keys()
    assert _keys_of(table, registry, keys) is _keys_of(table, registry, keys)
