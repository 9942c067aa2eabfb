"""Whole Zarr (format 2) chunks of a local store written as files, without zarr's I/O loop.

A sweep's chunk is exactly one Zarr chunk of each variable (the store's chunks are the
sweep's blocks along the sweep's dimensions, whole along the variable's own), so its
write needs none of zarr's general machinery (read-modify-write of partial chunks, a
thread hand-off per codec call, a coroutine per array): the block is laid out in C
order, encoded by the array's own compressor and written as the chunk's file, named as
the Zarr 2 specification names it (the chunk's indices joined by the array's
``dimension_separator``). That is what zarr writes for the same chunk, byte for byte
(``tests/unit/sweep/test_sweep_stream.py`` compares the stores), at a fifth of its cost
for the sweep's large variable and a tenth for its small ones (zarr's hand-offs cost
0.5-1.5 ms an array whatever its size).

Only arrays this covers are written so (format 2, a local store, C order, no filters);
the store's other arrays go through zarr (:meth:`ChunkFiles.of` returns None for them).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["ChunkFiles"]


@dataclass(frozen=True)
class ChunkFiles:
    """Where and how one Zarr 2 array of a local store keeps its chunks.

    Parameters
    ----------
    folder : pathlib.Path
        The array's folder in the store.
    chunks : tuple of int
        The chunk shape.
    shape : tuple of int
        The array's shape.
    dtype : numpy.dtype
        The array's data type as stored.
    fill_value : object
        What the parts of an edge chunk outside the array hold.
    separator : str
        The ``dimension_separator`` of the chunk names (``"."`` or ``"/"``).
    compressor : object or None
        A numcodecs codec (``encode``), or None (stored raw).
    """

    folder: Path
    chunks: tuple[int, ...]
    shape: tuple[int, ...]
    dtype: np.dtype[Any]
    fill_value: Any
    separator: str
    compressor: Any

    @classmethod
    def of(cls, array: Any) -> ChunkFiles | None:
        """How `array` (a ``zarr.Array``) keeps its chunks, or None where this does not apply.

        Applies to a format-2 array of a ``LocalStore`` in C order without filters.

        Parameters
        ----------
        array : zarr.Array
            An array of the store.

        Returns
        -------
        ChunkFiles or None
        """
        meta = array.metadata
        root = getattr(array.store, "root", None)
        if (
            getattr(meta, "zarr_format", None) != 2
            or type(array.store).__name__ != "LocalStore"
            or not isinstance(root, Path)
            or meta.filters
            or meta.order != "C"
            or meta.dimension_separator not in (".", "/")
        ):
            return None
        return cls(
            root / array.path,
            tuple(int(c) for c in meta.chunks),
            tuple(int(s) for s in meta.shape),
            np.dtype(meta.dtype.to_native_dtype()),
            meta.fill_value,
            str(meta.dimension_separator),
            meta.compressor,
        )

    def write(self, where: tuple[slice, ...], block: NDArray[Any]) -> bool:
        """Write `block` as the chunk whose region is `where`; False if it is not one chunk.

        Parameters
        ----------
        where : tuple of slice
            The region, one slice per dimension (``slice(None)``: the whole dimension).
        block : numpy.ndarray
            Its values in the array's unit, shaped as the region.

        Returns
        -------
        bool
            Whether it was written (else nothing was).
        """
        index = []
        for s, c, n in zip(where, self.chunks, self.shape, strict=True):
            start, stop, step = s.indices(n)
            if step != 1 or start % c or stop != min(start + c, n):
                return False
            index.append(start // c)
        chunk = np.ascontiguousarray(block, dtype=self.dtype)
        if chunk.shape != self.chunks:  # an edge chunk: stored whole, the rest filled
            fill = 0 if self.fill_value is None else self.fill_value
            full = np.full(self.chunks, fill, dtype=self.dtype)
            full[tuple(slice(0, k) for k in chunk.shape)] = chunk
            chunk = full
        data = chunk if self.compressor is None else self.compressor.encode(chunk)
        path = self.folder / self.separator.join(map(str, index))
        if self.separator == "/":
            path.parent.mkdir(parents=True, exist_ok=True)
        with open(path, "wb") as fh:
            fh.write(memoryview(data).cast("B") if isinstance(data, np.ndarray) else data)
        return True
