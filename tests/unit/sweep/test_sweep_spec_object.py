"""The resolved sweep is a frozen, picklable SweepSpec whose dict is the old JSON-able spec."""

import copy
import dataclasses
import doctest
import json
import pickle

import pytest

import railvib
import railvib.sweep
from railvib.errors import CaseError
from railvib.sweep import ChunkStore, SweepAxis, SweepLayout, SweepSpec, sweep_from_dict
from tests.unit.sweep.sweep_cases import BASE_CASE, small_sweep

PADS = [
    {"model": "spring_damper", "stiffness_n_per_m": 1.2e8, "damping_ns_per_m": 6e4},
    {"model": "hysteretic", "stiffness_n_per_m": 2.0e7, "loss_factor": 0.25},
]


def _table_sweep():
    return sweep_from_dict(
        small_sweep(
            axes=[
                {"field": "track.pad", "labels": ["stiff", "soft"], "values": copy.deepcopy(PADS)},
                {"field": "speed_kmh", "values": [60.0, 120.0]},
            ]
        )
    )


def test_as_dict_is_the_resolved_sweep():
    spec = sweep_from_dict(small_sweep())
    # the base case as the case loader resolves the same table on its own
    base = railvib.case_from_dict(copy.deepcopy(BASE_CASE)).model_dump(
        mode="json", exclude_none=True
    )
    speeds = [40.0, 80.0, 120.0, 160.0]  # 4 points from 40 to 160 inclusive
    expected = {
        "title": "test sweep",
        "mode": "product",
        "chunk_size": 4,
        "variables": ["psd_acceleration", "psd_force"],
        "summary_variable": "psd_acceleration",
        "base_case": base,
        "axes": [
            {
                "field": "track.pad_temperature_c",
                "dim": "track.pad_temperature_c",
                "group": "track.pad_temperature_c",
                "values": [-30.0, 0.0, 30.0],
                "coords": [-30.0, 0.0, 30.0],
            },
            {
                "field": "speed_kmh",
                "dim": "speed_kmh",
                "group": "speed_kmh",
                "values": speeds,
                "coords": speeds,
            },
        ],
    }
    d = spec.as_dict()
    assert d == expected
    assert list(d) == list(expected)  # key order: the manifest is written unsorted
    assert [list(ax) for ax in d["axes"]] == [list(ax) for ax in expected["axes"]]
    assert spec.to_json() == json.dumps(expected, sort_keys=True, default=str)


def test_attributes_and_properties():
    spec = sweep_from_dict(small_sweep())
    assert spec.title == "test sweep"
    assert spec.chunk_size == 4
    assert spec.variables == ("psd_acceleration", "psd_force")
    assert spec.summary_variable == "psd_acceleration"
    assert spec.fields == ("track.pad_temperature_c", "speed_kmh")
    assert spec.axes[1].values == (40.0, 80.0, 120.0, 160.0)
    assert spec.axes[1].size == 4
    bands = railvib.case_from_dict(copy.deepcopy(BASE_CASE)).output.rms_bands
    assert spec.rms_bands == tuple((float(lo), float(hi)) for lo, hi in bands)
    assert spec.base_case["speed_kmh"] == railvib.case_from_dict(BASE_CASE).speed_kmh


@pytest.mark.parametrize("make", [lambda: sweep_from_dict(small_sweep()), _table_sweep])
def test_spec_pickles_and_deep_copies(make):
    spec = make()
    for back in (pickle.loads(pickle.dumps(spec)), copy.deepcopy(spec), copy.copy(spec)):
        assert back == spec
        assert hash(back) == hash(spec)
        assert back.to_json() == spec.to_json()
        assert back.as_dict() == spec.as_dict()


def test_spec_is_read_only():
    spec = _table_sweep()
    with pytest.raises(dataclasses.FrozenInstanceError):
        spec.title = "other"  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        spec.axes[0].values = ()  # type: ignore[misc]
    with pytest.raises(TypeError):
        spec.base_case["speed_kmh"] = 1.0  # type: ignore[index]
    with pytest.raises(TypeError):
        spec.base_case["track"]["pad"]["alpha"] = 0.1  # type: ignore[index]
    with pytest.raises(AttributeError):
        spec.base_case["output"]["rms_bands"].append((1.0, 2.0))
    with pytest.raises(TypeError):
        spec.axes[0].values[0]["model"] = "hysteretic"  # type: ignore[index]
    with pytest.raises(AttributeError):
        spec.base_case._items = {}  # type: ignore[attr-defined]
    before = spec.to_json()
    # copies handed out are plain and mutable, and changing them leaves the spec alone
    d = spec.as_dict()
    d["base_case"]["speed_kmh"] = 1.0
    d["axes"][0]["values"][0]["model"] = "hysteretic"
    base = spec.base_case_dict()
    base["output"]["rms_bands"].append([1.0, 2.0])
    value = spec.axes[0].value(0)
    assert value == PADS[0]
    value["stiffness_n_per_m"] = 1.0
    override = SweepLayout(spec).overrides([0, 0])[0][1]
    assert isinstance(override, dict)
    override["model"] = "x"
    assert spec.to_json() == before


