"""Run the missing chunks of a sweep: serially, on local processes, or on a Dask cluster.

Whatever the executor, the chunks are the same and computed by the same
function (:func:`railvib.sweep.batch.compute_chunk`), so the results are
identical bit for bit. Only this (client) process writes chunk files.
"""

from __future__ import annotations

import multiprocessing as mp
import os
import signal
import sys
from collections.abc import Callable, Iterator
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from contextlib import AbstractContextManager, nullcontext
from pathlib import Path
from typing import Any

import xarray as xr
from numpy.typing import NDArray

from railvib.errors import CaseError, RailvibError
from railvib.sweep.batch import compute_chunk
from railvib.sweep.layout import SweepLayout
from railvib.sweep.progress import case_progress
from railvib.sweep.spec import SweepSpec
from railvib.sweep.store import ChunkStore

__all__ = ["SweepInterrupted", "check_scheduler", "describe_run", "run_sweep"]

#: how to install what a Dask cluster needs (the ``sweep`` extra: dask[distributed])
INSTALL_SWEEP_EXTRA = 'pip install "railvib[sweep]"'

ChunkResult = tuple[int, dict[str, NDArray[Any]]]


class SweepInterrupted(RailvibError):
    """A worker died or the run was stopped; finished chunks are kept."""


def _compute(spec: SweepSpec, chunk_id: int) -> ChunkResult:
    return chunk_id, compute_chunk(spec, chunk_id)


def check_scheduler(scheduler: Any) -> None:
    """Refuse a Dask scheduler when ``distributed`` is not installed, before any work.

    Local runs (any number of worker processes) use :mod:`concurrent.futures` and need
    nothing extra; only a cluster needs the optional ``sweep`` dependencies.

    Parameters
    ----------
    scheduler : str, distributed.Client or None
        The scheduler of :func:`run_sweep` (None: local processes, nothing to check).

    Raises
    ------
    CaseError
        ``scheduler = '<address>': needs the Dask "distributed" package: pip install
        "railvib[sweep]"``.
    """
    if scheduler is None:
        return
    try:
        import distributed  # noqa: F401  (the optional dependency of Dask runs)
    except ImportError:
        raise CaseError(
            "scheduler",
            scheduler if isinstance(scheduler, str) else type(scheduler).__name__,
            f'a Dask cluster needs the "distributed" package: {INSTALL_SWEEP_EXTRA}',
        ) from None


def describe_run(spec: SweepSpec, out: str | Path, *, scheduler: str | None = None) -> str:
    """Say what :func:`run_sweep` is about to do: cases, dimensions, chunks, where, into what.

    Parameters
    ----------
    spec : SweepSpec
        The resolved sweep.
    out : str or pathlib.Path
        Its output folder.
    scheduler : str, optional
        Address of the Dask scheduler it runs on (default: local processes).

    Returns
    -------
    str
        E.g. ``"12 cases (3 x 4 over track.pad_temperature_c, speed_kmh) in 3 chunks,
        on local processes -> out/"``.
    """
    where = f"Dask scheduler {scheduler}" if scheduler else "local processes"
    return f"{SweepLayout(spec).describe()}, on {where} -> {out}/"


