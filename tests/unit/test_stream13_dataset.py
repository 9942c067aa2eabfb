"""A run's dataset built once from its arrays equals the one built the old way (issue 13).

``run_system`` now wraps its arrays in one ``xr.Dataset`` construction, with the contact
check and the support forces computed on the NumPy arrays. The reference here is built
as before, step by step through xarray: the variables of one block, the units
coordinates (``with_unit_coordinates``), the support forces merged as DataArrays with
their coordinates, the contact check derived from the dataset. Every variable,
coordinate, attribute and dtype must be identical (``xr.testing.assert_identical``):
the arithmetic is the same, only the wrapping changed, so no tolerance.
"""

import numpy as np
import pytest
import xarray as xr
from scipy.stats import norm

import railvib
from railvib.case import build_spectrum, build_system
from railvib.grid import FrequencyGrid
from railvib.io import railvib_version
from railvib.labels import displacement_unit
from railvib.outputs import derive
from railvib.outputs.supports import gives_seat_forces, seat_positions, support_force_variables
from railvib.results import load_netcdf, save_netcdf
from railvib.results.units import QUANTITY_UNITS, with_unit_coordinates
from railvib.results.variables import VARIABLES, compute_variables
from railvib.solve import run_system

#: ballasted layers, a slab on bearings, a train's many wheels, the default case
PRESETS = ["wang2017_metro", "thompson_ballasted", "floating_slab_metro", "wang2017_metro_train6"]
GRID = FrequencyGrid.linear(0.5, 150.0, 0.5)  # 300 frequencies: one block


def old_way(system, grid, spectrum, threshold):
    """The result as the earlier code built it: xarray step by step."""
    f = grid.f
    s_r = spectrum.temporal(f, system.speed)
    pad_k = system.track.pad.stiffness(f, system.track.pad_temperature)
    seats = None
    if gives_seat_forces(system, f):
        seats = seat_positions(system.wheel_positions, system.track.sleeper_spacing)
    [(sl, frf)] = list(system.frf_blocks(f, block=f.size, observe=seats))
    values = compute_variables(frf, s_r, VARIABLES)
    labels = list(frf.labels)
    coords = {
        "frequency": ("frequency", f, {"units": "Hz", "long_name": "frequency"}),
        "response": ("response", labels, {"long_name": "response"}),
        "displacement_unit": (
            "response",
            [displacement_unit(lab) for lab in labels],
            {"long_name": "unit of the displacement"},
        ),
        "wheel": ("wheel", np.arange(1, frf.n_wheel + 1), {"long_name": "wheel"}),
    }
    data = {name: (var.dims, values[name], var.attrs) for name, var in VARIABLES.items()}
    data["static_contact_load"] = xr.DataArray(
        system.vehicle.static_wheel_loads(),
        dims=("wheel",),
        attrs={"units": "N", "long_name": "static contact load"},
    )
    data["pad_stiffness"] = xr.DataArray(
        pad_k,
        dims=("frequency",),
        attrs={"units": "N/m", "long_name": "railpad dynamic stiffness K' + iK'' (beam model)"},
    )
    attrs = {
        "psd_convention": "one-sided, per Hz, temporal (variance = integral of the PSD over f "
        "from 0 to inf)",
        "railvib_version": railvib_version(),
        "speed_m_per_s": system.speed,
        "contact_stiffness_n_per_m": system.contact_stiffness,
        "wheel_positions_m": system.wheel_positions,
        "sleeper_spacing_m": system.track.sleeper_spacing,
        "time_dependence": "exp(+i omega t)",
        "sign_convention": "displacements positive downward; irregularity > 0 is a dip",
    }
    ds = xr.Dataset(data, coords=coords, attrs=attrs)
    ds = with_unit_coordinates(ds, {n: n for n in VARIABLES if n in QUANTITY_UNITS})
    rail = None if seats is None else frf.rail_observed
    ds = ds.assign(support_force_variables(system, ds, rail=rail))
    settings = {"contact_check": {"loss_of_contact_threshold": threshold}}
    return derive(ds, ["contact_check"], settings)


@pytest.mark.parametrize("name", PRESETS)
def test_the_dataset_built_once_is_identical_to_the_old_way(name):
    case = railvib.load_preset_case(name)
    system, spectrum = build_system(case), build_spectrum(case)
    new = run_system(system, GRID, spectrum, loss_of_contact_threshold=0.02)
    ref = old_way(system, GRID, spectrum, 0.02)
    xr.testing.assert_identical(new, ref)
    assert {k: v.dtype for k, v in new.variables.items()} == {
        k: v.dtype for k, v in ref.variables.items()
    }


@pytest.mark.slow  # two netCDF files: ~1-3 s
def test_the_netcdf_file_is_identical_to_the_old_ways(tmp_path):
    case = railvib.load_preset_case("floating_slab_metro")
    system, spectrum = build_system(case), build_spectrum(case)
    new = save_netcdf(run_system(system, GRID, spectrum), tmp_path / "new.nc")
    ref = save_netcdf(old_way(system, GRID, spectrum, 0.01), tmp_path / "ref.nc")
    xr.testing.assert_identical(load_netcdf(new), load_netcdf(ref))


def test_the_contact_check_on_the_arrays_matches_an_independent_integral():
    """The check computed on the NumPy arrays: NumPy's own trapezoid and scipy's normal CDF.

    Tolerance 1e-13 relative: the same integral summed by another routine (rounding of
    a 300-term sum); the probability's relative sensitivity to the RMS is about
    (P0/sigma)^2 + 1, here below 100.
    """
    case = railvib.load_preset_case()
    system, spectrum = build_system(case), build_spectrum(case)
    ds = run_system(system, GRID, spectrum)
    sigma = np.sqrt(np.trapezoid(ds["psd_force"].values, GRID.f, axis=0))
    np.testing.assert_allclose(ds["contact_force_rms"].values, sigma, rtol=1e-13)
    p0 = system.vehicle.static_wheel_loads()
    x = p0 / sigma
    assert np.all(x**2 + 1 < 100)
    np.testing.assert_allclose(
        ds["loss_of_contact_probability"].values, norm.cdf(-x), rtol=100 * 1e-13
    )
    worst = norm.cdf(-x).max()
    assert bool(ds["linear_model_valid"]) == (worst <= 0.01)
