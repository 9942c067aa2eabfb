"""The Zarr store written chunk by chunk holds each chunk as computed; a stopped run resumes."""

import numpy as np
import pytest
import xarray as xr

from railvib.sweep import ChunkStore, run_sweep, sweep_from_dict
from railvib.sweep.layout import SweepLayout
from tests.unit.sweep.sweep_cases import small_sweep


@pytest.fixture
def spec():
    return sweep_from_dict(small_sweep())


def _block(ds, name, layout, chunk_id):
    """The values of variable `name` in chunk `chunk_id`, cases first (as in the chunk file)."""
    da = ds[name]
    own = [d for d in da.dims if d not in layout.dims]
    sel = dict(zip(layout.dims, layout.chunk_slices(chunk_id), strict=True))
    block = da.isel(sel).transpose(*layout.dims, *own).values
    return block.reshape((-1, *block.shape[len(layout.dims) :]))


def _capture(monkeypatch):
    """Each chunk's arrays as the run hands them to the store, by chunk id (latest kept)."""
    written = {}
    real_write = ChunkStore.write

    def write(self, chunk_id, arrays):
        written[chunk_id] = {k: np.array(v) for k, v in arrays.items()}
        return real_write(self, chunk_id, arrays)

    monkeypatch.setattr(ChunkStore, "write", write)
    return written


def test_store_holds_each_chunk_as_computed_after_a_resume(spec, tmp_path, monkeypatch):
    out = tmp_path / "out"
    written = _capture(monkeypatch)
    run_sweep(spec, out, workers=1, progress=False, assemble=False)
    assert not (out / "sweep.zarr").exists()  # not finished: the store stays in OUT/chunks
    store = ChunkStore(out, spec)
    first = dict(written)
    # two chunks are computed again (their records gone), the other is the first run's
    for cid in (0, 2):
        store.chunk_path(cid).unlink()
    written.clear()
    ds = run_sweep(spec, out, workers=1, progress=False)
    assert sorted(written) == [0, 2]
    layout = SweepLayout(spec)
    assert layout.n_chunks == 3
    for cid in range(layout.n_chunks):
        for key, value in (written.get(cid) or first[cid]).items():
            # the store holds the chunk's numbers themselves: compared exactly
            np.testing.assert_array_equal(
                _block(ds, key.removeprefix("summary/"), layout, cid), value, err_msg=key
            )
    assert not list(out.glob(".sweep.zarr.*"))
    assert not store.work_path.exists()  # moved into place as OUT/sweep.zarr


@pytest.mark.slow
def test_a_stopped_run_keeps_its_chunks_and_no_half_finished_sweep_zarr(
    spec, tmp_path, monkeypatch
):
    out = tmp_path / "out"
    real_write = ChunkStore.write
    calls = []

    def write_then_stop(self, chunk_id, arrays):
        calls.append(chunk_id)
        real_write(self, chunk_id, arrays)
        if len(calls) == 2:
            raise KeyboardInterrupt

    monkeypatch.setattr(ChunkStore, "write", write_then_stop)
    with pytest.raises(KeyboardInterrupt):
        run_sweep(spec, out, workers=1, progress=False)
    assert len(list((out / "chunks").glob("chunk-*.done"))) == 2
    assert ChunkStore(out, spec).work_path.is_dir(), "the store in progress is the resume record"
    assert not list(out.glob(".sweep.zarr.*"))
    assert not (out / "sweep.zarr").exists()
    monkeypatch.setattr(ChunkStore, "write", real_write)
    written = _capture(monkeypatch)
    ds = run_sweep(spec, out, workers=1, progress=False)  # the rerun finishes the sweep
    assert len(written) == 1  # only the chunk not recorded
    assert ds.sizes["speed_kmh"] == 4
    assert np.isfinite(ds.peak.values).all()


def test_without_dask_the_store_is_the_same(spec, tmp_path, monkeypatch):
    """Dask is the optional ``sweep`` extra: a plain install writes the same store."""
    import sys

    with_dask = run_sweep(spec, tmp_path / "a", workers=1, progress=False).load()
    monkeypatch.setitem(sys.modules, "dask", None)  # import dask raises ImportError
    monkeypatch.setitem(sys.modules, "dask.array", None)
    without = run_sweep(spec, tmp_path / "b", workers=1, progress=False).load()
    xr.testing.assert_identical(without.drop_attrs(), with_dask.drop_attrs())
