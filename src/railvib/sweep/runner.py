"""Run the missing chunks of a sweep: serially, on local processes, or on a Dask cluster.

Whatever the executor, the chunks are the same and computed by the same
function (:func:`railvib.sweep.batch.compute_chunk`), so the results are
identical bit for bit. Only this (client) process writes the store and the chunks'
records.
"""

from __future__ import annotations

import asyncio
import ctypes
import multiprocessing as mp
import multiprocessing.forkserver
import multiprocessing.resource_tracker
import os
import re
import signal
import socket
import sys
import threading
import time
from collections.abc import Callable, Generator, Iterator
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from contextlib import AbstractContextManager, closing, contextmanager, nullcontext
from importlib.util import find_spec
from pathlib import Path
from typing import Any

import xarray as xr
from numpy.typing import NDArray

from railvib.case import build_grid, case_from_dict
from railvib.errors import CaseError, RailvibError
from railvib.sweep.batch import compute_chunk
from railvib.sweep.layout import SweepLayout
from railvib.sweep.progress import case_progress
from railvib.sweep.spec import SweepSpec
from railvib.sweep.store import ChunkStore
from railvib.track.compiled import COMPILED_MIN_POINTS, LOADED_MIN_POINTS

__all__ = [
    "CONNECT_TIMEOUT_S",
    "SchedulerUnreachable",
    "SweepInterrupted",
    "check_scheduler",
    "connect_scheduler",
    "describe_run",
    "run_sweep",
]

#: how to install what a Dask cluster needs (the ``sweep`` extra: dask[distributed])
INSTALL_SWEEP_EXTRA = 'pip install "railvib[sweep]"'

ChunkResult = tuple[int, dict[str, NDArray[Any]]]

#: seconds :func:`connect_scheduler` waits for a Dask scheduler to answer by default
CONNECT_TIMEOUT_S = 5.0

#: the address schemes of Dask's communication backends (``distributed.comm``)
_SCHEMES = ("tcp", "tls", "ws", "wss", "ucx")

#: ``[SCHEME://]HOST:PORT``; HOST a name, an IPv4 address or an IPv6 one in brackets
_ADDRESS = re.compile(
    r"^(?:(?P<scheme>[a-z]+)://)?(?P<host>\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9_.-]+):(?P<port>\d{1,5})$"
)

#: what --scheduler accepts, for messages
_ADDRESS_HELP = (
    "a Dask scheduler address (--scheduler) HOST:PORT or SCHEME://HOST:PORT, SCHEME one of "
    f"{', '.join(_SCHEMES)}, PORT 1-65535, e.g. tcp://10.0.0.1:8786"
)


class SweepInterrupted(RailvibError):
    """A worker died or the run was stopped; finished chunks are kept."""


class SchedulerUnreachable(RailvibError):
    """The Dask scheduler given did not answer (nothing was computed or written)."""


def _compute(spec: SweepSpec, chunk_id: int) -> ChunkResult:
    return chunk_id, compute_chunk(spec, chunk_id)


def check_scheduler(scheduler: Any) -> None:
    """Refuse a malformed scheduler address, or one without ``distributed``, before any work.

    Local runs (any number of worker processes) use :mod:`concurrent.futures` and need
    nothing extra; only a cluster needs the optional ``sweep`` dependencies.

    Parameters
    ----------
    scheduler : str, distributed.Client or None
        The scheduler of :func:`run_sweep` (None: local processes, nothing to check):
        an address ``HOST:PORT`` or ``SCHEME://HOST:PORT`` (SCHEME ``tcp``, ``tls``,
        ``ws``, ``wss`` or ``ucx``), or a client.

    Raises
    ------
    CaseError
        ``scheduler = 'tcp:/x': a Dask scheduler address (--scheduler) HOST:PORT or
        ...``, or ``scheduler = '<address>': needs the Dask "distributed" package: pip
        install "railvib[sweep]"``.
    """
    if scheduler is None:
        return
    if isinstance(scheduler, str):
        _check_address(scheduler)
    try:
        import distributed  # noqa: F401  (the optional dependency of Dask runs)
    except ImportError:
        raise CaseError(
            "scheduler",
            scheduler if isinstance(scheduler, str) else type(scheduler).__name__,
            f'a Dask cluster needs the "distributed" package: {INSTALL_SWEEP_EXTRA}',
        ) from None


