"""Writing files and stamping them: atomic writes, figures, provenance.

Every file railvib writes goes through :func:`atomic_path` (a temporary file next
to the target, renamed onto it only when the writer succeeds), so a file is
either complete or absent whatever moment a run is stopped. Every PNG goes
through :func:`save_figure`, so figures share one resolution and are closed
after saving.
"""

from __future__ import annotations

import os
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
    "atomic_path",
    "new_figure",
    "binary_kind",
    "railvib_version",
    "read_toml",
    "save_figure",
    "write_text",
]

#: resolution of every PNG railvib writes, dots per inch
FIGURE_DPI = 110


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
        ``"a binary file"``; None when `data` is UTF-8 text without NUL bytes.
    """
    for magic, kind in _MAGIC:
        if data.startswith(magic):
            return kind
    if b"\x00" in data:
        return "a binary file"
    try:
        data.decode("utf-8")
    except UnicodeDecodeError as exc:
        if exc.start < len(data) - 4:  # not merely a character cut at the end of `data`
            return "a binary file"
    return None


def read_toml(path: str | Path, field: str, hint: str = "") -> dict[str, Any]:
    """Parse the TOML file `path`; an unreadable or invalid file is a one-line error.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.
    field : str
        What the file is (``"case"``, ``"sweep"``), named in the error.
    hint : str
        Where to get a good file, appended to the error when the file is binary or
        empty (e.g. ``"`railvib template > case.toml` writes one"``).

    Returns
    -------
    dict
        The parsed tables.

    Raises
    ------
    CaseError
        ``<field> = '<path>': a readable TOML file (...)``, ``a TOML <field> file, not
        a netCDF-4/HDF5 file ...`` (or another binary kind, or an empty file) or
        ``valid TOML (...)``.
    """
    try:
        raw = Path(path).read_bytes()
    except OSError as exc:
        raise CaseError(field, str(path), f"a readable TOML file ({exc.strerror})") from None
    tail = f"; {hint}" if hint else ""
    kind = binary_kind(raw[:4096])
    if kind is not None:
        raise CaseError(field, str(path), f"a TOML {field} file, not {kind}{tail}")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise CaseError(field, str(path), f"a UTF-8 TOML text file ({exc.reason})") from None
    if not text.strip():
        raise CaseError(field, str(path), f"a TOML {field} file, not an empty file{tail}")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CaseError(field, str(path), f"valid TOML ({exc})") from None


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
