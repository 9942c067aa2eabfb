"""``railvib run`` with the seats under the wheels taken from the contact's track solve
(issue 13): the support forces it writes are those of a separate solve, a slab track gets
none, and the run is one command that exits 0."""

from __future__ import annotations

import numpy as np
import pytest

import railvib
from railvib.case import build_system, load_case
from railvib.cli.main import main
from railvib.outputs.supports import support_force_variables
from railvib.results.dataset import load_netcdf

GRID = '[frequency]\nspacing = "log"\nf_min = 1.0\nf_max = 1000.0\nn = {n}\n'


@pytest.mark.parametrize(
    "n", [12, pytest.param(5000, marks=pytest.mark.slow)], ids=["one block", "two blocks"]
)
def test_run_writes_the_support_forces_of_a_separate_track_solve(tmp_path, monkeypatch, n):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "case.toml").write_text(
        'preset = "thompson_ballasted"\n' + GRID.format(n=n), encoding="utf-8"
    )
    assert main(["run", "case.toml", "-o", "out", "--no-plots"]) == 0
    ds = load_netcdf(tmp_path / "out" / "results.nc")
    system = build_system(load_case(tmp_path / "case.toml"))
    separate = support_force_variables(system, ds)  # its own receptance to the seats
    got = ds["psd_support_force"].values
    want = separate["psd_support_force"].values
    # reason: the same waves up to the Krylov series' term count (set per block) and the
    # summation order, through a netCDF round trip of float64: rounding, 1e-12 of the peak
    assert np.max(np.abs(got - want) / np.abs(want).max(axis=0, keepdims=True)) < 1e-12
    np.testing.assert_array_equal(ds["layer"].values, ["pad", "ballast"])


@pytest.mark.slow
def test_run_of_a_slab_track_writes_its_pad_and_bearing_forces(tmp_path, monkeypatch):
    # the slab's seats share the slab, so the block solve observes no seats; the forces come
    # from the contact forces through the slab (checked against the finite slab track in
    # tests/validation/test_track14_slab_supports.py): here, that the run writes them
    monkeypatch.chdir(tmp_path)
    (tmp_path / "case.toml").write_text(
        'preset = "floating_slab_metro"\n' + GRID.format(n=12), encoding="utf-8"
    )
    assert main(["run", "case.toml", "-o", "out", "--no-plots"]) == 0
    ds = load_netcdf(tmp_path / "out" / "results.nc")
    assert list(ds["layer"].values) == ["pad", "bearing"]
    psd = ds["psd_support_force"].values
    assert np.all(np.isfinite(psd))
    assert psd.max() > 0
    assert float(ds["psd_acceleration"].max()) > 0
    assert railvib.load_preset_case("floating_slab_metro").track.model == "floating_slab"
