"""Issue 10 in sweeps: the contact check per case, unit columns, the count, crossed-out plots.

The sweep is the issue's example along speed: a stiff pad on an FRA class 1 track at
20 km/h (loss of contact ~1e-4, within the linear model) and at 140 km/h (~40 %,
beyond it). Each case is checked against its own single run (``railvib.run``, the
reference path) and against the threshold's definition.
"""

import copy

import numpy as np
import pandas as pd
import pytest
import tomli_w

import railvib
from railvib.cli.main import main
from railvib.plot.sweep import INVALID_GID, plot_sweep, save_sweep_plots
from railvib.sweep import linear_model_line, load_sweep_dataset, run_sweep, sweep_from_dict
from railvib.sweep.dataset import save_sweep_csv
from tests.unit.test_run_outputs import STIFF

SPEEDS = [20.0, 140.0]


def _sweep(**over):
    d = {
        "title": "stiff pad along speed",
        "chunk_size": 4,
        "variables": [],
        "case": copy.deepcopy(STIFF),
        "axes": [{"field": "speed_kmh", "values": SPEEDS}],
    }
    d.update(over)
    return d


@pytest.fixture(scope="module")
def swept(tmp_path_factory):
    out = tmp_path_factory.mktemp("validity") / "out"
    return out, run_sweep(sweep_from_dict(_sweep()), out, workers=1, progress=False)


def test_each_case_carries_the_runs_contact_check(swept):
    _, ds = swept
    for i, v in enumerate(SPEEDS):
        one = railvib.run(railvib.case_from_dict({**STIFF, "speed_kmh": v}))
        # batched and single solves agree to ~1e-12 in the force (test_sweep_batch);
        # Phi(-x) magnifies a relative error in sigma by about x^2 (< 20 here): 1e-9
        np.testing.assert_allclose(
            ds["loss_of_contact_probability"].isel(speed_kmh=i).values,
            one["loss_of_contact_probability"].values,
            rtol=1e-9,
        )
        np.testing.assert_allclose(
            ds["contact_force_rms"].isel(speed_kmh=i).values,
            one["contact_force_rms"].values,
            rtol=1e-12,
        )
        assert bool(ds["linear_model_valid"].isel(speed_kmh=i)) == bool(one["linear_model_valid"])
    assert list(ds["linear_model_valid"].values) == [True, False]
    worst = ds["loss_of_contact_probability"].max("wheel").values
    assert worst[0] < 0.01 < 0.3 < worst[1] < 0.5  # ~1e-4 and ~40 % (the example)
    assert ds["linear_model_valid"].attrs["loss_of_contact_threshold"] == 0.01
    assert ds["loss_of_contact_probability"].dims == ("wheel", "speed_kmh")
    assert ds["contact_force_rms"].attrs["units"] == "N"


def test_closing_line_counts_the_cases_beyond_the_model(swept):
    _, ds = swept
    assert linear_model_line(ds) == "1 of 2 cases beyond the linear model (loss of contact > 1 %)"


def test_threshold_comes_from_the_base_case():
    spec = sweep_from_dict(
        _sweep(case={**copy.deepcopy(STIFF), "output": {"loss_of_contact_threshold": 0.5}})
    )
    assert spec.loss_of_contact_threshold == 0.5


def test_summary_units_per_response(swept, tmp_path):
    _, ds = swept
    labels = [str(r) for r in ds["response"].values]
    coord = ds["peak"].attrs["units_coordinate"]
    expected = ["(rad/s^2)^2/Hz" if r.endswith(".pitch") else "(m/s^2)^2/Hz" for r in labels]
    assert list(ds[coord].values) == expected
    rms_coord = ds["rms"].attrs["units_coordinate"]
    assert ds["rms_0.5_20_hz"].attrs["units_coordinate"] == rms_coord
    assert list(ds[rms_coord].values) == [
        "rad/s^2" if r.endswith(".pitch") else "m/s^2" for r in labels
    ]
    table = pd.read_csv(save_sweep_csv(ds, tmp_path / "s.csv"))
    assert len(table) == len(labels) * len(SPEEDS)
    pitch = table[table["response"] == "bogie1.pitch"]
    assert set(pitch["peak_unit"]) == {"(rad/s^2)^2/Hz"}
    assert set(pitch["rms_unit"]) == {"rad/s^2"}
    bounce = table[table["response"] == "wheelset1.bounce"]
    assert set(bounce["peak_unit"]) == {"(m/s^2)^2/Hz"}
    assert "dominant_frequency [Hz]" in table.columns
    assert "peak [(m/s^2)^2/Hz]" not in table.columns  # no single unit over mixed rows
    fast = table[table["speed_kmh"] == 140.0]
    assert set(fast["linear_model_valid"]) == {False}
    np.testing.assert_allclose(
        fast["loss_of_contact_probability_max [1]"].iloc[0],
        ds["loss_of_contact_probability"].isel(speed_kmh=1).max(),
        rtol=1e-8,  # written with 9 significant digits
    )


