"""Writing files and stamping them: atomic writes, staged output folders, figures, provenance.

Every file railvib writes goes through :func:`atomic_path` (a temporary file next
to the target, renamed onto it only when the writer succeeds), so a file is
either complete or absent whatever moment a run is stopped; a write the system
refuses (a full disk, a file-size limit, a read-only folder) is an
:class:`~railvib.errors.OutputError` naming the file, with the temporary removed.
The commands that write a set of files (``railvib run``, ``reproduce``, ``pad
fit``) write them into a staging folder swapped in at the end
(:func:`staged_folder`), so their folder holds one run's complete set. Every PNG
goes through :func:`save_figure`, so figures share one resolution and are closed
after saving.
"""

from __future__ import annotations

import ctypes
import errno as errnos
import functools
import os
import pickle
import re
import secrets
import shutil
import signal
import stat
import sys
import tempfile
import threading
import tomllib
import warnings
from collections.abc import Callable, Collection, Iterable, Iterator
from contextlib import contextmanager
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from railvib.errors import CaseError, OutputError

try:  # POSIX: a staging folder in use is locked, so no other run removes it
    import fcntl
except ImportError:  # pragma: no cover - Windows
    fcntl = None  # type: ignore[assignment]

if TYPE_CHECKING:  # matplotlib is imported only by code that draws
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = [
    "BACKGROUND_ENV",
    "FIGURE_DPI",
    "MAX_NESTING",
    "PNG_COMPRESS_LEVEL",
    "Background",
    "MAX_TABLE_BYTES",
    "MAX_TOML_BYTES",
    "StagedFolder",
    "atomic_path",
    "is_temporary_name",
    "os_error_reason",
    "remove_temporaries",
    "staged_folder",
    "binary_kind",
    "check_nesting",
    "new_figure",
    "railvib_version",
    "read_text",
    "read_toml",
    "save_figure",
    "write_text",
]

#: resolution of every PNG railvib writes, dots per inch
FIGURE_DPI = 110

#: zlib level of every PNG railvib writes: 1 encodes a figure in 8 ms instead of 12 ms
#: (Pillow's default, 6) for 10 % larger files; the pixels are the same
PNG_COMPRESS_LEVEL = 1

#: largest case or sweep file read, bytes (4 MiB; the template is 5 kB, a sweep over
#: inline tables some 100 kB): a larger file is refused before it is parsed
MAX_TOML_BYTES = 4 * 2**20
#: largest CSV table read (irregularity spectrum, pad measurements), bytes (64 MiB, about
#: two million rows; a measured spectrum has some thousand)
MAX_TABLE_BYTES = 64 * 2**20
#: deepest nesting of tables and arrays in a case or sweep file (a case nests 5 levels:
#: irregularity.long_wave.long_wave...; deeper input is refused before Python recurses)
MAX_NESTING = 32


@functools.cache
def railvib_version() -> str:
    """Installed railvib version (``"unknown"`` when run from a source tree).

    Looked up once per process: the metadata search costs ~1 ms, a tenth of a small run.
    """
    try:
        return version("railvib")
    except PackageNotFoundError:
        return "unknown"


def os_error_reason(exc: OSError) -> str:
    """The system's reason for `exc` in a few words (``"No space left on device"``).

    HDF5 and other libraries wrap the system's error in a long message; the error
    number gives the short text.

    Parameters
    ----------
    exc : OSError
        The error.

    Returns
    -------
    str
        :func:`os.strerror` of its error number, else its first line.
    """
    if isinstance(exc, OutputError):
        return exc.reason
    if exc.errno is not None:
        return os.strerror(exc.errno)
    return (str(exc).splitlines() or [type(exc).__name__])[0]


def _output_error(path: str | Path, exc: OSError) -> OutputError:
    return OutputError(path, os_error_reason(exc), exc.errno)


@contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path next to `path`; move it onto `path` only if the block succeeds.

    Parameters
    ----------
    path : str or pathlib.Path
        The file to write; its folder is created if missing.

    Yields
    ------
    pathlib.Path
        A temporary file in the same folder (so the final rename is atomic).

    Raises
    ------
    OutputError
        When the folder cannot be made or the file cannot be written or renamed (a
        full disk, a file-size limit, a read-only folder: any :class:`OSError` of the
        block), naming `path` and the system's reason; the temporary is removed and
        an existing `path` is left as it was.
    """
    path = Path(path)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent)
        os.close(fd)
    except OSError as exc:
        raise _output_error(path, exc) from None
    try:
        yield Path(tmp)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; give the usual file mode
        os.replace(tmp, path)
    except OutputError:
        raise
    except OSError as exc:
        raise _output_error(path, exc) from None
    finally:
        if os.path.lexists(tmp):
            try:
                os.unlink(tmp)
            except OSError:
                pass  # the folder went away or became read-only: nothing more to do


#: railvib's temporary names: ``.NAME.XXXXXXXX.part`` (:func:`tempfile.mkstemp`'s 8
#: characters; files of :func:`atomic_path`, folders of :func:`staged_folder`) and
#: ``.NAME.XXXXXXXX.old`` (a folder replaced by :func:`staged_folder`)
_TEMPORARY = re.compile(r"^\..+\.[a-z0-9_]{8}\.(part|old)$")


def is_temporary_name(name: str) -> bool:
    """Whether `name` is one of railvib's temporary names (``.results.nc.k2x_9qaz.part``).

    Parameters
    ----------
    name : str
        A file or folder name (no folder part).

    Returns
    -------
    bool
        True for the names :func:`atomic_path` and :func:`staged_folder` give their
        temporaries, which a stopped run may leave behind.
    """
    return _TEMPORARY.match(name) is not None


def _lock(folder: Path) -> int | None:
    """Hold an exclusive lock on `folder` (released when the fd is closed or the process dies)."""
    if fcntl is None:  # pragma: no cover - Windows
        return None
    fd = os.open(folder, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        os.close(fd)
        return None
    return fd


def _in_use(path: Path) -> bool:
    """Whether `path` is a folder locked by a running railvib (another run's staging folder)."""
    if fcntl is None or not path.is_dir() or path.is_symlink():
        return False
    try:
        fd = os.open(path, os.O_RDONLY)
    except OSError:
        return False
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        return True
    finally:
        os.close(fd)  # also releases the lock just taken
    return False


def _remove(path: Path) -> None:
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    else:
        try:
            path.unlink()
        except OSError:
            pass


def remove_temporaries(folder: str | Path, prefix: str = "") -> list[Path]:
    """Remove the temporaries a stopped railvib left in `folder` (its own names only).

    A run killed with SIGKILL (or a power cut) cannot clean up: it may leave
    ``.NAME.XXXXXXXX.part`` files of :func:`atomic_path` and staging folders of
    :func:`staged_folder`. Only names of that form (:func:`is_temporary_name`) are
    removed, and not a staging folder a running railvib holds (it is locked).

    Parameters
    ----------
    folder : str or pathlib.Path
        The folder to clean (not searched recursively); a missing one is fine.
    prefix : str
        Remove only temporaries whose name starts with ``"." + prefix + "."`` (e.g.
        the staging folders of one output folder); empty: all of them.

    Returns
    -------
    list of pathlib.Path
        What was removed.
    """
    folder = Path(folder)
    try:
        names = os.listdir(folder)
    except OSError:
        return []
    start = f".{prefix}." if prefix else "."
    removed = []
    for name in names:
        if name.startswith(start) and is_temporary_name(name):
            path = folder / name
            if not _in_use(path):
                _remove(path)
                removed.append(path)
    return removed


def _exchange(a: Path, b: Path) -> bool:
    """Swap the paths `a` and `b` in one step (Linux ``renameat2(RENAME_EXCHANGE)``).

    Returns False, having changed nothing, where the system or file system has no
    such call; raises OSError for any other failure.
    """
    if not sys.platform.startswith("linux"):
        return False
    try:
        renameat2 = ctypes.CDLL(None, use_errno=True).renameat2
    except (AttributeError, OSError):  # pragma: no cover - a libc without it (musl < 1.2?)
        return False
    at_fdcwd, rename_exchange = -100, 2
    renameat2.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p]
    renameat2.argtypes += [ctypes.c_uint]
    if renameat2(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), rename_exchange) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errnos.ENOSYS, errnos.EINVAL, errnos.ENOTSUP, errnos.EOPNOTSUPP):
        return False
    raise OSError(err, os.strerror(err), str(b))


