"""The resumable chunk store of a sweep, and the labelled dataset assembled from it.

Layout of a sweep folder::

    OUT/manifest.json          fingerprint, layout and the resolved sweep
    OUT/chunks/chunk-000012.npz one file per finished chunk, written atomically
    OUT/sweep.zarr             the assembled dataset (written when all chunks exist)
    OUT/sweep.nc, OUT/summary.csv, OUT/plots/   optional exports

Each chunk is written to a temporary file and moved into place with
``os.replace``, so a chunk file exists completely or not at all, whatever
moment the run is killed. The fingerprint (hash of the resolved sweep, the
data files it reads and the railvib version) is stored in the manifest and in
every chunk; a different sweep is refused, never mixed in.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import tempfile
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from railvib.errors import RailvibError
from railvib.io import atomic_path, railvib_version
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
    "default_plot_folder",
    "fingerprint",
]

_CHUNK_RE = re.compile(r"^chunk-(\d{6,})\.npz$")


class SweepMismatchError(RailvibError):
    """The output folder holds chunks of a different sweep."""


def fingerprint(spec: SweepSpec) -> str:
    """SHA-256 of the resolved sweep, the contents of data files it names, and the version.

    Parameters
    ----------
    spec : SweepSpec
        A resolved sweep (:func:`railvib.sweep.spec.sweep_from_dict`); hashed as
        :meth:`~railvib.sweep.spec.SweepSpec.as_dict`.

    Returns
    -------
    str
        Hex digest.
    """
    data = spec.as_dict()
    files = {p: _file_hash(p) for p in sorted(_data_paths(data))}
    blob = json.dumps(
        {"spec": data, "files": files, "railvib": railvib_version()}, sort_keys=True, default=str
    )
    return hashlib.sha256(blob.encode()).hexdigest()


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

    @property
    def chunk_dir(self) -> Path:
        """Folder of the chunk files."""
        return self.root / "chunks"

    def chunk_path(self, chunk_id: int) -> Path:
        """File of chunk `chunk_id`."""
        return self.chunk_dir / f"chunk-{chunk_id:06d}.npz"

    def open(self, overwrite: bool = False) -> None:
        """Create the folder and manifest, or check that an existing one is this sweep.

        Parameters
        ----------
        overwrite : bool
            Discard the chunks of a different sweep instead of refusing.

        Raises
        ------
        SweepMismatchError
            The folder holds a different sweep (and `overwrite` is false).
        """
        manifest = self.root / MANIFEST
        if manifest.exists():
            try:
                old = json.loads(manifest.read_text(encoding="utf-8"))
            except (OSError, ValueError):
                old = {}
            if old.get("fingerprint") != self.fingerprint:
                if not overwrite:
                    raise SweepMismatchError(self._mismatch_message(old))
                self._clear()
        if self.chunk_dir.exists():
            for tmp in self.chunk_dir.glob(".*.part"):
                tmp.unlink(missing_ok=True)  # left by a killed run
        self.chunk_dir.mkdir(parents=True, exist_ok=True)
        if not manifest.exists():
            with atomic_path(manifest) as tmp:
                tmp.write_text(json.dumps(self._manifest(), indent=1, default=str), "utf-8")

    def _clear(self) -> None:
        for name in (MANIFEST, ZARR_NAME, "chunks"):
            p = self.root / name
            if p.is_dir():
                shutil.rmtree(p)
            elif p.exists():
                p.unlink()

    def _mismatch_message(self, old: dict[str, Any]) -> str:
        n_done = len(list(self.chunk_dir.glob("chunk-*.npz"))) if self.chunk_dir.exists() else 0
        what = []
        old_spec = old.get("spec") or {}
        new_spec = self.spec.as_dict()
        for key in ("base_case", "axes", "chunk_size", "variables", "summary_variable", "mode"):
            if old_spec.get(key) != new_spec.get(key):
                what.append(key)
        if old.get("railvib_version") != self._manifest()["railvib_version"]:
            what.append("railvib version")
        changed = ", ".join(what) or "data files"
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
            "spec": self.spec.as_dict(),
        }

    def done(self) -> set[int]:
        """Chunk ids already finished (each checked against the fingerprint).

        Raises
        ------
        SweepMismatchError
            A chunk file belongs to another sweep.
        """
        out: set[int] = set()
        if not self.chunk_dir.exists():
            return out
        for p in self.chunk_dir.iterdir():
            m = _CHUNK_RE.match(p.name)
            if m is None:
                continue
            cid = int(m.group(1))
            with np.load(p) as z:
                fp = str(z["fingerprint"])
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

    # -- assembly ----------------------------------------------------------------------------
    def assemble(self) -> xr.Dataset:
        """Assemble the labelled dataset of the whole sweep from the finished chunks.

        Returns
        -------
        xarray.Dataset
            Dimensions ``frequency``, ``response`` (``wheel`` for forces) and the
            sweep dimensions; summary variables over ``response`` and the sweep
            dimensions.
        """
        lay = self.layout
        arrays: dict[str, NDArray[Any]] = {}
        for cid in range(lay.n_chunks):
            chunk = self.read(cid)
            sl = lay.chunk_slices(cid)
            shape = lay.chunk_shape(cid)
            for name, value in chunk.items():
                if name not in arrays:
                    arrays[name] = np.empty(lay.shape + value.shape[1:], dtype=value.dtype)
                arrays[name][sl] = value.reshape(shape + value.shape[1:])
        return sweep_dataset(self.spec, arrays, self.fingerprint)

    def write_zarr(self, ds: xr.Dataset) -> Path:
        """Write `ds` to ``OUT/sweep.zarr`` atomically (temporary folder, then rename).

        The store is chunked by case: one Zarr chunk per sweep chunk.

        Parameters
        ----------
        ds : xarray.Dataset
            The assembled sweep dataset (:meth:`assemble`).

        Returns
        -------
        pathlib.Path
            The Zarr store, ``OUT/sweep.zarr``.
        """
        target = self.root / ZARR_NAME
        tmp = Path(tempfile.mkdtemp(prefix=".sweep.zarr.", suffix=".part", dir=self.root))
        try:
            encoding = {}
            block = dict(zip(self.layout.dims, self.layout.block, strict=True))
            for name, da in ds.data_vars.items():
                encoding[name] = {"chunks": tuple(block.get(str(d), da.sizes[d]) for d in da.dims)}
            ds.to_zarr(tmp / "store", mode="w", zarr_format=2, consolidated=True, encoding=encoding)
            if target.exists():
                shutil.rmtree(target)
            os.replace(tmp / "store", target)
        finally:
            shutil.rmtree(tmp, ignore_errors=True)
        return target
