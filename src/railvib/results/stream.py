"""A run's netCDF file written frequency block by block, and the integrals it needs kept on the way.

A grid too large to hold (10^6 frequencies: a 608 MB dataset) is solved in blocks
(:meth:`railvib.coupling.CoupledSystem.frf_blocks`); :class:`NetCDFStream` writes each
block's variables into ``results.nc`` as it comes, so memory is bounded by the block,
not by the grid. The file has the layout of :func:`railvib.results.save_netcdf` (complex
variables over a ``part`` dimension, booleans as int8) and opens with
:func:`railvib.results.load_netcdf` or plain xarray. The first block is written by
xarray with ``frequency`` an unlimited dimension, which h5netcdf then resizes to the
grid; the later blocks are written into it through h5py; the variables without a
frequency dimension (the contact check, the RMS values) are written with placeholders
and overwritten at the end (:meth:`NetCDFStream.finish`). HDF5 writes through a Python
file object (h5py's ``fileobj`` driver) that keeps the first failed write's error and
drops every write after it (:class:`GuardedFile`): HDF5 left with a failed write
crashes the interpreter when it later closes the file (h5py 3.16), so it never sees
one; the run stops with the error before the file is opened again, and the file is
discarded. The file is built
under a temporary name and renamed at the end (:func:`railvib.io.atomic_path`): a run
that fails or is stopped leaves no half-written file.

:class:`RunningIntegral` keeps the trapezoidal integral over frequency of a block's
samples and of the interval joining it to the block before: the sum over the blocks
equals the whole grid's :func:`railvib.grid.trapezoid` to rounding.
"""

from __future__ import annotations

import os
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from io import FileIO
from pathlib import Path

import h5netcdf
import h5py
import numpy as np
import xarray as xr
from numpy.typing import NDArray

from railvib.grid import trapezoid
from railvib.io import atomic_path
from railvib.results.dataset import BOOL_STORED_AS, _decoded, _encode

__all__ = ["NetCDFStream", "RunningIntegral", "WRITE_FREQUENCIES", "netcdf_stream"]

#: frequencies gathered before one write into each variable of the file: a write
#: through h5py costs ~0.2 ms of Python whatever its size, so the solve's blocks of
#: 4096 frequencies are written 16 at a time (~40 MB of the default case held)
WRITE_FREQUENCIES = 2**16


class RunningIntegral:
    """The trapezoidal integral over frequency of samples given block by block.

    Each :meth:`add` integrates its block and the interval from the last frequency of
    the block before, so after the last block :attr:`total` is the integral over the
    whole grid (:func:`railvib.grid.trapezoid` of all samples, to rounding: the sum is
    taken block by block).
    """

    def __init__(self) -> None:
        self._total: NDArray[np.float64] | None = None
        self._last: tuple[float, NDArray[np.float64]] | None = None

    def add(self, f: NDArray[np.float64], y: NDArray[np.float64]) -> None:
        """Add the samples `y` (frequency first) at frequencies `f` (Hz, after the last block's)."""
        part = trapezoid(y, f, axis=0) if f.size > 1 else np.zeros(y.shape[1:])
        if self._last is not None:
            f0, y0 = self._last
            part = part + (f[0] - f0) * (y[0] + y0) / 2.0
        self._total = part if self._total is None else self._total + part
        self._last = (float(f[-1]), np.array(y[-1]))

    @property
    def total(self) -> NDArray[np.float64]:
        """The integral so far: the unit of the samples times Hz (a variance for a PSD)."""
        assert self._total is not None, "at least one block"
        return self._total


#: bytes per frequency reserved beyond the first block's, for the criteria's variables
#: over frequency added at the end (the floor accelerations: 8 bytes per floor point)
RESERVE_EXTRA = 128