def _check_address(address: str) -> tuple[str, str, int]:
    """``(scheme, host, port)`` of a scheduler address; a CaseError if it is malformed."""
    m = _ADDRESS.match(address.strip())
    port = int(m.group("port")) if m else 0
    scheme = (m.group("scheme") or "tcp") if m else ""
    if m is None or scheme not in _SCHEMES or not 1 <= port <= 65535:
        raise CaseError("scheduler", address, _ADDRESS_HELP)
    return scheme, m.group("host").strip("[]"), port


@contextmanager
def connect_scheduler(scheduler: Any, timeout: float = CONNECT_TIMEOUT_S) -> Iterator[Any]:
    """Connect to a Dask scheduler within `timeout` seconds, or say that it cannot be reached.

    Parameters
    ----------
    scheduler : str, distributed.Client or None
        An address (checked by :func:`check_scheduler`), a client (used as it is, not
        closed), or None (local processes: yields None).
    timeout : float
        Time to wait for the scheduler to accept the connection and answer (s, > 0).

    Yields
    ------
    distributed.Client or None
        The client, closed on leaving the block when this function opened it.

    Raises
    ------
    CaseError
        A malformed address, or ``distributed`` not installed.
    SchedulerUnreachable
        ``cannot reach the Dask scheduler at tcp://HOST:PORT within 5 s (why); ...``:
        nothing listens there, the host is unknown, or what answers is not a Dask
        scheduler.
    """
    check_scheduler(scheduler)
    if not isinstance(scheduler, str):
        yield scheduler
        return
    if not timeout > 0:
        raise CaseError("scheduler timeout", timeout, "> 0 (s)")
    client = _open_client(scheduler, float(timeout))
    try:
        yield client
    finally:
        client.close()


def _open_client(address: str, timeout: float) -> Any:
    """A ``distributed.Client`` of `address`, or SchedulerUnreachable after `timeout` seconds."""
    from distributed import Client

    scheme, host, port = _check_address(address)

    def unreachable(why: str) -> SchedulerUnreachable:
        return SchedulerUnreachable(
            f"cannot reach the Dask scheduler at {address} within {timeout:g} s ({why}); check "
            "the address and that the scheduler runs (dask scheduler), or give more time "
            "with --scheduler-timeout"
        )

    if scheme != "ucx":  # every other backend runs over TCP: a refused port fails at once
        try:
            socket.create_connection((host, port), timeout=timeout).close()
        except OSError as exc:
            raise unreachable(exc.strerror or type(exc).__name__) from None
    # Dask's handshake, bounded: a Client made for a server that is not a Dask scheduler
    # (silent, or sending anything) hangs or fails, then hangs again when it is collected
    try:
        asyncio.run(asyncio.wait_for(_handshake(address, timeout), timeout))
    except TimeoutError:
        raise unreachable("it accepts connections but does not answer") from None
    except Exception as exc:  # noqa: BLE001  (whatever a foreign server makes Dask raise)
        raise unreachable(f"what answers is not a Dask scheduler: {type(exc).__name__}") from None
    return Client(address, timeout=timeout, set_as_default=False)


