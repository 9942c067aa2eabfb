"""The resumable store of a sweep: its Zarr store, written chunk by chunk, and what is done.

Layout of a sweep folder::

    OUT/manifest.json             fingerprint, layout and the resolved sweep
    OUT/chunks/sweep.zarr         the Zarr store being filled, each sweep chunk's region
                                  written once as it arrives
    OUT/chunks/chunk-000012.done  a chunk's resume record: written (atomically) after its
                                  region, with the fingerprint and a CRC-32 of each array
    OUT/sweep.zarr                the finished store (moved into place when every chunk
                                  is done)
    OUT/sweep.nc, OUT/summary.csv, OUT/plots/   optional exports

A chunk counts as done only when its record exists: the record is renamed into place
(``os.replace``) after the chunk's region is written, so a run killed while it writes a
region leaves that region without a record, and the next run computes it again and
overwrites it. The store's layout (metadata and coordinates) is written to a temporary
folder and renamed into place, so it is complete or absent. The fingerprint (hash of the
resolved sweep, the data files it reads and the railvib version) is stored in the
manifest and in every record; a different sweep is refused, never mixed in. A region
whose values no longer match their record's CRC (a damaged or deleted Zarr chunk) is
computed again.
"""

from __future__ import annotations

import asyncio
import hashlib
import json
import os
import re
import shutil
import tempfile
import threading
import warnings
import zlib
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from railvib.errors import DamagedOutputWarning, RailvibError
from railvib.io import atomic_path, railvib_version, remove_temporaries
from railvib.sweep.dataset import sweep_dataset
from railvib.sweep.folder import (
    CSV_NAME,
    MANIFEST,
    NETCDF_NAME,
    PLOTS_NAME,
    ZARR_NAME,
    default_output_folder,
    default_plot_folder,
)
from railvib.sweep.layout import SweepLayout
from railvib.sweep.spec import SweepSpec

__all__ = [
    "CSV_NAME",
    "MANIFEST",
    "NETCDF_NAME",
    "PLOTS_NAME",
    "ZARR_NAME",
    "ChunkStore",
    "SweepMismatchError",
    "default_output_folder",
    "data_file_hashes",
    "default_plot_folder",
    "fingerprint",
    "remove_leftovers",
]

_RECORD_RE = re.compile(r"^chunk-(\d{6,})\.done$")

#: the Zarr store being filled, in the chunks folder (moved to ``OUT/sweep.zarr`` when done)
WORK_NAME = "sweep.zarr"


class SweepMismatchError(RailvibError):
    """The output folder holds chunks of a different sweep."""


class _Damaged(Exception):
    """A chunk's record or region is damaged; the message says how, in a few words."""


#: the sweep's own temporaries (``.<name>.<random>.part`` of :func:`railvib.io.atomic_path`
#: and of the store's layout, :meth:`ChunkStore.write`), by sub-folder: the prefixes of
#: their names, or ``("",)`` for a folder that holds nothing but railvib's files
_LEFTOVERS: dict[str, tuple[str, ...]] = {
    ".": ("manifest.json", "sweep.zarr", "sweep.nc", "summary.csv"),
    "chunks": ("",),
    PLOTS_NAME: ("",),
}


def remove_leftovers(root: str | Path) -> list[Path]:
    """Remove the temporary files a killed run left in sweep folder `root`.

    Only railvib's own temporary names (``.sweep.zarr.XXXX.part``,
    ``.chunk-000003.done.XXXX.part``, ...; :func:`railvib.io.is_temporary_name`) in the
    folder, its ``chunks`` and its ``plots`` are touched, through
    :func:`railvib.io.remove_temporaries`.

    Parameters
    ----------
    root : str or pathlib.Path
        A sweep's output folder (need not exist).

    Returns
    -------
    list of pathlib.Path
        What was removed.
    """
    removed = []
    for sub, prefixes in _LEFTOVERS.items():
        for prefix in prefixes:
            removed += remove_temporaries(Path(root) / sub, prefix)
    return removed