def test_lists_and_tuples_come_back_as_given():
    ax = SweepAxis(
        field="irregularity",
        dim="irr",
        group="irr",
        values=({"bands": [1.0, 2.0], "pair": (3.0, 4.0)},),
        coords=("a",),
    )
    value = ax.as_dict()["values"][0]
    assert type(value["bands"]) is list
    assert type(value["pair"]) is tuple
    assert value == {"bands": [1.0, 2.0], "pair": (3.0, 4.0)}


def test_from_dict_round_trips_the_manifest(tmp_path):
    spec = _table_sweep()
    assert SweepSpec.from_dict(spec.as_dict()) == spec
    assert SweepSpec.from_dict(json.loads(spec.to_json())) == spec
    store = ChunkStore(tmp_path / "out", spec)
    store.open()
    manifest = json.loads((tmp_path / "out" / "manifest.json").read_text())
    back = SweepSpec.from_dict(manifest["spec"])
    assert back == spec
    assert (
        ChunkStore(tmp_path / "out", back).fingerprint
        == store.fingerprint
        == manifest["fingerprint"]
    )
    with pytest.raises(CaseError, match="sweep.axes"):
        SweepSpec.from_dict({k: v for k, v in spec.as_dict().items() if k != "axes"})


def _axis(field, values, group=None, dim=None):
    return SweepAxis(
        field=field, dim=dim or field, group=group or dim or field, values=values, coords=values
    )


@pytest.mark.parametrize(
    ("change", "field"),
    [
        ({"chunk_size": 0}, "chunk_size"),
        ({"chunk_size": 2.5}, "chunk_size"),
        ({"mode": "grid"}, "mode"),
        ({"variables": ("psd_accel",)}, "variables[0]"),
        ({"summary_variable": "psd_force"}, "summary_variable"),
        ({"base_case": [1, 2]}, "base_case"),
        ({"axes": ()}, "axes"),
        ({"axes": (_axis("speed_kmh", (40.0,)), _axis("speed_kmh", (80.0,)))}, "axes.dim"),
        (
            {
                "axes": (
                    _axis("speed_kmh", (40.0, 80.0), group="z"),
                    _axis("track.pad_temperature_c", (1.0,), group="z"),
                )
            },
            "axes.track.pad_temperature_c",
        ),
    ],
)
def test_hand_built_spec_is_validated(change, field):
    spec = sweep_from_dict(small_sweep())
    fields = {f.name: getattr(spec, f.name) for f in dataclasses.fields(SweepSpec)}
    assert SweepSpec(**fields) == spec
    with pytest.raises(CaseError) as err:
        SweepSpec(**{**fields, **change})
    assert err.value.field == field


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"values": (), "coords": ()}, "axes.speed_kmh.values"),
        ({"values": (1.0, 2.0), "coords": ("a",)}, "axes.speed_kmh.coords"),
        ({"values": (1.0,), "coords": (1.0,), "dim": ""}, "axes.dim"),
    ],
)
def test_hand_built_axis_is_validated(kwargs, field):
    with pytest.raises(CaseError) as err:
        SweepAxis(**{"field": "speed_kmh", "dim": "speed_kmh", "group": "speed_kmh", **kwargs})
    assert err.value.field == field


def test_module_docstring_example():
    failures, tried = doctest.testmod(railvib.sweep, verbose=False)
    assert tried > 0
    assert failures == 0


def test_dict_style_access_is_deprecated_but_works():
    from railvib.errors import RailvibDeprecationWarning
    from railvib.sweep import sweep_from_dict
    from tests.unit.sweep.sweep_cases import small_sweep

    spec = sweep_from_dict(small_sweep())
    with pytest.warns(RailvibDeprecationWarning, match=r"spec\.base_case"):
        bands = spec["base_case"]["output"]["rms_bands"]
    assert [tuple(b) for b in bands] == [tuple(b) for b in spec.rms_bands]
