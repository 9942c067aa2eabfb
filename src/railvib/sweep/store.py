"""The resumable chunk store of a sweep, and its Zarr store, written chunk by chunk.

Layout of a sweep folder::

    OUT/manifest.json          fingerprint, layout and the resolved sweep
    OUT/chunks/chunk-000012.npz one file per finished chunk, written atomically
    OUT/sweep.zarr             the assembled dataset (each chunk written into a temporary
                               store as it arrives; moved into place when all exist)
    OUT/sweep.nc, OUT/summary.csv, OUT/plots/   optional exports

Each chunk is written to a temporary file and moved into place with
``os.replace``, so a chunk file exists completely or not at all, whatever
moment the run is killed. The fingerprint (hash of the resolved sweep, the
data files it reads and the railvib version) is stored in the manifest and in
every chunk; a different sweep is refused, never mixed in.
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
import zipfile
from collections.abc import Iterator
from contextlib import contextmanager
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

_CHUNK_RE = re.compile(r"^chunk-(\d{6,})\.npz$")


class SweepMismatchError(RailvibError):
    """The output folder holds chunks of a different sweep."""


#: what reading a damaged chunk file or manifest raises
_DAMAGED = (OSError, EOFError, ValueError, KeyError, zipfile.BadZipFile)

#: the sweep's own temporaries (``.<name>.<random>.part`` of :func:`railvib.io.atomic_path`
#: and :meth:`ChunkStore.begin_zarr`), by sub-folder: the prefixes of their names, or
#: ``("",)`` for a folder that holds nothing but railvib's files
_LEFTOVERS: dict[str, tuple[str, ...]] = {
    ".": ("manifest.json", "sweep.zarr", "sweep.nc", "summary.csv"),
    "chunks": ("",),
    PLOTS_NAME: ("",),
}


def remove_leftovers(root: str | Path) -> list[Path]:
    """Remove the temporary files a killed run left in sweep folder `root`.

    Only railvib's own temporary names (``.sweep.zarr.XXXX.part``,
    ``.chunk-000003.npz.XXXX.part``, ...; :func:`railvib.io.is_temporary_name`) in the
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


async def _gather(writes: list[Any]) -> None:
    """Await the coroutines `writes` together (zarr writes of one chunk)."""
    await asyncio.gather(*writes)


def _import_store_libraries() -> None:
    """Import what writing the Zarr store needs (zarr, and Dask where installed)."""
    import zarr  # noqa: F401  (imported ahead of its use in ChunkStore._open_zarr)

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


def _read_chunk_stamp(path: Path) -> str:
    """The fingerprint stamped in a chunk file, after reading every array (CRC-checked)."""
    with open(path, "rb") as fh, np.load(fh, allow_pickle=False) as z:  # closed if not a zip
        for name in z.files:
            z[name]  # noqa: B018  (reading checks the member's CRC and .npy header)
        return str(z["fingerprint"])


def _chunk_stamp(path: Path) -> str | None:
    """The fingerprint of a chunk file; None when it is damaged."""
    try:
        return _read_chunk_stamp(path)
    except _DAMAGED:
        return None