async def _gather(calls: list[Any]) -> list[Any]:
    """Await the coroutines `calls` together (zarr reads or writes of one chunk)."""
    return list(await asyncio.gather(*calls))


def _import_store_libraries() -> None:
    """Import what writing the Zarr store needs (zarr, and Dask where installed)."""
    import zarr  # noqa: F401  (imported ahead of its use in ChunkStore._open_work)

    try:
        import dask.array  # noqa: F401
    except ImportError:
        pass


def _remove(path: Path) -> None:
    """Remove a file or a folder (not what a link points to)."""
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    else:
        path.unlink(missing_ok=True)


def _read_manifest(path: Path) -> tuple[dict[str, Any], str | None]:
    """The manifest's contents, or ``({}, why)`` when it is damaged."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except UnicodeDecodeError:
        return {}, "not UTF-8 text"
    except json.JSONDecodeError as exc:
        return {}, f"not valid JSON: {exc.msg} at line {exc.lineno}"
    except OSError as exc:
        return {}, _reason(exc)
    if not isinstance(data, dict) or not isinstance(data.get("fingerprint"), str):
        return {}, "no fingerprint"
    return data, None


def _read_record(path: Path) -> dict[str, Any]:
    """A chunk's record: ``{"fingerprint": str, "crc32": {name: int}}``; `_Damaged` if not."""
    try:
        data = json.loads(path.read_bytes().decode("utf-8"))
    except OSError as exc:
        raise _Damaged(_reason(exc)) from None
    except ValueError:  # not UTF-8, not JSON (cut short, empty, garbage)
        raise _Damaged("cut short or not a chunk record") from None
    crc = data.get("crc32") if isinstance(data, dict) else None
    if not isinstance(data, dict) or not isinstance(data.get("fingerprint"), str):
        raise _Damaged("no fingerprint")
    if not isinstance(crc, dict) or not all(isinstance(v, int) for v in crc.values()):
        raise _Damaged("no checksums")
    return data


def _record_stamp(path: Path) -> str | None:
    """The fingerprint of a chunk's record; None when it is damaged."""
    try:
        return str(_read_record(path)["fingerprint"])
    except _Damaged:
        return None


def _crc(value: NDArray[Any]) -> int:
    """CRC-32 of an array's bytes in C order (a chunk's array, cases first)."""
    return zlib.crc32(np.ascontiguousarray(value).data)


def _as_list(value: Any) -> list[Any]:
    """A JSON list attribute (``_ARRAY_DIMENSIONS``) as a list."""
    assert isinstance(value, list | tuple), value
    return list(value)


def _reason(exc: BaseException) -> str:
    """What is wrong with a damaged file, in a few words."""
    text = getattr(exc, "strerror", None) or str(exc)
    return " ".join(text.split())[:120] or type(exc).__name__


def _changed(key: str, old: Any, new: Any) -> str:
    """``base_case`` -> ``base_case (track.pad.k0_n_per_m, speed_kmh)``: the fields that differ."""
    if key != "base_case" or not isinstance(old, dict) or not isinstance(new, dict):
        return key
    fields = _differing(old, new)
    shown = ", ".join(fields[:3]) + (", ..." if len(fields) > 3 else "")
    return f"{key} ({shown})" if fields else key


def _differing(old: dict[str, Any], new: dict[str, Any], prefix: str = "") -> list[str]:
    out: list[str] = []
    for k in sorted(set(old) | set(new)):
        a, b = old.get(k), new.get(k)
        if isinstance(a, dict) and isinstance(b, dict):
            out += _differing(a, b, f"{prefix}{k}.")
        elif a != b:
            out.append(f"{prefix}{k}")
    return out


