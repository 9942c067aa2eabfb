"""Wheel-rail force criteria against closed forms."""

import numpy as np
import pytest
import xarray as xr

from railvib.outputs import ContactCheck, WheelRailForces


def _dataset(psd_level, loads):
    f = np.linspace(1.0, 101.0, 1001)
    psd = np.outer(np.ones_like(f), psd_level)  # white, N^2/Hz: variance = level * 100 Hz
    return xr.Dataset(
        {
            "psd_force": (("frequency", "wheel"), psd),
            "static_contact_load": (("wheel",), np.asarray(loads, dtype=float)),
        },
        coords={"frequency": f, "wheel": [1, 2]},
    )


def test_three_sigma_and_load_factor_closed_form():
    ds = _dataset([1e4, 4e4], [6e4, 6e4])
    out = WheelRailForces().compute(ds)
    sigma = np.sqrt(np.array([1e4, 4e4]) * 100.0)  # 1000 N and 2000 N
    assert out["dynamic_load_3sigma"].values == pytest.approx(3 * sigma, rel=1e-12)
    assert out["dynamic_load_factor"].values == pytest.approx(1 + 3 * sigma / 6e4, rel=1e-12)
    assert float(out["car_dynamic_load_factor"]) == pytest.approx(1.1, rel=1e-12)
    assert out["dynamic_load_factor"].attrs["units"] == "1"


def test_load_factor_and_loss_of_contact_read_the_same_sigma():
    ds = _dataset([1e4, 4e4], [6e4, 3e4])
    forces = WheelRailForces().compute(ds)
    contact = ContactCheck().compute(ds)
    # 1 + 3 sigma / P0 = 1 + 3 / (P0 / sigma): both criteria from the one force RMS
    ratio = ds["static_contact_load"].values / contact["contact_force_rms"].values
    assert forces["dynamic_load_factor"].values == pytest.approx(1 + 3 / ratio, rel=1e-12)
