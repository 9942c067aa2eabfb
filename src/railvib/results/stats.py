"""Summary statistics of response PSDs: peak, dominant frequency, RMS over bands."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pandas as pd
import xarray as xr
from scipy.integrate import trapezoid

from railvib.docstrings import fill_doc
from railvib.results.units import (
    QUANTITY_UNITS,
    quantity_unit,
    rms_quantity,
    summary_quantity,
    with_unit_coordinates,
)

__all__ = [
    "band_rms",
    "dominant_frequency",
    "peak",
    "summary",
    "summary_attrs",
    "summary_names",
    "summary_table",
]

#: parameter documentation shared by the statistics (:func:`railvib.docstrings.fill_doc`)
_SHARED = {
    "psd": """psd : xarray.DataArray
    One-sided PSD per Hz (e.g. (m/s^2)^2/Hz) with a ``frequency`` dimension in Hz.""",
    "band": """band : (float, float), optional
    Frequency band ``(f_lo, f_hi)`` in Hz, inclusive; None: the whole grid.""",
}


@fill_doc(_SHARED)
def peak(psd: xr.DataArray, band: tuple[float, float] | None = None) -> xr.DataArray:
    """Largest PSD value over `band` (Hz, inclusive; whole grid if None).

    Parameters
    ----------
    {psd}
    {band}

    Returns
    -------
    xarray.DataArray
        The peak in the unit of `psd`, over the dimensions of `psd` other than ``frequency``.

    Raises
    ------
    ValueError
        If `band` holds no grid frequency.
    """
    return _in_band(psd, band).max("frequency")


@fill_doc(_SHARED)
def dominant_frequency(psd: xr.DataArray, band: tuple[float, float] | None = None) -> xr.DataArray:
    """Frequency (Hz) of the largest PSD value over `band`.

    Parameters
    ----------
    {psd}
    {band}

    Returns
    -------
    xarray.DataArray
        Frequency of the peak in Hz, over the dimensions of `psd` other than ``frequency``.

    Raises
    ------
    ValueError
        If `band` holds no grid frequency.
    """
    sel = _in_band(psd, band)
    return sel["frequency"][sel.argmax("frequency")].drop_vars("frequency", errors="ignore")


@fill_doc(_SHARED)
def band_rms(psd: xr.DataArray, band: tuple[float, float] | None = None) -> xr.DataArray:
    """RMS = sqrt(integral of the one-sided PSD over `band`), trapezoidal rule on the grid.

    Parameters
    ----------
    {psd}
    {band}

    Returns
    -------
    xarray.DataArray
        RMS in the square root of the unit of `psd` times Hz (e.g. m/s^2), over the
        dimensions of `psd` other than ``frequency``.

    Raises
    ------
    ValueError
        If `band` holds no grid frequency.
    """
    sel = _in_band(psd, band)
    axis = sel.get_axis_num("frequency")
    var = trapezoid(sel.values, sel["frequency"].values, axis=axis)
    dims = [d for d in sel.dims if d != "frequency"]
    coords = {k: v for k, v in sel.coords.items() if "frequency" not in v.dims}
    return xr.DataArray(np.sqrt(var), dims=dims, coords=coords)


def summary_names(bands: Sequence[Sequence[float]]) -> list[str]:
    """Names of the variables :func:`summary` returns for RMS bands `bands` (Hz)."""
    return ["peak", "dominant_frequency", "rms"] + [f"rms_{lo:g}_{hi:g}_hz" for lo, hi in bands]


def summary_attrs(name: str, variable: str, psd_units: str) -> dict[str, str]:
    """``units`` and ``long_name`` of summary variable `name` of PSD `variable`.

    Parameters
    ----------
    name : str
        One of :func:`summary_names`.
    variable : str
        The PSD summarised, e.g. ``"psd_acceleration"``.
    psd_units : str
        Units of that PSD (of its translational responses).

    Returns
    -------
    dict of str
        ``units`` (of the translational responses, :func:`railvib.results.units.quantity_unit`),
        ``long_name`` and, where pitch responses differ, a ``note``.
    """
    what = variable.removeprefix("psd_")
    amplitude = rms_quantity(variable)
    rms_units = quantity_unit(amplitude) if amplitude else f"sqrt({psd_units}*Hz)"
    note = {"note": "pitch responses are in rad-based units"}
    if name == "peak":
        return {"units": psd_units, "long_name": f"peak {what} PSD", **note}
    if name == "dominant_frequency":
        return {"units": "Hz", "long_name": f"frequency of the peak {what} PSD"}
    if name == "rms":
        return {"units": rms_units, "long_name": f"{what} RMS over the grid", **note}
    lo, hi = name.removeprefix("rms_").removesuffix("_hz").split("_")
    return {"units": rms_units, "long_name": f"{what} RMS over {lo}-{hi} Hz", **note}


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
        Variables ``peak``, ``dominant_frequency``, ``rms`` and ``rms_<lo>_<hi>_hz``
        (see :func:`summary_names`), with units. Where the unit differs between
        responses (pitch in rad-based units), the unit of each response is in a
        coordinate over ``response`` named by the variable's ``units_coordinate``
        attribute (``psd_acceleration_unit`` for the peak, ``acceleration_unit`` for
        the RMS values of an acceleration PSD; :mod:`railvib.results.units`).
    """
    psd = ds[variable]
    unit = str(psd.attrs.get("units", ""))
    psd = psd.drop_vars([c for c in psd.coords if str(c).endswith("_unit")])
    names = summary_names(bands)
    values = [peak(psd), dominant_frequency(psd), band_rms(psd)]
    values += [band_rms(psd, (lo, hi)) for lo, hi in bands]
    out = xr.Dataset(
        {
            name: da.assign_attrs(summary_attrs(name, variable, unit))
            for name, da in zip(names, values, strict=True)
        }
    )
    if variable not in QUANTITY_UNITS or unit != quantity_unit(variable):
        return out  # units not in the table (or not railvib's): the PSD's unit for every row
    quantities = {name: summary_quantity(name, variable) for name in names}
    return with_unit_coordinates(out, {k: v for k, v in quantities.items() if v is not None})


