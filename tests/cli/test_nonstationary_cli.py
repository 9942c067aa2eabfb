"""``railvib run`` of a ``mode = "nonstationary"`` case: files, units, summary, atomic folder."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from railvib.cli.main import main
from railvib.nonstationary import NONSTATIONARY_FILES
from railvib.results.dataset import load_netcdf

CASE = """preset = "wang2017_metro"
mode = "nonstationary"

[speed_profile]
kind = "uniform"
v_start_kmh = 40.0
v_end_kmh = 0.0
acceleration_ms2 = 2.0

[nonstationary]
n_wavenumbers = 64
map_times = 9
map_frequencies = 20
"""


def _run(tmp_path, monkeypatch, *args):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "case.toml").write_text(CASE, encoding="utf-8")
    return main(["run", "case.toml", "-o", "out", *args])


def test_nonstationary_run_writes_its_files(tmp_path, monkeypatch, capsys):
    assert _run(tmp_path, monkeypatch, "--no-plots") == 0
    out = capsys.readouterr().out
    assert "largest RMS acceleration (exact)" in out
    assert "Quasi-stationary validity" in out
    written = {p.name for p in (tmp_path / "out").iterdir()}
    assert written == {"results.nc", "rms_time.csv", "summary.md"}
    assert written <= set(NONSTATIONARY_FILES)
    ds = load_netcdf(tmp_path / "out" / "results.nc")
    for name, var in ds.data_vars.items():
        assert "units" in var.attrs, name
        assert "long_name" in var.attrs, name
    assert ds["psd_acceleration"].dims == ("map_time", "frequency", "response")
    # the run starts in the stationary state at 40 km/h: the exact PEM (modal time stepping)
    # and the quasi-stationary estimate (the stationary solver) agree there to round-off
    exact0 = ds["rms_acceleration"].isel(time=0)
    qs0 = ds["rms_acceleration_qs"].isel(map_time=0)
    np.testing.assert_allclose(exact0, qs0, rtol=1e-8)
    # braking 40 -> 0 km/h at 2 m/s^2 lasts 11.1 / 2 = 5.56 s and covers 30.9 m
    assert float(ds.time[-1]) == pytest.approx(40 / 3.6 / 2.0)
    assert float(ds.position[-1]) == pytest.approx((40 / 3.6) ** 2 / 4.0)
    header = (tmp_path / "out" / "rms_time.csv").read_text().splitlines()[0]
    assert "rms acceleration carbody.pitch (rad/s^2)" in header
    assert "rms force wheel1 (N)" in header


@pytest.mark.slow
def test_nonstationary_run_with_plots_replaces_an_earlier_run(tmp_path, monkeypatch):
    assert _run(tmp_path, monkeypatch) == 0
    first = {p.name for p in (tmp_path / "out").iterdir()}
    assert first == set(NONSTATIONARY_FILES)
    (tmp_path / "out" / "notes.txt").write_text("mine")
    assert main(["run", "case.toml", "-o", "out", "--no-plots"]) == 0
    second = {p.name for p in (tmp_path / "out").iterdir()}
    assert second == {"results.nc", "rms_time.csv", "summary.md", "notes.txt"}
    with xr.open_dataset(tmp_path / "out" / "results.nc") as ds:
        assert ds.attrs["method"] == "both"


def test_the_docs_example_case_builds():
    from pathlib import Path

    from railvib.case import load_case
    from railvib.nonstationary import build_run

    root = Path(__file__).resolve().parents[2]
    run = build_run(load_case(root / "docs" / "examples" / "braking.toml"))
    # 80 km/h = 22.22 m/s over 1 m waves: Nyquist step 1 / (2 * 22.22) s, half of it by default
    assert run.dt == pytest.approx(1.0 / (4 * 80 / 3.6))
    assert run.profile.duration == pytest.approx(80 / 3.6)
    assert run.band.wavenumber.size == 1000