#: environment variable: ``0``: :meth:`StagedFolder.background` works in the process itself
#: (when its result is asked for); ``1``: in a forked child wherever one may be forked;
#: unset: in a child where a CPU is idle (:func:`_can_fork`)
BACKGROUND_ENV = "RAILVIB_BACKGROUND"

_PR_SET_PDEATHSIG = 1  # prctl(2): the signal a process gets when its parent dies


def _can_fork() -> bool:
    """Whether background work may run in a forked child, and pays.

    Linux only (the child is told to die with its parent, ``prctl(PR_SET_PDEATHSIG)``),
    with a second CPU to run on, no other Python thread (a thread holding a lock at the
    fork would leave it held in the child), and :data:`BACKGROUND_ENV` not ``0``. Unless
    it is ``1``, also only while a CPU is idle (the 1-minute load average at least half a
    CPU below their number): on a busy machine a second process gets no more CPU time
    than the first (the scheduler shares it out per session) and the fork's copied
    pages cost 0.3-0.7 s CPU more than drawing in the process (measured at load 10 on
    2 CPUs: 4.5 s against 3.9 s).
    """
    switch = os.environ.get(BACKGROUND_ENV, "")
    if switch == "0" or not sys.platform.startswith("linux") or threading.active_count() > 1:
        return False
    cpus = len(os.sched_getaffinity(0))
    if cpus < 2:
        return False
    return switch == "1" or os.getloadavg()[0] <= cpus - 0.5


@contextmanager
def _sigint_held() -> Iterator[None]:
    """Hold Ctrl-C (SIGINT) back in this thread for the block; a pending one follows it.

    A no-op where signal masks do not exist (Windows, where nothing is forked either).
    """
    if not hasattr(signal, "pthread_sigmask"):
        yield
        return
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)


def _die_with(parent: int) -> None:
    """In a forked child: be killed when the parent dies (SIGKILL included), or exit now."""
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    if os.getppid() != parent:  # the parent died before the line above
        os._exit(1)


class Background:
    """A function run in a forked child process while the caller goes on.

    Made by :meth:`StagedFolder.background`. Where no child may be forked
    (:func:`_can_fork`) the function runs in the process itself, when :meth:`result` is
    first called. The child inherits the loaded modules and the data (no copy, no
    pickling of the arguments); it sends back the function's return value or the
    exception it raised (pickled), and dies with its parent.

    Parameters
    ----------
    function : callable
        What to run; its return value and exceptions must pickle.
    *args
        Its arguments.
    """

    def __init__(self, function: Callable[..., Any], *args: Any) -> None:
        self._call = functools.partial(function, *args)
        self._pid: int | None = None
        self._fd: int | None = None
        if _can_fork():
            self._fork()

    @property
    def forked(self) -> bool:
        """Whether the function runs in a child process (else in this one, at :meth:`result`)."""
        return self._pid is not None

    def _fork(self) -> None:
        """Fork the child with Ctrl-C held back: the parent alone answers it.

        SIGINT is blocked across the fork; the child ignores it before unblocking (a
        Ctrl-C reaches the whole foreground group, and one arriving in the child's
        after-fork hooks printed "Exception ignored ... KeyboardInterrupt"), and the
        parent unblocks it after the fork, so a Ctrl-C pending there is raised in the
        parent, which stops the child (:meth:`cancel`, or the child's death signal).
        """
        read, write = os.pipe()
        parent = os.getpid()
        with _sigint_held():
            with warnings.catch_warnings():
                # Python >= 3.12 warns at any fork of a process with a second OS thread:
                # numpy's BLAS keeps an idle pool, which it shuts down around a fork itself
                warnings.filterwarnings(
                    "ignore", "This process .* multi-threaded", DeprecationWarning
                )
                pid = os.fork()
            if pid == 0:  # pragma: no cover - the child (its coverage is not collected)
                signal.signal(signal.SIGINT, signal.SIG_IGN)
                signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
                os.close(read)
                self._child(write, parent)
            os.close(write)
            self._pid, self._fd = pid, read

    def _child(self, fd: int, parent: int) -> None:  # pragma: no cover - the child
        """Run the function, send its outcome down `fd`, and exit (never returns)."""
        code = 1
        try:
            _die_with(parent)
            try:
                outcome: tuple[str, Any] = ("ok", self._call())
            except BaseException as exc:  # noqa: BLE001 - sent to the parent, raised there
                outcome = ("error", exc)
            try:
                data = pickle.dumps(outcome)
            except Exception as exc:  # noqa: BLE001 - an unpicklable outcome
                data = pickle.dumps(("error", RuntimeError(f"{outcome[1]!r} ({exc})")))
            with os.fdopen(fd, "wb") as out:
                out.write(data)
            code = 0
        finally:
            os._exit(code)  # no cleanup of the parent's state (its staging folder, files)

    def result(self) -> Any:
        """The function's return value (waiting for the child); its exception is raised here.

        Returns
        -------
        object
            What the function returned. A child that died without a word (killed) is
            replaced by running the function here.
        """
        if self._pid is None:
            return self._call()
        assert self._fd is not None
        with os.fdopen(self._fd, "rb") as pipe:
            self._fd = None
            data = pipe.read()
        os.waitpid(self._pid, 0)
        self._pid = None
        if not data:  # the child was killed (out of memory, ...): do the work here
            return self._call()
        status, value = pickle.loads(data)  # noqa: S301 - our own child's bytes
        if status == "error":
            raise value
        return value

    def cancel(self) -> None:
        """Stop the child, if any, and wait for it (the work is abandoned)."""
        if self._pid is not None:
            try:
                os.kill(self._pid, signal.SIGKILL)
            except ProcessLookupError:  # pragma: no cover - already reaped
                pass
            os.waitpid(self._pid, 0)
            self._pid = None
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None


