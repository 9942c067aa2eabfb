"""The labelled xarray dataset of a sweep, and its netCDF/CSV exports."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from railvib import units
from railvib.case import build_grid, build_system, case_from_dict
from railvib.results.dataset import PSD_CONVENTION, atomic_path, save_netcdf
from railvib.sweep.batch import case_labels, summary_names
from railvib.sweep.layout import SweepLayout

__all__ = [
    "field_unit",
    "load_sweep_dataset",
    "save_sweep_csv",
    "save_sweep_netcdf",
    "summary_variables",
    "sweep_dataset",
]

_PER_FREQ_ATTRS = {
    "psd_acceleration": (units.ACCELERATION_PSD, "acceleration PSD"),
    "psd_displacement": (units.DISPLACEMENT_PSD, "displacement PSD"),
    "psd_force": (units.FORCE_PSD, "dynamic wheel-rail contact force PSD"),
    "irregularity_psd": (units.DISPLACEMENT_PSD, "irregularity PSD applied"),
}
_SUFFIX_UNITS = (
    ("_n_per_m", "N/m"),
    ("_ns_per_m", "N s/m"),
    ("_kmh", "km/h"),
    ("_c", "degC"),
    ("_hz", "Hz"),
    ("_s", "s"),
    ("_m", "m"),
)


def field_unit(field: str) -> str:
    """Return the unit of a dotted case field, from the schema or the field name's suffix."""
    from railvib.case.schema import Case

    model: Any = Case
    for part in field.split("."):
        info = getattr(model, "model_fields", {}).get(part)
        if info is None:
            break
        extra = info.json_schema_extra
        if isinstance(extra, dict) and "unit" in extra:
            return str(extra["unit"])
        model = info.annotation
    last = field.split(".")[-1]
    for suffix, unit in _SUFFIX_UNITS:
        if last.endswith(suffix):
            return unit
    return ""


def summary_variables(ds: xr.Dataset) -> list[str]:
    """Names of the summary variables of a sweep dataset."""
    return [str(n) for n, da in ds.data_vars.items() if "frequency" not in da.dims]


