"""Figures of a moving-vehicle run: the random PSDs against the stationary ones, and the lines."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from railvib.io import new_figure, save_figure

__all__ = ["MOVING_STEMS", "save_moving_plots"]

#: the figures :func:`save_moving_plots` writes (file stems)
MOVING_STEMS = ("moving_psd", "moving_lines")


def _psd_panel(ax, ds: xr.Dataset, stem: str, dim: str, label: object, title: str) -> None:  # noqa: ANN001
    f = ds.frequency.values
    moving = ds[f"{stem}psd"].sel({dim: label}).values
    still = ds[f"{stem}psd_stationary"].sel({dim: label}).values
    over = ds[f"{stem}psd_over_period"].sel({dim: label}).values  # (phase, frequency)
    ax.fill_between(f, over.min(axis=0), over.max(axis=0), color="0.85", label="over the period")
    ax.loglog(f, still, color="0.3", lw=1.0, label="stationary (fixed position)")
    ax.loglog(f, moving, color="C3", lw=1.0, label="moving (time-averaged)")
    for x in ds.line_frequency.values:
        if f[0] <= x <= f[-1]:
            ax.axvline(x, color="C0", lw=0.6, ls=":")
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel(f"PSD ({ds[f'{stem}psd'].attrs['units'].split(' ')[0]})")
    ax.set_title(title)
    ax.legend(fontsize=7)


def save_moving_plots(ds: xr.Dataset, outdir: str | Path) -> list[Path]:
    """Write ``moving_psd.png`` and ``moving_lines.png`` of a moving dataset to `outdir`.

    ``moving_psd``: the time-averaged PSDs of the leading wheel's contact force and of the
    rail under it, with the stationary PSDs, the range over the sleeper period and the
    line frequencies dotted. ``moving_lines``: the sleeper-passing lines of a smooth rail
    (contact force per wheel, and the rail under the leading wheel).

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`railvib.movingrun.run_moving`.
    outdir : str or pathlib.Path
        Folder for the PNG files.

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    outdir = Path(outdir)
    rail = next(str(r) for r in ds.response.values if str(r).startswith("rail@"))
    fig, axes = new_figure((10.0, 4.0), ncols=2)
    _psd_panel(axes[0], ds, "contact_force_", "wheel", 1, "contact force, wheel 1")
    _psd_panel(axes[1], ds, "", "response", rail, f"rail displacement, {rail}")
    files = [save_figure(fig, outdir / "moving_psd.png")]
    fig, axes = new_figure((10.0, 4.0), ncols=2)
    f_line = ds.line_frequency.values
    width = 0.8 * float(f_line[0]) / max(ds.wheel.size, 1)
    for j, w in enumerate(ds.wheel.values):
        amp = ds.contact_force_line_amplitude.sel(wheel=w).values
        axes[0].bar(f_line + (j - (ds.wheel.size - 1) / 2) * width, amp, width, label=f"wheel {w}")
    axes[0].set_yscale("log")
    axes[0].set_xlabel("frequency n v/d (Hz)")
    axes[0].set_ylabel("peak contact force (N)")
    axes[0].set_title("sleeper-passing lines, smooth rail")
    axes[0].legend(fontsize=7)
    amp = ds.line_amplitude.sel(response=rail).values
    axes[1].stem(f_line, np.asarray(amp, dtype=float))
    axes[1].set_yscale("log")
    axes[1].set_xlabel("frequency n v/d (Hz)")
    axes[1].set_ylabel("peak displacement (m)")
    axes[1].set_title(f"sleeper-passing lines, {rail}")
    files.append(save_figure(fig, outdir / "moving_lines.png"))
    return files
