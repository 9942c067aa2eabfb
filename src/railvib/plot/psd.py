"""PSD plots. Functions take result datasets, draw on ``ax`` (created if None), return axes."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg", force=False)
import matplotlib.pyplot as plt  # noqa: E402
import xarray as xr  # noqa: E402
from matplotlib.axes import Axes  # noqa: E402

from railvib.io import save_figure  # noqa: E402
from railvib.response import rail_label  # noqa: E402

__all__ = ["OVERVIEW_GROUPS", "axis_label", "plot_psd", "save_overview"]

#: (file stem, title, responses) of the overview figures written by ``railvib run``
OVERVIEW_GROUPS: tuple[tuple[str, str, tuple[str, ...]], ...] = (
    ("psd_carbody", "Car body", ("carbody.bounce",)),
    ("psd_bogie", "Bogies", ("bogie1.bounce", "bogie2.bounce")),
    ("psd_wheelset", "Wheelsets", tuple(f"wheelset{i}.bounce" for i in range(1, 5))),
    ("psd_rail", "Rail under the wheels", tuple(rail_label(i) for i in range(1, 5))),
)


def axis_label(da: xr.DataArray) -> str:
    """``long_name [units]`` from a DataArray's attributes.

    Parameters
    ----------
    da : xarray.DataArray
        A variable with ``long_name`` (else its name) and, optionally, ``units`` attributes.

    Returns
    -------
    str
        The axis label, without brackets when there is no unit.
    """
    name = da.attrs.get("long_name", da.name or "")
    unit = da.attrs.get("units")
    return f"{name} [{unit}]" if unit else str(name)


def plot_psd(
    ds: xr.Dataset,
    responses: Sequence[str],
    *,
    variable: str = "psd_acceleration",
    ax: Axes | None = None,
    xlim: tuple[float, float] | None = None,
    logx: bool = False,
    label: str = "",
    **line_kw: object,
) -> Axes:
    """Plot PSDs of `responses` against frequency on a log PSD axis.

    Parameters
    ----------
    ds : xarray.Dataset
        A result dataset.
    responses : sequence of str
        Response labels to draw.
    variable : str
        Data variable (``psd_acceleration`` or ``psd_displacement``).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on.
    xlim : (float, float), optional
        Frequency range in Hz.
    logx : bool
        Logarithmic frequency axis.
    label : str
        Prefix of the legend labels (e.g. the case name).
    **line_kw
        Passed to ``Axes.plot``.

    Returns
    -------
    matplotlib.axes.Axes
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(7, 4))
    da = ds[variable]
    if xlim is not None:
        da = da.sel(frequency=slice(*xlim))
    for resp in responses:
        text = f"{label} {resp}".strip() if len(responses) > 1 or not label else label
        ax.plot(da["frequency"], da.sel(response=resp), label=text, **line_kw)  # type: ignore[arg-type]
    ax.set_yscale("log")
    if logx:
        ax.set_xscale("log")
    ax.set_xlabel(axis_label(ds["frequency"]))
    ax.set_ylabel(axis_label(ds[variable]))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize="small", loc="upper right")
    return ax


def save_overview(ds: xr.Dataset, outdir: str | Path) -> list[Path]:
    """Write one PNG per response group (car body, bogies, wheelsets, rail) to `outdir`.

    Parameters
    ----------
    ds : xarray.Dataset
        A result dataset of :func:`railvib.run`.
    outdir : str or pathlib.Path
        Folder for the PNG files (``<stem>.png`` of :data:`OVERVIEW_GROUPS`).

    Returns
    -------
    list of pathlib.Path
        The files written; a group with none of its responses in `ds` is skipped.
    """
    outdir = Path(outdir)
    written = []
    for stem, title, responses in OVERVIEW_GROUPS:
        present = [r for r in responses if r in ds["response"].values]
        if not present:
            continue
        fig, ax = plt.subplots(figsize=(7, 4))
        plot_psd(ds, present, ax=ax)
        ax.set_title(title)
        written.append(save_figure(fig, outdir / f"{stem}.png"))
    return written