def summary_table(stats: xr.Dataset) -> pd.DataFrame:
    """The summary of one run as a table: one row per response, every figure with its unit.

    Columns: ``peak`` and ``peak_unit`` (the PSD's unit of that row, e.g.
    (m/s^2)^2/Hz or (rad/s^2)^2/Hz), ``dominant_frequency [Hz]``, ``rms`` and
    ``rms_<lo>_<hi>_hz`` (RMS over the grid and over each band, Hz) and ``rms_unit``
    (their unit in that row, e.g. m/s^2 or rad/s^2).

    Parameters
    ----------
    stats : xarray.Dataset
        The result of :func:`summary` (over ``response`` only).

    Returns
    -------
    pandas.DataFrame
        Indexed by ``response``.
    """
    labels = [str(r) for r in stats["response"].values]
    columns: dict[str, object] = {}
    rms_names = [str(n) for n in stats.data_vars if str(n).startswith("rms")]

    def units_of(name: str) -> list[str]:
        da = stats[name]
        coord = da.attrs.get("units_coordinate")
        if coord is not None and coord in stats.coords:
            return [str(u) for u in stats[coord].values]
        return [str(da.attrs.get("units", ""))] * len(labels)

    columns["peak"] = stats["peak"].values
    columns["peak_unit"] = units_of("peak")
    freq_unit = stats["dominant_frequency"].attrs.get("units", "Hz")
    columns[f"dominant_frequency [{freq_unit}]"] = stats["dominant_frequency"].values
    for name in rms_names:
        columns[name] = stats[name].values
    if rms_names:
        columns["rms_unit"] = units_of(rms_names[0])
    return pd.DataFrame(columns, index=pd.Index(labels, name="response"))


def _in_band(psd: xr.DataArray, band: tuple[float, float] | None) -> xr.DataArray:
    if band is None:
        return psd
    f = psd["frequency"]
    sel = psd.where((f >= band[0]) & (f <= band[1]), drop=True)
    if sel.sizes["frequency"] == 0:
        raise ValueError(f"band {band} Hz holds no grid frequency")
    return sel