def _crossed(ax):
    return [a for a in ax.get_children() if a.get_gid() == INVALID_GID]


def test_lines_cross_out_the_invalid_case(swept):
    _, ds = swept
    ax = plot_sweep(ds, "peak", "bogie1.pitch")
    (marks,) = _crossed(ax)
    peak_fast = float(ds["peak"].sel(response="bogie1.pitch").isel(speed_kmh=1))
    np.testing.assert_array_equal(marks.get_offsets(), [[140.0, peak_fast]])
    assert "beyond the linear model (loss of contact > 1 %)" in [
        t.get_text() for t in ax.get_legend().get_texts()
    ]
    assert ax.get_ylabel() == "peak acceleration PSD [(rad/s^2)^2/Hz]"  # a pitch response
    ax = plot_sweep(ds, "loss_of_contact_probability")
    assert ax.get_ylabel().endswith("worst wheel [1]")
    np.testing.assert_array_equal(
        ax.lines[0].get_ydata(), ds["loss_of_contact_probability"].max("wheel").values
    )


@pytest.mark.slow  # 2-8 s (a subprocess, figures or a Monte Carlo): kept out of the fast suite
def test_heat_map_crosses_out_the_invalid_cells(tmp_path):
    d = _sweep(
        axes=[
            {"field": "speed_kmh", "values": SPEEDS},
            {"field": "irregularity.class_number", "name": "fra_class", "values": [1, 2]},
        ]
    )
    ds = run_sweep(sweep_from_dict(d), tmp_path / "o", workers=1, progress=False)
    assert ds["linear_model_valid"].transpose("speed_kmh", "fra_class").values.tolist() == [
        [True, True],
        [False, False],
    ]
    ax = plot_sweep(ds, "rms", "wheelset1.bounce", x="speed_kmh", y="fra_class")
    (marks,) = _crossed(ax)
    # the 140 km/h column is invalid for both track classes
    assert sorted(zip(marks.get_xdata(), marks.get_ydata(), strict=True)) == [
        (140.0, 1),
        (140.0, 2),
    ]
    written = save_sweep_plots(ds, tmp_path / "p", ["loss_of_contact_probability", "peak"])
    assert written[0] == tmp_path / "p" / "sweep_loss_of_contact_probability.png"


def test_sweep_strict_exits_3_and_the_closing_line_counts(tmp_path, capsys):
    f = tmp_path / "s.toml"
    f.write_text(tomli_w.dumps(_sweep()))
    args = ["sweep", str(f), "-j", "1", "--no-progress"]
    assert main([*args, "-o", str(tmp_path / "a")]) == 0
    last = capsys.readouterr().err.strip().splitlines()[-1]
    assert last == (
        f"written {tmp_path / 'a'}/sweep.zarr; "
        "1 of 2 cases beyond the linear model (loss of contact > 1 %)"
    )
    assert main([*args, "-o", str(tmp_path / "b"), "--strict"]) == 3
    err = capsys.readouterr().err.strip().splitlines()
    assert (
        err[-1] == "error: --strict: 1 of 2 cases beyond the linear model (loss of contact > 1 %)"
    )
    assert load_sweep_dataset(tmp_path / "b").sizes["speed_kmh"] == 2  # written all the same
    slow = _sweep(axes=[{"field": "speed_kmh", "values": [10.0, 20.0]}])
    f.write_text(tomli_w.dumps(slow))
    assert main([*args, "-o", str(tmp_path / "c"), "--strict"]) == 0
