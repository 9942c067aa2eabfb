"""The sweep store as its own resume record (issue 13): a chunk is done once its record exists.

Each chunk's region of ``OUT/chunks/sweep.zarr`` is written once, then its record
``chunk-NNNNNN.done``; these tests stand for the moments a run can stop between the two,
and for a store that is gone or left with zarr's partial writes.
"""

import shutil
import subprocess

import pytest
import xarray as xr

from railvib.errors import DamagedOutputWarning
from railvib.sweep import ChunkStore, run_sweep, sweep_from_dict
from railvib.sweep import runner as runner_mod
from tests.unit.sweep.sweep_cases import assert_recomputed, small_sweep


def _tiny():
    """Three cases of one chunk each, on a 20-frequency grid (a fraction of a second)."""
    d = small_sweep(
        chunk_size=1,
        variables=["psd_acceleration"],
        axes=[{"field": "speed_kmh", "values": [40.0, 80.0, 120.0]}],
    )
    d["case"]["frequency"]["n"] = 20
    return d


@pytest.fixture(scope="module")
def finished(tmp_path_factory):
    spec = sweep_from_dict(_tiny())
    out = tmp_path_factory.mktemp("done") / "out"
    return spec, out, run_sweep(spec, out, workers=1, progress=False).load()


def _copy(src, dst):
    subprocess.run(["cp", "-a", str(src), str(dst)], check=True)
    return dst


@pytest.fixture
def computed(monkeypatch):
    """The chunk ids the next runs compute."""
    ids = []
    real = runner_mod._compute
    monkeypatch.setattr(runner_mod, "_compute", lambda s, cid: ids.append(cid) or real(s, cid))
    return ids


def _cut_short(out):
    """A finished folder as a run leaves it when stopped after its last record (not moved)."""
    (out / "sweep.zarr").rename(out / "chunks" / "sweep.zarr")


def test_a_region_written_without_its_record_is_computed_again(finished, tmp_path, computed):
    # the run stopped between writing chunk 1's region and renaming its record into place:
    # the region may be anything (here: garbage), and it is not trusted
    spec, done, reference = finished
    out = _copy(done, tmp_path / "out")
    _cut_short(out)
    store = ChunkStore(out, spec)
    store.chunk_path(1).unlink()
    (store.work_path / "psd_acceleration" / "0.0.1").write_bytes(b"half a region")
    ds = run_sweep(spec, out, workers=1, progress=False)  # no warning: chunk 1 is not done
    assert computed == [1]
    assert_recomputed(ds, reference)
    assert not store.work_path.exists()


def test_zarr_partial_writes_of_a_killed_run_are_removed(finished, tmp_path, computed):
    spec, done, reference = finished
    out = _copy(done, tmp_path / "out")
    _cut_short(out)
    store = ChunkStore(out, spec)
    store.chunk_path(2).unlink()
    # zarr writes each chunk file through ``<key>.<uuid hex>.partial`` and a rename
    partial = store.work_path / "peak" / "0.2.0123456789abcdef0123456789abcdef.partial"
    partial.write_bytes(b"half")
    ds = run_sweep(spec, out, workers=1, progress=False)
    assert computed == [2]
    assert not list((out / "sweep.zarr").rglob("*.partial"))
    assert_recomputed(ds, reference)


def test_a_finished_sweep_is_checked_not_written_again(finished, tmp_path, computed):
    spec, done, reference = finished
    out = _copy(done, tmp_path / "out")
    files = {p: p.stat().st_mtime_ns for p in out.rglob("*") if p.is_file()}
    ds = run_sweep(spec, out, workers=1, progress=False)
    assert computed == []
    assert {p: p.stat().st_mtime_ns for p in out.rglob("*") if p.is_file()} == files
    xr.testing.assert_identical(ds, reference)


def test_a_deleted_store_is_computed_again_whole(finished, tmp_path, computed):
    spec, done, reference = finished
    out = _copy(done, tmp_path / "out")
    shutil.rmtree(out / "sweep.zarr")  # the records describe a store that is gone
    with pytest.warns(DamagedOutputWarning, match="Zarr store of the 3 finished chunks .* is gone"):
        ds = run_sweep(spec, out, workers=1, progress=False)
    assert sorted(computed) == [0, 1, 2]
    assert sorted(p.name for p in (out / "chunks").iterdir()) == [
        f"chunk-00000{i}.done" for i in range(3)
    ]
    assert_recomputed(ds, reference)
