"""The xarray accessor ``ds.railvib`` (railvib.accessor, registered by ``import railvib``).

Expected values are closed forms on hand-made datasets (a flat PSD: RMS^2 = S (f2 - f1),
a band's mean square S (upper - lower)), or the library's own functions called
directly where the accessor must be the same call (no duplicated logic).
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import railvib
from railvib.errors import CaseError
from railvib.outputs.octave import BAND_EDGE_RATIO, third_octave_bands

SRC = Path(__file__).resolve().parents[2] / "src"

S0 = 2.0e-3  # (m/s^2)^2/Hz, the flat PSD of the hand-made results
RESPONSES = ["carbody.bounce", "carbody.pitch", "wheelset1.bounce", "rail@wheel1"]


def _result(f, extra=None):
    """A minimal result: a flat acceleration and displacement PSD over `extra` dims too."""
    extra = extra or {}
    shape = (f.size, len(RESPONSES), *(len(v) for v in extra.values()))
    dims = ("frequency", "response", *extra)
    coords = {
        "frequency": ("frequency", f, {"units": "Hz", "long_name": "frequency"}),
        "response": RESPONSES,
        **{k: (k, np.asarray(v)) for k, v in extra.items()},
    }
    scale = np.ones(shape)
    for i, values in enumerate(extra.values()):  # each sweep point its own level
        scale = scale * np.reshape(
            np.arange(1, len(values) + 1), (-1,) + (1,) * (len(extra) - 1 - i)
        )
    return xr.Dataset(
        {
            "psd_acceleration": (
                dims,
                S0 * scale,
                {"units": "(m/s^2)^2/Hz", "long_name": "acceleration PSD"},
            ),
            "psd_displacement": (
                dims,
                1e-9 * scale,
                {"units": "m^2/Hz", "long_name": "displacement PSD"},
            ),
        },
        coords=coords,
    )


@pytest.fixture
def flat():
    return _result(np.linspace(0.5, 200.0, 3991))


_PROBE = """
import sys
import railvib
states = ['xarray' in sys.modules]
import xarray as xr
states += ['railvib' in vars(xr.Dataset), 'railvib.accessor' in sys.modules]
xr.Dataset({'a': ('frequency', [1.0])}).railvib
states += ['railvib.accessor' in sys.modules]
print(json.dumps(states))
"""


@pytest.mark.slow  # a fresh interpreter importing xarray: 1-3 s
def test_import_railvib_registers_the_accessor_when_xarray_comes_later():
    # xarray imported after railvib (isort's order): registered as soon as xarray is
    path = os.pathsep.join([str(SRC), os.environ.get("PYTHONPATH", "")])
    out = subprocess.run(
        [sys.executable, "-c", "import json" + _PROBE],
        env={**os.environ, "PYTHONPATH": path},
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    # no xarray for import railvib; registered; the accessor's module loads on first use
    assert json.loads(out.strip().splitlines()[-1]) == [False, True, False, True]


def test_the_accessor_is_registered_in_this_process():
    assert "railvib" in vars(xr.Dataset)
    assert type(xr.Dataset().railvib).__name__ == "RailvibAccessor"


def test_rms_of_a_flat_psd_is_the_closed_form(flat):
    rms = flat.railvib.rms((10.0, 110.0))
    # the grid has 0.05 Hz steps: 10 and 110 Hz are grid points, the band is exact
    np.testing.assert_allclose(rms.values, np.sqrt(S0 * 100.0), rtol=1e-12)  # rounding only
    assert rms.attrs["units"] == "m/s^2"
    unit_of = rms[rms.attrs["units_coordinate"]]
    assert str(unit_of.sel(response="carbody.pitch").item()) == "rad/s^2"  # rad-based pitch
    whole = flat.railvib.rms()
    np.testing.assert_allclose(whole.values, np.sqrt(S0 * 199.5), rtol=1e-12)


def test_rms_of_a_band_without_grid_points_is_refused(flat):
    with pytest.raises(ValueError, match="holds no grid frequency"):
        flat.railvib.rms((500.0, 600.0))


def test_summary_is_the_library_summary(flat):
    got = flat.railvib.summary([(1.0, 20.0)])
    expected = railvib.summary(flat, [(1.0, 20.0)])
    xr.testing.assert_identical(got, expected)
    assert got["peak"].attrs["units"] == "(m/s^2)^2/Hz"


def test_a_missing_psd_is_named_with_the_ones_there(flat):
    with pytest.raises(CaseError, match="psd_force.*psd_acceleration"):
        flat.railvib.rms(variable="psd_force")


def test_octave_bands_of_a_flat_psd(flat):
    out = flat.railvib.octave_bands(["acceleration", "displacement"])
    bands = third_octave_bands(0.5, 200.0)
    np.testing.assert_allclose(out["band"].values, bands.exact)
    width = bands.exact * (BAND_EDGE_RATIO - 1.0 / BAND_EDGE_RATIO)  # upper - lower, Hz
    ms = out["octave_ms_acceleration"].sel(response="carbody.bounce").values
    np.testing.assert_allclose(ms, S0 * width, rtol=1e-10)  # a linear PSD is integrated exactly
    level = out["octave_level_acceleration"].sel(response="carbody.bounce").values
    np.testing.assert_allclose(level, 10 * np.log10(S0 * width / 1e-12), rtol=1e-10)  # re 1e-6
    assert out["octave_level_acceleration"].attrs["units"] == "dB"
    assert set(out.data_vars) == {
        "octave_ms_acceleration",
        "octave_level_acceleration",
        "octave_ms_displacement",
        "octave_level_displacement",
    }


def test_octave_bands_default_to_every_psd_present(flat):
    # a sweep-like result holds no force PSD: acceleration, velocity, displacement only
    assert {
        str(v).removeprefix("octave_level_")
        for v in flat.railvib.octave_bands().data_vars
        if "level" in v
    } == {
        "acceleration",
        "velocity",
        "velocity_vdb",
        "displacement",
    }
    with pytest.raises(CaseError, match="quantity = 'force'"):
        flat.railvib.octave_bands(["force"])


def test_octave_bands_keep_the_sweep_dimensions():
    ds = _result(np.linspace(0.5, 200.0, 3991), {"speed_kmh": [40.0, 80.0, 120.0]})
    out = ds.railvib.octave_bands(["acceleration"])
    ms = out["octave_ms_acceleration"]
    assert ms.dims == ("band", "response", "speed_kmh")
    np.testing.assert_array_equal(ms["speed_kmh"].values, [40.0, 80.0, 120.0])
    ratio = ms.sel(speed_kmh=120.0) / ms.sel(speed_kmh=40.0)
    np.testing.assert_allclose(ratio.values, 3.0, rtol=1e-12)  # the third point is 3 x S0


def test_plot_psd_draws_the_data_with_the_units_of_the_attrs(flat):
    ax = flat.railvib.plot_psd(["carbody.bounce", "rail@wheel1"])
    assert ax.get_ylabel() == "acceleration PSD [(m/s^2)^2/Hz]"
    assert ax.get_xlabel() == "frequency [Hz]"
    assert [line.get_label() for line in ax.get_lines()] == ["carbody.bounce", "rail@wheel1"]
    np.testing.assert_array_equal(ax.get_lines()[0].get_ydata(), np.full(3991, S0))
    pitch = flat.railvib.plot_psd(["carbody.bounce", "carbody.pitch"])
    assert pitch.get_ylabel() == "acceleration PSD [(m/s^2)^2/Hz; (rad/s^2)^2/Hz]"


def test_plot_psd_of_a_sweep_draws_one_line_per_point():
    ds = _result(np.linspace(0.5, 200.0, 400), {"speed_kmh": [40.0, 80.0]})
    ax = ds.railvib.plot_psd(["wheelset1.bounce"], variable="psd_displacement")
    labels = [line.get_label() for line in ax.get_lines()]
    assert labels == ["speed_kmh=40", "speed_kmh=80"]
    other = ds.railvib.plot_psd(["wheelset1.bounce"], label="case A")
    assert [line.get_label() for line in other.get_lines()] == [
        "case A speed_kmh=40",
        "case A speed_kmh=80",
    ]
    np.testing.assert_allclose(ax.get_lines()[1].get_ydata(), 2e-9)
    assert ax.get_ylabel() == "displacement PSD [m^2/Hz]"


def test_plot_psd_default_responses_and_a_bad_label(flat):
    ax = flat.railvib.plot_psd()
    assert [line.get_label() for line in ax.get_lines()] == [
        "carbody.bounce",
        "wheelset1.bounce",
        "rail@wheel1",
    ]  # the defaults the result holds (it has no bogie)
    with pytest.raises(CaseError, match="response = 'bogie9.bounce'"):
        flat.railvib.plot_psd(["bogie9.bounce"])


@pytest.fixture(scope="module")
def run_result():
    return railvib.run(railvib.load_preset_case())


@pytest.mark.slow  # a run and a 6 MB netCDF file: 2-3 s
def test_on_a_run_and_its_netcdf_file(run_result, tmp_path):
    # a real run: the stored band levels of the run and the accessor's are one computation
    stored = run_result["octave_level_force"].reset_coords(drop=True)
    xr.testing.assert_allclose(
        run_result.railvib.octave_bands(["force"])["octave_level_force"].reset_coords(drop=True),
        stored,
    )
    path = railvib.save_netcdf(run_result, tmp_path / "results.nc")
    with xr.open_dataset(path) as raw:  # plain xarray, as a notebook user opens results.nc
        np.testing.assert_allclose(
            raw.railvib.rms((0.5, 20.0)).values,
            run_result.railvib.rms((0.5, 20.0)).values,
            rtol=1e-12,
        )