def run_sweep(
    spec: SweepSpec,
    out: str | Path,
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    progress: bool = True,
    overwrite: bool = False,
    assemble: bool = True,
) -> xr.Dataset | None:
    """Compute the missing chunks of a sweep and assemble its Zarr store.

    Parameters
    ----------
    spec : SweepSpec
        A resolved sweep (:func:`railvib.sweep.load_sweep`).
    out : str or pathlib.Path
        Output folder; finished chunks found there are kept (resume).
    workers : int, optional
        Local worker processes (default: all cores); ``1`` runs in this process.
        Ignored with `scheduler`.
    scheduler : str, optional
        Address of a Dask distributed scheduler (``tcp://host:8786``), or a
        ``distributed.Client`` object.
    progress : bool
        Show a progress bar (cases done, rate, time left).
    overwrite : bool
        Discard chunks of a different sweep in `out` instead of refusing.
    assemble : bool
        Write ``sweep.zarr`` and return the dataset when all chunks are done.

    Returns
    -------
    xarray.Dataset or None
        The sweep dataset (None when `assemble` is false).

    Raises
    ------
    SweepMismatchError
        `out` holds chunks of a different sweep.
    SweepInterrupted
        A local worker process died; rerun to resume.
    CaseError
        A `scheduler` given without Dask's ``distributed`` installed (checked first).
    """
    check_scheduler(scheduler)
    store = ChunkStore(out, spec)
    store.open(overwrite=overwrite)
    todo = store.missing()
    lay = store.layout
    sizes = {cid: _n(lay.chunk_shape(cid)) for cid in todo}
    # with `assemble`, each chunk goes into sweep.zarr as it arrives (overlapped with compute)
    with (
        store.streaming(assemble),
        _progress(progress, lay.n_cases, lay.n_cases - sum(sizes.values())) as advance,
    ):
        if scheduler is not None:
            results = _dask(spec, todo, scheduler)
        elif (workers or os.cpu_count() or 1) <= 1 or len(todo) <= 1:
            results = (_compute(spec, cid) for cid in todo)
        else:
            results = _local(spec, todo, workers or os.cpu_count() or 1)
        for cid, arrays in results:
            store.write(cid, arrays)
            advance(sizes[cid])
    if not assemble:
        return None
    return store.finish_zarr()


def _n(shape: tuple[int, ...]) -> int:
    n = 1
    for s in shape:
        n *= s
    return n


def _mp_context() -> Any:
    if sys.platform.startswith("linux"):
        ctx = mp.get_context("forkserver")
        ctx.set_forkserver_preload(["railvib.sweep.batch"])
        return ctx
    return mp.get_context("spawn")


def _ignore_sigint() -> None:
    """Leave Ctrl-C to the parent, which stops the pool and keeps the finished chunks."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _local(spec: SweepSpec, todo: list[int], workers: int) -> Iterator[ChunkResult]:
    """Chunks on local processes, at most 2 queued per worker; yields as they finish."""
    pool = ProcessPoolExecutor(
        max_workers=min(workers, len(todo)), mp_context=_mp_context(), initializer=_ignore_sigint
    )
    pending: set[Future[ChunkResult]] = set()
    queue = list(reversed(todo))
    try:
        while queue or pending:
            while queue and len(pending) < 2 * workers:
                pending.add(pool.submit(_compute, spec, queue.pop()))
            done, pending = wait(pending, return_when=FIRST_COMPLETED)
            for fut in done:
                try:
                    yield fut.result()
                except BrokenProcessPool:
                    raise SweepInterrupted(
                        "a worker process died; the finished chunks are saved - rerun the "
                        "same command to compute the rest"
                    ) from None
    finally:
        for fut in pending:
            fut.cancel()
        pool.shutdown(wait=True, cancel_futures=True)


def _dask(spec: SweepSpec, todo: list[int], scheduler: Any) -> Iterator[ChunkResult]:
    """Chunks on a Dask distributed cluster; yields as they finish."""
    from distributed import Client, as_completed

    own = isinstance(scheduler, str)
    client = Client(scheduler) if own else scheduler
    try:
        spec_future = client.scatter(spec, broadcast=True)
        futures = [
            client.submit(
                _compute, spec_future, cid, key=f"railvib-chunk-{cid}-{id(spec)}", pure=False
            )
            for cid in todo
        ]
        try:
            for fut in as_completed(futures):
                yield fut.result()
                fut.release()
        finally:
            client.cancel(futures)
    finally:
        if own:
            client.close()


def _progress(
    enabled: bool, total: int, done: int
) -> AbstractContextManager[Callable[[int], None]]:
    if not enabled:
        return nullcontext(lambda n: None)
    return case_progress(total, done)
