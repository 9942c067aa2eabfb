"""xarray's probes for dask, deferred until dask is loaded (``railvib run`` start-up).

Where dask is installed, xarray imports it to answer questions whose answer is "no"
while it is not loaded: whether the data of each variable it makes is a dask array
(the first answer imports ``dask.array``: 0.2-0.4 s), whether it is any dask collection
(imports ``dask``: 0.1 s), and, at every ``to_netcdf``, which dask scheduler is active
(imports ``dask`` and ``distributed``: 0.3 s). A ``railvib run`` makes no dask array,
and an object can only be a dask array or collection, or a scheduler be active, once
dask is loaded; so :func:`defer_dask_probe` makes the three answer from the modules
loaded: "no" (no array, no collection, no scheduler: xarray's answer where dask is not
installed) while dask is not, dask's own answer once it is (a later ``import
dask.array`` and its arrays work as before). A version of xarray without these
internals is left as it is.
"""

from __future__ import annotations

import functools
import sys
from collections.abc import Callable
from typing import Any

__all__ = ["defer_dask_probe"]


class _DaskArrayType(type):
    """``isinstance(x, DaskArrayIfLoaded)``: whether `x` is a ``dask.array.Array``, if loaded."""

    def __instancecheck__(cls, obj: object) -> bool:
        module = sys.modules.get("dask.array")
        return module is not None and isinstance(obj, module.Array)


class DaskArrayIfLoaded(metaclass=_DaskArrayType):
    """Stands for ``dask.array.Array`` in xarray's type tests without importing dask."""


def _is_dask_collection(x: object) -> bool:
    """The ``is_dask_collection`` of xarray, false without importing dask while it is not loaded."""
    base = sys.modules.get("dask.base")
    return base is not None and bool(base.is_dask_collection(x))


def _scheduler(original: Callable[..., str | None]) -> Callable[..., str | None]:
    """The ``get_dask_scheduler`` of xarray, None (no scheduler) while dask is not loaded."""

    @functools.wraps(original)
    def get_dask_scheduler(get: Any = None, collection: Any = None) -> str | None:
        if "dask" not in sys.modules:
            return None
        return original(get, collection)

    return get_dask_scheduler


def defer_dask_probe() -> bool:
    """Make xarray's dask tests answer from the loaded modules, not by importing dask.

    Returns
    -------
    bool
        Whether xarray's probes were replaced (False: dask is loaded already, or this
        xarray has other internals; nothing changed).
    """
    if "dask" in sys.modules:
        return False
    try:
        from xarray.backends import locks, writers
        from xarray.namedarray import pycompat, utils
    except ImportError:  # pragma: no cover - another layout of xarray
        return False
    cache: Any = getattr(pycompat, "_cached_duck_array_modules", None)
    module_type: Any = getattr(pycompat, "DuckArrayModule", None)
    if not isinstance(cache, dict) or module_type is None or "dask" in cache:
        return False
    probes = (utils.__dict__.get("is_dask_collection"), writers.__dict__.get("get_dask_scheduler"))
    if not all(map(callable, probes)) or probes[1] is not locks.get_dask_scheduler:
        return False
    cache["dask"] = _DeferredDask()
    utils.is_dask_collection = _is_dask_collection  # type: ignore[assignment]
    writers.get_dask_scheduler = locks.get_dask_scheduler = _scheduler(locks.get_dask_scheduler)
    return True


class _DeferredDask:
    """xarray's record of the dask module (``DuckArrayModule``), read when dask is loaded."""

    type = (DaskArrayIfLoaded,)

    def __getattr__(self, name: str) -> Any:
        """``module``, ``version``, ``available``: xarray's own record, made on first use."""
        from xarray.namedarray.pycompat import DuckArrayModule

        return getattr(DuckArrayModule("dask"), name)
