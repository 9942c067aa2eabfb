"""The one public call that wires the pipeline: case -> coupled FRFs -> PSD dataset."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr
from numpy.typing import NDArray
from scipy.integrate import trapezoid
from scipy.stats import norm

from railvib.case import Case, build_grid, build_spectrum, build_system, load_case
from railvib.coupling import CoupledSystem
from railvib.grid import FrequencyGrid
from railvib.io import railvib_version
from railvib.results.dataset import build_dataset
from railvib.spectra.base import SpatialSpectrum

__all__ = ["contact_check", "case_toml", "railvib_version", "run", "run_system"]

#: probability of loss of contact above which ``railvib run`` prints a note
LOSS_OF_CONTACT_NOTE = 0.01


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
        **contact_check(system, f, frf.contact_force, s_r),
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
    return build_dataset(frf, s_r, attrs=meta, extra=extra)


def contact_check(
    system: CoupledSystem,
    f: NDArray[np.float64],
    force_frf: NDArray[np.complex128],
    irregularity_psd: NDArray[np.float64],
) -> dict[str, xr.DataArray]:
    """Linearity check: dynamic contact force against the static load of each contact.

    PEM (like any linear model) assumes the wheels never leave the rail. For a
    Gaussian force with RMS ``sigma`` over the analysed band, the probability that
    the dynamic force exceeds the static load ``P0`` in tension is ``Phi(-P0/sigma)``.
    ``railvib run`` prints a note where it exceeds :data:`LOSS_OF_CONTACT_NOTE`.

    Returns
    -------
    dict of xarray.DataArray
        ``contact_force_rms`` (N), ``static_contact_load`` (N) and
        ``loss_of_contact_probability`` (-), each over ``wheel``.
    """
    sigma = np.sqrt(trapezoid(np.abs(force_frf) ** 2 * irregularity_psd[:, None], f, axis=0))
    p0 = system.vehicle.static_wheel_loads()
    probability = norm.cdf(-p0 / np.maximum(sigma, np.finfo(float).tiny))
    band = f"{f[0]:g}-{f[-1]:g} Hz"
    return {
        "contact_force_rms": xr.DataArray(
            sigma, dims=("wheel",), attrs={"units": "N", "long_name": f"contact force RMS, {band}"}
        ),
        "static_contact_load": xr.DataArray(
            p0, dims=("wheel",), attrs={"units": "N", "long_name": "static contact load"}
        ),
        "loss_of_contact_probability": xr.DataArray(
            probability,
            dims=("wheel",),
            attrs={
                "units": "1",
                "long_name": "probability of loss of contact, Phi(-P0/sigma), Gaussian",
            },
        ),
    }


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