class GuardedFile:
    """An unbuffered file for HDF5 that remembers its first failed write and drops the rest.

    Parameters
    ----------
    file : io.FileIO
        The open file (``w+b``, unbuffered: a write fails when it is made).
    """

    def __init__(self, file: FileIO) -> None:
        self._file = file
        #: the first write's error (a full disk, a file-size limit), or None
        self.error: OSError | None = None

    def write(self, data: bytes) -> int:
        """Write `data` (bytes); after a failed write, drop it (the file is discarded)."""
        n = memoryview(data).nbytes
        if self.error is None and not self._file.closed:
            try:
                self._file.write(data)
            except OSError as exc:
                self.error = exc
        return n  # also once closed: a handle HDF5 closes late (at exit) writes nothing

    def truncate(self, size: int | None = None) -> int:
        """Resize the file to `size` bytes (dropped after a failed write)."""
        if self.error is None and not self._file.closed:
            try:
                return self._file.truncate(size)
            except OSError as exc:
                self.error = exc
        return 0 if size is None else size

    def read(self, size: int = -1) -> bytes:
        """Read up to `size` bytes (none once closed)."""
        return b"" if self._file.closed else self._file.read(size)

    def readinto(self, buffer: bytearray) -> int | None:
        """Read into `buffer`; the number of bytes read (none once closed)."""
        return 0 if self._file.closed else self._file.readinto(buffer)

    def seek(self, offset: int, whence: int = 0) -> int:
        """Move to byte `offset` (from `whence`)."""
        return offset if self._file.closed else self._file.seek(offset, whence)

    def tell(self) -> int:
        """The position, bytes."""
        return 0 if self._file.closed else self._file.tell()

    def flush(self) -> None:
        """Nothing to flush: the file is unbuffered."""

    def readable(self) -> bool:
        """True."""
        return True

    def writable(self) -> bool:
        """True."""
        return True

    def seekable(self) -> bool:
        """True."""
        return True

    def reserve(self, size: int) -> None:
        """Set aside `size` bytes of disk for the file before HDF5 writes them.

        A full disk or a file-size limit then fails here, before HDF5 has written into
        the space (``posix_fallocate``; where the system has none, the writes are
        guarded only). The file's end is HDF5's at its close.

        Parameters
        ----------
        size : int
            Bytes the file will take at most (the space beyond its end is released
            when HDF5 closes it).
        """
        if self.error is None and hasattr(os, "posix_fallocate"):
            try:
                os.posix_fallocate(self._file.fileno(), 0, size)
            except OSError as exc:
                self.error = exc

    def check(self) -> None:
        """Raise the first failed write's error, if any.

        Raises
        ------
        OSError
            The error of the first write that failed.
        """
        if self.error is not None:
            raise self.error


