"""``save_netcdf`` / ``load_netcdf`` write any result dataset: booleans, complex, attributes.

netCDF has no boolean type and no dict or string-sequence attributes; the writer
stores booleans as int8 marked ``dtype_stored_as = "bool"`` and such attribute
values as their ``str``, and the reader restores booleans and complex variables.
Expected values are the inputs themselves (a round trip).
"""

import numpy as np
import xarray as xr

from railvib.results import load_netcdf, save_netcdf


def test_netcdf_round_trip_of_booleans_and_non_netcdf_attributes(tmp_path):
    ds = xr.Dataset(
        {
            "flag": ("x", np.array([True, False, True]), {"units": "1", "long_name": "flag"}),
            "value": ("x", np.array([1.0, 2.0, 3.0]), {"units": "m", "long_name": "value"}),
            "frf": ("x", np.array([1.0, 2.0j, -3.0]), {"units": "m/m", "long_name": "frf"}),
        },
        coords={"x": ("x", [0.0, 1.0, 2.0], {"units": "s", "long_name": "x"})},
        attrs={
            "timings": {"pem_seconds": 0.5},
            "labels": ("a", "b"),
            "quick": True,
            "seed": 3,
            "dt": 1e-4,
            "positions": np.array([0.3, -1.9]),
        },
    )
    path = save_netcdf(ds, tmp_path / "r.nc")
    raw = xr.load_dataset(path, engine="h5netcdf")
    assert raw["flag"].dtype == np.int8
    assert raw["flag"].attrs["dtype_stored_as"] == "bool"
    back = load_netcdf(path)
    assert back["flag"].dtype == bool
    np.testing.assert_array_equal(back["flag"].values, ds["flag"].values)
    assert back["flag"].attrs == ds["flag"].attrs
    xr.testing.assert_identical(back["value"], ds["value"])
    xr.testing.assert_identical(back["frf"], ds["frf"])  # complex: no storage attribute left
    assert back.attrs["timings"] == "{'pem_seconds': 0.5}"
    assert back.attrs["labels"] == "('a', 'b')"
    assert back.attrs["quick"] == "True"
    assert back.attrs["seed"] == 3
    assert back.attrs["dt"] == 1e-4
    np.testing.assert_array_equal(back.attrs["positions"], [0.3, -1.9])
    assert ds["flag"].dtype == bool
    assert isinstance(ds.attrs["timings"], dict)  # the input is untouched