class StagedFolder:
    """The staging folder of a command's output (see :func:`staged_folder`).

    Parameters
    ----------
    target : pathlib.Path
        The output folder as the user named it (shown in messages and file lists).
    path : pathlib.Path
        The staging folder the command writes into.
    """

    def __init__(self, target: Path, path: Path) -> None:
        self.target = target
        self.path = path
        self._background: list[Background] = []

    def background(self, function: Callable[..., Any], *args: Any) -> Background:
        """Run ``function(*args)`` beside the command, in a second process where possible.

        For files written into :attr:`path` while the command writes others (``railvib
        run`` draws its figures while it writes ``results.nc`` and the tables). The
        command collects the outcome with :meth:`Background.result` before the block
        ends; if the block fails or is interrupted first, the child is stopped before
        the staging folder is removed.

        Parameters
        ----------
        function : callable
            What to run (its return value and exceptions must pickle).
        *args
            Its arguments.

        Returns
        -------
        Background
            The work under way.
        """
        # Ctrl-C held back until the work is on the list: one raised between the fork
        # and the append would leave a child writing into a stage being removed
        with _sigint_held():
            work = Background(function, *args)
            self._background.append(work)
        return work

    def _cancel(self) -> None:
        for work in self._background:
            work.cancel()

    def final(self, path: str | Path) -> Path:
        """Where the staged file `path` lies once the folder is committed.

        Parameters
        ----------
        path : str or pathlib.Path
            A file inside :attr:`path`.

        Returns
        -------
        pathlib.Path
            The same file below :attr:`target`.
        """
        return self.target / Path(path).relative_to(self.path)

    def finals(self, paths: Iterable[str | Path]) -> list[Path]:
        """:meth:`final` of each of `paths`.

        Parameters
        ----------
        paths : iterable of str or pathlib.Path
            Files inside :attr:`path`.

        Returns
        -------
        list of pathlib.Path
        """
        return [self.final(p) for p in paths]


def _kind(path: Path) -> str:
    mode = path.stat().st_mode
    if stat.S_ISCHR(mode):
        return "a character device"
    if stat.S_ISBLK(mode):
        return "a block device"
    if stat.S_ISFIFO(mode):
        return "a named pipe"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "a file"


