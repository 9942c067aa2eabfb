"""Issue 10, item 1: every figure carries the unit of its own (response, quantity).

The expected units are written out from the definitions (a pitch DOF is an angle in
rad, a bounce DOF and the rail a displacement in m, a contact force in N; PSDs are
per Hz; an RMS is the square root of the PSD integrated over Hz), never read back
from the code.
"""

import csv

import numpy as np
import pytest
import xarray as xr

import railvib
from railvib.results import save_csv
from railvib.results.stats import summary_table
from railvib.results.units import quantity_unit, with_unit_coordinates

BOUNCE, PITCH, RAIL = "bogie1.bounce", "bogie1.pitch", "rail@wheel2"

#: (quantity, unit of a bounce or rail response, unit of a pitch response)
EXPECTED = [
    ("displacement", "m", "rad"),
    ("acceleration", "m/s^2", "rad/s^2"),
    ("psd_displacement", "m^2/Hz", "rad^2/Hz"),
    ("psd_acceleration", "(m/s^2)^2/Hz", "(rad/s^2)^2/Hz"),
    ("frf_displacement", "m/m", "rad/m"),
    ("force", "N", "N"),
    ("psd_force", "N^2/Hz", "N^2/Hz"),
    ("frf_force", "N/m", "N/m"),
    ("irregularity_psd", "m^2/Hz", "m^2/Hz"),
]


@pytest.mark.parametrize(("quantity", "linear", "angular"), EXPECTED)
def test_unit_of_each_response_and_quantity(quantity, linear, angular):
    assert quantity_unit(quantity, BOUNCE) == linear
    assert quantity_unit(quantity, RAIL) == linear
    assert quantity_unit(quantity) == linear
    assert quantity_unit(quantity, PITCH) == angular


def test_unknown_quantity_is_refused():
    with pytest.raises(KeyError):
        quantity_unit("velocity_psd_squared", BOUNCE)


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


def _expected(labels, linear, angular):
    return [angular if lab.endswith(".pitch") else linear for lab in labels]


def test_dataset_has_a_units_coordinate_per_mixed_variable(run_ds, tmp_path):
    labels = [str(r) for r in run_ds["response"].values]
    for name, linear, angular in (
        ("psd_acceleration", "(m/s^2)^2/Hz", "(rad/s^2)^2/Hz"),
        ("psd_displacement", "m^2/Hz", "rad^2/Hz"),
        ("frf_displacement", "m/m", "rad/m"),
    ):
        coord = run_ds[name].attrs["units_coordinate"]
        assert list(run_ds[coord].values) == _expected(labels, linear, angular), name
        assert run_ds[name].attrs["units"] == linear  # the bounce unit stays the attribute
    # forces are in N at every wheel: no coordinate needed
    assert "units_coordinate" not in run_ds["psd_force"].attrs
    loaded = railvib.load_netcdf(railvib.save_netcdf(run_ds, tmp_path / "r.nc"))
    coord = loaded["psd_acceleration"].attrs["units_coordinate"]
    assert list(loaded[coord].values) == _expected(labels, "(m/s^2)^2/Hz", "(rad/s^2)^2/Hz")


def test_force_csv_headed_by_wheel_in_newton(run_ds, tmp_path):
    path = save_csv(run_ds, tmp_path / "f.csv", variable="psd_force")
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["frequency [Hz]"] + [f"wheel{j} [N^2/Hz]" for j in (1, 2, 3, 4)]
    # %.6e keeps 7 significant digits: 1e-6 relative covers the rounding and the parse
    np.testing.assert_allclose(
        np.array(rows[1:], dtype=float)[:, 1:], run_ds["psd_force"].values, rtol=1e-6, atol=0
    )


def test_summary_rows_carry_their_own_units(run_ds):
    table = summary_table(railvib.summary(run_ds, bands=[(1.0, 20.0)]))
    labels = list(table.index)
    assert list(table["peak_unit"]) == _expected(labels, "(m/s^2)^2/Hz", "(rad/s^2)^2/Hz")
    assert list(table["rms_unit"]) == _expected(labels, "m/s^2", "rad/s^2")
    assert "dominant_frequency [Hz]" in table.columns
    assert "displacement_unit" not in table.columns  # the m/rad column next to accelerations
    # the values are the summary's, untouched
    stats = railvib.summary(run_ds, bands=[(1.0, 20.0)])
    np.testing.assert_array_equal(table["peak"].values, stats["peak"].values)
    np.testing.assert_array_equal(table["rms_1_20_hz"].values, stats["rms_1_20_hz"].values)


def test_summary_of_displacement_has_displacement_units(run_ds):
    table = summary_table(railvib.summary(run_ds, variable="psd_displacement"))
    labels = list(table.index)
    assert list(table["peak_unit"]) == _expected(labels, "m^2/Hz", "rad^2/Hz")
    assert list(table["rms_unit"]) == _expected(labels, "m", "rad")


def test_a_variable_with_one_unit_gets_no_coordinate():
    ds = xr.Dataset(
        {"psd_acceleration": (("frequency", "response"), np.ones((2, 2)))},
        coords={"frequency": [1.0, 2.0], "response": ["carbody.bounce", "rail@wheel1"]},
    )
    out = with_unit_coordinates(ds, {"psd_acceleration": "psd_acceleration"})
    assert "psd_acceleration_unit" not in out.coords
    assert "units_coordinate" not in out["psd_acceleration"].attrs
