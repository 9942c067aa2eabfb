"""The labelled xarray dataset of a sweep, and its netCDF/CSV exports."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr
from numpy.typing import NDArray

from railvib.case import Case, build_grid, build_system, case_from_dict
from railvib.errors import CaseError
from railvib.io import atomic_path, railvib_version
from railvib.outputs import ContactCheck, RideComfort, WheelRailForces, loss_of_contact_threshold
from railvib.results.dataset import PSD_CONVENTION, load_netcdf, save_netcdf
from railvib.results.stats import summary_attrs, summary_names
from railvib.results.units import QUANTITY_UNITS, summary_quantity, with_unit_coordinates
from railvib.results.variables import VARIABLES
from railvib.solve import criteria_settings
from railvib.sweep.batch import CONTACT_SUMMARY, CRITERIA_SUMMARY
from railvib.sweep.folder import CSV_NAME, MANIFEST, NETCDF_NAME, PLOTS_NAME, ZARR_NAME
from railvib.sweep.layout import SweepLayout
from railvib.sweep.spec import SweepSpec
from railvib.sweep.trains import TRAIN_CARS, label_car, sweep_labels

__all__ = [
    "field_unit",
    "linear_model_line",
    "load_sweep_dataset",
    "save_sweep_csv",
    "save_sweep_extras",
    "save_sweep_netcdf",
    "summary_table",
    "summary_variables",
    "sweep_dataset",
]

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
    """Names of the summary variables of a sweep dataset.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep dataset (:func:`sweep_dataset`).

    Returns
    -------
    list of str
        The data variables without a ``frequency`` dimension, in dataset order.
    """
    return [str(n) for n, da in ds.data_vars.items() if "frequency" not in da.dims]


def sweep_dataset(spec: SweepSpec, arrays: dict[str, NDArray[Any]], fingerprint: str) -> xr.Dataset:
    """Label the assembled arrays of a sweep.

    Parameters
    ----------
    spec : SweepSpec
        The resolved sweep.
    arrays : dict of numpy.ndarray
        Per-frequency variables ``(*sweep_shape, n_freq[, n_resp])`` and
        ``summary/<name>`` variables ``(*sweep_shape, n_resp)``, each in the unit of its
        variable (:data:`railvib.results.variables.VARIABLES`, e.g. (m/s^2)^2/Hz) or
        summary (:func:`railvib.results.stats.summary_attrs`).
    fingerprint : str
        The sweep's fingerprint (stored as an attribute).

    Returns
    -------
    xarray.Dataset
        Dimensions ``frequency``, ``response`` / ``wheel``, then the sweep dimensions;
        the contact check of every case (``contact_force_rms``,
        ``loss_of_contact_probability``, ``linear_model_valid``) where the chunks hold
        it; per-response units coordinates where pitch and bounce units differ
        (:func:`railvib.results.units.with_unit_coordinates`).
    """
    layout = SweepLayout(spec)
    base = case_from_dict(spec.base_case_dict(), warn=False)
    system = build_system(base)
    f = build_grid(base).f
    labels, wheels = sweep_labels(spec)  # a sweep over train length: the longest train's
    dims = layout.dims
    n_wheel = len(wheels)
    coords: dict[str, Any] = {
        "frequency": ("frequency", f, {"units": "Hz", "long_name": "frequency"}),
        "response": ("response", list(labels), {"long_name": "response"}),
        "wheel": ("wheel", np.arange(1, n_wheel + 1), {"long_name": "wheel"}),
    }
    for ax in spec.axes:
        attrs = {"long_name": ax.field, "units": field_unit(ax.field), "case_field": ax.field}
        coords[ax.dim] = (ax.group, _coord_array(list(ax.coords)), attrs)
    data: dict[str, Any] = {}
    sweep_dims = tuple(dims)
    for name in spec.variables:
        var = VARIABLES[name]
        da = xr.DataArray(arrays[name], dims=(*sweep_dims, *var.dims))
        data[name] = da.transpose(*var.dims, *sweep_dims).assign_attrs(var.attrs)
    summarised = spec.summary_variable
    for name in summary_names(spec.rms_bands):
        da = xr.DataArray(arrays[f"summary/{name}"], dims=(*sweep_dims, "response"))
        attrs = summary_attrs(name, summarised, VARIABLES[summarised].units)
        data[name] = da.transpose("response", *sweep_dims).assign_attrs(attrs)
    check = ContactCheck(loss_of_contact_threshold=spec.loss_of_contact_threshold)
    contact_attrs = check.variable_attrs(float(f[0]), float(f[-1]))
    for name, extra in CONTACT_SUMMARY.items():
        if f"summary/{name}" not in arrays:  # chunks of an older railvib
            continue
        da = xr.DataArray(arrays[f"summary/{name}"], dims=(*sweep_dims, *extra))
        data[name] = da.transpose(*extra, *sweep_dims).assign_attrs(contact_attrs[name])
    criteria = criteria_settings(base, system, f)
    criteria_attrs = WheelRailForces().variable_attrs(float(f[0]), float(f[-1]))
    if "ride_comfort" in criteria:
        comfort = RideComfort(**criteria["ride_comfort"])
        coords.update(comfort.floor_coordinate())
        criteria_attrs.update(comfort.variable_attrs(comfort.band(f)))
    for name, extra in CRITERIA_SUMMARY.items():
        if f"summary/{name}" not in arrays:  # chunks of an older railvib, or no comfort
            continue
        da = xr.DataArray(arrays[f"summary/{name}"], dims=(*sweep_dims, *extra))
        data[name] = da.transpose(*extra, *sweep_dims).assign_attrs(criteria_attrs[name])
    if f"summary/{TRAIN_CARS}" in arrays:  # a sweep over train length (NaN-padded)
        data[TRAIN_CARS] = xr.DataArray(
            arrays[f"summary/{TRAIN_CARS}"],
            dims=sweep_dims,
            attrs={"long_name": "number of cars of the case's train", "units": "1"},
        )
        car = "car of each {} (its values are NaN where train_cars is smaller; docs/sweeps.md)"
        coords["response_car"] = (
            "response",
            [label_car(r) for r in labels],
            {"long_name": car.format("response")},
        )
        coords["wheel_car"] = (
            "wheel",
            [label_car(w) for w in wheels],
            {"long_name": car.format("wheel")},
        )
    quantities = {name: name for name in spec.variables if name in QUANTITY_UNITS}
    for name in summary_names(spec.rms_bands):
        quantity = summary_quantity(name, summarised)
        if quantity is not None:
            quantities[name] = quantity
    attrs = {
        "title": spec.title,
        "psd_convention": PSD_CONVENTION,
        "railvib_version": railvib_version(),
        "sweep_fingerprint": fingerprint,
        "sweep_spec_json": spec.to_json(),
        "base_case_toml": base.to_toml(),
        "sweep_dims": ",".join(dims),
        "summary_variable": spec.summary_variable,
        "time_dependence": "exp(+i omega t)",
    }
    return with_unit_coordinates(xr.Dataset(data, coords=coords, attrs=attrs), quantities)


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

    Raises
    ------
    CaseError
        ``sweep = '<path>': ...`` naming what `path` is instead: a ``railvib run``
        folder or result, an unfinished sweep, a file that is not netCDF, ...
    """
    path = Path(path)
    if path.is_dir() and (path / ZARR_NAME).is_dir():
        path = path / ZARR_NAME
    if path.is_dir():
        if not any((path / name).exists() for name in _ZARR_MARKERS):
            raise CaseError("sweep", str(path), _not_a_sweep_folder(path))
        try:
            ds = xr.open_zarr(path, consolidated=True).load()
        except (OSError, ValueError, KeyError) as exc:  # zarr's errors derive from these
            raise CaseError("sweep", str(path), f"a readable sweep.zarr store ({exc})") from None
        _check_complete(ds, path)
        return ds
    if path.suffix == ".nc" and path.is_file():
        try:
            ds = load_netcdf(path)  # booleans (linear_model_valid) come back boolean
        except (OSError, ValueError) as exc:
            reason = " ".join(str(exc).split())[:120]
            raise CaseError("sweep", str(path), f"a readable netCDF file ({reason})") from None
        if "sweep_dims" not in ds.attrs:
            raise CaseError("sweep", str(path), f"a sweep's netCDF export; {_RUN_RESULT}")
        return ds
    raise CaseError("sweep", str(path), f"{_WHAT}; this is not one")


