"""The library functions behind ``railvib sweep``: folders, the run description, exports, plots."""

from pathlib import Path

import pytest

from railvib.errors import CaseError
from railvib.plot.sweep import save_sweep_plots
from railvib.sweep import (
    default_output_folder,
    default_plot_folder,
    describe_run,
    load_sweep_dataset,
    run_sweep,
    save_sweep_extras,
    sweep_from_dict,
)
from tests.unit.sweep.sweep_cases import small_sweep


@pytest.fixture(scope="module")
def done(tmp_path_factory):
    """A finished 3 x 4 sweep folder and its dataset."""
    out = tmp_path_factory.mktemp("sweep") / "out"
    ds = run_sweep(sweep_from_dict(small_sweep()), out, workers=1, progress=False)
    return out, ds


def test_default_output_folder_is_the_stem_in_the_current_folder():
    assert default_output_folder("cases/temp_speed.toml") == Path("temp_speed.sweep")
    assert default_output_folder(Path("/abs/s.toml")) == Path("s.sweep")


def test_default_plot_folder(done, tmp_path):
    out, _ = done
    assert default_plot_folder(out) == out / "plots"
    assert default_plot_folder(out / "sweep.zarr") == out / "plots"
    nc = tmp_path / "exports" / "s.nc"
    assert default_plot_folder(nc) == tmp_path / "exports" / "plots"


def test_describe_run():
    spec = sweep_from_dict(small_sweep())
    # 3 temperatures x 4 speeds; chunks of 4 cases run along speed (shares the track): 3 chunks
    what = "12 cases (3 x 4 over track.pad_temperature_c, speed_kmh) in 3 chunks"
    assert describe_run(spec, Path("out")) == f"{what}, on local processes -> out/"
    assert (
        describe_run(spec, "o", scheduler="tcp://10.0.0.1:8786")
        == f"{what}, on Dask scheduler tcp://10.0.0.1:8786 -> o/"
    )


@pytest.mark.slow  # 2-8 s (a subprocess, figures or a Monte Carlo): kept out of the fast suite
def test_save_sweep_extras_writes_what_is_asked(done, tmp_path):
    _, ds = done
    assert save_sweep_extras(ds, tmp_path / "none") == []
    assert not (tmp_path / "none").exists()
    assert save_sweep_extras(ds, tmp_path, csv=True) == [tmp_path / "summary.csv"]
    assert not (tmp_path / "sweep.nc").exists()
    written = save_sweep_extras(ds, tmp_path, netcdf=True, csv=True, plots=True)
    assert written[:2] == [tmp_path / "sweep.nc", tmp_path / "summary.csv"]
    assert {p.parent for p in written[2:]} == {tmp_path / "plots"}
    # the default plots: peak and dominant frequency of car body, wheelset 1, rail at wheel 1
    assert len(written[2:]) == 6
    assert all(p.stat().st_size > 0 for p in written)
    load_sweep_dataset(tmp_path / "sweep.nc")


def test_save_sweep_plots_takes_the_axes(done, tmp_path):
    _, ds = done
    paths = save_sweep_plots(
        ds, tmp_path, ["rms"], ["rail@wheel2"], x="speed_kmh", y="track.pad_temperature_c"
    )
    assert paths == [tmp_path / "sweep_rms_rail_at_wheel2.png"]
    with pytest.raises(CaseError) as err:
        save_sweep_plots(ds, tmp_path, ["peak"], x="temperature")
    assert err.value.field == "x"
    with pytest.raises(CaseError) as err:
        save_sweep_plots(ds, tmp_path, ["peak"], y="speed")
    assert err.value.field == "y"
