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
"""

from __future__ import annotations

import importlib
import importlib.util
from typing import TYPE_CHECKING, Any

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