async def _handshake(address: str, timeout: float) -> None:
    """Open and close one Dask connection to `address` (its handshake included)."""
    from distributed.comm import connect

    comm = await connect(address, timeout=timeout)
    await comm.close()


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
    scheduler_timeout: float = CONNECT_TIMEOUT_S,
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
        Move the store into place as ``OUT/sweep.zarr`` and return the dataset when all
        chunks are done (false: the chunks are written into ``OUT/chunks`` only).
    scheduler_timeout : float
        Time to wait for the Dask scheduler at address `scheduler` to answer (s)
        (:func:`connect_scheduler`), before anything is written.

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
        A malformed `scheduler` address, or one given without Dask's ``distributed``
        installed (checked first).
    SchedulerUnreachable
        The scheduler at address `scheduler` does not answer (nothing is written).
    """
    with connect_scheduler(scheduler, scheduler_timeout) as client:  # before any file
        store = ChunkStore(out, spec)
        store.open(overwrite=overwrite)
        todo = store.missing()
        lay = store.layout
        sizes = {cid: _n(lay.chunk_shape(cid)) for cid in todo}
        done_before = lay.n_cases - sum(sizes.values())
        # each chunk is written once, into the store in OUT/chunks, as it arrives
        # (overlapped with compute); the store and the chunks' records stay if the run stops
        store.prepare()
        with (
            _progress(progress, lay.n_cases, done_before) as advance,
            # closed at once on any exception (Ctrl-C while a chunk is written): the pool
            # stops now, not when the traceback is collected at exit, half-started workers
            # and all
            closing(_results(spec, todo, client, workers)) as results,
        ):
            for cid, arrays in results:
                store.write(cid, arrays)
                advance(sizes[cid])
    if not assemble:
        return None
    return store.finish()


def _results(
    spec: SweepSpec, todo: list[int], client: Any, workers: int | None
) -> Generator[ChunkResult, None, None]:
    """The chunks `todo` as they finish: on `client`, local processes, or in this process."""
    if client is not None:
        yield from _dask(spec, todo, client)
    elif (workers or os.cpu_count() or 1) <= 1 or len(todo) <= 1:
        for cid in todo:
            yield _compute(spec, cid)
    else:
        yield from _local(spec, todo, workers or os.cpu_count() or 1)


def _n(shape: tuple[int, ...]) -> int:
    n = 1
    for s in shape:
        n *= s
    return n


def _mp_context(spec: SweepSpec) -> Any:
    """The workers' start method: forked from a fork server that imported the sweep's code.

    Where the sweep's workers solve on the compiled kernels, the fork server loads them
    too (:mod:`railvib.sweep.preload`), once for every worker. The fork server is started
    once per process: a later sweep's workers are forked from the first one's.
    """
    if sys.platform.startswith("linux"):
        ctx = mp.get_context("forkserver")
        preload = ["railvib.sweep.batch"]
        if _workers_load_kernels(spec):
            preload.append("railvib.sweep.preload")
        ctx.set_forkserver_preload(preload)
        return ctx
    return mp.get_context("spawn")


def _workers_load_kernels(spec: SweepSpec) -> bool:
    """Whether the workers of `spec` load the compiled kernels (numba not imported here)."""
    if os.environ.get("RAILVIB_COMPILED", "1") == "0" or find_spec("numba") is None:
        return False
    n_freq = build_grid(case_from_dict(spec.base_case_dict(), warn=False)).f.size
    lay = SweepLayout(spec)
    return (
        min(spec.chunk_size, lay.n_cases) * n_freq >= LOADED_MIN_POINTS
        and lay.n_cases * n_freq >= COMPILED_MIN_POINTS
    )


def _start_forkserver(ctx: Any) -> None:
    """Start the fork server with Ctrl-C blocked, so that only this process sees it.

    A terminal sends Ctrl-C to the whole process group; the fork server, still
    importing its preload modules, would print a KeyboardInterrupt traceback. It
    inherits the blocked signal (and ignores it once started), and so do the workers
    it forks until :func:`_worker_init` ignores it; here the signal is delivered when
    unblocked.
    """
    if ctx.get_start_method() != "forkserver":
        return
    # first the resource tracker: starting it unblocks SIGINT (it blocks it for itself)
    multiprocessing.resource_tracker.ensure_running()
    with _sigint_deferred():
        multiprocessing.forkserver.ensure_running()


@contextmanager
def _sigint_deferred() -> Iterator[None]:
    """Hold back Ctrl-C during the block; one that comes is raised at its end.

    Processes started in the block inherit SIGINT blocked. In this process the signal
    may land on any thread (BLAS, the pool's), so it is also caught by a handler that
    only notes it (in the main thread; elsewhere Python cannot set handlers).
    """
    masks = hasattr(signal, "pthread_sigmask")  # not on Windows
    main = threading.current_thread() is threading.main_thread()
    caught: list[int] = []
    previous = signal.signal(signal.SIGINT, lambda n, _: caught.append(n)) if main else None
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT}) if masks else None
    try:
        yield
    finally:
        if mask is not None:
            signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        if main:
            signal.signal(signal.SIGINT, previous)
    if caught:
        if callable(previous):
            previous(signal.SIGINT, None)
        elif previous == signal.SIG_DFL:
            raise KeyboardInterrupt


#: ``prctl`` option: the signal a process gets when its parent dies (linux/prctl.h)
_PR_SET_PDEATHSIG = 1

#: seconds between two checks of a worker that its sweep process still runs
_WATCH_INTERVAL_S = 0.5


def _worker_init(client_pid: int) -> None:
    """Set up a worker process: Ctrl-C left to the client, and death with it.

    The client (the sweep's main process) stops the pool on Ctrl-C and keeps the
    finished chunks. Should it be killed (SIGKILL), nothing would stop the workers,
    the fork server and the resource tracker (each holds the others' pipes open): a
    watchdog thread ends the worker within half a second of the client (POSIX), and
    the worker gets SIGTERM when its parent, the fork server, dies (Linux
    ``PR_SET_PDEATHSIG``). The fork server and the resource tracker then end by
    themselves, their last client gone.

    Parameters
    ----------
    client_pid : int
        Process id of the sweep's main process.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if sys.platform.startswith("linux"):
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGTERM), 0, 0, 0)
    if os.name == "posix":  # on Windows os.kill(pid, 0) would end the client
        watchdog = threading.Thread(
            target=_watch_client, args=(client_pid,), name="railvib-watchdog", daemon=True
        )
        watchdog.start()


def _watch_client(client_pid: int) -> None:
    """End this worker process once the process `client_pid` has ended."""
    while _alive(client_pid):
        time.sleep(_WATCH_INTERVAL_S)
    os._exit(1)  # nothing to save: results go to the client, which is gone


def _alive(pid: int) -> bool:
    """Whether process `pid` runs (a zombie, dead but not yet reaped, does not)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return True  # no /proc (not Linux): the signal test is all there is
    return stat.rpartition(")")[2].split()[:1] != ["Z"]


def _local(spec: SweepSpec, todo: list[int], workers: int) -> Iterator[ChunkResult]:
    """Chunks on local processes, at most 2 queued per worker; yields as they finish."""
    ctx = _mp_context(spec)
    _start_forkserver(ctx)
    pool = ProcessPoolExecutor(
        max_workers=min(workers, len(todo)),
        mp_context=ctx,
        initializer=_worker_init,
        initargs=(os.getpid(),),
    )
    pending: set[Future[ChunkResult]] = set()
    queue = list(reversed(todo))
    try:
        while queue or pending:
            while queue and len(pending) < 2 * workers:
                # a submit may start a worker: a Ctrl-C then would leave it half-started
                # (the pool gone, it prints a traceback); raised once it is started
                with _sigint_deferred():
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


def _dask(spec: SweepSpec, todo: list[int], client: Any) -> Iterator[ChunkResult]:
    """Chunks on a Dask distributed cluster (through `client`); yields as they finish."""
    from distributed import as_completed

    spec_future = client.scatter(spec, broadcast=True)
    futures = [
        client.submit(_compute, spec_future, cid, key=f"railvib-chunk-{cid}-{id(spec)}", pure=False)
        for cid in todo
    ]
    try:
        for fut in as_completed(futures, loop=client.loop):
            yield fut.result()
            fut.release()
    finally:
        client.cancel(futures)


def _progress(
    enabled: bool, total: int, done: int
) -> AbstractContextManager[Callable[[int], None]]:
    if not enabled:
        return nullcontext(lambda n: None)
    return case_progress(total, done)
