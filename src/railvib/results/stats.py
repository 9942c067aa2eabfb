"""Summary statistics of response PSDs: peak, dominant frequency, RMS over bands."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr
from scipy.integrate import trapezoid

__all__ = ["band_rms", "dominant_frequency", "peak", "summary"]


def peak(psd: xr.DataArray, band: tuple[float, float] | None = None) -> xr.DataArray:
    """Largest PSD value over `band` (Hz, inclusive; whole grid if None)."""
    return _in_band(psd, band).max("frequency")


def dominant_frequency(psd: xr.DataArray, band: tuple[float, float] | None = None) -> xr.DataArray:
    """Frequency (Hz) of the largest PSD value over `band`."""
    sel = _in_band(psd, band)
    return sel["frequency"][sel.argmax("frequency")].drop_vars("frequency", errors="ignore")


def band_rms(psd: xr.DataArray, band: tuple[float, float] | None = None) -> xr.DataArray:
    """RMS = sqrt(integral of the one-sided PSD over `band`), trapezoidal rule on the grid."""
    sel = _in_band(psd, band)
    axis = sel.get_axis_num("frequency")
    var = trapezoid(sel.values, sel["frequency"].values, axis=axis)
    dims = [d for d in sel.dims if d != "frequency"]
    coords = {k: v for k, v in sel.coords.items() if "frequency" not in v.dims}
    return xr.DataArray(np.sqrt(var), dims=dims, coords=coords)


def summary(
    ds: xr.Dataset,
    bands: Sequence[tuple[float, float]] = (),
    variable: str = "psd_acceleration",
) -> xr.Dataset:
    """Peak, dominant frequency and RMS (whole grid and each band) of every response.

    Parameters
    ----------
    ds : xarray.Dataset
        A result dataset with a ``frequency`` dimension.
    bands : sequence of (float, float)
        Frequency bands in Hz for band RMS values.
    variable : str
        The PSD variable to summarise.

    Returns
    -------
    xarray.Dataset
        Variables ``peak``, ``dominant_frequency``, ``rms`` and ``rms_<lo>_<hi>_hz``.
    """
    psd = ds[variable]
    unit = psd.attrs.get("units", "")
    rms_unit = "m/s^2" if variable == "psd_acceleration" else f"sqrt({unit}*Hz)"
    out = xr.Dataset(
        {
            "peak": peak(psd).assign_attrs(units=unit, long_name="peak PSD"),
            "dominant_frequency": dominant_frequency(psd).assign_attrs(
                units="Hz", long_name="frequency of the peak PSD"
            ),
            "rms": band_rms(psd).assign_attrs(units=rms_unit, long_name="RMS over the grid"),
        }
    )
    for lo, hi in bands:
        name = f"rms_{lo:g}_{hi:g}_hz"
        out[name] = band_rms(psd, (lo, hi)).assign_attrs(
            units=rms_unit, long_name=f"RMS over {lo:g}-{hi:g} Hz"
        )
    return out


def _in_band(psd: xr.DataArray, band: tuple[float, float] | None) -> xr.DataArray:
    if band is None:
        return psd
    f = psd["frequency"]
    sel = psd.where((f >= band[0]) & (f <= band[1]), drop=True)
    if sel.sizes["frequency"] == 0:
        raise ValueError(f"band {band} Hz holds no grid frequency")
    return sel