def sweep_dataset(
    spec: dict[str, Any], arrays: dict[str, NDArray[Any]], fingerprint: str
) -> xr.Dataset:
    """Label the assembled arrays of a sweep.

    Parameters
    ----------
    spec : dict
        The resolved sweep.
    arrays : dict of numpy.ndarray
        Per-frequency variables ``(*sweep_shape, n_freq[, n_resp])`` and
        ``summary/<name>`` variables ``(*sweep_shape, n_resp)``.
    fingerprint : str
        The sweep's fingerprint (stored as an attribute).

    Returns
    -------
    xarray.Dataset
        Dimensions ``frequency``, ``response`` / ``wheel``, then the sweep dimensions.
    """
    layout = SweepLayout(spec)
    base = case_from_dict(spec["base_case"])
    system = build_system(base)
    f = build_grid(base).f
    labels = case_labels(system)
    dims = layout.dims
    n_wheel = system.vehicle.wheel_offsets.size
    coords: dict[str, Any] = {
        "frequency": ("frequency", f, {"units": "Hz", "long_name": "frequency"}),
        "response": ("response", labels, {"long_name": "response"}),
        "wheel": ("wheel", np.arange(1, n_wheel + 1), {"long_name": "wheel"}),
    }
    for ax in spec["axes"]:
        values = ax["coords"]
        attrs = {
            "long_name": ax["field"],
            "units": field_unit(ax["field"]),
            "case_field": ax["field"],
        }
        coords[ax["dim"]] = (ax["group"], _coord_array(values), attrs)
    data: dict[str, Any] = {}
    sweep_dims = tuple(dims)
    for name in spec["variables"]:
        unit, long_name = _PER_FREQ_ATTRS[name]
        extra = (
            ()
            if name == "irregularity_psd"
            else ("wheel",)
            if name == "psd_force"
            else ("response",)
        )
        da = xr.DataArray(arrays[name], dims=(*sweep_dims, "frequency", *extra))
        data[name] = da.transpose("frequency", *extra, *sweep_dims).assign_attrs(
            units=unit, long_name=long_name
        )
    psd_unit = _PER_FREQ_ATTRS[spec["summary_variable"]][0]
    rms_unit = "m/s^2" if spec["summary_variable"] == "psd_acceleration" else "m"
    what = spec["summary_variable"].replace("psd_", "")
    for name in summary_names(spec["base_case"]["output"]["rms_bands"]):
        da = xr.DataArray(arrays[f"summary/{name}"], dims=(*sweep_dims, "response"))
        da = da.transpose("response", *sweep_dims)
        if name == "peak":
            attrs = {"units": psd_unit, "long_name": f"peak {what} PSD"}
        elif name == "dominant_frequency":
            attrs = {"units": "Hz", "long_name": f"frequency of the peak {what} PSD"}
        elif name == "rms":
            attrs = {"units": rms_unit, "long_name": f"{what} RMS over the grid"}
        else:
            lo, hi = name[4:-3].split("_")
            attrs = {"units": rms_unit, "long_name": f"{what} RMS over {lo}-{hi} Hz"}
        attrs["note"] = "pitch responses are in rad-based units"
        data[name] = da.assign_attrs(attrs)
    from railvib.solve import case_toml

    attrs = {
        "title": spec["title"],
        "psd_convention": PSD_CONVENTION,
        "railvib_version": _version(),
        "sweep_fingerprint": fingerprint,
        "sweep_spec_json": json.dumps(spec, sort_keys=True, default=str),
        "base_case_toml": case_toml(base),
        "sweep_dims": ",".join(dims),
        "summary_variable": spec["summary_variable"],
        "time_dependence": "exp(+i omega t)",
    }
    return xr.Dataset(data, coords=coords, attrs=attrs)


def _version() -> str:
    from railvib.solve import railvib_version

    return railvib_version()


def _coord_array(values: list[Any]) -> NDArray[Any]:
    if all(isinstance(v, bool) for v in values):
        return np.asarray(values, dtype=bool)
    if all(isinstance(v, int) and not isinstance(v, bool) for v in values):
        return np.asarray(values, dtype=np.int64)
    if all(isinstance(v, int | float) and not isinstance(v, bool) for v in values):
        return np.asarray(values, dtype=float)
    return np.asarray([str(v) for v in values])


def load_sweep_dataset(path: str | Path) -> xr.Dataset:
    """Open a sweep result: a sweep folder, its ``sweep.zarr`` or a netCDF export.

    Parameters
    ----------
    path : str or pathlib.Path
        Folder written by ``railvib sweep``, a ``.zarr`` store or a ``.nc`` file.

    Returns
    -------
    xarray.Dataset
        Loaded into memory.
    """
    from railvib.errors import CaseError

    path = Path(path)
    if path.is_dir() and (path / "sweep.zarr").is_dir():
        path = path / "sweep.zarr"
    if path.suffix == ".nc" and path.is_file():
        return xr.load_dataset(path, engine="h5netcdf")
    if path.is_dir():
        return xr.open_zarr(path, consolidated=True).load()
    raise CaseError("sweep", str(path), "a sweep folder, a sweep.zarr store or a .nc file")


def save_sweep_netcdf(ds: xr.Dataset, path: str | Path) -> Path:
    """Write the sweep dataset to netCDF-4 atomically."""
    return save_netcdf(ds, path)


def save_sweep_csv(ds: xr.Dataset, path: str | Path) -> Path:
    """Write the summary variables as one CSV table (a row per response and case)."""
    names = summary_variables(ds)
    table = ds[names].to_dataframe()
    table.columns = [f"{c} [{ds[c].attrs.get('units', '')}]" for c in table.columns]
    path = Path(path)
    with atomic_path(path) as tmp:
        table.to_csv(tmp, float_format="%.9g")
    return path
