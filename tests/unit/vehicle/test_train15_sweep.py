"""A sweep over train length: one dataset, each length equal to running it alone.

The dataset's response and wheel axes are the longest train's; a shorter train's values
for the cars it lacks are NaN, and a single car reads as car 1 (docs/sweeps.md).
"""

import re
from pathlib import Path

import numpy as np
import pytest

import railvib
from railvib.case.load import merge_case_dicts
from railvib.errors import CaseError
from railvib.labels import leading_car_label
from railvib.results.stats import summary_names
from railvib.sweep import SweepLayout, load_sweep, sweep_dataset, sweep_from_dict
from railvib.sweep.batch import compute_chunk
from railvib.sweep.dataset import _check_complete, summary_table
from railvib.sweep.spec import nested_override
from railvib.sweep.trains import length_groups, sweep_labels

ROOT = Path(__file__).resolve().parents[3]

#: the sweep's batched solve and railvib.run differ by rounding only (measured 1e-14)
RTOL = 1e-10

GRID = {"spacing": "log", "f_min": 0.5, "f_max": 500.0, "n": 30}


def _spec(axes, chunk_size=4, mode="product", variables=("psd_acceleration", "psd_force")):
    return sweep_from_dict(
        {
            "chunk_size": chunk_size,
            "mode": mode,
            "variables": list(variables),
            "case": {"preset": "wang2017_metro", "frequency": GRID},
            "axes": axes,
        }
    )


def _alone(spec, index):
    """The case at sweep `index` run on its own: the dataset of railvib.run."""
    d = spec.base_case_dict()
    for field, value in SweepLayout(spec).overrides(index):
        d = merge_case_dicts(d, nested_override(field, value))
    return railvib.run(railvib.case_from_dict(d))


def _check_chunks(spec):
    lay = SweepLayout(spec)
    labels, wheels = sweep_labels(spec)
    for chunk in range(lay.n_chunks):
        out = compute_chunk(spec, chunk)
        for i, index in enumerate(lay.chunk_indices(chunk)):
            ds = _alone(spec, index)
            mine = [str(r) for r in ds.response.values]
            if not mine[0].startswith("car1."):  # a single car is the train's car 1
                mine = [leading_car_label(r) for r in mine]
            at = [labels.index(r) for r in mine]
            others = np.setdiff1d(np.arange(len(labels)), at)
            want = ds["psd_acceleration"].values
            got = out["psd_acceleration"][i]
            scale = np.abs(want).max(axis=0, keepdims=True)
            assert np.max(np.abs(got[:, at] - want) / scale) < RTOL, (chunk, i)
            assert np.isnan(got[:, others]).all()
            n_w = ds.sizes["wheel"]
            force = out["psd_force"][i]
            assert np.max(np.abs(force[:, :n_w] - ds["psd_force"].values)) < RTOL * np.max(
                ds["psd_force"].values
            )
            assert np.isnan(force[:, n_w:]).all()
            assert np.isnan(out["summary/contact_force_rms"][i, n_w:]).all()
            assert np.isfinite(out["summary/contact_force_rms"][i, :n_w]).all()
            assert len(wheels) >= n_w


@pytest.mark.slow
def test_each_train_length_of_a_sweep_equals_running_it_alone():
    # chunks of 4 split the (3 lengths x 2 speeds) block across lengths; lengths unsorted
    spec = _spec(
        [
            {"field": "train.cars", "name": "cars", "values": [1, 3, 2]},
            {"field": "speed_kmh", "values": [60.0, 100.0]},
        ]
    )
    assert length_groups(spec) == ("cars",)
    _check_chunks(spec)


@pytest.mark.slow
def test_zipped_train_tables_with_their_gaps_equal_running_them_alone():
    spec = _spec(
        [
            {
                "field": "train",
                "labels": ["one", "two, 3 m", "two, 40 m"],
                "values": [{"cars": 1}, {"cars": 2, "gap_m": 3.0}, {"cars": 2, "gap_m": 40.0}],
            },
            {"field": "speed_kmh", "values": [70.0, 110.0, 60.0], "zip": "train"},
        ],
        mode="zip",
    )
    _check_chunks(spec)


