"""The deprecated parameter-bundle call forms of the validation API.

The reference models used to take the system as loose parameters (vehicle, rail,
pad, spacing, k_H, wheel position, speed, ...). They now take the
:class:`~railvib.coupling.CoupledSystem` of the symplectic path. A call whose first
argument is a :class:`~railvib.vehicle.Vehicle` is the old form: it still works,
with the old behaviour, and emits a :class:`~railvib.errors.RailvibDeprecationWarning`
naming the call to use instead.
"""

from __future__ import annotations

import functools
import warnings
from collections.abc import Callable
from typing import Any, ParamSpec, TypeVar

from railvib.coupling import CoupledSystem
from railvib.errors import RailvibDeprecationWarning
from railvib.vehicle.assembly import Vehicle

__all__ = ["SYSTEM_FROM_BUNDLE", "bundle_form", "warn_deprecated"]

P = ParamSpec("P")
T = TypeVar("T")

#: how to build the system the new forms take from the old parameters
SYSTEM_FROM_BUNDLE = (
    "system = CoupledSystem(vehicle, PeriodicTrack(rail, pad, sleeper_spacing, pad_temperature), "
    "contact_stiffness, leading_wheel_position, speed)"
)


def warn_deprecated(old: str, new: str, stacklevel: int = 3) -> None:
    """Emit a :class:`RailvibDeprecationWarning`: `old` is deprecated, call `new`.

    Parameters
    ----------
    old, new : str
        The deprecated call and its replacement, as code.
    stacklevel : int
        Passed to :func:`warnings.warn`; 3 points at the caller of the function that warns.
    """
    warnings.warn(
        f"{old} is deprecated; call {new} instead", RailvibDeprecationWarning, stacklevel=stacklevel
    )


def bundle_form(
    legacy: Callable[..., T], old: str, new: str
) -> Callable[[Callable[P, T]], Callable[P, T]]:
    """Decorate a ``func(system, ...)`` so that ``func(vehicle, ...)`` calls `legacy`, warning.

    Parameters
    ----------
    legacy : callable
        Implementation of the old parameter-bundle form.
    old, new : str
        The old and the new call, for the warning.
    """

    def decorate(func: Callable[P, T]) -> Callable[P, T]:
        @functools.wraps(func)
        def dispatch(*args: P.args, **kwargs: P.kwargs) -> T:
            first: Any = args[0] if args else kwargs.get("system", kwargs.get("vehicle"))
            if isinstance(first, CoupledSystem):
                return func(*args, **kwargs)
            if not isinstance(first, Vehicle):
                raise TypeError(
                    f"{func.__name__}() takes a railvib.coupling.CoupledSystem first, "
                    f"not {type(first).__name__}"
                )
            warn_deprecated(old, new)
            return legacy(*args, **kwargs)

        return dispatch

    return decorate
