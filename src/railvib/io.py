"""Writing files and stamping them: atomic writes, figures, provenance.

Every file railvib writes goes through :func:`atomic_path` (a temporary file next
to the target, renamed onto it only when the writer succeeds), so a file is
either complete or absent whatever moment a run is stopped. Every PNG goes
through :func:`save_figure`, so figures share one resolution and are closed
after saving.
"""

from __future__ import annotations

import os
import stat
import tempfile
import tomllib
from collections.abc import Iterator
from contextlib import contextmanager
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from railvib.errors import CaseError

if TYPE_CHECKING:  # matplotlib is imported only by code that draws
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = [
    "FIGURE_DPI",
    "MAX_NESTING",
    "MAX_TABLE_BYTES",
    "MAX_TOML_BYTES",
    "atomic_path",
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

#: largest case or sweep file read, bytes (4 MiB; the template is 5 kB, a sweep over
#: inline tables some 100 kB): a larger file is refused before it is parsed
MAX_TOML_BYTES = 4 * 2**20
#: largest CSV table read (irregularity spectrum, pad measurements), bytes (64 MiB, about
#: two million rows; a measured spectrum has some thousand)
MAX_TABLE_BYTES = 64 * 2**20
#: deepest nesting of tables and arrays in a case or sweep file (a case nests 5 levels:
#: irregularity.long_wave.long_wave...; deeper input is refused before Python recurses)
MAX_NESTING = 32


def railvib_version() -> str:
    """Installed railvib version (``"unknown"`` when run from a source tree)."""
    try:
        return version("railvib")
    except PackageNotFoundError:
        return "unknown"


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
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; give the usual file mode
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


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
            fig.savefig(tmp, dpi=dpi, format="png")
    finally:
        if fig.canvas.manager is not None:  # a pyplot figure: release it (else nothing holds it)
            import matplotlib.pyplot as plt

            plt.close(fig)
    return path
