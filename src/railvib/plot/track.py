"""Track-alone plots: receptance magnitude and phase, decay rates in bands, dispersion.

The functions draw a dataset of :func:`railvib.trackrun.track_dataset` (no physics
here) on the given axes (created when None) and return them.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.axes import Axes

from railvib.io import new_figure, save_figure
from railvib.plot.axes import log_axis

__all__ = [
    "TRACK_PLOT_STEMS",
    "plot_decay_rate",
    "plot_dispersion",
    "plot_receptance",
    "save_track_plots",
]

#: the figures :func:`save_track_plots` writes (file stems)
TRACK_PLOT_STEMS = ("receptance", "decay_rate", "dispersion")


def plot_receptance(ds: xr.Dataset, axes: tuple[Axes, Axes] | None = None) -> tuple[Axes, Axes]:
    """Receptance magnitude (m/N, log) and phase (degrees) against frequency, per position.

    Parameters
    ----------
    ds : xarray.Dataset
        A track dataset (``receptance_magnitude``, ``receptance_phase``).
    axes : (Axes, Axes), optional
        Axes for magnitude and phase; a new figure when None.

    Returns
    -------
    (matplotlib.axes.Axes, matplotlib.axes.Axes)
    """
    if axes is None:  # for interactive use: a pyplot figure, in the user's backend
        import matplotlib.pyplot as plt

        _, axes = plt.subplots(2, 1, figsize=(7, 6.5), sharex=True)
    ax_m, ax_p = axes
    f = ds["frequency"].values
    x_load = float(ds.attrs["load_position_m"])
    for x in ds["position"].values:
        label = f"x - x_load = {x - x_load:+.3g} m"
        ax_m.plot(f, ds["receptance_magnitude"].sel(position=x).values, lw=1.0, label=label)
        ax_p.plot(f, np.degrees(ds["receptance_phase"].sel(position=x).values), lw=1.0)
    log_axis(ax_m, "x")
    log_axis(ax_m, "y")
    ax_m.set_ylabel("|receptance| (m/N)")
    ax_m.set_title(f"rail receptance, unit force at x = {x_load:.3g} m")
    ax_m.legend(fontsize="small")
    ax_p.set_ylabel("phase (degrees)")
    ax_p.set_xlabel("frequency (Hz)")
    ax_p.set_ylim(-185.0, 185.0)
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
    return ax_m, ax_p


def plot_decay_rate(ds: xr.Dataset, ax: Axes | None = None) -> Axes:
    """EN 15461 track decay rate per one-third octave band (steps), least-attenuated wave beside.

    Parameters
    ----------
    ds : xarray.Dataset
        A track dataset (``decay_rate``, ``wave_decay_band``, ``band_lower``,
        ``band_upper``, attribute ``decay_rate_floor_db_per_m``).
    ax : Axes, optional
        Axes to draw on; a new figure when None.

    Returns
    -------
    matplotlib.axes.Axes
    """
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(7, 4.5))
    lower = ds["band_lower"].values
    upper = ds["band_upper"].values
    edges = np.concatenate([lower, upper[-1:]])
    for name, style, label in (
        ("decay_rate", "C0-", "track decay rate (EN 15461)"),
        ("wave_decay_band", "C3--", "least-attenuated wave"),
    ):
        values = ds[name].values
        ax.stairs(values, edges, baseline=None, color=style[:2], ls=style[2:], lw=1.5, label=label)
    floor = float(ds.attrs["decay_rate_floor_db_per_m"])
    ax.axhline(floor, color="0.4", ls=":", lw=1.0, label="2 DR_min (EN 15461 clause 7)")
    log_axis(ax, "x")
    log_axis(ax, "y")
    ax.set_xlabel("frequency (Hz), one-third octave bands")
    ax.set_ylabel("decay rate (dB/m)")
    ax.set_title("track decay rate")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize="small")
    return ax


def plot_dispersion(ds: xr.Dataset, axes: tuple[Axes, Axes] | None = None) -> tuple[Axes, Axes]:
    """Decay (dB/m) and phase constant (rad/m) of each wave against frequency; stop bands shaded.

    Parameters
    ----------
    ds : xarray.Dataset
        A track dataset (``wave_decay``, ``wavenumber``, ``propagates``).
    axes : (Axes, Axes), optional
        Axes for decay and phase constant; a new figure when None.

    Returns
    -------
    (matplotlib.axes.Axes, matplotlib.axes.Axes)
    """
    if axes is None:
        import matplotlib.pyplot as plt

        _, axes = plt.subplots(2, 1, figsize=(7, 6.5), sharex=True)
    ax_d, ax_k = axes
    f = ds["frequency"].values
    for j, wave in enumerate(ds["wave"].values):
        ax_d.plot(f, ds["wave_decay"].sel(wave=wave).values, f"C{j}-", lw=1.0, label=f"wave {wave}")
        ax_k.plot(f, ds["wavenumber"].sel(wave=wave).values, f"C{j}-", lw=1.0)
    first = ds["propagates"].isel(wave=0).values
    stop = ~first
    for ax in axes:
        ax.fill_between(f, 0, 1, where=stop, transform=ax.get_xaxis_transform(), color="0.85", lw=0)
        ax.grid(True, which="both", alpha=0.3)
    log_axis(ax_d, "x")
    log_axis(ax_d, "y")
    ax_d.set_ylabel("decay (dB/m)")
    ax_d.set_title("waves of the periodic track (grey: wave 1 in a stop band)")
    ax_d.legend(fontsize="small")
    ax_k.set_ylabel("phase constant |arg mu| / period (rad/m)")
    ax_k.set_xlabel("frequency (Hz)")
    return ax_d, ax_k


def save_track_plots(ds: xr.Dataset, folder: str | Path) -> list[Path]:
    """Write the figures of :data:`TRACK_PLOT_STEMS` as PNGs into `folder`.

    Parameters
    ----------
    ds : xarray.Dataset
        A track dataset.
    folder : str or pathlib.Path
        Existing folder.

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    folder = Path(folder)
    fig, axes = new_figure((7, 6.5), nrows=2, sharex=True)
    plot_receptance(ds, (axes[0], axes[1]))
    files = [save_figure(fig, folder / "receptance.png")]
    fig, ax = new_figure((7, 4.5))
    plot_decay_rate(ds, ax)
    files.append(save_figure(fig, folder / "decay_rate.png"))
    fig, axes = new_figure((7, 6.5), nrows=2, sharex=True)
    plot_dispersion(ds, (axes[0], axes[1]))
    files.append(save_figure(fig, folder / "dispersion.png"))
    return files
