"""Result files: netCDF round trip is exact, writes are atomic, CSV layout and values.

netCDF-4 stores float64 and int64 verbatim, so a round trip must give identical values:
every comparison below is np.array_equal, no tolerance.
"""

import csv
import os
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import railvib
from railvib.results import save_csv

COMPLEX_FRFS = ("frf_displacement", "frf_force")


@pytest.fixture(scope="module")
def run_ds():
    case = railvib.case_from_dict(
        {
            "preset": "wang2017_metro",
            "frequency": {"f_min": 1.0, "f_max": 50.0, "step": 1.0},
            "output": {"rms_bands": [[1.0, 20.0], [20.0, 50.0]]},  # the preset's 100-1000 Hz is off
        }
    )
    return railvib.run(case)


@pytest.fixture
def saved(run_ds, tmp_path):
    path = railvib.save_netcdf(run_ds, tmp_path / "result.nc")
    return path, railvib.load_netcdf(path)


def _attrs_equal(a, b):
    if a.keys() != b.keys():
        return False
    return all(np.array_equal(np.asarray(a[k]), np.asarray(b[k])) for k in a)


# --------------------------------------------------------------------- a run's dataset


def test_every_variable_survives_exactly(run_ds, saved):
    _, loaded = saved
    assert set(loaded.variables) == set(run_ds.variables)
    for name, var in run_ds.variables.items():
        got = loaded[name]
        assert got.dims == var.dims, name
        assert got.dtype == var.dtype, name
        assert np.array_equal(got.values, var.values), name


def test_complex_frfs_come_back_complex_and_are_stored_as_parts(run_ds, saved):
    path, loaded = saved
    raw = xr.load_dataset(path, engine="h5netcdf")  # the file as written, no recombining
    assert list(raw["part"].values) == ["real", "imag"]
    for name in COMPLEX_FRFS:
        assert np.iscomplexobj(run_ds[name].values)  # the case really has complex FRFs
        assert loaded[name].dtype == np.complex128
        assert np.array_equal(loaded[name].values, run_ds[name].values), name
        assert raw[name].dims == (*run_ds[name].dims, "part")
        assert not np.iscomplexobj(raw[name].values)
        assert np.array_equal(raw[name].sel(part="real").values, run_ds[name].values.real)
        assert np.array_equal(raw[name].sel(part="imag").values, run_ds[name].values.imag)


def test_dims_and_coords_survive(run_ds, saved):
    _, loaded = saved
    assert dict(loaded.sizes) == dict(run_ds.sizes)
    assert "part" not in loaded.dims
    assert "part" not in loaded.variables
    assert set(loaded.coords) == set(run_ds.coords)
    for name in run_ds.coords:
        assert np.array_equal(loaded[name].values, run_ds[name].values), name
        assert loaded[name].dims == run_ds[name].dims, name
        assert _attrs_equal(loaded[name].attrs, run_ds[name].attrs), name


def test_global_attrs_survive(run_ds, saved):
    _, loaded = saved
    assert _attrs_equal(loaded.attrs, run_ds.attrs)
    assert loaded.attrs["case_toml"] == run_ds.attrs["case_toml"]  # multi-line string


def test_variable_attrs_survive(run_ds, saved):
    _, loaded = saved
    for name, var in run_ds.data_vars.items():
        got = loaded[name].attrs
        for key, value in var.attrs.items():
            assert key in got, (name, key)
            assert np.array_equal(np.asarray(got[key]), np.asarray(value)), (name, key)
        assert got["units"], name
        assert got["long_name"], name


def test_variable_attrs_are_exactly_the_originals(run_ds, saved):
    _, loaded = saved
    for name in COMPLEX_FRFS:
        assert loaded[name].attrs == run_ds[name].attrs


def test_write_leaves_only_the_target_file(run_ds, tmp_path):
    railvib.save_netcdf(run_ds, tmp_path / "result.nc")
    save_csv(run_ds, tmp_path / "result.csv")
    assert sorted(os.listdir(tmp_path)) == ["result.csv", "result.nc"]  # no .part left


def test_failed_write_keeps_the_old_file_and_leaves_no_temporary(run_ds, tmp_path, monkeypatch):
    target = tmp_path / "result.nc"
    railvib.save_netcdf(run_ds, target)
    before = target.read_bytes()

    def disk_full(self, path=None, *args, **kwargs):  # half a file, then the write fails
        if path is not None:  # save_netcdf builds the file in memory (path None) since issue 11
            Path(path).write_bytes(b"half a netCDF file")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", disk_full)
    with pytest.raises(OSError, match="No space left"):
        railvib.save_netcdf(run_ds, target)
    assert target.read_bytes() == before
    assert os.listdir(tmp_path) == ["result.nc"]
    with pytest.raises(OSError, match="No space left"):
        railvib.save_netcdf(run_ds, tmp_path / "new.nc")
    assert os.listdir(tmp_path) == ["result.nc"]  # no half-written new file


def test_save_does_not_change_the_dataset(run_ds, tmp_path):
    before = run_ds["frf_force"].copy(deep=True)
    railvib.save_netcdf(run_ds, tmp_path / "result.nc")
    assert "part" not in run_ds.dims
    assert "complex_stored_as" not in run_ds["frf_force"].attrs
    assert np.array_equal(run_ds["frf_force"].values, before.values)