def _check_folder_path(target: Path, field: str) -> None:
    """Refuse a `target` that is not a folder or lies below a file (before any work)."""
    try:
        if target.exists() and not target.is_dir():
            raise CaseError(field, str(target), f"a folder, not {_kind(target)}")
        for above in target.parents:
            if above.exists():
                if not above.is_dir():
                    raise CaseError(
                        field, str(target), f"a folder path ({str(above)!r} is {_kind(above)})"
                    )
                break
    except OSError as exc:  # e.g. a component that cannot be searched
        raise CaseError(field, str(target), f"a folder ({os_error_reason(exc)})") from None


def _check_writable(real: Path, target: Path) -> None:
    """Refuse an existing folder that cannot be written (read-only file system or mode)."""
    if not real.is_dir():
        return
    if os.statvfs(real).f_flag & os.ST_RDONLY:
        err = errnos.EROFS
    elif not os.access(real, os.W_OK | os.X_OK):  # as root: only without CAP_DAC_OVERRIDE
        err = errnos.EACCES
    else:
        return
    raise OutputError(target, os.strerror(err), err)


def _walk_files(root: Path) -> list[str]:
    """Every non-folder entry below `root`, as relative POSIX paths."""
    out = []
    for folder, dirs, files in os.walk(root):
        rel = Path(folder).relative_to(root)
        out += [(rel / name).as_posix() for name in files]
        out += [(rel / name).as_posix() for name in dirs if (Path(folder) / name).is_symlink()]
    return sorted(out)


def _only_owned(folder: Path, owned: Collection[str]) -> bool:
    """Whether `folder` holds nothing but `owned` files (and their folders) and temporaries."""
    owned_dirs = {p.as_posix() for name in owned for p in Path(name).parents if str(p) != "."}
    for here, dirs, files in os.walk(folder):
        rel = Path(here).relative_to(folder)
        for name in files:
            if (rel / name).as_posix() not in owned and not is_temporary_name(name):
                return False
        for name in list(dirs):
            rel_dir = (rel / name).as_posix()
            if is_temporary_name(name):
                dirs.remove(name)
            elif rel_dir not in owned_dirs or (Path(here) / name).is_symlink():
                return False
    return True


def _contains_cwd(folder: Path) -> bool:
    try:
        cwd = Path(os.getcwd()).resolve()
    except OSError:
        return False
    return cwd == folder or folder in cwd.parents


def _folder_mode() -> int:
    umask = os.umask(0)
    os.umask(umask)
    return 0o777 & ~umask


@contextmanager
def staged_folder(
    outdir: str | Path, owned: Collection[str] = (), *, field: str = "output"
) -> Iterator[StagedFolder]:
    """Write a command's files into a staging folder; put them in `outdir` only if all succeed.

    The block writes into ``staged.path``. When it ends without an error the set is
    committed: a new `outdir` (or one that holds nothing but files of `owned` and
    railvib's temporaries, i.e. an earlier result of the same command) is replaced by
    the staging folder in one step (Linux ``renameat2(RENAME_EXCHANGE)``; elsewhere
    two renames), so whatever moment the process is killed, `outdir` holds either the
    complete earlier set or the complete new one. A folder that also holds other
    files (a case file, the user's notes) keeps them: the new files are renamed into
    it one by one and the earlier `owned` files the new set lacks are removed (a
    commit of a few milliseconds). When the block fails (or is interrupted), the
    staging folder and any folder made for it are removed: nothing new is left.

    Temporaries of earlier runs that were killed (:func:`remove_temporaries`) are
    removed on entry, before any work.

    Parameters
    ----------
    outdir : str or pathlib.Path
        The output folder (created if missing, with its parents).
    owned : collection of str
        Relative POSIX paths of every file the command may write there (e.g.
        ``"results.nc"``, ``"cases/x.toml"``): the earlier set it replaces.
    field : str
        The option naming the folder, in error messages.

    Yields
    ------
    StagedFolder
        ``.path``: the folder to write into; ``.final(p)``: where a file ends up.

    Raises
    ------
    CaseError
        `outdir` is not a folder (a file, ``/dev/full``) or lies below a file (on
        entry, before the block runs).
    OutputError
        The folder cannot be created or written (a read-only file system or folder,
        no permission, a full disk), on entry, before the block runs; or a file of the
        block, named by its final path.
    """
    target = Path(outdir)
    _check_folder_path(target, field)
    real = Path(os.path.realpath(target))
    _check_writable(real, target)
    made = [p for p in (real, *real.parents) if not p.exists()]
    try:
        real.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise _output_error(target, exc) from None
    remove_temporaries(real.parent, real.name)
    if real.is_dir():
        remove_temporaries(real)
        for sub in {Path(name).parent for name in owned} - {Path(".")}:
            remove_temporaries(real / sub)
    beside = not (real.is_dir() and os.path.ismount(real))
    try:
        stage = _make_stage(real, beside)
    except OSError as exc:
        if not beside or not real.is_dir():
            _remove_made(made)
            raise _output_error(target, exc) from None
        beside = False  # the parent is not writable: stage inside the folder itself
        try:
            stage = _make_stage(real, beside)
        except OSError as exc2:
            raise _output_error(target, exc2) from None
    lock = _lock(stage)
    staged = StagedFolder(target, stage)
    try:
        try:
            yield staged
        except OutputError as exc:
            raise _renamed(exc, staged) from None
        staged._cancel()  # background work not collected: stopped before the commit
        try:
            _commit(stage, real, owned, beside)
        except OSError as exc:
            raise _output_error(target, exc) from None
    except BaseException:
        staged._cancel()  # no child writing into the stage while it is removed
        _remove(stage)
        _remove_made(made)
        raise
    finally:
        if lock is not None:
            os.close(lock)


