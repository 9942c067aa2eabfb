"""A sweep chunk written as Zarr chunk files is what zarr itself writes, byte for byte."""

import numpy as np
import pytest

from railvib.sweep.zarrchunks import ChunkFiles

zarr = pytest.importorskip("zarr")


def _pair(tmp_path, shape, chunks, dtype, separator="."):
    """Two equal empty format-2 arrays: one written by zarr, one by ChunkFiles."""
    out = []
    for name in ("by_zarr", "direct"):
        out.append(
            zarr.create_array(
                str(tmp_path / name),
                shape=shape,
                chunks=chunks,
                dtype=dtype,
                zarr_format=2,
                chunk_key_encoding={"name": "v2", "separator": separator},
            )
        )
    return out


def _files(array_root):
    return {
        p.relative_to(array_root).as_posix(): p.read_bytes()
        for p in array_root.rglob("*")
        if p.is_file() and not p.name.startswith(".z")
    }


@pytest.mark.parametrize("separator", [".", "/"])
@pytest.mark.parametrize("dtype", ["f8", "bool"])
def test_every_chunk_and_edge_chunk_is_the_file_zarr_writes(tmp_path, dtype, separator):
    rng = np.random.default_rng(1)
    shape, chunks = (3, 7, 10), (3, 2, 4)  # 7 and 10 leave edge chunks of 1 and 2
    by_zarr, direct = _pair(tmp_path, shape, chunks, dtype, separator)
    files = ChunkFiles.of(direct)
    assert files is not None
    for j in range(0, 7, 2):
        for k in range(0, 10, 4):
            where = (slice(None), slice(j, min(j + 2, 7)), slice(k, min(k + 4, 10)))
            block = rng.random((3, min(j + 2, 7) - j, min(k + 4, 10) - k)) > 0.5
            block = block if dtype == "bool" else rng.random(block.shape)
            by_zarr[where] = block
            assert files.write(where, block)
    ours, theirs = _files(tmp_path / "direct"), _files(tmp_path / "by_zarr")
    assert ours.keys() == theirs.keys()
    assert len(ours) == 4 * 3
    assert ours == theirs
    # and zarr reads the direct chunks back as the values written
    np.testing.assert_array_equal(zarr.open_array(str(tmp_path / "direct"))[:], by_zarr[:])


def test_a_region_that_is_not_one_chunk_is_left_to_zarr(tmp_path):
    _, direct = _pair(tmp_path, (8, 8), (4, 4), "f8")
    files = ChunkFiles.of(direct)
    block = np.ones((4, 4))
    assert not files.write((slice(2, 6), slice(0, 4)), block)  # straddles two chunks
    assert not files.write((slice(0, 2), slice(0, 4)), block[:2])  # part of a chunk
    assert not _files(tmp_path / "direct")


def test_format_3_arrays_are_not_covered(tmp_path):
    a = zarr.create_array(str(tmp_path / "v3"), shape=(4,), chunks=(2,), dtype="f8")
    assert ChunkFiles.of(a) is None