class NetCDFStream:
    """A netCDF file of one run written block by block (see the module's description).

    Parameters
    ----------
    file : GuardedFile
        The open file.
    n_freq : int
        Frequencies of the whole grid.
    """

    def __init__(self, file: GuardedFile, n_freq: int) -> None:
        self._file = file
        self._n = n_freq
        self._h5: h5py.File | None = None
        self._along: list[str] = []
        self._datasets: dict[str, h5py.Dataset] = {}
        self._buffers: dict[str, NDArray[np.generic]] = {}
        self._start = 0  # the grid index of the buffers' first frequency
        self._held = 0  # frequencies in the buffers
        self._size = WRITE_FREQUENCIES  # frequencies the buffers hold
        self._stored_as: dict[str, str] = {}  # the complex ("part") and boolean variables

    def first(self, ds: xr.Dataset) -> None:
        """Write the first block: `ds` holds every variable of the result, its first frequencies.

        Parameters
        ----------
        ds : xarray.Dataset
            The result of the first block (:func:`railvib.results.dataset.assemble`),
            with the variables without a frequency dimension as placeholders.
        """
        out = _encode(ds)
        n_block = out.sizes["frequency"]
        encoding = {
            name: {"chunksizes": (n_block, *var.shape[1:])}
            for name, var in out.variables.items()
            if var.dims[:1] == ("frequency",)
        }
        out.to_netcdf(  # type: ignore[call-overload]
            self._file, engine="h5netcdf", unlimited_dims=("frequency",), encoding=encoding
        )
        self._along = [str(k) for k in encoding]
        for name in self._along:
            attrs = out[name].attrs
            if attrs.get("complex_stored_as") == "part":
                self._stored_as[name] = "complex"
            elif attrs.get(BOOL_STORED_AS) == "bool":
                self._stored_as[name] = "bool"
        self._file.check()  # before HDF5 reads the file back
        per_frequency = sum(out[k].nbytes for k in self._along) / n_block
        self._file.reserve(int(per_frequency * self._n + RESERVE_EXTRA * self._n) + 2**20)
        with h5netcdf.File(self._file, "a") as nc:  # netCDF's own resize of the dimension
            nc.resize_dimension("frequency", self._n)
        self._file.check()
        # the values through h5py (its datasets looked up once): h5netcdf's per-write
        # checks cost 3 ms a block
        self._h5 = h5py.File(self._file, "r+")
        self._datasets = {name: self._h5[name] for name in self._along}
        self._file.check()

    def rows(self, sl: slice) -> dict[str, NDArray[np.generic]]:
        """The rows where a later block goes: to be filled in place with its values.

        The blocks must come in the grid's order; they are gathered into writes of up to
        :data:`WRITE_FREQUENCIES` frequencies (the rest written by :meth:`finish`), each
        filled where it is written from: no copy of a block is made.

        Parameters
        ----------
        sl : slice
            The block's indices into the whole grid.

        Returns
        -------
        dict of str to numpy.ndarray
            By name of every variable over ``frequency`` (``frequency`` among them), its
            rows for the block, frequency first, of the result's type (complex and
            boolean: views of the stored (re, im) pairs and int8 values), to be filled
            before the next call.
        """
        assert self._h5 is not None, "first() before rows()"
        n = sl.stop - sl.start
        if self._held and (sl.start != self._start + self._held or self._held + n > self._size):
            self._flush()
        if n > self._size:  # a block larger than a write: the buffers grown to it
            self._buffers, self._size = {}, n
        if not self._held:
            self._start = sl.start
        out: dict[str, NDArray[np.generic]] = {}
        for name, dataset in self._datasets.items():
            if name not in self._buffers:
                self._buffers[name] = np.empty((self._size, *dataset.shape[1:]), dataset.dtype)
            rows = self._buffers[name][self._held : self._held + n]
            kind = self._stored_as.get(name)
            if kind == "complex":  # (re, im) pairs: a complex array's own layout
                rows = rows.view(np.result_type(rows.dtype, np.complex64))[..., 0]
            elif kind == "bool":
                rows = rows.view(np.bool_)
            out[name] = rows
        self._held += n
        return out

    def _flush(self) -> None:
        """Write the gathered blocks into the file."""
        if self._held:
            where = slice(self._start, self._start + self._held)
            for name, dataset in self._datasets.items():
                dataset[where] = self._buffers[name][: self._held]
            self._held = 0
        self._file.check()

    def finish(self, whole: Mapping[str, xr.Variable]) -> None:
        """Overwrite the placeholders with the values over the whole grid, and close HDF5.

        Parameters
        ----------
        whole : mapping of str to xarray.Variable
            The variables without a frequency dimension (contact check, RMS values).
        """
        assert self._h5 is not None, "first() before finish()"
        self._flush()
        self._buffers = {}
        for name, var in whole.items():
            self._h5[name][...] = _stored(np.asarray(var.values))
        self.close()
        self._file.check()

    def open(self) -> xr.Dataset:
        """The file written so far, opened lazily (each variable read when used; after finish).

        Returns
        -------
        xarray.Dataset
            As :func:`railvib.results.dataset.open_netcdf` opens it (complex and boolean
            variables restored, and so loaded); close it before :meth:`append`.
        """
        self._file.check()
        return _decoded(xr.open_dataset(self._file, engine="h5netcdf"))  # type: ignore[arg-type]

    def append(self, ds: xr.Dataset) -> None:
        """Add the variables of `ds` (new names; their new coordinates with them) to the file.

        Parameters
        ----------
        ds : xarray.Dataset
            Variables over the file's dimensions or new ones (after :meth:`finish`).
        """
        _encode(ds).to_netcdf(self._file, mode="a", engine="h5netcdf")  # type: ignore[call-overload]
        self._file.check()

    def close(self) -> None:
        """Close HDF5's handle of the file (idempotent)."""
        if self._h5 is not None:
            self._datasets = {}
            self._h5.close()
            self._h5 = None


def _stored(value: NDArray[np.generic]) -> NDArray[np.generic]:
    """`value` as :func:`railvib.results.save_netcdf` stores it: complex as (re, im), bool i1."""
    if np.iscomplexobj(value):
        return np.stack([value.real, value.imag], axis=-1)
    if value.dtype == bool:
        return value.astype("i1")
    return value


@contextmanager
def netcdf_stream(path: str | Path, n_freq: int) -> Iterator[NetCDFStream]:
    """A :class:`NetCDFStream` to `path`, put in place when the block ends without error.

    Parameters
    ----------
    path : str or pathlib.Path
        The netCDF file.
    n_freq : int
        Frequencies of the whole grid.

    Yields
    ------
    NetCDFStream
        The writer of the temporary file (renamed to `path` at the end; removed if the
        block raises).

    Raises
    ------
    railvib.errors.OutputError
        The file cannot be written (full disk, read-only folder); an existing `path` is
        left as it was and no temporary remains.
    """
    with atomic_path(path) as tmp, FileIO(tmp, "w+") as raw:
        file = GuardedFile(raw)
        stream = NetCDFStream(file, n_freq)
        try:
            yield stream
        finally:
            stream.close()
            file.check()  # a failed write's error, before any error that it caused