def _make_stage(real: Path, beside: bool) -> Path:
    if beside:
        stage = Path(tempfile.mkdtemp(prefix=f".{real.name}.", suffix=".part", dir=real.parent))
    else:
        real.mkdir(exist_ok=True)
        stage = Path(tempfile.mkdtemp(prefix=".railvib.", suffix=".part", dir=real))
    os.chmod(stage, _folder_mode())  # mkdtemp makes 0700; give the usual folder mode
    return stage


def _remove_made(made: list[Path]) -> None:
    for path in made:  # innermost first; only folders this call made, and only if empty
        try:
            path.rmdir()
        except OSError:
            pass


def _renamed(exc: OutputError, staged: StagedFolder) -> OutputError:
    try:
        return exc.with_path(staged.final(exc.path))
    except ValueError:  # not a staged file
        return exc


def _commit(stage: Path, real: Path, owned: Collection[str], beside: bool) -> None:
    """Put the staged files in place (see :func:`staged_folder`)."""
    if beside and not os.path.lexists(real):
        os.rename(stage, real)
        return
    if beside and real.is_dir() and _only_owned(real, owned) and not _contains_cwd(real):
        os.chmod(stage, stat.S_IMODE(real.stat().st_mode))
        if _exchange(stage, real):
            _remove(stage)  # now the earlier set
            return
        aside = real.parent / f".{real.name}.{secrets.token_hex(4)}.old"
        os.rename(real, aside)
        os.rename(stage, real)
        _remove(aside)
        return
    new = _walk_files(stage)
    for rel in new:
        (real / rel).parent.mkdir(parents=True, exist_ok=True)
        os.replace(stage / rel, real / rel)
    for rel in set(owned) - set(new):
        stale = real / rel
        if stale.is_file() or stale.is_symlink():
            stale.unlink()
    _remove(stage)


#: leading bytes of the binary files a user may pass by mistake, and what they are
_MAGIC = (
    (b"\x89HDF\r\n\x1a\n", "a netCDF-4/HDF5 file (e.g. results.nc)"),
    (b"CDF\x01", "a netCDF file"),
    (b"CDF\x02", "a netCDF file"),
    (b"\x89PNG\r\n\x1a\n", "a PNG image"),
    (b"%PDF", "a PDF file"),
    (b"PK\x03\x04", "a zip archive"),
    (b"\x1f\x8b", "a gzip archive"),
)


def binary_kind(data: bytes) -> str | None:
    """What a file starting with `data` is, if it is not text (None for text).

    Parameters
    ----------
    data : bytes
        The first bytes of the file (a few hundred are enough).

    Returns
    -------
    str or None
        E.g. ``"a netCDF-4/HDF5 file (e.g. results.nc)"``, ``"a PNG image"`` or
        ``"a binary file"`` (one holding NUL bytes); None for text, in any encoding:
        :func:`read_text` says where text that is not UTF-8 is not.
    """
    for magic, kind in _MAGIC:
        if data.startswith(magic):
            return kind
    if b"\x00" in data:
        return "a binary file"
    return None


