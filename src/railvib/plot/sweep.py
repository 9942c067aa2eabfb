"""Plots of sweep summaries: lines over one sweep axis, heat maps over two.

Functions take a sweep dataset (:func:`railvib.sweep.load_sweep_dataset`), draw
on ``ax`` (created if None) and return the axes.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.colors import LogNorm

from railvib.errors import CaseError, did_you_mean
from railvib.io import new_figure, save_figure
from railvib.labels import leading_car_label
from railvib.outputs import loss_of_contact_threshold
from railvib.plot import DEFAULT_SWEEP_RESPONSES

__all__ = [
    "DEFAULT_RESPONSES",
    "INVALID_GID",
    "plot_sweep",
    "save_axes",
    "save_sweep_plots",
    "sweep_dims",
]

#: ``gid`` of the markers that cross out the cases beyond the linear model
INVALID_GID = "linear_model_invalid"

#: responses drawn by :func:`save_sweep_plots` when present
DEFAULT_RESPONSES = DEFAULT_SWEEP_RESPONSES


def sweep_dims(ds: xr.Dataset) -> list[str]:
    """Return the sweep dimensions of a sweep dataset, in file order.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep dataset (its ``sweep_dims`` attribute, comma-separated text or a list).

    Returns
    -------
    list of str
        The dimension names; empty if the attribute is missing.
    """
    dims = ds.attrs.get("sweep_dims", "")
    if isinstance(dims, str):
        return [d for d in dims.split(",") if d]
    return [str(d) for d in dims]


def _axis_values(ds: xr.Dataset, dim: str) -> tuple[np.ndarray, str]:
    """Values and label of a sweep dimension (its first coordinate along it)."""
    names = [dim] if dim in ds.coords else [n for n, c in ds.coords.items() if c.dims == (dim,)]
    if not names:
        return np.arange(ds.sizes[dim]), dim
    c = ds.coords[names[0]]
    unit = c.attrs.get("units", "")
    return c.values, f"{names[0]} [{unit}]" if unit else str(names[0])


def _resolve(
    ds: xr.Dataset,
    variable: str,
    response: str | Sequence[str],
    x: str | None,
    y: str | None,
    kind: str,
) -> tuple[list[str], list[str], str, str | None]:
    """Check a plot request against `ds`: the responses, sweep dims and the x and y chosen."""
    if variable not in ds.data_vars or "frequency" in ds[variable].dims:
        allowed = [str(n) for n, v in ds.data_vars.items() if "frequency" not in v.dims]
        close = did_you_mean(variable, allowed)
        raise CaseError("variable", variable, f"one of {', '.join(allowed)}{close}")
    responses = [response] if isinstance(response, str) else list(response)
    labels = [str(r) for r in ds["response"].values]
    for r in responses:
        if r not in labels:
            raise CaseError("response", r, f"one of {', '.join(labels)}{did_you_mean(r, labels)}")
    dims = sweep_dims(ds) or [str(d) for d in ds[variable].dims if d != "response"]
    varying = [d for d in dims if ds.sizes[d] > 1] or dims
    for name, dim in (("x", x), ("y", y)):
        if dim is not None and dim not in dims:
            raise CaseError(name, dim, f"one of {', '.join(dims)}{did_you_mean(dim, dims)}")
    x = x or next((d for d in varying if d != y), varying[0])
    if x == y:
        others = [d for d in dims if d != x]
        choice = f"one of {', '.join(others)}" if others else "omitted (one sweep dimension)"
        raise CaseError("y", y, f"a sweep dimension other than x = {x!r}: {choice}")
    if y is None and kind != "lines":
        rest = [d for d in varying if d != x]
        y = rest[0] if rest and kind in ("auto", "heatmap") else None
    if kind == "heatmap" and y is None:
        raise CaseError("y", None, "a second sweep dimension with more than one value")
    return responses, dims, x, y


def plot_sweep(
    ds: xr.Dataset,
    variable: str = "peak",
    response: str | Sequence[str] = "wheelset1.bounce",
    *,
    x: str | None = None,
    y: str | None = None,
    sel: Mapping[str, Any] | None = None,
    kind: str = "auto",
    ax: Axes | None = None,
) -> Axes:
    """Draw a summary variable over one sweep axis (lines) or two (heat map).

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep dataset.
    variable : str
        Summary variable: ``peak`` (PSD units), ``dominant_frequency`` (Hz),
        ``rms`` or ``rms_<lo>_<hi>_hz`` (m/s^2; rad/s^2 for a pitch response), or one of
        the contact check: ``contact_force_rms`` (N) and ``loss_of_contact_probability``
        (drawn for the worst wheel), ``linear_model_valid``, or a criterion
        (``comfort_aw``, ``mean_comfort_index``, ``sperling_wz``: the worst floor point;
        ``dynamic_load_factor``: the worst wheel; ``car_dynamic_load_factor``).
    response : str or sequence of str
        Response label(s); a heat map takes one. Ignored by the contact-check variables.
    x, y : str, optional
        Sweep dimensions for the horizontal and vertical axes (default: the
        first one or two dimensions with more than one value).
    sel : mapping, optional
        Index positions (int) of the other sweep dimensions; default 0.
    kind : {"auto", "lines", "heatmap"}
        ``auto`` draws a heat map when two dimensions vary.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on.

    Returns
    -------
    matplotlib.axes.Axes
        Cases beyond the linear model (``linear_model_valid`` false) are crossed out
        with red ``x`` markers (``gid`` :data:`INVALID_GID`, one legend entry): a
        scatter over lines, a marker line over a heat map.
    """
    responses, dims, x, y = _resolve(ds, variable, response, x, y, kind)
    keep = {x} | ({y} if y else set())
    pick = {d: int((sel or {}).get(d, 0)) for d in dims if d not in keep}
    da = ds[variable].isel(pick)
    per_response = "response" in da.dims
    if not per_response:
        for extra in ("wheel", "floor"):  # a criterion per wheel or per floor point
            if extra in da.dims:
                da = da.max(extra, keep_attrs=True)
                da.attrs["long_name"] = f"{da.attrs.get('long_name', variable)}, worst {extra}"
        da = da.astype(float).expand_dims(response=[variable]).assign_attrs(da.attrs)
        responses = [variable]
    invalid = _invalid(ds, pick) if variable != "linear_model_valid" else None
    if ax is None:
        import matplotlib.pyplot as plt  # for interactive use: the user's backend

        _, ax = plt.subplots(figsize=(7.0, 4.5), constrained_layout=True)
    unit = _unit(ds, da, responses) if per_response else da.attrs.get("units", "")
    long_name = da.attrs.get("long_name", variable)
    xv, xlabel = _axis_values(ds, x)
    fixed = ", ".join(
        f"{_axis_values(ds, d)[1].split(' [')[0]}={_axis_values(ds, d)[0][i]}"
        for d, i in pick.items()
    )
    if y is None:
        for i, r in enumerate(responses):
            yvals = da.sel(response=r).transpose(x).values
            ax.plot(xv, yvals, marker="o", ms=3, label=r)
            if invalid is not None:  # a scatter: ax.lines keeps one line per response
                bad = invalid.transpose(x).values
                ax.scatter(
                    np.asarray(xv)[bad],
                    yvals[bad],
                    marker="x",
                    s=80,
                    linewidths=2,
                    color="red",
                    zorder=3,
                    gid=INVALID_GID,
                    label=_invalid_label(ds) if i == 0 and bad.any() else "_nolegend_",
                )
        ax.set_xlabel(xlabel)
        ax.set_ylabel(f"{long_name} [{unit}]")
        values = np.asarray(da.values, dtype=float)
        positive = np.isfinite(values) & (values > 0)
        if variable not in ("dominant_frequency", "linear_model_valid") and positive.any():
            ax.set_yscale("log")  # not when nothing is > 0 (all zero, or NaN in a damaged store)
        ax.legend(fontsize="small")
        ax.grid(True, which="both", alpha=0.3)
    else:
        z = da.sel(response=responses[0]).transpose(y, x).values
        yv, ylabel = _axis_values(ds, y)
        numeric = np.issubdtype(np.asarray(xv).dtype, np.number) and np.issubdtype(
            np.asarray(yv).dtype, np.number
        )
        norm = LogNorm() if variable != "dominant_frequency" and np.all(z > 0) else None
        if numeric:
            mesh = ax.pcolormesh(xv, yv, z, shading="nearest", norm=norm)
        else:
            mesh = ax.pcolormesh(z, norm=norm)
            ax.set_xticks(np.arange(len(xv)) + 0.5, [str(v) for v in xv], rotation=45)
            ax.set_yticks(np.arange(len(yv)) + 0.5, [str(v) for v in yv])
        ax.figure.colorbar(mesh, ax=ax, label=f"{long_name} [{unit}]")
        if invalid is not None:
            bad = invalid.transpose(y, x).values
            jj, ii = np.nonzero(bad)
            if numeric:
                px, py = np.asarray(xv)[ii], np.asarray(yv)[jj]
            else:
                px, py = ii + 0.5, jj + 0.5
            ax.plot(  # markers, not a collection: ax.collections keeps the heat map alone
                px,
                py,
                ls="none",
                marker="x",
                ms=10,
                mew=2,
                color="red",
                gid=INVALID_GID,
                label=_invalid_label(ds),
            )
            if bad.any():
                ax.legend(fontsize="small", loc="upper right")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        fixed = f"{responses[0]}" + (f"; {fixed}" if fixed else "")
    if fixed:
        ax.set_title(fixed, fontsize="small")
    return ax


def _invalid(ds: xr.Dataset, pick: Mapping[str, int]) -> xr.DataArray | None:
    """True where a case is beyond the linear model (None: the sweep has no contact check)."""
    if "linear_model_valid" not in ds:
        return None
    return ~ds["linear_model_valid"].isel(pick).astype(bool)


def _invalid_label(ds: xr.Dataset) -> str:
    return (
        f"beyond the linear model (loss of contact > {100 * loss_of_contact_threshold(ds):.3g} %)"
    )


def _unit(ds: xr.Dataset, da: xr.DataArray, responses: Sequence[str]) -> str:
    """The unit of `da` for `responses` (from its per-response units coordinate if any)."""
    coord = da.attrs.get("units_coordinate")
    if coord is None or coord not in ds.coords:
        return str(da.attrs.get("units", ""))
    units = dict(zip(ds["response"].values, ds[coord].values, strict=True))
    found = list(dict.fromkeys(str(units[r]) for r in responses))
    return "; ".join(found)


def save_axes(ax: Axes, path: str | Path) -> Path:
    """Save the figure of `ax` as a PNG atomically and close it.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes whose (top-level) figure is written, as drawn (no tight layout).
    path : str or pathlib.Path
        The PNG file.

    Returns
    -------
    pathlib.Path
        `path`.
    """
    return save_figure(ax, path, tight=False)


def save_sweep_plots(
    ds: xr.Dataset,
    outdir: str | Path,
    variables: Sequence[str] = ("peak", "dominant_frequency"),
    responses: Sequence[str] | None = None,
    *,
    x: str | None = None,
    y: str | None = None,
) -> list[Path]:
    """Write one PNG per (variable, response): heat map if two axes vary, else lines.

    The files are ``sweep_<variable>_<response>.png`` (``.`` -> ``_``, ``@`` ->
    ``_at_``), drawn by :func:`plot_sweep`; a variable of the contact check (no
    ``response`` dimension) is one figure, ``sweep_<variable>.png``. Cases beyond the
    linear model are crossed out in every figure.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep dataset.
    outdir : str or pathlib.Path
        Folder for the PNG files (created if missing).
    variables : sequence of str
        Summary variables to draw: ``peak`` (PSD units), ``dominant_frequency``
        (Hz), ``rms`` or ``rms_<lo>_<hi>_hz`` (m/s^2).
    responses : sequence of str, optional
        Responses (default, also when empty: those of :data:`DEFAULT_RESPONSES` present).
    x, y : str, optional
        Sweep dimensions for the horizontal axis and for a heat map's vertical
        axis (default: as :func:`plot_sweep` chooses).

    Returns
    -------
    list of pathlib.Path
        The files written.

    Raises
    ------
    CaseError
        An unknown variable, response or sweep dimension.
    """
    outdir = Path(outdir)
    labels = [str(r) for r in ds["response"].values]
    if not responses:  # the defaults present, or those of a train's leading car
        picked = [r if r in labels else leading_car_label(r) for r in DEFAULT_RESPONSES]
        responses = [r for r in picked if r in labels]
    responses = list(responses)
    for variable in variables:  # every request is checked before any file is written
        _resolve(ds, variable, responses, x, y, "auto")
    outdir.mkdir(parents=True, exist_ok=True)
    written = []
    for variable in variables:
        if variable in ds.data_vars and "response" not in ds[variable].dims:
            path = outdir / f"sweep_{variable}.png"  # a case's contact check: one figure
            _, ax = new_figure(figsize=(7.0, 4.5), layout="constrained")
            save_axes(plot_sweep(ds, variable, responses[:1] or labels[:1], x=x, y=y, ax=ax), path)
            written.append(path)
            continue
        for r in responses:
            path = outdir / f"sweep_{variable}_{r.replace('@', '_at_').replace('.', '_')}.png"
            _, ax = new_figure(figsize=(7.0, 4.5), layout="constrained")
            save_axes(plot_sweep(ds, variable, r, x=x, y=y, ax=ax), path)
            written.append(path)
    return written
