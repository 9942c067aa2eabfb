"""A sweep over rail_model gives each reading's own run (before: the pad of the first
reading's cases was reused for the others, rail_pair's contact force RMS 15 % high)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

import railvib
from railvib.case import case_from_dict
from railvib.cli.main import main

GRID = {"spacing": "log", "f_min": 1.0, "f_max": 100.0, "n": 8}
READINGS = ["single_rail", "rail_pair", "half_car"]


@pytest.mark.slow  # a sweep and three runs: ~2.5 s
def test_sweep_over_rail_model_equals_each_run(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "base.toml").write_text(
        'preset = "wang2017_metro"\n[frequency]\nspacing = "log"\nf_min = 1.0\n'
        "f_max = 100.0\nn = 8\n",
        encoding="utf-8",
    )
    values = ", ".join(f'"{r}"' for r in READINGS)
    (tmp_path / "sweep.toml").write_text(
        f'base = "base.toml"\n[[axes]]\nfield = "rail_model"\nvalues = [{values}]\n',
        encoding="utf-8",
    )
    assert main(["sweep", "sweep.toml", "-o", "out"]) == 0
    ds = xr.open_zarr(tmp_path / "out" / "sweep.zarr")
    for reading in READINGS:
        case = case_from_dict(
            {"preset": "wang2017_metro", "rail_model": reading, "frequency": GRID}
        )
        alone = railvib.run(case)
        got = ds["contact_force_rms"].sel(rail_model=reading).values
        # the same solve batched or alone: rounding, 1e-12
        np.testing.assert_allclose(got, alone["contact_force_rms"].values, rtol=1e-12)
