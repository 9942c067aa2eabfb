"""Exception and warning classes of railvib.

Every error a user can trigger through bad input is a :class:`CaseError`, whose
message names the field, the value received and what is allowed, on one line.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable
from typing import Any

__all__ = [
    "CaseError",
    "DamagedOutputWarning",
    "LinearModelInvalid",
    "NonFiniteResult",
    "OutputError",
    "PlausibilityWarning",
    "RailvibDeprecationWarning",
    "RailvibError",
    "SolverWarning",
    "did_you_mean",
    "excerpt",
]

#: longest text of a value a :class:`CaseError` message shows (longer ones are cut)
MAX_VALUE_CHARS = 200


class RailvibError(Exception):
    """Base class of every railvib error."""

    #: exit code of the command line when this error ends a command
    exit_code: int = 2


class LinearModelInvalid(RailvibError):
    """A result lies beyond the linear model (``--strict``): loss of contact above the threshold.

    The results are written all the same; the command line exits with code 3.
    """

    exit_code = 3


class OutputError(RailvibError, OSError):
    """A file or folder could not be written: names it and why, on one line.

    Raised for the environment's faults (a full disk, a file-size limit, a read-only
    or missing folder, a path below a file), never with a partial file left behind
    (:func:`railvib.io.atomic_path`). It is an :class:`OSError` too, so code that
    catches those keeps working; the command line prints it as one ``error:`` line
    and exits with code 2.

    Parameters
    ----------
    path : str or os.PathLike
        The file or folder that could not be written, as the user named it.
    reason : str
        Why, e.g. ``"No space left on device"``.
    errno : int, optional
        The operating system's error number (``errno.ENOSPC``, ...).
    """

    def __init__(self, path: Any, reason: str, errno: int | None = None) -> None:
        self.path = str(path)
        self.reason = reason
        Exception.__init__(self, f"cannot write {self.path}: {reason}")
        self.errno = errno
        self.strerror = reason
        self.filename = self.path

    def __str__(self) -> str:
        return f"cannot write {self.path}: {self.reason}"

    def __reduce__(self) -> tuple[Any, ...]:
        return (type(self), (self.path, self.reason, self.errno))

    def with_path(self, path: Any) -> OutputError:
        """The same error naming `path` instead (e.g. the final name of a staged file).

        Parameters
        ----------
        path : str or os.PathLike
            The name to show.

        Returns
        -------
        OutputError
        """
        return type(self)(path, self.reason, self.errno)


class NonFiniteResult(RailvibError):
    """A computed result holds NaN or infinite values; nothing is written.

    The message names the variable, how many frequencies are affected and the first
    one (Hz); the inputs behind it are beyond what the solver resolves in floating
    point (the command line exits with code 2).
    """


class CaseError(RailvibError, ValueError):
    """Invalid input: names the field, the value and what is allowed.

    Parameters
    ----------
    field : str
        Dotted name of the offending field, e.g. ``"vehicle.carbody_mass"``.
    value : Any
        The value received.
    allowed : str
        What would have been accepted, with units, e.g. ``"> 0 (kg)"``.
    """

    def __init__(self, field: str, value: Any, allowed: str) -> None:
        self.field = field
        self.value = value
        self.allowed = allowed
        super().__init__(f"{field} = {_shown(value)}: {allowed}")


class PlausibilityWarning(UserWarning):
    """Legal but suspicious input (a likely unit slip or typo): names the field and the value.

    The case is run as given; the message says why the value looks wrong, on one line
    (``field = value: why (unit)``), and the CLI prints it as ``warning: <message>``.
    Escalate it with ``-W error::railvib.errors.PlausibilityWarning`` to refuse such
    cases, or filter it to silence it.

    Parameters
    ----------
    field : str
        Dotted name of the field, e.g. ``"speed_kmh"``.
    value : Any
        The value received (or, for a derived quantity, a text naming it).
    note : str
        Why the value is suspicious, with units, e.g. ``"above 450 km/h, ..."``.
    """

    def __init__(self, field: str, value: Any, note: str) -> None:
        self.field = field
        self.value = value
        self.note = note
        super().__init__(f"{field} = {value!r}: {note}")

    def __reduce__(self) -> tuple[Any, ...]:
        return (type(self), (self.field, self.value, self.note))


class DamagedOutputWarning(UserWarning):
    """A file an earlier run left is damaged (truncated, unreadable); railvib rewrites it.

    E.g. a sweep chunk file cut short by a full disk: it is recomputed. The message
    names the file and what is done about it, on one line, and the CLI prints it as
    ``warning: <message>``.
    """


class SolverWarning(RuntimeWarning):
    """A numerical result may have lost accuracy (e.g. at the pinned-pinned frequency)."""


class RailvibDeprecationWarning(DeprecationWarning):
    """A public name or call form is deprecated; the message says what to call instead.

    The deprecated form keeps working (same result) until it is removed in a later
    release. Filter this class to silence or escalate railvib's deprecations alone.
    """


def _shown(value: Any) -> str:
    """``repr(value)``, cut to :data:`MAX_VALUE_CHARS` (a message never echoes a whole file)."""
    text = repr(value)
    if len(text) <= MAX_VALUE_CHARS:
        return text
    return f"{text[: MAX_VALUE_CHARS - 30]}... ({len(text):,} characters)"


def excerpt(text: str, limit: int = 40) -> str:
    """At most `limit` printable characters of `text`, for an error message about a file.

    A message must not echo a file's contents (the file may be anything a path
    points to, e.g. ``/etc/passwd``), but a few characters help to recognise it.

    Parameters
    ----------
    text : str
        Text read from a file (a header cell, a row).
    limit : int
        Most characters kept (a count).

    Returns
    -------
    str
        `text` with every non-printable character (control characters, line breaks)
        replaced by ``?``, cut to `limit` characters with ``...`` when longer.
    """
    clean = "".join(c if c.isprintable() else "?" for c in str(text)[: limit + 1])
    return clean if len(clean) <= limit else clean[: max(limit - 3, 0)] + "..."


def did_you_mean(word: Any, choices: Iterable[str]) -> str:
    """``"; did you mean 'speed_kmh'?"`` when `word` is close to one of `choices`, else ``""``.

    Parameters
    ----------
    word : Any
        The unknown key or name a user wrote (non-text gives ``""``).
    choices : iterable of str
        The keys or names allowed there.

    Returns
    -------
    str
        The suggestion, to append to a :class:`CaseError`'s `allowed` text: the
        closest choice by :func:`difflib.get_close_matches` (similarity >= 0.6), else
        the one choice that `word` (3 characters or more) begins, as in ``dampin`` ->
        ``damping_ns_per_m``.
    """
    if not isinstance(word, str):
        return ""
    names = [str(c) for c in choices]
    close = difflib.get_close_matches(word, names, n=1, cutoff=0.6)
    if not close and len(word) >= 3:
        close = [c for c in names if c.startswith(word)]
    return f"; did you mean {close[0]!r}?" if len(close) == 1 else ""
