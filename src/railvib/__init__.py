"""railvib: frequency-domain random vibration of railway vehicle-track coupled systems.

The rail is an infinite periodic structure solved by the symplectic (wave)
method, the vehicle a 10-DOF pitch-plane car on linearised Hertz springs, and
the stationary track irregularity enters by the pseudo-excitation method.

Examples
--------
>>> import railvib
>>> case = railvib.load_preset_case()            # the paper's default case
>>> ds = railvib.run(case)                        # xarray.Dataset of PSDs and FRFs
>>> railvib.summary(ds).dominant_frequency.sel(response="bogie1.bounce").item() < 10
True
"""

from railvib.case import Case, build_system, case_from_dict, load_case
from railvib.coupling import CoupledSystem
from railvib.errors import CaseError, RailvibError, SolverWarning
from railvib.grid import FrequencyGrid
from railvib.presets import DEFAULT_PRESET, list_presets
from railvib.results import load_netcdf, save_netcdf, summary
from railvib.solve import run, run_system
from railvib.track import PeriodicTrack, Rail
from railvib.vehicle import Vehicle, pitch_plane_10dof


def load_preset_case(name: str = DEFAULT_PRESET) -> Case:
    """The validated case of preset `name` (default: the paper's analysis)."""
    return case_from_dict({"preset": name})


__all__ = [
    "Case",
    "CaseError",
    "CoupledSystem",
    "FrequencyGrid",
    "PeriodicTrack",
    "Rail",
    "RailvibError",
    "SolverWarning",
    "Vehicle",
    "build_system",
    "case_from_dict",
    "list_presets",
    "load_case",
    "load_netcdf",
    "load_preset_case",
    "pitch_plane_10dof",
    "run",
    "run_system",
    "save_netcdf",
    "summary",
]