def _check_complete(ds: xr.Dataset, path: Path) -> None:
    """Refuse a store with values missing: Zarr reads a deleted chunk file as NaN.

    Every value a sweep writes is finite (a case whose result is not is an error of
    its own), so a NaN in a real or complex variable means a chunk of the store was
    deleted or overwritten after the sweep finished.
    """
    for name, da in ds.data_vars.items():
        if da.dtype.kind in "fc":
            missing = int(np.count_nonzero(~np.isfinite(da.values) & _present(ds, da)))
            if missing:
                raise CaseError(
                    "sweep",
                    str(path),
                    f"a complete sweep.zarr store ({name} has {missing:,} of {da.size:,} "
                    "values missing: chunk files deleted or damaged); rerun the same "
                    "`railvib sweep` command, which rebuilds sweep.zarr from its finished cases",
                )


def _present(ds: xr.Dataset, da: xr.DataArray) -> NDArray[np.bool_]:
    """Where `da` holds a value: all of it, but for the cars a shorter train lacks.

    A sweep over train length pads the responses and wheels of the cars a train does not
    have with NaN (:mod:`railvib.sweep.trains`); those are not missing values.
    """
    present = xr.ones_like(da, dtype=bool)
    if TRAIN_CARS in ds:
        for dim, coord in (("response", "response_car"), ("wheel", "wheel_car")):
            if dim in da.dims:
                present = present & (ds[coord] <= ds[TRAIN_CARS])
    return np.asarray(present.transpose(*da.dims).values)