def fingerprint(spec: SweepSpec) -> str:
    """SHA-256 of what a sweep's results depend on: the resolved sweep, its data files, version.

    The title is left out: it changes no result, so a retitled sweep resumes (and its
    dataset takes the new title).

    Parameters
    ----------
    spec : SweepSpec
        A resolved sweep (:func:`railvib.sweep.spec.sweep_from_dict`); hashed as
        :meth:`~railvib.sweep.spec.SweepSpec.as_dict` without ``title``.

    Returns
    -------
    str
        Hex digest.
    """
    data = _results_spec(spec)
    blob = json.dumps(
        {"spec": data, "files": data_file_hashes(spec), "railvib": railvib_version()},
        sort_keys=True,
        default=str,
    )
    return hashlib.sha256(blob.encode()).hexdigest()


def _results_spec(spec: SweepSpec) -> dict[str, Any]:
    """:meth:`SweepSpec.as_dict` without what changes no result (the title)."""
    data = spec.as_dict()
    del data["title"]
    return data


def data_file_hashes(spec: SweepSpec) -> dict[str, str]:
    """SHA-256 of each data file the sweep reads (irregularity and pad tables), by path.

    Parameters
    ----------
    spec : SweepSpec
        A resolved sweep.

    Returns
    -------
    dict of str
        Hex digest by path as written in the resolved sweep; ``"unreadable"`` for a
        file that cannot be read.
    """
    return {p: _file_hash(p) for p in sorted(_data_paths(spec.as_dict()))}


def _data_paths(node: Any) -> set[str]:
    out: set[str] = set()
    if isinstance(node, dict):
        for key, value in node.items():
            if key == "path" and isinstance(value, str):
                out.add(value)
            else:
                out |= _data_paths(value)
    elif isinstance(node, list):
        for value in node:
            out |= _data_paths(value)
    return out


def _file_hash(path: str) -> str:
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError:
        return "unreadable"