def test_the_dataset_is_labelled_as_the_longest_train():
    spec = _spec([{"field": "train.cars", "values": [2, 1]}], variables=())
    labels, wheels = sweep_labels(spec)
    assert wheels == tuple(f"car{c}.wheel{j}" for c in (1, 2) for j in range(1, 5))
    assert labels[0] == "car1.carbody.bounce"
    assert labels[-1] == "rail@car2.wheel4"
    arrays = {f"summary/{n}": np.zeros((2, len(labels))) for n in summary_names(spec.rms_bands)}
    ds = sweep_dataset(spec, arrays, "x")
    assert list(ds.response.values) == list(labels)
    assert list(ds.wheel.values) == list(range(1, 9))


def test_a_sweep_without_train_length_keeps_its_labels():
    spec = _spec([{"field": "speed_kmh", "values": [60.0, 80.0]}])
    assert length_groups(spec) == ()
    labels, wheels = sweep_labels(spec)
    assert labels[0] == "carbody.bounce"
    assert wheels == ("wheel1", "wheel2", "wheel3", "wheel4")


def test_a_train_length_axis_checks_the_criteria_of_each_train():
    # the comfort body car2.carbody exists in a two-car train only: named at load time
    with pytest.raises(CaseError) as err:
        sweep_from_dict(
            {
                "case": {
                    "preset": "wang2017_metro",
                    "frequency": GRID,
                    "train": {"cars": 2},
                    "criteria": {"comfort_body": "car2.carbody"},
                },
                "axes": [{"field": "train.cars", "values": [2, 1]}],
            }
        )
    assert "axes[0].values[1]" in str(err.value)


def test_the_example_of_docs_sweeps_loads_as_the_longest_train(tmp_path):
    text = (ROOT / "docs" / "sweeps.md").read_text(encoding="utf-8")
    section = text[text.index("## Trains of several lengths") :]
    example = re.search(r"```toml\n(.*?)```", section, flags=re.S).group(1)
    (tmp_path / "trains.toml").write_text(example, encoding="utf-8")
    spec = load_sweep(tmp_path / "trains.toml")
    assert SweepLayout(spec).shape == (4, 2)
    labels, wheels = sweep_labels(spec)
    assert len(wheels) == 24  # six cars of four wheelsets
    assert "car6.carbody.bounce" in labels


def _dataset(spec):
    arrays = {}
    for chunk in range(SweepLayout(spec).n_chunks):
        for name, value in compute_chunk(spec, chunk).items():
            arrays.setdefault(name, []).append(value)
    return sweep_dataset(spec, {k: np.concatenate(v) for k, v in arrays.items()}, "x")


@pytest.mark.slow
def test_the_padding_is_marked_and_real_gaps_are_still_found(tmp_path):
    spec = _spec([{"field": "train.cars", "values": [2, 1]}], chunk_size=2)
    ds = _dataset(spec)
    assert ds.train_cars.values.tolist() == [2, 1]
    assert ds.wheel_car.values.tolist() == [1, 1, 1, 1, 2, 2, 2, 2]
    present = ds.response_car <= ds.train_cars
    assert np.isfinite(ds.rms.where(present)).sum() == 2 * 14 + 14
    _check_complete(ds, tmp_path)  # the padding is not a missing value
    broken = ds.copy(deep=True)
    broken["rms"].loc[{"response": "car1.carbody.bounce", "train.cars": 1}] = np.nan
    with pytest.raises(CaseError, match="rms has 1 of"):
        _check_complete(broken, tmp_path)
    table = summary_table(ds)
    assert len(table) == 2 * 14 + 14  # rows of the cars each train has
    assert set(table["train_cars"]) == {1, 2}