#: what a sweep result is, as said in errors
_WHAT = "a sweep folder (written by `railvib sweep`), its sweep.zarr store or a .nc export"
#: files that mark a folder as a Zarr store (v2 consolidated or not, v3)
_ZARR_MARKERS = (".zmetadata", ".zgroup", "zarr.json")
_RUN_RESULT = (
    "this is the result of `railvib run`, which draws its PSD plots itself (psd_*.png "
    "next to results.nc; run it without --no-plots)"
)


def _not_a_sweep_folder(folder: Path) -> str:
    """Why `folder` is not a sweep result, and what to do."""
    if (folder / "results.nc").is_file() or (folder / "summary.md").is_file():
        return f"{_WHAT}; {_RUN_RESULT.replace('the result', 'a folder')}"
    if (folder / MANIFEST).is_file():
        return (
            f"{_WHAT}; this sweep is unfinished (no {ZARR_NAME} yet): rerun the same "
            "`railvib sweep` command to finish it"
        )
    return f"{_WHAT}; this folder holds none"


def save_sweep_netcdf(ds: xr.Dataset, path: str | Path) -> Path:
    """Write the sweep dataset `ds` to the netCDF file `path` (:func:`railvib.save_netcdf`)."""
    return save_netcdf(ds, path)


def linear_model_line(ds: xr.Dataset) -> str:
    """How many cases of a sweep lie beyond the linear model, in one line.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep dataset (:func:`sweep_dataset`).

    Returns
    -------
    str
        E.g. ``"3 of 12 cases beyond the linear model (loss of contact > 1 %)"``; a
        sweep assembled without the contact check says so.
    """
    if "linear_model_valid" not in ds:
        return "linear model check: not in this sweep (assembled by an older railvib)"
    valid = np.asarray(ds["linear_model_valid"].values, dtype=bool)
    threshold = loss_of_contact_threshold(ds)
    n_bad = int(valid.size - np.count_nonzero(valid))
    return (
        f"{n_bad} of {valid.size} cases beyond the linear model "
        f"(loss of contact > {100.0 * threshold:.3g} %)"
    )


