"""Figures of a non-stationary run: the PSD against time and frequency, RMS against time."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.colors import LogNorm

from railvib.io import new_figure, save_figure

__all__ = ["NONSTATIONARY_STEMS", "save_nonstationary_plots"]

#: the figures :func:`save_nonstationary_plots` writes (file stems)
NONSTATIONARY_STEMS = ("psd_map", "rms_time")
#: the responses drawn: (variable, dimension, label)
_DRAWN = (("acceleration", "response", "carbody.bounce"), ("force", "wheel", 1))


def _map_panel(ax, ds: xr.Dataset, name: str, dim: str, label: object) -> None:  # noqa: ANN001
    psd = ds[f"psd_{name}"].sel({dim: label})
    values = np.asarray(psd.values, dtype=float).T  # (frequency, time)
    positive = values[values > 0]
    if positive.size == 0:
        return
    top = float(positive.max())
    norm = LogNorm(vmin=max(float(positive.min()), top * 1e-6), vmax=top)
    mesh = ax.pcolormesh(
        ds["map_time"].values,
        ds["frequency"].values,
        np.where(values > 0, values, np.nan),
        shading="nearest",
        norm=norm,
    )
    ax.set_yscale("log")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("frequency (Hz)")
    what = f"wheel {label} contact force" if dim == "wheel" else f"{label} acceleration"
    ax.set_title(f"S(f; t) of the {what}")
    ax.figure.colorbar(mesh, ax=ax, label=psd.attrs.get("units", ""))


def save_nonstationary_plots(ds: xr.Dataset, outdir: str | Path) -> list[Path]:
    """Write ``psd_map.png`` and ``rms_time.png`` of a non-stationary dataset to `outdir`.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`railvib.nonstationary.nonstationary_dataset`.
    outdir : str or pathlib.Path
        Folder for the PNG files.

    Returns
    -------
    list of pathlib.Path
        The files written (the map only when the exact PSDs are in `ds`).
    """
    outdir = Path(outdir)
    files = []
    if "psd_acceleration" in ds:
        fig, axes = new_figure((11, 4.2), ncols=2, layout="constrained")
        for ax, (name, dim, label) in zip(axes, _DRAWN, strict=True):
            _map_panel(ax, ds, name, dim, label)
        files.append(save_figure(fig, outdir / "psd_map.png", tight=False))
    fig, axes = new_figure((11, 4.2), ncols=2, layout="constrained")
    for ax, (name, dim, label) in zip(axes, _DRAWN, strict=True):
        unit = ""
        if f"rms_{name}" in ds:
            da = ds[f"rms_{name}"].sel({dim: label})
            unit = da.attrs["units"]
            ax.plot(ds["time"], da, label="exact PEM")
        if f"rms_{name}_qs" in ds:
            da = ds[f"rms_{name}_qs"].sel({dim: label})
            unit = da.attrs["units"]
            ax.plot(ds["map_time"], da, "--", label="quasi-stationary")
        ax.set_xlabel("time (s)")
        ax.set_ylabel(f"RMS ({unit})")
        what = f"wheel {label} contact force" if dim == "wheel" else f"{label} acceleration"
        ax.set_title(f"RMS of the {what}")
        speed = ax.twinx()
        speed.plot(ds["time"], 3.6 * ds["speed"], color="0.6", lw=0.8)
        speed.set_ylabel("speed (km/h)", color="0.4")
        ax.legend(loc="best")
    files.append(save_figure(fig, outdir / "rms_time.png", tight=False))
    return files
