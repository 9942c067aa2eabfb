"""The Zarr store written chunk by chunk holds the chunk files; a stopped run leaves none."""

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


def test_streamed_store_equals_the_chunk_files_after_a_resume(spec, tmp_path):
    out = tmp_path / "out"
    run_sweep(spec, out, workers=1, progress=False, assemble=False)
    store = ChunkStore(out, spec)
    # two chunks are computed (and streamed) by the second run, the others come from files
    for cid in (0, 2):
        store.chunk_path(cid).unlink()
    ds = run_sweep(spec, out, workers=1, progress=False)
    layout = SweepLayout(spec)
    assert layout.n_chunks == 3
    for cid in range(layout.n_chunks):
        for key, value in store.read(cid).items():
            # the store holds the chunk's numbers themselves: compared exactly
            np.testing.assert_array_equal(
                _block(ds, key.removeprefix("summary/"), layout, cid), value, err_msg=key
            )
    assert not list(out.glob(".sweep.zarr.*"))


@pytest.mark.slow
def test_a_stopped_run_keeps_its_chunks_and_leaves_no_store_in_progress(
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
    assert len(list((out / "chunks").glob("chunk-*.npz"))) == 2
    assert not list(out.glob(".sweep.zarr.*")), "the store in progress is removed"
    assert not (out / "sweep.zarr").exists()
    monkeypatch.setattr(ChunkStore, "write", real_write)
    ds = run_sweep(spec, out, workers=1, progress=False)  # the rerun finishes the sweep
    assert ds.sizes["speed_kmh"] == 4


def test_without_dask_the_store_is_the_same(spec, tmp_path, monkeypatch):
    """Dask is the optional ``sweep`` extra: a plain install writes the same store."""
    import sys

    with_dask = run_sweep(spec, tmp_path / "a", workers=1, progress=False).load()
    monkeypatch.setitem(sys.modules, "dask", None)  # import dask raises ImportError
    monkeypatch.setitem(sys.modules, "dask.array", None)
    without = run_sweep(spec, tmp_path / "b", workers=1, progress=False).load()
    xr.testing.assert_identical(without.drop_attrs(), with_dask.drop_attrs())
