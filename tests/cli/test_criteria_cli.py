"""``railvib run`` reports the engineering criteria: summary lines, dataset, CSV, figures."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from railvib.cli.main import main
from railvib.results import load_netcdf

#: a quick case on a linear grid whose points include 80 Hz (the end of the comfort band)
CASE = (
    'preset = "wang2017_metro"\n'
    '[frequency]\nspacing = "linear"\nf_min = 0.5\nf_max = 200.0\nstep = 0.5\n'
)


def _wb(f):
    """ISO 2631-4 Wb, written out here from its Annex A parameters (not railvib's code)."""
    p = 2j * np.pi * f
    w = 2 * np.pi * np.array([0.4, 100.0, 16.0, 16.0, 2.5, 4.0])
    q1 = 1 / np.sqrt(2)
    h = p**2 / (p**2 + w[0] * p / q1 + w[0] ** 2)
    h *= w[1] ** 2 / (p**2 + w[1] * p / q1 + w[1] ** 2)
    h *= (1 + p / w[2]) / (1 + p / (0.55 * w[3]) + (p / w[3]) ** 2)
    h *= (p**2 + w[4] * p / 0.9 + w[4] ** 2) / (p**2 + w[5] * p / 0.95 + w[5] ** 2)
    return 1.024 * np.abs(h)


@pytest.fixture(scope="module")
def run_folder(tmp_path_factory):
    root = tmp_path_factory.mktemp("criteria")
    (root / "case.toml").write_text(CASE, encoding="utf-8")
    assert main(["run", str(root / "case.toml"), "-o", str(root / "out")]) == 0
    return root / "out"


@pytest.mark.slow
def test_run_prints_the_criteria_with_units_and_categories(tmp_path, capsys):
    (tmp_path / "case.toml").write_text(CASE, encoding="utf-8")
    assert main(["run", str(tmp_path / "case.toml"), "-o", str(tmp_path / "o"), "--no-plots"]) == 0
    out = capsys.readouterr().out
    comfort = next(line for line in out.splitlines() if line.startswith("ride comfort (Wb"))
    assert "m/s^2" in comfort
    assert "uncomfortable" in comfort  # an ISO 2631-1 Annex C category ("not uncomfortable")
    assert "N_MV" in comfort
    assert "Wz" in comfort
    assert "dynamic load factor 1 + 3 sigma/P0" in out


@pytest.mark.slow
def test_dataset_holds_the_criteria_with_units(run_folder):
    ds = load_netcdf(run_folder / "results.nc")
    for name in (
        "comfort_aw",
        "mean_comfort_index",
        "sperling_wz",
        "dynamic_load_factor",
        "octave_level_acceleration",
        "octave_level_force",
    ):
        assert ds[name].attrs["units"], name
    assert ds["comfort_aw"].attrs["units"] == "m/s^2"
    assert ds["octave_level_force"].attrs["reference"] == "1 N"
    assert ds["floor"].values.tolist() == pytest.approx([6.3, 0.0, -6.3])  # bogies, centre


@pytest.mark.slow
def test_a_w_at_the_centre_is_the_weighted_carbody_bounce(run_folder):
    # at s = 0 the floor moves with the car body's bounce: a_w from the stored PSD with an
    # independently written Wb, by the trapezoidal rule over the grid points 0.5..80 Hz
    ds = load_netcdf(run_folder / "results.nc")
    f = ds["frequency"].values
    psd = ds["psd_acceleration"].sel(response="carbody.bounce").values
    inside = f <= 80.0
    expected = np.sqrt(np.trapezoid(_wb(f[inside]) ** 2 * psd[inside], f[inside]))
    got = float(ds["comfort_aw"].sel(floor=0.0))
    assert got == pytest.approx(expected, rel=1e-9)  # same rule on the same points
    # and the dynamic load factor is 1 + 3 RMS / P0 of the stored force PSD
    sigma = np.sqrt(np.trapezoid(ds["psd_force"].values, f, axis=0))
    load = ds["static_contact_load"].values
    assert ds["dynamic_load_factor"].values == pytest.approx(1 + 3 * sigma / load, rel=1e-12)


@pytest.mark.slow
def test_criteria_files_and_figures(run_folder):
    table = pd.read_csv(run_folder / "criteria.csv")
    assert {"criterion", "where", "value", "unit", "category"} <= set(table.columns)
    assert (table["criterion"] == "loss-of-contact probability").sum() == 4  # per wheel
    octaves = pd.read_csv(run_folder / "third_octave.csv", index_col=0)
    assert octaves.index[0] == pytest.approx(0.63)  # the first whole band above 0.5 Hz
    assert "carbody.bounce [dB re 1e-6 m/s^2]" in octaves.columns
    assert (run_folder / "third_octave.png").stat().st_size > 1000
    assert (run_folder / "comfort.png").stat().st_size > 1000


@pytest.mark.slow
def test_grid_above_the_comfort_range_says_comfort_is_not_computed(tmp_path, capsys):
    case = CASE.replace("f_min = 0.5", "f_min = 100.0").replace("step = 0.5", "step = 50.0")
    (tmp_path / "case.toml").write_text(case, encoding="utf-8")
    assert main(["run", str(tmp_path / "case.toml"), "-o", str(tmp_path / "o"), "--no-plots"]) == 0
    assert (
        "ride comfort: not computed (the grid does not reach 0.5-80 Hz)" in capsys.readouterr().out
    )


SWEEP = """title = "comfort vs speed"
variables = []
[case]
preset = "wang2017_metro"
[case.frequency]
spacing = "linear"
f_min = 0.5
f_max = 100.0
step = 0.5
[[axes]]
field = "speed_kmh"
values = [60.0, 100.0]
"""


@pytest.mark.slow
def test_sweep_stores_the_criteria_of_each_case_as_a_run_computes_them(tmp_path):

    import railvib
    from railvib.sweep import load_sweep, run_sweep

    (tmp_path / "sweep.toml").write_text(SWEEP, encoding="utf-8")
    ds = run_sweep(load_sweep(tmp_path / "sweep.toml"), tmp_path / "out", workers=1, progress=False)
    assert ds is not None
    ds = ds.load()
    for speed in (60.0, 100.0):
        case = railvib.case_from_dict(
            {
                "preset": "wang2017_metro",
                "speed_kmh": speed,
                "frequency": {"spacing": "linear", "f_min": 0.5, "f_max": 100.0, "step": 0.5},
            }
        )
        run = railvib.run(case)
        # the sweep's batched solver against the run's: the same responses to rounding
        for name in ("comfort_aw", "sperling_wz", "mean_comfort_index", "dynamic_load_factor"):
            got = ds[name].sel(speed_kmh=speed).values
            assert got == pytest.approx(run[name].values, rel=1e-9), name
    assert ds["comfort_aw"].attrs["units"] == "m/s^2"
