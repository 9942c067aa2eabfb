"""Figures of the engineering criteria: one-third-octave bar plots and the comfort panel."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.axes import Axes

from railvib.io import new_figure, save_figure
from railvib.outputs.comfort import ISO2631_COMFORT
from railvib.outputs.weighting import WEIGHTINGS
from railvib.plot.axes import SuperscriptLogFormatter

__all__ = ["comfort_panel", "octave_bars", "save_criteria_plots"]

#: the responses drawn in the one-third-octave figure, where the run has them
OCTAVE_RESPONSES = ("carbody.bounce", "bogie1.bounce", "wheelset1.bounce", "rail@wheel1")


def octave_bars(ds: xr.Dataset, ax: Axes, variable: str = "octave_level_acceleration") -> None:
    """Grouped bars of one-third-octave levels against the nominal mid-band frequency.

    Parameters
    ----------
    ds : xarray.Dataset
        A run's result with the output ``third_octave``.
    ax : matplotlib.axes.Axes
        Where to draw.
    variable : str
        ``octave_level_acceleration`` (dB re 1e-6 m/s^2) or another ``octave_level_*``.
    """
    da = ds[variable]
    labels = [r for r in OCTAVE_RESPONSES if r in ds["response"].values]
    n = max(len(labels), 1)
    x = np.arange(ds.sizes["band"])
    for k, label in enumerate(labels):
        ax.bar(x + (k - (n - 1) / 2) * 0.8 / n, da.sel(response=label).values, 0.8 / n, label=label)
    ax.set_xticks(x, [f"{v:g}" for v in ds["band_nominal"].values], rotation=90, fontsize=7)
    ax.set_xlabel("one-third-octave band, nominal mid-band frequency (Hz)")
    ax.set_ylabel(f"acceleration level ({da.attrs['long_name'].rsplit(', ', 1)[1]})")
    ax.legend(fontsize=8)
    ax.grid(True, axis="y", alpha=0.3)


def comfort_panel(ds: xr.Dataset, axes: tuple[Axes, Axes]) -> None:
    """Weighted floor acceleration PSDs, and a_w of each floor point against ISO 2631-1 Annex C.

    Parameters
    ----------
    ds : xarray.Dataset
        A run's result with the output ``ride_comfort``.
    axes : (Axes, Axes)
        Left: the PSDs weighted by the run's weighting; right: a_w per floor point
        over the comfort ranges of ISO 2631-1:1997, Annex C.
    """
    left, right = axes
    f = ds["frequency"].values
    weighting = ds["comfort_aw"].attrs["weighting"]
    w2 = WEIGHTINGS[weighting].magnitude(f) ** 2
    floors = ds["floor"].values
    for k, s in enumerate(floors):
        left.loglog(f, ds["psd_floor_acceleration"].values[:, k] * w2, label=f"s = {s:+g} m")
    for axis in (left.xaxis, left.yaxis):  # matplotlib's labels, drawn without mathtext
        axis.set_major_formatter(SuperscriptLogFormatter())
        axis.set_minor_formatter(SuperscriptLogFormatter(labelOnlyBase=False))
    left.set_xlabel("frequency (Hz)")
    left.set_ylabel(f"{weighting}-weighted floor acceleration PSD ((m/s^2)^2/Hz)")
    left.legend(fontsize=8)
    left.grid(True, which="both", alpha=0.3)
    a_w = ds["comfort_aw"].values
    top = max(float(a_w.max()) * 1.3, 0.4)
    for lo, hi, name in ISO2631_COMFORT:
        if lo < top:
            right.axhspan(lo, min(hi, top), alpha=0.08, color="k")
            right.text(len(floors) - 0.5, lo, name, fontsize=7, va="bottom", ha="right")
    right.bar(np.arange(len(floors)), a_w, 0.6)
    right.set_xticks(np.arange(len(floors)), [f"s = {s:+g} m" for s in floors])
    right.set_ylim(0.0, top)
    right.set_ylabel(f"a_w ({weighting}) (m/s^2)")
    right.set_title("ISO 2631-1 Annex C", fontsize=9)


def save_criteria_plots(ds: xr.Dataset, outdir: str | Path) -> list[Path]:
    """Write ``third_octave.png`` and ``comfort.png`` for the criteria `ds` holds.

    Parameters
    ----------
    ds : xarray.Dataset
        A run's result.
    outdir : str or pathlib.Path
        Folder for the PNG files.

    Returns
    -------
    list of pathlib.Path
        The files written (a criterion the run did not compute is skipped).
    """
    outdir = Path(outdir)
    files = []
    if "octave_level_acceleration" in ds:
        fig, ax = new_figure((10.0, 4.5), layout="constrained")
        octave_bars(ds, ax)
        files.append(save_figure(fig, outdir / "third_octave.png", tight=False))
    if "comfort_aw" in ds:
        fig, axes = new_figure((11.0, 4.5), layout="constrained", ncols=2)
        comfort_panel(ds, (axes[0], axes[1]))
        files.append(save_figure(fig, outdir / "comfort.png", tight=False))
    return files