def _reason(exc: BaseException) -> str:
    """What is wrong with a damaged file, in a few words."""
    if isinstance(exc, EOFError | zipfile.BadZipFile):
        return "cut short or not a chunk file"
    if isinstance(exc, KeyError):
        return "no fingerprint"
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
    """Finished chunks of one sweep in folder `root`.

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
        self._stream = False  # write() streams into the Zarr store (begin_zarr)
        self._zarr: Any = None  # the Zarr group being filled, or None
        self._arrays: dict[str, Any] = {}  # its variables (zarr.AsyncArray), by name
        self._sync: Any = None  # zarr's runner of a coroutine on its I/O loop
        self._zarr_dir: Path | None = None
        self._dims: dict[str, tuple[str, ...]] = {}
        self._streamed: set[int] = set()

    @property
    def chunk_dir(self) -> Path:
        """Folder of the chunk files."""
        return self.root / "chunks"

    def chunk_path(self, chunk_id: int) -> Path:
        """File of chunk `chunk_id`."""
        return self.chunk_dir / f"chunk-{chunk_id:06d}.npz"

    def open(self, overwrite: bool = False) -> None:
        """Create the folder and manifest, or check that an existing one is this sweep.

        Leftovers of a killed run (the temporary files and folders railvib writes
        before a rename) are removed first. A damaged manifest is written again when
        the chunk files, each stamped with the fingerprint, show that the folder is
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
            manifest is damaged and its chunk files are not this sweep's.
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
        stamps = [_chunk_stamp(p) for p in self._chunk_files()]
        foreign = [s for s in stamps if s is not None and s != self.fingerprint]
        where = self.root / MANIFEST
        if foreign and not overwrite:
            raise SweepMismatchError(
                f"{where} is damaged ({damage}) and {len(foreign)} of the {len(stamps)} chunk "
                f"files in {self.chunk_dir} belong to a different sweep; use another --output "
                "folder, or --overwrite to discard them"
            )
        if foreign:
            self._clear()
            done = "written again; the chunks of the other sweep are discarded (--overwrite)"
        else:
            where.unlink()
            done = "written again" + (
                f" ({len(stamps)} chunk files of this sweep kept)" if stamps else ""
            )
        warnings.warn(f"{where} is damaged ({damage}); {done}", DamagedOutputWarning, stacklevel=3)

    def _chunk_files(self) -> list[Path]:
        if not self.chunk_dir.is_dir():
            return []
        return sorted(p for p in self.chunk_dir.iterdir() if _CHUNK_RE.match(p.name))

    def _clear(self) -> None:
        for name in (MANIFEST, ZARR_NAME, "chunks"):
            p = self.root / name
            if p.is_dir():
                shutil.rmtree(p)
            elif p.exists():
                p.unlink()

    def _mismatch_message(self, old: dict[str, Any]) -> str:
        n_done = len(self._chunk_files())
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

    def done(self) -> set[int]:
        """Chunk ids already finished (each checked against the fingerprint).

        A damaged chunk file (cut short, empty, not a chunk) is removed with a
        :class:`~railvib.errors.DamagedOutputWarning` naming it, so that it is computed
        again.

        Raises
        ------
        SweepMismatchError
            A chunk file belongs to another sweep.
        """
        out: set[int] = set()
        for p in self._chunk_files():
            m = _CHUNK_RE.match(p.name)
            assert m is not None  # _chunk_files matches the names
            cid = int(m.group(1))
            try:
                fp = _read_chunk_stamp(p)
            except _DAMAGED as exc:
                warnings.warn(
                    f"chunk file {p} is damaged ({_reason(exc)}); it is computed again",
                    DamagedOutputWarning,
                    stacklevel=2,
                )
                _remove(p)
                continue
            if fp != self.fingerprint or cid >= self.layout.n_chunks:
                raise SweepMismatchError(
                    f"chunk file {p} belongs to a different sweep; use another --output "
                    "folder, or --overwrite to discard it"
                )
            out.add(cid)
        return out

    def missing(self) -> list[int]:
        """Chunk ids still to compute, in order."""
        done = self.done()
        return [i for i in range(self.layout.n_chunks) if i not in done]

    def write(self, chunk_id: int, arrays: dict[str, NDArray[Any]]) -> Path:
        """Write one finished chunk atomically (temporary file, then ``os.replace``).

        The rename makes the chunk all-or-nothing against the death of any process
        (Ctrl-C, SIGKILL, a worker dying); there is no fsync, so after a power
        failure the file system decides.

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
            The chunk file.
        """
        path = self.chunk_path(chunk_id)
        payload = {k.replace("/", "__"): v for k, v in arrays.items()}
        with atomic_path(path) as tmp:
            with open(tmp, "wb") as fh:
                np.savez(fh, fingerprint=np.array(self.fingerprint), **payload)  # type: ignore[arg-type]
        if self._stream:
            self._write_region(chunk_id, arrays)
        return path

    def read(self, chunk_id: int) -> dict[str, NDArray[Any]]:
        """Read the arrays of one finished chunk.

        Parameters
        ----------
        chunk_id : int
            Chunk number (C order over the chunk grid).

        Returns
        -------
        dict of numpy.ndarray
            The arrays given to :meth:`write`, by name.
        """
        with np.load(self.chunk_path(chunk_id)) as z:
            return {k.replace("__", "/"): z[k] for k in z.files if k != "fingerprint"}

    # -- streaming into the Zarr store ------------------------------------------------------
    def begin_zarr(self) -> None:
        """Stream the chunks into ``sweep.zarr`` from now on: each :meth:`write` adds its own.

        At the first chunk the store's metadata and coordinates are written to a
        temporary folder (the variables as lazy placeholders: nothing of the size of the
        sweep is held); then each chunk is compressed and written as it arrives, while
        the workers compute the next, and the parent holds one chunk at a time.
        :meth:`finish_zarr` adds the chunks finished by an earlier run and moves the
        store into place. Zarr and Dask are imported now, in a thread of their own, while
        the workers start (their imports are most of the layout's cost).
        """
        self._stream = True
        threading.Thread(target=_import_store_libraries, name="railvib-zarr-import").start()

    def _open_zarr(self, example: dict[str, NDArray[Any]]) -> None:
        """Write the store's layout, shaped and typed after one chunk's `example` arrays.

        With Dask (the optional ``sweep`` extra) the variables are lazy placeholders and
        only the metadata is written; without it they are zero-stride views of one zero
        (no memory), written as compressed zero chunks that the chunks then overwrite.
        """
        import zarr
        from zarr.core.sync import sync  # what zarr's own synchronous API runs on

        da: Any
        try:
            import dask.array as da  # lazy placeholders of the layout (only when assembling)
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
        tmp = Path(tempfile.mkdtemp(prefix=".sweep.zarr.", suffix=".part", dir=self.root))
        options: dict[str, Any] = {"compute": da is None, "encoding": self._encoding(template)}
        template.to_zarr(tmp / "store", mode="w", zarr_format=2, consolidated=True, **options)
        self._zarr_dir = tmp
        self._zarr = zarr.open_group(str(tmp / "store"), mode="r+")
        self._dims = {str(name): tuple(map(str, v.dims)) for name, v in template.data_vars.items()}
        self._arrays = {name: self._zarr[name].async_array for name in self._dims}
        self._sync = sync

    def _encoding(self, ds: xr.Dataset) -> dict[str, dict[str, Any]]:
        block = dict(zip(self.layout.dims, self.layout.block, strict=True))
        return {
            str(name): {"chunks": tuple(block.get(str(d), v.sizes[d]) for d in v.dims)}
            for name, v in ds.data_vars.items()
        }

    def _write_region(self, chunk_id: int, arrays: dict[str, NDArray[Any]]) -> None:
        """Write one chunk's arrays into their block of every Zarr variable.

        All the variables' blocks are written in one call on zarr's I/O loop (gathered
        coroutines): written one by one, each small summary variable costs about a
        millisecond of zarr's synchronisation, two thirds of a chunk's writing.
        """
        if self._zarr is None:
            self._open_zarr(arrays)
        lay = self.layout
        sl = dict(zip(lay.dims, lay.chunk_slices(chunk_id), strict=True))
        shape = lay.chunk_shape(chunk_id)
        n = len(lay.dims)
        writes = []
        for key, value in arrays.items():
            name = key.removeprefix("summary/")
            dims = self._dims[name]
            block = value.reshape(shape + value.shape[1:])  # sweep dims first
            own = dims[: len(dims) - n]  # the variable's own dims, then the sweep's
            order = [n + i for i in range(len(own))] + list(range(n))
            where = tuple(sl.get(d, slice(None)) for d in dims)
            writes.append(self._arrays[name].setitem(where, np.transpose(block, order)))
        self._sync(_gather(writes))
        self._streamed.add(chunk_id)

    @contextmanager
    def streaming(self, enabled: bool = True) -> Iterator[None]:
        """Stream the chunks written in the block into the Zarr store (:meth:`begin_zarr`).

        If the block is left by an exception (Ctrl-C, a worker dying), the store in
        progress is removed; the chunk files stay for a rerun.

        Parameters
        ----------
        enabled : bool
            False: write the chunk files only.
        """
        if enabled:
            self.begin_zarr()
        try:
            yield
        except BaseException:
            self.discard_zarr()
            raise

    def discard_zarr(self) -> None:
        """Remove the store in progress (the run stopped; the chunk files are kept)."""
        if self._zarr_dir is not None:
            shutil.rmtree(self._zarr_dir, ignore_errors=True)
        self._zarr = self._zarr_dir = None
        self._arrays = {}
        self._stream = False
        self._streamed = set()

    def finish_zarr(self) -> xr.Dataset:
        """Add the chunks written before :meth:`begin_zarr`, then move the store into place.

        Returns
        -------
        xarray.Dataset
            The sweep dataset opened from ``OUT/sweep.zarr`` (read lazily: values are
            loaded on access, so the sweep need not fit in memory).
        """
        assert self._stream, "begin_zarr first"
        for cid in range(self.layout.n_chunks):
            if cid not in self._streamed:
                self._write_region(cid, self.read(cid))
        assert self._zarr_dir is not None, "a sweep has at least one chunk"
        target = self.root / ZARR_NAME
        try:
            if target.exists():
                shutil.rmtree(target)
            os.replace(self._zarr_dir / "store", target)
        finally:
            self.discard_zarr()
        return xr.open_zarr(target, consolidated=True, chunks=None)