# ------------------------------------------------------------------ a hand-built one


def _tiny():
    z2 = np.array(
        [[1.0 + 2.0j, -3.5 - 0.25j], [1e-300 + 1e300j, 5e-324 - 7.0j], [0.0 + 0.0j, 2.0 - 0.0j]]
    )
    z3 = (np.arange(24.0) - 11.5).reshape(3, 2, 4) * (0.3 - 1.7j)
    return xr.Dataset(
        {
            "h": (("frequency", "response"), z2, {"units": "m/m", "long_name": "an FRF"}),
            "h3": (("frequency", "response", "wheel"), z3, {"units": "N/m", "long_name": "3-D"}),
            "z1": (("frequency",), np.array([1j, -1.0, 0.5 + 0.5j]), {"units": "N/m"}),
            "real": (("frequency",), np.array([0.1, 0.2, 0.3]), {"units": "m^2/Hz"}),
        },
        coords={
            "frequency": ("frequency", [0.5, 1.0, 2.0], {"units": "Hz"}),
            "response": ["a.bounce", "rail@wheel1"],
            "wheel": [1, 2, 3, 4],
        },
        attrs={"title": "tiny", "speed_m_per_s": 20.0, "positions_m": np.array([0.0, -2.5])},
    )


def test_hand_built_complex_dataset_round_trips_exactly(tmp_path):
    ds = _tiny()
    loaded = railvib.load_netcdf(railvib.save_netcdf(ds, tmp_path / "tiny.nc"))
    assert set(loaded.variables) == set(ds.variables)
    for name, var in ds.variables.items():
        assert loaded[name].dims == var.dims, name
        assert loaded[name].dtype == var.dtype, name
        assert np.array_equal(loaded[name].values, var.values), name
    assert _attrs_equal(loaded.attrs, ds.attrs)
    assert dict(loaded.sizes) == dict(ds.sizes)


def test_real_and_imaginary_parts_are_bit_exact_for_finite_values(tmp_path):
    ds = _tiny()
    loaded = railvib.load_netcdf(railvib.save_netcdf(ds, tmp_path / "tiny.nc"))
    # bit patterns, not values: catches e.g. a subnormal flushed to zero
    for name in ("h", "h3", "z1"):
        a, b = loaded[name].values, ds[name].values
        assert np.array_equal(a.real.view(np.int64), b.real.view(np.int64)), name
        assert np.array_equal(a.imag.view(np.int64), b.imag.view(np.int64)), name


@pytest.mark.parametrize(
    "z",
    [
        pytest.param(complex(1.0, np.inf), id="inf-imag"),
        pytest.param(complex(2.0, np.nan), id="nan-imag"),
        pytest.param(complex(3.0, -0.0), id="negative-zero-imag"),
    ],
)
def test_non_finite_and_signed_zero_imaginary_parts_round_trip(tmp_path, z):
    ds = xr.Dataset(
        {"h": (("frequency",), np.array([z, 1.0 + 1.0j]))}, coords={"frequency": [1.0, 2.0]}
    )
    got = railvib.load_netcdf(railvib.save_netcdf(ds, tmp_path / "t.nc"))["h"].values[0]
    assert got.real == z.real
    assert np.array_equal(got.imag, z.imag, equal_nan=True)
    assert np.signbit(got.imag) == np.signbit(z.imag)


# ----------------------------------------------------------------------------- CSV


def _read_csv(path):
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    return rows[0], np.array(rows[1:], dtype=float)


#: (bounce and rail, pitch) units of each PSD: a pitch DOF is an angle (CONVENTIONS.md)
_CSV_UNITS = {
    "psd_acceleration": ("(m/s^2)^2/Hz", "(rad/s^2)^2/Hz"),
    "psd_displacement": ("m^2/Hz", "rad^2/Hz"),
}


@pytest.mark.parametrize("variable", ["psd_acceleration", "psd_displacement"])
def test_csv_header_and_values(run_ds, tmp_path, variable):
    path = save_csv(run_ds, tmp_path / "out.csv", variable=variable)
    header, table = _read_csv(path)
    # issue 10: every column carries the unit of its own response; the pitch columns
    # were headed with the bounce unit (m-based) before
    linear, angular = _CSV_UNITS[variable]
    assert run_ds[variable].attrs["units"] == linear
    labels = [str(r) for r in run_ds["response"].values]
    assert any(label.endswith(".pitch") for label in labels)
    expected = [f"{lab} [{angular if lab.endswith('.pitch') else linear}]" for lab in labels]
    assert header == ["frequency [Hz]", *expected]
    assert table.shape == (run_ds.sizes["frequency"], 1 + len(labels))
    # the CSV is written with %.6e: 7 significant digits, a relative rounding of at most
    # 5e-7; 1e-6 (6 significant digits) covers it with the decimal parse's own rounding
    np.testing.assert_allclose(table[:, 0], run_ds["frequency"].values, rtol=1e-6, atol=0)
    np.testing.assert_allclose(table[:, 1:], run_ds[variable].values, rtol=1e-6, atol=0)