def read_text(
    path: str | Path, field: str, what: str, *, hint: str = "", max_bytes: int = MAX_TABLE_BYTES
) -> str:
    """The UTF-8 text of the input file `path`; any other file is a one-line error.

    Refused, each naming `path`: a file that cannot be read, a folder, a device or
    pipe (``/dev/zero``), a file over `max_bytes`, a binary file (:func:`binary_kind`)
    and text that is not UTF-8 (with the offset and line of the first bad byte).
    A leading byte-order mark is dropped.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.
    field : str
        The field the file is given as (``"case"``, ``"irregularity.path"``), named in
        the error.
    what : str
        What the file should be, for the error (``"TOML case file"``, ``"CSV table"``).
    hint : str
        Where to get a good file, appended to the error for a binary file.
    max_bytes : int
        Largest size accepted, bytes.

    Returns
    -------
    str
        The text.

    Raises
    ------
    CaseError
        ``<field> = '<path>': a <what> ...`` saying what is wrong with the file.
    """
    path = Path(path)
    tail = f"; {hint}" if hint else ""
    try:
        info = path.stat()  # before opening: opening a pipe would wait for a writer
        mode = info.st_mode
        if stat.S_ISDIR(mode):
            raise IsADirectoryError(21, "Is a directory")
        if not stat.S_ISREG(mode):
            raise CaseError(field, str(path), f"a {what} (a regular file, not a device or pipe)")
        if info.st_size > max_bytes:
            raise _too_large(field, path, what, max_bytes, info.st_size)
        with open(path, "rb") as fh:
            raw = fh.read(max_bytes + 1)
    except OSError as exc:
        raise CaseError(field, str(path), f"a readable {what} ({exc.strerror})") from None
    if len(raw) > max_bytes:  # it grew since stat()
        raise _too_large(field, path, what, max_bytes, len(raw))
    kind = binary_kind(raw[:4096])
    if kind is not None:
        raise CaseError(field, str(path), f"a {what}, not {kind}{tail}")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw.count(b"\n", 0, exc.start) + 1
        raise CaseError(
            field,
            str(path),
            f"a {what} in UTF-8 text; byte 0x{raw[exc.start]:02x} at offset {exc.start} (line "
            f"{line}) is not UTF-8: save the file as UTF-8",
        ) from None
    return text.removeprefix("\ufeff")


def _too_large(field: str, path: Path, what: str, max_bytes: int, size: int) -> CaseError:
    return CaseError(
        field,
        str(path),
        f"a {what} of at most {max_bytes / 2**20:g} MiB; this one has {size / 2**20:.3g} MiB",
    )


def read_toml(path: str | Path, field: str, hint: str = "") -> dict[str, Any]:
    """Parse the TOML file `path`; an unreadable or invalid file is a one-line error.

    Parameters
    ----------
    path : str or pathlib.Path
        The file (UTF-8 text of at most :data:`MAX_TOML_BYTES`, see :func:`read_text`).
    field : str
        What the file is (``"case"``, ``"sweep"``), named in the error.
    hint : str
        Where to get a good file, appended to the error when the file is binary or
        empty (e.g. ``"`railvib template > case.toml` writes one"``).

    Returns
    -------
    dict
        The parsed tables (nested at most :data:`MAX_NESTING` levels deep).

    Raises
    ------
    CaseError
        ``<field> = '<path>': a readable TOML file (...)``, ``a TOML <field> file (text),
        not a netCDF-4/HDF5 file ...`` (or another binary kind, text that is not UTF-8,
        or an empty file), ``valid TOML (...)``, or a value nested too deep (named by
        its dotted key).
    """
    text = read_text(path, field, f"TOML {field} file", hint=hint, max_bytes=MAX_TOML_BYTES)
    if not text.strip():
        tail = f"; {hint}" if hint else ""
        raise CaseError(field, str(path), f"a TOML {field} file, not an empty file{tail}")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CaseError(field, str(path), f"valid TOML ({exc})") from None
    except RecursionError:  # arrays or inline tables some 400 levels deep
        raise CaseError(
            field, str(path), f"TOML nested at most {MAX_NESTING} levels deep (arrays, tables)"
        ) from None
    check_nesting(data, field)
    return data


