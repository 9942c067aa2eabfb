"""Figures of the engineering criteria: one-third-octave bar plots and the comfort panel."""

from __future__ import annotations

from collections.abc import Collection
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from railvib.io import new_figure, save_figure
from railvib.outputs.comfort import ISO2631_COMFORT
from railvib.outputs.weighting import WEIGHTINGS
from railvib.plot.axes import SuperscriptLogFormatter

__all__ = ["CRITERIA_MARGINS_IN", "comfort_panel", "octave_bars", "save_criteria_plots"]

#: margins of the criteria figures, inches (left, right, bottom, top, and the gap between
#: the comfort figure's panels): those the constrained layout found for them (three-digit
#: levels, the band labels turned upright, the comfort ranges' labels), plus 0.05-0.1 in;
#: fixed, since measuring the drawn text for the layout took 40 % of their drawing time
CRITERIA_MARGINS_IN = {
    "third_octave": {"left": 0.68, "right": 0.08, "bottom": 0.6, "top": 0.08},
    "comfort": {"left": 0.78, "right": 0.2, "bottom": 0.53, "top": 0.27, "gap": 0.72},
}

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


def save_criteria_plots(
    ds: xr.Dataset, outdir: str | Path, *, stems: Collection[str] | None = None
) -> list[Path]:
    """Write ``third_octave.png`` and ``comfort.png`` for the criteria `ds` holds.

    Parameters
    ----------
    ds : xarray.Dataset
        A run's result.
    outdir : str or pathlib.Path
        Folder for the PNG files.
    stems : collection of str, optional
        Only the figures of these file stems (``third_octave``, ``comfort``); None: both.

    Returns
    -------
    list of pathlib.Path
        The files written (a criterion the run did not compute is skipped).
    """
    outdir = Path(outdir)
    files = []
    if "octave_level_acceleration" in ds and (stems is None or "third_octave" in stems):
        fig, ax = new_figure((10.0, 4.5))
        octave_bars(ds, ax)
        _margins(fig, "third_octave")
        files.append(save_figure(fig, outdir / "third_octave.png", tight=False))
    if "comfort_aw" in ds and (stems is None or "comfort" in stems):
        fig, axes = new_figure((11.0, 4.5), ncols=2)
        comfort_panel(ds, (axes[0], axes[1]))
        _margins(fig, "comfort")
        files.append(save_figure(fig, outdir / "comfort.png", tight=False))
    return files


def _margins(fig: Figure, stem: str) -> None:
    """Lay `fig` out with the margins :data:`CRITERIA_MARGINS_IN` gives for `stem`."""
    m = CRITERIA_MARGINS_IN[stem]
    width, height = fig.get_size_inches()
    panels = len(fig.axes)
    panel = (width - m["left"] - m["right"] - m.get("gap", 0.0) * (panels - 1)) / panels
    fig.subplots_adjust(
        left=m["left"] / width,
        right=1.0 - m["right"] / width,
        bottom=m["bottom"] / height,
        top=1.0 - m["top"] / height,
        wspace=m.get("gap", 0.0) / panel,
    )