class ChunkStore:
    """The Zarr store of one sweep in folder `root`, and the record of its finished chunks.

    Parameters
    ----------
    root : str or pathlib.Path
        The sweep's output folder.
    spec : SweepSpec
        The resolved sweep.
    """

    def __init__(self, root: str | Path, spec: SweepSpec) -> None:
        self.root = Path(root)
        self.spec = spec
        self.layout = SweepLayout(spec)
        self.fingerprint = fingerprint(spec)
        self._path: Path | None = None  # the Zarr store open, or None
        self._writable = False  # it is the store being filled (OUT/chunks/sweep.zarr)
        self._arrays: dict[str, Any] = {}  # its variables (zarr.AsyncArray), by name
        self._dims: dict[str, tuple[str, ...]] = {}  # their dimensions, by name
        self._sync: Any = None  # zarr's runner of a coroutine on its I/O loop

    @property
    def chunk_dir(self) -> Path:
        """Folder of the store being filled and of the chunks' records."""
        return self.root / "chunks"

    @property
    def work_path(self) -> Path:
        """The Zarr store being filled (``OUT/chunks/sweep.zarr``)."""
        return self.chunk_dir / WORK_NAME

    def chunk_path(self, chunk_id: int) -> Path:
        """The record of chunk `chunk_id` (it exists once the chunk's region is written)."""
        return self.chunk_dir / f"chunk-{chunk_id:06d}.done"

    def open(self, overwrite: bool = False) -> None:
        """Create the folder and manifest, or check that an existing one is this sweep.

        Leftovers of a killed run (the temporary files and folders railvib writes
        before a rename) are removed first. A damaged manifest is written again when
        the chunks' records, each stamped with the fingerprint, show that the folder is
        this sweep's (with a :class:`~railvib.errors.DamagedOutputWarning`); an edit
        that changes no result (the title) only updates the manifest.

        Parameters
        ----------
        overwrite : bool
            Discard the chunks of a different sweep instead of refusing.

        Raises
        ------
        SweepMismatchError
            The folder holds a different sweep (and `overwrite` is false), or its
            manifest is damaged and its chunks' records are not this sweep's.
        """
        manifest = self.root / MANIFEST
        remove_leftovers(self.root)
        if manifest.exists():
            old, damage = _read_manifest(manifest)
            if damage is not None:
                self._repair_manifest(damage, overwrite)
            elif old.get("fingerprint") != self.fingerprint:
                if not overwrite:
                    raise SweepMismatchError(self._mismatch_message(old))
                self._clear()
            elif old != self._manifest():  # e.g. a new title: same results
                self._write_manifest()
        self.chunk_dir.mkdir(parents=True, exist_ok=True)
        if not manifest.exists():
            self._write_manifest()

    def _write_manifest(self) -> None:
        with atomic_path(self.root / MANIFEST) as tmp:
            tmp.write_text(json.dumps(self._manifest(), indent=1, default=str), "utf-8")

    def _repair_manifest(self, damage: str, overwrite: bool) -> None:
        """Rewrite a damaged manifest if the chunks are this sweep's; else refuse or clear."""
        stamps = [_record_stamp(p) for p in self._records()]
        foreign = [s for s in stamps if s is not None and s != self.fingerprint]
        where = self.root / MANIFEST
        if foreign and not overwrite:
            raise SweepMismatchError(
                f"{where} is damaged ({damage}) and {len(foreign)} of the {len(stamps)} chunk "
                f"records in {self.chunk_dir} belong to a different sweep; use another --output "
                "folder, or --overwrite to discard them"
            )
        if foreign:
            self._clear()
            done = "written again; the chunks of the other sweep are discarded (--overwrite)"
        else:
            where.unlink()
            done = "written again" + (
                f" ({len(stamps)} finished chunks of this sweep kept)" if stamps else ""
            )
        warnings.warn(f"{where} is damaged ({damage}); {done}", DamagedOutputWarning, stacklevel=3)

    def _records(self) -> list[Path]:
        if not self.chunk_dir.is_dir():
            return []
        return sorted(p for p in self.chunk_dir.iterdir() if _RECORD_RE.match(p.name))

    def _clear(self) -> None:
        for name in (MANIFEST, ZARR_NAME, "chunks"):
            p = self.root / name
            if p.is_dir():
                shutil.rmtree(p)
            elif p.exists():
                p.unlink()

    def _mismatch_message(self, old: dict[str, Any]) -> str:
        n_done = len(self._records())
        what = []
        old_spec = old.get("spec") or {}
        new_spec = self.spec.as_dict()
        for key in ("base_case", "axes", "chunk_size", "variables", "summary_variable", "mode"):
            if old_spec.get(key) != new_spec.get(key):
                what.append(_changed(key, old_spec.get(key), new_spec.get(key)))
        if old.get("railvib_version") != railvib_version():
            what.append("railvib version")
        old_files = old.get("files")
        if isinstance(old_files, dict):
            now = data_file_hashes(self.spec)
            what += [
                f"data file {p}"
                for p in sorted(set(old_files) | set(now))
                if old_files.get(p) != now.get(p)
            ]
        # an older manifest has no file hashes: say what else may differ
        changed = ", ".join(what) or (
            "data files"
            if isinstance(old_files, dict)
            else "data files, or the railvib that wrote it fingerprinted sweeps otherwise"
        )
        return (
            f"sweep output {self.root} holds {n_done} finished chunks of a different sweep "
            f"(changed: {changed}); they no longer match this sweep file. Use another "
            f"--output folder, or --overwrite to discard them."
        )

    def _manifest(self) -> dict[str, Any]:
        lay = self.layout
        return {
            "fingerprint": self.fingerprint,
            "railvib_version": railvib_version(),
            "dims": list(lay.dims),
            "shape": list(lay.shape),
            "block": list(lay.block),
            "n_cases": lay.n_cases,
            "n_chunks": lay.n_chunks,
            "files": data_file_hashes(self.spec),
            "spec": self.spec.as_dict(),
        }

    def _data_path(self) -> Path | None:
        """Where the finished chunks' regions are: the store being filled, or the finished one."""
        for path in (self.work_path, self.root / ZARR_NAME):
            if (path / ".zmetadata").is_file():
                return path
        return None

    def done(self) -> set[int]:
        """Chunk ids already finished: each record checked, and its region against its CRCs.

        A damaged record (cut short, empty, not a record), or a region whose values do
        not match their record (a Zarr chunk deleted or damaged), is removed with a
        :class:`~railvib.errors.DamagedOutputWarning` naming it, so that the chunk is
        computed again (and its region overwritten).

        Raises
        ------
        SweepMismatchError
            A record belongs to another sweep.
        """
        records: dict[int, dict[str, int]] = {}
        for p in self._records():
            m = _RECORD_RE.match(p.name)
            assert m is not None  # _records matches the names
            cid = int(m.group(1))
            try:
                record = _read_record(p)
            except _Damaged as exc:
                self._damaged(p, f"chunk record {p} is damaged ({exc})")
                continue
            if record["fingerprint"] != self.fingerprint or cid >= self.layout.n_chunks:
                raise SweepMismatchError(
                    f"chunk record {p} belongs to a different sweep; use another --output "
                    "folder, or --overwrite to discard it"
                )
            records[cid] = record["crc32"]
        if not records:
            return set()
        data = self._data_path()
        if data is None:
            warnings.warn(
                f"the Zarr store of the {len(records)} finished chunks in {self.chunk_dir} is "
                "gone; they are computed again",
                DamagedOutputWarning,
                stacklevel=2,
            )
            for cid in records:
                self.chunk_path(cid).unlink()
            return set()
        return {cid for cid, crcs in records.items() if self._region_intact(data, cid, crcs)}

    def _damaged(self, record: Path, message: str) -> None:
        warnings.warn(f"{message}; it is computed again", DamagedOutputWarning, stacklevel=4)
        _remove(record)

    def _region_intact(self, data: Path, chunk_id: int, crcs: dict[str, int]) -> bool:
        """Whether chunk `chunk_id`'s region in store `data` holds the values of its record."""
        try:
            arrays = self._read_region(data, chunk_id, list(crcs))
            bad = [k.removeprefix("summary/") for k, v in arrays.items() if _crc(v) != crcs[k]]
        except Exception as exc:  # noqa: BLE001  (whatever a damaged Zarr chunk makes zarr raise)
            bad = [f"unreadable: {type(exc).__name__}"]
        if bad:
            what = ", ".join(bad[:3]) + (", ..." if len(bad) > 3 else "")
            self._damaged(
                self.chunk_path(chunk_id), f"chunk {chunk_id} of {data} is damaged ({what})"
            )
            for name in self._dims:  # whatever is in their place (a folder) is written anew
                _remove(data / name / self._chunk_key(chunk_id, name))
        return not bad

    def _chunk_key(self, chunk_id: int, name: str) -> str:
        """The name of chunk `chunk_id`'s Zarr chunk file in variable `name` (``0.0.3``)."""
        where, _ = self._region(chunk_id, name)
        chunks = self._arrays[name].metadata.chunks
        return ".".join(str((s.start or 0) // c) for s, c in zip(where, chunks, strict=True))

    def missing(self) -> list[int]:
        """Chunk ids still to compute, in order."""
        done = self.done()
        return [i for i in range(self.layout.n_chunks) if i not in done]

    def prepare(self) -> None:
        """Import zarr (and Dask where installed) in a thread, while the workers start.

        Their imports are most of the cost of the store's layout, written at the first
        chunk.
        """
        threading.Thread(target=_import_store_libraries, name="railvib-zarr-import").start()

    def write(self, chunk_id: int, arrays: dict[str, NDArray[Any]]) -> Path:
        """Write one finished chunk: its region of the Zarr store, then its record.

        The record (the fingerprint and a CRC-32 of each array) is renamed into place
        after the region is written, so a chunk is done only once its region is
        complete, against the death of any process (Ctrl-C, SIGKILL, a worker dying);
        there is no fsync, so after a power failure the file system decides (and a
        region that does not match its record is computed again).

        Parameters
        ----------
        chunk_id : int
            Chunk number (C order over the chunk grid).
        arrays : dict of numpy.ndarray
            The chunk's results (:func:`railvib.sweep.batch.compute_chunk`), each in the
            unit of its variable or summary, cases first.

        Returns
        -------
        pathlib.Path
            The chunk's record.
        """
        if not self._writable:
            self._open_work(arrays)
        self._write_region(chunk_id, arrays)
        record = {"fingerprint": self.fingerprint, "crc32": {k: _crc(v) for k, v in arrays.items()}}
        path = self.chunk_path(chunk_id)
        with atomic_path(path) as tmp:
            tmp.write_text(json.dumps(record), "utf-8")
        return path

    def read(self, chunk_id: int) -> dict[str, NDArray[Any]]:
        """Read the arrays of one finished chunk back from the store.

        Parameters
        ----------
        chunk_id : int
            Chunk number (C order over the chunk grid).

        Returns
        -------
        dict of numpy.ndarray
            The arrays given to :meth:`write`, by name, cases first.
        """
        data = self._data_path()
        assert data is not None, "a finished chunk is in a store"
        keys = list(_read_record(self.chunk_path(chunk_id))["crc32"])
        return self._read_region(data, chunk_id, keys)

    # -- the Zarr store ----------------------------------------------------------------------
    def _open_work(self, example: dict[str, NDArray[Any]]) -> None:
        """Open the store being filled: the one a run left, the finished one, or a new one.

        A store is reused only while records of it exist (else it may be an older
        railvib's, or a run's killed before its first record); the finished
        ``OUT/sweep.zarr`` moves back to ``OUT/chunks`` while chunks are written again,
        so that it is never there half-written. A new store's layout is written, shaped
        and typed after one chunk's `example` arrays, into a temporary folder renamed
        into place.
        """
        data = self._data_path() if self._records() else None
        if data is None:
            _remove(self.work_path)
            self._write_layout(example)
        elif data != self.work_path:
            os.replace(data, self.work_path)
        for name in self.work_path.iterdir():  # what zarr was writing when a run was killed
            if name.is_dir():
                for part in name.glob("*.partial"):
                    _remove(part)
        self._open(self.work_path, writable=True)

    def _open(self, path: Path, writable: bool = False) -> None:
        """Open the Zarr store `path` for the regions of its result variables."""
        import zarr
        from zarr.core.sync import sync  # what zarr's own synchronous API runs on

        group = zarr.open_group(str(path), mode="r+" if writable else "r")
        arrays = dict(group.arrays())
        dims = {
            name: [str(d) for d in _as_list(a.attrs["_ARRAY_DIMENSIONS"])]
            for name, a in arrays.items()
        }
        coords = {d for names in dims.values() for d in names}
        for arr in arrays.values():
            coords.update(str(arr.attrs.get("coordinates", "")).split())
        self._dims = {str(n): tuple(d) for n, d in dims.items() if n not in coords}
        self._arrays = {name: arrays[name].async_array for name in self._dims}
        self._sync = sync
        self._path = path
        self._writable = writable

    def _write_layout(self, example: dict[str, NDArray[Any]]) -> None:
        """Write the store's metadata and coordinates as ``OUT/chunks/sweep.zarr``, atomically.

        With Dask (the optional ``sweep`` extra) the variables are lazy placeholders and
        only the metadata is written; without it they are zero-stride views of one zero
        (no memory), written as zero chunks that the chunks then overwrite.
        """
        da: Any
        try:
            import dask.array as da  # lazy placeholders of the layout
        except ImportError:
            da = None
        lay = self.layout

        def placeholder(value: NDArray[Any]) -> Any:
            shape = lay.shape + value.shape[1:]
            if da is None:
                return np.broadcast_to(np.zeros((), dtype=value.dtype), shape)
            return da.zeros(shape, dtype=value.dtype, chunks=-1)

        arrays = {name: placeholder(value) for name, value in example.items()}
        template = sweep_dataset(self.spec, arrays, self.fingerprint)
        tmp = Path(tempfile.mkdtemp(prefix=f".{WORK_NAME}.", suffix=".part", dir=self.chunk_dir))
        options: dict[str, Any] = {"compute": da is None, "encoding": self._encoding(template)}
        try:
            template.to_zarr(tmp / "store", mode="w", zarr_format=2, consolidated=True, **options)
            os.replace(tmp / "store", self.work_path)
        finally:
            shutil.rmtree(tmp, ignore_errors=True)

    def _encoding(self, ds: xr.Dataset) -> dict[str, dict[str, Any]]:
        """One Zarr chunk per sweep chunk (zarr's default compressor, Blosc-LZ4)."""
        block = dict(zip(self.layout.dims, self.layout.block, strict=True))
        return {
            str(name): {"chunks": tuple(block.get(str(d), v.sizes[d]) for d in v.dims)}
            for name, v in ds.data_vars.items()
        }

    def _region(self, chunk_id: int, name: str) -> tuple[tuple[slice, ...], list[int]]:
        """Where chunk `chunk_id` lies in variable `name`; the axes of its sweep-first block."""
        lay = self.layout
        sl = dict(zip(lay.dims, lay.chunk_slices(chunk_id), strict=True))
        dims = self._dims[name]
        n = len(lay.dims)
        own = len(dims) - n  # the variable's own dims, then the sweep's
        order = [n + i for i in range(own)] + list(range(n))
        return tuple(sl.get(d, slice(None)) for d in dims), order

    def _write_region(self, chunk_id: int, arrays: dict[str, NDArray[Any]]) -> None:
        """Write one chunk's arrays into their block of every Zarr variable.

        All the variables' blocks are written in one call on zarr's I/O loop (gathered
        coroutines): written one by one, each small summary variable costs about a
        millisecond of zarr's synchronisation, two thirds of a chunk's writing.
        """
        shape = self.layout.chunk_shape(chunk_id)
        writes = []
        for key, value in arrays.items():
            name = key.removeprefix("summary/")
            where, order = self._region(chunk_id, name)
            block = value.reshape(shape + value.shape[1:])  # sweep dims first
            writes.append(self._arrays[name].setitem(where, np.transpose(block, order)))
        self._sync(_gather(writes))

    def _read_region(self, data: Path, chunk_id: int, keys: list[str]) -> dict[str, NDArray[Any]]:
        """Chunk `chunk_id`'s arrays `keys` read from store `data`, cases first (as written)."""
        if self._path != data:
            self._open(data)
        n = len(self.layout.dims)
        reads, backs = [], []
        for key in keys:
            where, order = self._region(chunk_id, key.removeprefix("summary/"))
            reads.append(self._arrays[key.removeprefix("summary/")].getitem(where))
            backs.append(np.argsort(order))
        out = {}
        for key, value, back in zip(keys, self._sync(_gather(reads)), backs, strict=True):
            block = np.ascontiguousarray(np.transpose(value, back))  # sweep dims first
            out[key] = block.reshape((-1, *block.shape[n:]))
        return out

    def finish(self) -> xr.Dataset:
        """Move the store into place once every chunk is done (its title brought up to date).

        Returns
        -------
        xarray.Dataset
            The sweep dataset opened from ``OUT/sweep.zarr`` (read lazily: values are
            loaded on access, so the sweep need not fit in memory).
        """
        import zarr

        data = self._data_path()
        assert data is not None, "a sweep has at least one chunk"
        self._path, self._writable, self._arrays = None, False, {}
        group = zarr.open_group(str(data), mode="r+")
        if group.attrs.get("title") != self.spec.title:  # a retitled sweep (same results)
            group.attrs["title"] = self.spec.title
            zarr.consolidate_metadata(str(data), zarr_format=2)
        target = self.root / ZARR_NAME
        if data != target:
            _remove(target)  # a store no record describes (an older railvib's)
            os.replace(data, target)
        return xr.open_zarr(target, consolidated=True, chunks=None)