def check_nesting(data: Any, field: str, limit: int = MAX_NESTING) -> None:
    """Refuse tables and lists nested more than `limit` levels deep in `data`.

    Validation, copies and model builders recurse into nested tables; a limit
    well above what any case needs turns a hostile input into a one-line error
    instead of a ``RecursionError``. The walk itself does not recurse.

    Parameters
    ----------
    data : object
        Parsed input (dicts, lists, tuples and scalars).
    field : str
        Name of `data` in errors (``"case"``).
    limit : int
        Deepest nesting accepted (levels below `data`).

    Raises
    ------
    CaseError
        Naming the dotted key where the nesting passes `limit`.
    """
    stack: list[tuple[Any, tuple[str, ...]]] = [(data, ())]
    while stack:
        node, where = stack.pop()
        if isinstance(node, dict):
            children = [(v, (*where, str(k))) for k, v in node.items()]
        elif isinstance(node, list | tuple):
            children = [(v, (*where, f"[{i}]")) for i, v in enumerate(node)]
        else:
            continue
        if children and len(where) >= limit:
            shown = ".".join(where[:8]).replace(".[", "[")
            raise CaseError(
                f"{shown}..." if len(where) > 8 else shown or field,
                f"<nested deeper than {limit} levels>",
                f"tables and lists nested at most {limit} levels deep",
            )
        stack.extend(children)


def write_text(path: str | Path, text: str) -> Path:
    """Write `text` (UTF-8) to `path` atomically and return the path."""
    path = Path(path)
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return path


def new_figure(
    figsize: tuple[float, float],
    *,
    layout: Literal["constrained", "compressed", "tight"] | None = None,
    **subplots: Any,
) -> tuple[Figure, Any]:
    """A figure and its axes for writing to a file, outside pyplot.

    A :class:`matplotlib.figure.Figure` made directly has no GUI window and needs
    no backend, so a library that writes figures neither switches the user's
    backend nor opens windows, and is not slowed by pyplot's figure manager.
    (Plot functions called without axes still draw on a new pyplot figure, for
    interactive use.)

    Parameters
    ----------
    figsize : (float, float)
        Width and height of the figure (unit: inch).
    layout : str, optional
        Layout engine (``"constrained"``, ``"tight"``) or None.
    **subplots
        Passed to :meth:`matplotlib.figure.Figure.subplots` (``nrows``, ``ncols``,
        ``sharex``, ``squeeze``, ...).

    Returns
    -------
    (matplotlib.figure.Figure, axes)
        The figure and what ``Figure.subplots`` returns (one Axes or an array).
    """
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, layout=layout)
    return fig, fig.subplots(**subplots)


def save_figure(
    fig: Figure | Axes, path: str | Path, *, dpi: int = FIGURE_DPI, tight: bool = True
) -> Path:
    """Write `fig` as a PNG atomically, then close it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure or matplotlib.axes.Axes
        The figure, or axes whose (top-level) figure is written.
    path : str or pathlib.Path
        The PNG file.
    dpi : int
        Resolution, dots per inch.
    tight : bool
        Apply ``fig.tight_layout()`` before saving.

    Returns
    -------
    pathlib.Path
        `path`.
    """
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    if isinstance(fig, Axes):
        fig = fig.get_figure(root=True)  # type: ignore[assignment]
    if not isinstance(fig, Figure):
        raise TypeError(f"save_figure needs a matplotlib Figure or Axes, not {type(fig).__name__}")
    if tight:
        fig.tight_layout()
    path = Path(path)
    try:
        with atomic_path(path) as tmp:
            fig.savefig(
                tmp, dpi=dpi, format="png", pil_kwargs={"compress_level": PNG_COMPRESS_LEVEL}
            )
    finally:
        if fig.canvas.manager is not None:  # a pyplot figure: release it (else nothing holds it)
            import matplotlib.pyplot as plt

            plt.close(fig)
    return path
