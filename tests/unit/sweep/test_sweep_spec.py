"""Sweep files are validated like case files, with field-named errors."""

import copy

import numpy as np
import pytest

from railvib.errors import CaseError
from railvib.sweep import SweepLayout, load_sweep, sweep_from_dict
from tests.unit.sweep.sweep_cases import BASE_CASE, small_sweep


def test_ranges_values_and_log_ranges_resolve():
    spec = sweep_from_dict(
        small_sweep(
            axes=[
                {"field": "speed_kmh", "start": 40.0, "stop": 160.0, "step": 40.0},
                {"field": "track.pad_temperature_c", "start": -40.0, "stop": 40.0, "num": 3},
                {
                    "field": "contact.stiffness",
                    "start": 1e8,
                    "stop": 1e10,
                    "num": 3,
                    "spacing": "log",
                },
                {"field": "rail_model", "values": ["single_rail", "rail_pair"]},
            ]
        )
    )
    vals = [list(ax.values) for ax in spec.axes]
    assert vals[0] == [40.0, 80.0, 120.0, 160.0]  # stop included where it lands
    assert vals[1] == [-40.0, 0.0, 40.0]
    # log range: exact decades up to rounding of geomspace (1 ulp-level reason)
    np.testing.assert_allclose(vals[2], [1e8, 1e9, 1e10], rtol=1e-15)
    assert vals[3] == ["single_rail", "rail_pair"]
    assert SweepLayout(spec).shape == (4, 3, 3, 2)


def test_zip_groups_share_a_dimension():
    spec = sweep_from_dict(
        small_sweep(
            axes=[
                {"field": "track.pad_temperature_c", "values": [-20.0, 20.0], "zip": "climate"},
                {"field": "speed_kmh", "values": [60.0, 100.0], "zip": "climate"},
                {"field": "contact.leading_wheel_position", "values": [0.0, 0.3, 0.45]},
            ]
        )
    )
    lay = SweepLayout(spec)
    assert lay.dims == ("climate", "contact.leading_wheel_position")
    assert lay.shape == (2, 3)
    whole = sweep_from_dict(
        small_sweep(
            mode="zip",
            axes=small_sweep()["axes"][:1]
            + [{"field": "speed_kmh", "values": [40.0, 80.0, 120.0]}],
        )
    )
    assert SweepLayout(whole).shape == (3,)


@pytest.mark.parametrize(
    ("axes", "field", "text"),
    [
        ([{"field": "speed_kmh", "values": [80.0, -5.0]}], "speed_kmh", "must be > 0"),
        ([{"field": "vehicle.carbody_mas", "values": [1.0]}], "vehicle.carbody_mas", "unknown key"),
        ([{"field": "frequency.f_max", "values": [100.0]}], "axes[0].field", "cannot vary"),
        ([{"field": "speed_kmh", "values": [1.0], "start": 1.0}], "axes[0].values", "one of"),
        ([{"field": "speed_kmh", "start": 1.0, "stop": 2.0}], "axes[0].num", "exactly one"),
        (
            [{"field": "speed_kmh", "start": 0.0, "stop": 2.0, "num": 3, "spacing": "log"}],
            "axes[0].start",
            "log",
        ),
        ([{"field": "speed_kmh", "values": [40.0, 40.0]}], "axes[0].values", "distinct"),
        (
            [
                {"field": "speed_kmh", "values": [40.0], "zip": "a"},
                {"field": "track.pad_temperature_c", "values": [1.0, 2.0], "zip": "a"},
            ],
            "axes.track.pad_temperature_c",
            "equal lengths",
        ),
        (
            [{"field": "track.pad", "values": [{"model": "hysteretic"}]}],
            "axes[0].labels",
            "required",
        ),
        ([{"field": "speed_kmh", "values": [40.0], "colour": 1}], "axes[0].colour", "unknown key"),
        ([], "axes", ""),
    ],
)
def test_bad_sweeps_name_the_field(axes, field, text):
    with pytest.raises(CaseError) as err:
        sweep_from_dict(small_sweep(axes=axes))
    assert err.value.field == field
    assert text in err.value.allowed


def test_bad_value_inside_a_table_axis_names_the_pad_field():
    bad = [
        {
            "field": "track.pad",
            "labels": ["soft", "broken"],
            "values": [
                {"model": "spring_damper", "stiffness_n_per_m": 2e7},
                {"model": "spring_damper", "stiffness_n_per_m": -1.0},
            ],
        }
    ]
    with pytest.raises(CaseError) as err:
        sweep_from_dict(small_sweep(axes=bad))
    assert err.value.field.startswith("track.pad")
    assert "axes[0].values[1]" in str(err.value)


def test_missing_case_and_unknown_variable():
    with pytest.raises(CaseError, match="case"):
        sweep_from_dict({"axes": [{"field": "speed_kmh", "values": [40.0]}]})
    with pytest.raises(CaseError) as err:
        sweep_from_dict(small_sweep(variables=["psd_accel"]))
    assert err.value.field == "variables[0]"


def test_base_file_plus_overrides(tmp_path):
    import tomli_w

    base = copy.deepcopy(BASE_CASE)
    (tmp_path / "base.toml").write_text(tomli_w.dumps(base))
    sweep = {
        "base": "base.toml",
        "case": {"speed_kmh": 120.0},
        "axes": [{"field": "track.pad_temperature_c", "values": [0.0, 10.0]}],
    }
    (tmp_path / "s.toml").write_text(tomli_w.dumps(sweep))
    spec = load_sweep(tmp_path / "s.toml")
    assert spec.base_case["speed_kmh"] == 120.0
    assert spec.base_case["track"]["pad"]["model"] == "fractional_zener"
    with pytest.raises(CaseError, match="readable"):
        load_sweep(tmp_path / "missing.toml")


def test_temperature_axis_with_a_temperature_blind_pad_is_refused():
    import re

    spec = {
        "case": {"preset": "wang2017_metro"},
        "axes": [{"field": "track.pad_temperature_c", "values": [-30.0, 20.0]}],
    }
    with pytest.raises(
        CaseError, match=re.escape("axes.track.pad_temperature_c = 'spring_damper'")
    ):
        sweep_from_dict(spec)
