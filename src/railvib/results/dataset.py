"""Labelled results: the xarray.Dataset of one run, and its atomic netCDF/CSV files."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from railvib import units
from railvib.pem import acceleration_psd, response_psd

__all__ = ["atomic_path", "build_dataset", "load_netcdf", "save_csv", "save_netcdf"]

PSD_CONVENTION = "one-sided, per Hz, temporal (variance = integral of the PSD over f from 0 to inf)"


def build_dataset(
    f: NDArray[np.float64],
    labels: list[str],
    frf: NDArray[np.complex128],
    dof_units: list[str],
    force_frf: NDArray[np.complex128],
    irregularity_psd: NDArray[np.float64],
    attrs: dict[str, Any],
    extra: dict[str, xr.DataArray] | None = None,
) -> xr.Dataset:
    """Assemble the result dataset of one case.

    Parameters
    ----------
    f : numpy.ndarray
        Frequencies in Hz, ``(n_freq,)``.
    labels : list of str
        Response labels, ``(n_resp,)``, e.g. ``"wheelset2.bounce"``, ``"rail@wheel2"``.
    frf : numpy.ndarray
        Complex displacement per unit irregularity, ``(n_freq, n_resp)``.
    dof_units : list of str
        Displacement unit of each response (``"m"`` or ``"rad"``).
    force_frf : numpy.ndarray
        Complex contact force per unit irregularity, ``(n_freq, n_wheel)``, N/m.
    irregularity_psd : numpy.ndarray
        One-sided temporal irregularity PSD applied, m^2/Hz, ``(n_freq,)``.
    attrs : dict
        Global attributes (case TOML, version, ...).
    extra : dict of xarray.DataArray, optional
        Further variables (e.g. the pad stiffness) to include.

    Returns
    -------
    xarray.Dataset
    """
    psd_u = response_psd(frf, irregularity_psd)
    psd_a = acceleration_psd(f, psd_u)
    psd_p = response_psd(force_frf, irregularity_psd)
    coords = {
        "frequency": ("frequency", f, {"units": "Hz", "long_name": "frequency"}),
        "response": ("response", labels, {"long_name": "response"}),
        "displacement_unit": ("response", dof_units, {"long_name": "unit of the displacement"}),
        "wheel": ("wheel", np.arange(1, force_frf.shape[1] + 1), {"long_name": "wheel"}),
    }
    data = {
        "psd_acceleration": (
            ("frequency", "response"),
            psd_a,
            {
                "units": units.ACCELERATION_PSD,
                "long_name": "acceleration PSD",
                "note": "pitch responses are in (rad/s^2)^2/Hz",
            },
        ),
        "psd_displacement": (
            ("frequency", "response"),
            psd_u,
            {
                "units": units.DISPLACEMENT_PSD,
                "long_name": "displacement PSD",
                "note": "pitch responses are in rad^2/Hz",
            },
        ),
        "frf_displacement": (
            ("frequency", "response"),
            frf,
            {
                "units": "m/m",
                "long_name": "displacement per unit irregularity (complex)",
                "note": "pitch responses are in rad/m; exp(+i omega t); input = profile at the "
                "leading wheel",
            },
        ),
        "psd_force": (
            ("frequency", "wheel"),
            psd_p,
            {"units": units.FORCE_PSD, "long_name": "dynamic wheel-rail contact force PSD"},
        ),
        "frf_force": (
            ("frequency", "wheel"),
            force_frf,
            {"units": "N/m", "long_name": "contact force per unit irregularity (complex)"},
        ),
        "irregularity_psd": (
            ("frequency",),
            irregularity_psd,
            {"units": units.DISPLACEMENT_PSD, "long_name": "irregularity PSD applied"},
        ),
    }
    ds = xr.Dataset(data, coords=coords, attrs={"psd_convention": PSD_CONVENTION, **attrs})
    for name, da in (extra or {}).items():
        ds[name] = da
    return ds


@contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path next to `path`; move it onto `path` only if the block succeeds."""
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


def _split_complex(ds: xr.Dataset) -> xr.Dataset:
    out = ds.copy()
    for name, da in ds.data_vars.items():
        if np.iscomplexobj(da.values):
            parts = xr.concat([da.real, da.imag], dim="part").transpose(*da.dims, "part")
            out[name] = parts.assign_attrs({**da.attrs, "complex_stored_as": "part"})
    if "part" in out.dims:
        out = out.assign_coords(part=["real", "imag"])
    return out


def save_netcdf(ds: xr.Dataset, path: str | Path) -> Path:
    """Write `ds` to netCDF-4 atomically; complex variables get a ``part`` (real, imag) dim."""
    path = Path(path)
    with atomic_path(path) as tmp:
        _split_complex(ds).to_netcdf(tmp, engine="h5netcdf")
    return path


def load_netcdf(path: str | Path) -> xr.Dataset:
    """Read a dataset written by :func:`save_netcdf`, recombining complex variables."""
    ds = xr.load_dataset(path, engine="h5netcdf")
    for name, da in list(ds.data_vars.items()):
        if da.attrs.get("complex_stored_as") == "part":
            attrs = {k: v for k, v in da.attrs.items() if k != "complex_stored_as"}
            ds[name] = (da.sel(part="real") + 1j * da.sel(part="imag")).assign_attrs(attrs)
    return ds.drop_vars("part", errors="ignore")


def save_csv(ds: xr.Dataset, path: str | Path, variable: str = "psd_acceleration") -> Path:
    """Write one (frequency x response) variable as a CSV table, atomically."""
    da = ds[variable]
    df = da.to_pandas()
    unit = da.attrs.get("units", "")
    df.columns = [f"{c} [{unit}]" for c in df.columns]
    df.index.name = "frequency [Hz]"
    path = Path(path)
    with atomic_path(path) as tmp:
        df.to_csv(tmp, float_format="%.6e")
    return path
