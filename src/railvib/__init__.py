"""railvib: frequency-domain random vibration of railway vehicle-track coupled systems.

The rail is an infinite periodic structure solved by the symplectic (wave)
method, the vehicle a 10-DOF pitch-plane car on linearised Hertz springs, and
the stationary track irregularity enters by the pseudo-excitation method.

The names below load on first use (PEP 562), so ``import railvib`` and the
command line start without the numerical stack (numpy, scipy, xarray).

Examples
--------
>>> import railvib
>>> case = railvib.load_preset_case()            # the paper's default case
>>> ds = railvib.run(case)                        # xarray.Dataset of PSDs and FRFs
>>> railvib.summary(ds).dominant_frequency.sel(response="bogie1.bounce").item() < 10
True
>>> float(ds.railvib.rms().sel(response="carbody.bounce")) > 0  # the xarray accessor
True

Importing railvib registers the accessor ``ds.railvib`` (:mod:`railvib.accessor`) on
``xarray.Dataset``: at once when xarray is already imported, else as soon as it is, so
``import railvib`` does not load xarray; :mod:`railvib.accessor` itself loads on the
first use of ``ds.railvib``.
"""

from __future__ import annotations

import importlib
import importlib.util
import sys
from types import ModuleType
from typing import TYPE_CHECKING, Any, cast

if TYPE_CHECKING:  # what the facade gives, for type checkers and IDEs
    from railvib.case import Case, build_system, case_from_dict, load_case, load_preset_case  # noqa: F401
    from railvib.coupling import CoupledSystem  # noqa: F401
    from railvib.errors import CaseError, PlausibilityWarning, RailvibError, SolverWarning  # noqa: F401
    from railvib.grid import FrequencyGrid  # noqa: F401
    from railvib.presets import DEFAULT_PRESET, list_presets  # noqa: F401
    from railvib.results import load_netcdf, save_netcdf, summary  # noqa: F401
    from railvib.solve import run, run_system  # noqa: F401
    from railvib.track import PeriodicTrack, Rail  # noqa: F401
    from railvib.vehicle import Vehicle, pitch_plane_10dof  # noqa: F401

#: the module of each public name, imported when the name is first used
_FACADE: dict[str, str] = {
    "Case": "railvib.case",
    "CaseError": "railvib.errors",
    "CoupledSystem": "railvib.coupling",
    "DEFAULT_PRESET": "railvib.presets",
    "FrequencyGrid": "railvib.grid",
    "PeriodicTrack": "railvib.track",
    "PlausibilityWarning": "railvib.errors",
    "Rail": "railvib.track",
    "RailvibError": "railvib.errors",
    "SolverWarning": "railvib.errors",
    "Vehicle": "railvib.vehicle",
    "build_system": "railvib.case",
    "case_from_dict": "railvib.case",
    "list_presets": "railvib.presets",
    "load_case": "railvib.case",
    "load_netcdf": "railvib.results",
    "load_preset_case": "railvib.case",
    "pitch_plane_10dof": "railvib.vehicle",
    "run": "railvib.solve",
    "run_system": "railvib.solve",
    "save_netcdf": "railvib.results",
    "summary": "railvib.results",
}

__all__ = sorted(set(_FACADE) - {"DEFAULT_PRESET"})


def __getattr__(name: str) -> Any:
    """A public name (imported from its module), or a subpackage (``railvib.case``)."""
    if name in _FACADE:
        value = getattr(importlib.import_module(_FACADE[name]), name)
    elif not name.startswith("__") and importlib.util.find_spec(f"railvib.{name}") is not None:
        value = importlib.import_module(f"railvib.{name}")
    else:
        raise AttributeError(f"module 'railvib' has no attribute {name!r}")
    globals()[name] = value  # the next use is a plain attribute
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_FACADE))


#: the name of the xarray accessor, and the module and class it loads on first use
ACCESSOR = ("railvib", "railvib.accessor", "RailvibAccessor")


class _Accessor:
    """``xarray.Dataset.railvib``: loads :mod:`railvib.accessor` on first use, then its class.

    xarray's accessor protocol (a class attribute whose ``__get__`` gives the accessor
    of a dataset), without importing the accessor's module (and the numerical stack)
    when it is registered.
    """

    def __get__(self, ds: Any, owner: type | None = None) -> Any:
        _, module, name = ACCESSOR
        cls = getattr(importlib.import_module(module), name)
        return cls if ds is None else cls(ds)


def _register_accessor(xarray: ModuleType) -> None:
    """Put the ``railvib`` accessor on ``xarray.Dataset`` unless something holds the name."""
    dataset = xarray.Dataset
    if ACCESSOR[0] not in vars(dataset):
        setattr(dataset, ACCESSOR[0], _Accessor())


class _RegisterAfter:
    """The loader of xarray, wrapped: after xarray has run, the accessor is registered.

    Duck-typed (``create_module``, ``exec_module``): ``importlib.abc`` costs 50 ms to import.
    """

    def __init__(self, loader: Any) -> None:
        self._loader = loader

    def create_module(self, spec: Any) -> Any:
        return self._loader.create_module(spec)

    def exec_module(self, module: ModuleType) -> None:
        module.__loader__ = self._loader  # xarray's own loader again, for resources
        if module.__spec__ is not None:
            module.__spec__.loader = self._loader
        self._loader.exec_module(module)
        _register_accessor(module)


class _WhenXarrayIsImported:
    """A finder on ``sys.meta_path`` that waits for ``import xarray`` (then leaves)."""

    def find_spec(self, name: str, path: Any = None, target: Any = None) -> Any:
        if name != "xarray":
            return None
        sys.meta_path.remove(self)
        spec = importlib.util.find_spec(name)
        if spec is not None and spec.loader is not None:
            spec.loader = cast(Any, _RegisterAfter(spec.loader))  # a loader (duck-typed)
        return spec


if "xarray" in sys.modules:
    _register_accessor(sys.modules["xarray"])
else:
    sys.meta_path.insert(0, _WhenXarrayIsImported())
