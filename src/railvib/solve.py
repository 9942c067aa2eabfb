"""The one public call that wires the pipeline: case -> coupled FRFs -> PSD dataset."""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from railvib.case import Case, build_grid, build_spectrum, build_system, load_case
from railvib.coupling import CoupledSystem
from railvib.grid import FrequencyGrid
from railvib.io import railvib_version
from railvib.outputs import DEFAULT_OUTPUTS, LOSS_OF_CONTACT_NOTE, derive
from railvib.results.dataset import build_dataset
from railvib.spectra.base import SpatialSpectrum

__all__ = ["LOSS_OF_CONTACT_NOTE", "case_toml", "railvib_version", "run", "run_system"]


def case_toml(case: Case) -> str:
    """The full, resolved case as TOML text (same as :meth:`railvib.case.Case.to_toml`)."""
    return case.to_toml()


def run_system(
    system: CoupledSystem,
    grid: FrequencyGrid,
    spectrum: SpatialSpectrum,
    attrs: dict[str, str] | None = None,
) -> xr.Dataset:
    """Response PSDs and FRFs of a coupled system under a stationary irregularity.

    Parameters
    ----------
    system : CoupledSystem
        Vehicle, track, contact, wheel positions and speed.
    grid : FrequencyGrid
        Frequencies (Hz).
    spectrum : SpatialSpectrum
        Irregularity spectrum (spatial, one-sided).
    attrs : dict, optional
        Extra global attributes.

    Returns
    -------
    xarray.Dataset
        See :func:`railvib.results.build_dataset`.
    """
    f = grid.f
    frf = system.frf(f)
    s_r = spectrum.temporal(f, system.speed)
    pad_k = system.track.pad.stiffness(f, system.track.pad_temperature)
    extra = {
        "static_contact_load": xr.DataArray(
            system.vehicle.static_wheel_loads(),
            dims=("wheel",),
            attrs={"units": "N", "long_name": "static contact load"},
        ),
        "pad_stiffness": xr.DataArray(
            pad_k,
            dims=("frequency",),
            attrs={"units": "N/m", "long_name": "railpad dynamic stiffness K' + iK'' (beam model)"},
        ),
    }
    meta = {
        "railvib_version": railvib_version(),
        "speed_m_per_s": system.speed,
        "contact_stiffness_n_per_m": system.contact_stiffness,
        "wheel_positions_m": system.wheel_positions,
        "sleeper_spacing_m": system.track.sleeper_spacing,
        "time_dependence": "exp(+i omega t)",
        "sign_convention": "displacements positive downward; irregularity > 0 is a dip",
        **(attrs or {}),
    }
    return derive(build_dataset(frf, s_r, attrs=meta, extra=extra), DEFAULT_OUTPUTS)


def run(case: Case | str | Path) -> xr.Dataset:
    """Run one case (a validated :class:`~railvib.case.Case` or a TOML path).

    Examples
    --------
    >>> import railvib
    >>> ds = railvib.run(railvib.load_preset_case())
    >>> float(ds.psd_acceleration.sel(response="wheelset2.bounce").max()) > 0
    True
    """
    if not isinstance(case, Case):
        case = load_case(case)
    return run_system(
        build_system(case),
        build_grid(case),
        build_spectrum(case),
        attrs={"title": case.title, "case_toml": case.to_toml(), "rail_model": case.rail_model},
    )
