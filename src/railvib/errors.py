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
    "PlausibilityWarning",
    "RailvibDeprecationWarning",
    "RailvibError",
    "SolverWarning",
    "did_you_mean",
]


class RailvibError(Exception):
    """Base class of every railvib error."""

    #: exit code of the command line when this error ends a command
    exit_code: int = 2


class LinearModelInvalid(RailvibError):
    """A result lies beyond the linear model (``--strict``): loss of contact above the threshold.

    The results are written all the same; the command line exits with code 3.
    """

    exit_code = 3


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
        super().__init__(f"{field} = {value!r}: {allowed}")


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