def summary_table(ds: xr.Dataset) -> pd.DataFrame:
    """The summary variables of a sweep as one table: a row per response and case.

    Per-response statistics (``peak``, ``dominant_frequency``, ``rms``, ...) are
    columns, each followed, where its unit differs between responses, by the unit of
    each row (``peak_unit``, ``rms_unit`` after the last RMS column); columns of one
    unit are headed ``<name> [<unit>]``. The contact check of the case is joined to
    each of its rows: ``contact_force_rms_max [N]`` and
    ``loss_of_contact_probability_max [1]`` (worst wheel) and ``linear_model_valid``.
    Over trains of several lengths (``train_cars`` in `ds`) each case has the rows of the
    responses its own train has, and a ``train_cars`` column.

    Parameters
    ----------
    ds : xarray.Dataset
        The sweep dataset (:func:`sweep_dataset`).

    Returns
    -------
    pandas.DataFrame
        Indexed by ``response`` and the sweep dimensions.
    """
    names = sorted(
        (n for n in summary_variables(ds) if "response" in ds[n].dims), key=_statistic_order
    )
    unit_coords = [str(c) for c in ds.coords if str(c).endswith("_unit")]
    table = ds[names].drop_vars(unit_coords).to_dataframe()[names]
    responses = table.index.get_level_values("response")
    columns: dict[str, Any] = {}
    by_coord: dict[str, list[str]] = {}
    for name in names:
        coord = ds[name].attrs.get("units_coordinate")
        if coord is not None and coord in ds.coords:
            by_coord.setdefault(str(coord), []).append(name)
    for name in table.columns:
        coord = ds[name].attrs.get("units_coordinate") if name in ds else None
        if coord in by_coord:
            columns[name] = table[name].values
            if by_coord[coord][-1] == name:
                unit_of = dict(zip(ds["response"].values, ds[coord].values, strict=True))
                columns[f"{by_coord[coord][0]}_unit"] = [unit_of[r] for r in responses]
        elif name in ds:
            columns[f"{name} [{ds[name].attrs.get('units', '')}]"] = table[name].values
        else:  # a coordinate along the sweep (zipped axes)
            columns[name] = table[name].values
    out = pd.DataFrame(columns, index=table.index)
    dims = [d for d in out.index.names if d != "response"]
    per_case = {}
    for name, column in (
        ("contact_force_rms", "contact_force_rms_max [N]"),
        ("loss_of_contact_probability", "loss_of_contact_probability_max [1]"),
    ):
        if name in ds:
            per_case[column] = ds[name].max("wheel")
    if "linear_model_valid" in ds:
        per_case["linear_model_valid"] = ds["linear_model_valid"]
    if TRAIN_CARS in ds:
        per_case[TRAIN_CARS] = ds[TRAIN_CARS]
    if per_case and dims:
        cases = xr.Dataset(per_case).drop_vars(unit_coords, errors="ignore").to_dataframe()
        cases = cases[list(per_case)]
        out = out.join(cases, on=dims)
    if TRAIN_CARS in ds:  # a row per response the case's train has
        car_of = dict(zip(ds["response"].values, ds["response_car"].values, strict=True))
        out = out[[car_of[r] for r in responses] <= out[TRAIN_CARS].to_numpy()]
    return out


def _statistic_order(name: str) -> tuple[int, float, float, str]:
    """Peak, dominant frequency, RMS, then the band RMS values by band, then the rest."""
    fixed = {"peak": 0, "dominant_frequency": 1, "rms": 2}
    if name in fixed:
        return fixed[name], 0.0, 0.0, name
    if name.startswith("rms_") and name.endswith("_hz"):
        try:
            lo, hi = (float(x) for x in name.removeprefix("rms_").removesuffix("_hz").split("_"))
        except ValueError:
            return 4, 0.0, 0.0, name
        return 3, lo, hi, name
    return 4, 0.0, 0.0, name


def save_sweep_csv(ds: xr.Dataset, path: str | Path) -> Path:
    """Write the summary variables as one CSV table (a row per response and case).

    Parameters
    ----------
    ds : xarray.Dataset
        The sweep dataset (:func:`sweep_dataset`).
    path : str or pathlib.Path
        The CSV file: the table of :func:`summary_table` (columns of one unit headed
        ``<variable> [<units>]``, the others followed by a unit column).

    Returns
    -------
    pathlib.Path
        `path`.
    """
    table = summary_table(ds)
    path = Path(path)
    with atomic_path(path) as tmp:
        table.to_csv(tmp, float_format="%.9g")
    return path


def save_sweep_extras(
    ds: xr.Dataset,
    out: str | Path,
    *,
    netcdf: bool = False,
    csv: bool = False,
    plots: bool = False,
) -> list[Path]:
    """Write the optional exports of a sweep into its output folder.

    Parameters
    ----------
    ds : xarray.Dataset
        The sweep dataset (:func:`railvib.sweep.run_sweep`).
    out : str or pathlib.Path
        The sweep's output folder.
    netcdf : bool
        Write the whole dataset to ``OUT/sweep.nc`` (:func:`save_sweep_netcdf`).
    csv : bool
        Write the summary table to ``OUT/summary.csv`` (:func:`save_sweep_csv`).
    plots : bool
        Draw the default summary plots into ``OUT/plots``
        (:func:`railvib.plot.sweep.save_sweep_plots`).

    Returns
    -------
    list of pathlib.Path
        The files written, in this order (netCDF, CSV, plots).
    """
    out = Path(out)
    written: list[Path] = []
    if netcdf:
        written.append(save_sweep_netcdf(ds, out / NETCDF_NAME))
    if csv:
        written.append(save_sweep_csv(ds, out / CSV_NAME))
    if plots:
        from railvib.plot.sweep import save_sweep_plots  # matplotlib: only when plotting

        written.extend(save_sweep_plots(ds, out / PLOTS_NAME))
    return written
