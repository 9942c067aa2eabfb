"""Chunk store: chunks done once recorded, resume, refusal of a changed sweep, Zarr/netCDF/CSV."""

import json

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from railvib.sweep import (
    ChunkStore,
    SweepMismatchError,
    load_sweep_dataset,
    run_sweep,
    save_sweep_csv,
    save_sweep_netcdf,
    sweep_from_dict,
)
from railvib.sweep import runner as runner_mod
from tests.unit.sweep.sweep_cases import small_sweep


@pytest.fixture
def spec():
    return sweep_from_dict(small_sweep())


def test_dataset_layout_and_zarr_round_trip(spec, tmp_path):
    ds = run_sweep(spec, tmp_path / "out", workers=1, progress=False)
    assert ds.psd_acceleration.dims == (
        "frequency",
        "response",
        "track.pad_temperature_c",
        "speed_kmh",
    )
    assert ds.psd_force.dims[:2] == ("frequency", "wheel")
    assert ds.peak.dims == ("response", "track.pad_temperature_c", "speed_kmh")
    assert ds["speed_kmh"].attrs["units"] == "km/h"
    assert ds["track.pad_temperature_c"].attrs["units"] == "degC"
    for name, da in ds.data_vars.items():
        assert da.attrs.get("units") is not None, name
        assert da.attrs.get("long_name"), name
    back = load_sweep_dataset(tmp_path / "out")
    xr.testing.assert_identical(back.drop_attrs(), ds.drop_attrs())
    store = xr.open_zarr(tmp_path / "out" / "sweep.zarr")
    # one Zarr chunk per sweep chunk along the sweep dims (chunk_size 4 along speed)
    assert store.psd_acceleration.encoding["chunks"][2:] == (1, 4)


def test_netcdf_and_csv_exports(spec, tmp_path):
    ds = run_sweep(spec, tmp_path / "out", workers=1, progress=False)
    nc = load_sweep_dataset(save_sweep_netcdf(ds, tmp_path / "s.nc"))
    np.testing.assert_array_equal(nc.peak.values, ds.peak.values)
    table = pd.read_csv(save_sweep_csv(ds, tmp_path / "s.csv"))
    assert len(table) == ds.sizes["response"] * 12
    assert "dominant_frequency [Hz]" in table.columns


def test_resume_recomputes_only_missing_chunks(spec, tmp_path, monkeypatch):
    out = tmp_path / "out"
    full = run_sweep(spec, out, workers=1, progress=False)
    store = ChunkStore(out, spec)
    assert store.missing() == []
    kept = {p.name: p.stat().st_mtime_ns for p in store.chunk_dir.iterdir()}
    store.chunk_path(1).unlink()
    # what a run killed while it renamed the record leaves (mkstemp: 8 characters)
    (store.chunk_dir / ".chunk-000001.done.k2x_9qaz.part").write_bytes(b"half a record")
    computed = []
    real = runner_mod._compute

    def spy(s, cid):
        computed.append(cid)
        return real(s, cid)

    monkeypatch.setattr(runner_mod, "_compute", spy)
    again = run_sweep(spec, out, workers=1, progress=False)
    assert computed == [1]
    for p in store.chunk_dir.iterdir():
        if p.name != "chunk-000001.done":
            assert p.stat().st_mtime_ns == kept[p.name]
    assert not list(store.chunk_dir.glob(".*.part"))
    xr.testing.assert_identical(again, full)


def test_changed_sweep_is_refused_with_a_clear_message(spec, tmp_path):
    out = tmp_path / "out"
    run_sweep(spec, out, workers=1, progress=False)
    changed = sweep_from_dict(
        small_sweep(
            axes=[
                {"field": "track.pad_temperature_c", "values": [-30.0, 0.0, 35.0]},
                {"field": "speed_kmh", "start": 40.0, "stop": 160.0, "num": 4},
            ]
        )
    )
    with pytest.raises(SweepMismatchError, match=r"different sweep \(changed: axes\)"):
        run_sweep(changed, out, workers=1, progress=False)
    ds = run_sweep(changed, out, workers=1, progress=False, overwrite=True)
    assert ds["track.pad_temperature_c"].values.tolist() == [-30.0, 0.0, 35.0]
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["fingerprint"] == ChunkStore(out, changed).fingerprint


def test_foreign_chunk_file_is_refused(spec, tmp_path):
    other = sweep_from_dict(small_sweep(chunk_size=3))
    run_sweep(other, tmp_path / "a", workers=1, progress=False)
    store = ChunkStore(tmp_path / "b", spec)
    store.open()
    (tmp_path / "a" / "chunks" / "chunk-000000.done").rename(store.chunk_path(0))
    with pytest.raises(SweepMismatchError, match="different sweep"):
        store.missing()


@pytest.mark.slow  # starts worker processes: ~5 s
def test_local_processes_equal_serial_bit_for_bit(spec, tmp_path):
    serial = run_sweep(spec, tmp_path / "serial", workers=1, progress=False)
    parallel = run_sweep(spec, tmp_path / "par", workers=2, progress=False)
    xr.testing.assert_identical(parallel, serial)
