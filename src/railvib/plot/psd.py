"""PSD plots. Functions take result datasets, draw on ``ax`` (created if None), return axes.

:func:`save_overview` writes the figures of ``railvib run``: one per response
group (bounce accelerations of the car body, bogies, wheelsets and the rail under
the wheels; the pitch accelerations in rad-based units), the contact-force PSDs,
the irregularity PSD applied and the pad's storage stiffness and loss factor, on a
log frequency axis, with y-limits from the data (:func:`psd_ylim`) and a title
stating the case and its speed.
"""

from __future__ import annotations

import textwrap
from collections.abc import Callable, Collection, Sequence
from functools import partial
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from railvib.io import new_figure, save_figure
from railvib.labels import leading_car_label
from railvib.plot import OVERVIEW_GROUPS
from railvib.plot.axes import SuperscriptLogFormatter, label_log_axis, log_axis
from railvib.results.units import QUANTITY_UNITS, quantity_unit

__all__ = [
    "OVERVIEW_GROUPS",
    "OVERVIEW_MARGINS_IN",
    "PSD_DECADES",
    "SuperscriptLogFormatter",
    "axis_label",
    "case_title",
    "overview_figures",
    "plot_irregularity_psd",
    "plot_pad_stiffness",
    "plot_psd",
    "plot_wheel_psd",
    "psd_ylim",
    "save_overview",
]

#: size of a one-panel overview figure, inches (width, height)
_ONE_PANEL_IN = (7.0, 4.3)

#: decades of PSD shown below the peak by :func:`psd_ylim`
PSD_DECADES = 8.0

_KN_PER_MM = 1e6  # N/m


def _log(ax: Axes, axis: str) -> None:
    """Make the x or y `axis` of `ax` logarithmic (:func:`railvib.plot.axes.log_axis`).

    A PSD (y) axis spans many decades: it keeps a tick and a grid line per decade and
    no minor ticks; the frequency (x) axis keeps its minor grid.
    """
    log_axis(ax, axis, minor=axis == "x")


def _new_axes(ax: Axes | None, figsize: tuple[float, float]) -> Axes:
    """`ax`, or for interactive use new axes on a pyplot figure (in the user's backend)."""
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    return plt.subplots(figsize=figsize)[1]


def psd_ylim(values: ArrayLike, decades: float = PSD_DECADES) -> tuple[float, float] | None:
    """Y-limits of a log PSD axis from the data: ``(peak / 10**decades, 2 * peak)``.

    Parameters
    ----------
    values : array_like
        The PSD values drawn, in their unit (e.g. (m/s^2)^2/Hz); zeros, negative and
        non-finite values are ignored.
    decades : float
        Decades shown below the peak (dimensionless, decades of the PSD).

    Returns
    -------
    (float, float) or None
        The limits, in the unit of `values`; None when no value is positive.
    """
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v) & (v > 0)]
    if v.size == 0:
        return None
    top = float(v.max())
    return top / 10.0**decades, 2.0 * top


def case_title(ds: xr.Dataset) -> str:
    """The title and speed of a run from its attributes: ``"<title> - 80 km/h (22.22 m/s)"``.

    Parameters
    ----------
    ds : xarray.Dataset
        A result of :func:`railvib.run` (attributes ``title``, ``speed_m_per_s``).

    Returns
    -------
    str
        The title; the speed in km/h and m/s where known.
    """
    title = str(ds.attrs.get("title", "")).strip()
    speed = ds.attrs.get("speed_m_per_s")
    if speed is None:
        return title
    v = float(speed)
    text = f"{v * 3.6:.4g} km/h ({v:.4g} m/s)"
    return f"{title} - {text}" if title else text


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


def _unit(ds: xr.Dataset, variable: str, responses: Sequence[str]) -> str:
    """The unit of `variable` for `responses`: one unit, or each distinct one joined by ``; ``."""
    da = ds[variable]
    unit = str(da.attrs.get("units", ""))
    if variable in QUANTITY_UNITS and unit == quantity_unit(variable):
        found = list(dict.fromkeys(quantity_unit(variable, str(r)) for r in responses))
        return "; ".join(found)
    return unit


def _limits(ax: Axes, values: ArrayLike, ylim: tuple[float, float] | str | None) -> None:
    if ylim == "auto":
        auto = psd_ylim(values)
        if auto is not None:
            ax.set_ylim(*auto)
    elif ylim is not None and not isinstance(ylim, str):
        ax.set_ylim(*ylim)


def plot_psd(
    ds: xr.Dataset,
    responses: Sequence[str],
    *,
    variable: str = "psd_acceleration",
    ax: Axes | None = None,
    xlim: tuple[float, float] | None = None,
    logx: bool = False,
    label: str = "",
    ylim: tuple[float, float] | str | None = None,
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
    ylim : (float, float), "auto" or None
        PSD axis limits in the unit of `variable`; ``"auto"``: from the data drawn
        (:func:`psd_ylim`); None: matplotlib's.
    **line_kw
        Passed to ``Axes.plot``.

    Returns
    -------
    matplotlib.axes.Axes
        The y-label carries the unit of the responses drawn (rad-based for pitch).
    """
    ax = _new_axes(ax, (7, 4))
    da = ds[variable]
    if xlim is not None:
        da = da.sel(frequency=slice(*xlim))
    for resp in responses:
        text = f"{label} {resp}".strip() if len(responses) > 1 or not label else label
        ax.plot(da["frequency"], da.sel(response=resp), label=text, **line_kw)  # type: ignore[arg-type]
    _log(ax, "y")
    if logx:
        _log(ax, "x")
    _limits(ax, da.sel(response=list(responses)).values, ylim)
    ax.set_xlabel(axis_label(ds["frequency"]))
    name = da.attrs.get("long_name", variable)
    ax.set_ylabel(f"{name} [{_unit(ds, variable, responses)}]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize="small", loc="upper right")
    return ax


def plot_wheel_psd(
    ds: xr.Dataset,
    variable: str = "psd_force",
    *,
    ax: Axes | None = None,
    logx: bool = True,
    ylim: tuple[float, float] | str | None = "auto",
) -> Axes:
    """Plot a PSD over ``wheel`` (the contact forces) against frequency, one line per wheel.

    Parameters
    ----------
    ds : xarray.Dataset
        A result dataset.
    variable : str
        A ``(frequency, wheel)`` PSD, e.g. ``psd_force`` (N^2/Hz).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on.
    logx : bool
        Logarithmic frequency axis.
    ylim : (float, float), "auto" or None
        PSD axis limits in the unit of `variable` (see :func:`plot_psd`).

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _new_axes(ax, (7, 4))
    da = ds[variable]
    for wheel in da["wheel"].values:
        ax.plot(da["frequency"], da.sel(wheel=wheel), label=f"wheel {wheel}")
    _log(ax, "y")
    if logx:
        _log(ax, "x")
    _limits(ax, da.values, ylim)
    ax.set_xlabel(axis_label(ds["frequency"]))
    ax.set_ylabel(axis_label(da))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize="small", loc="upper right")
    return ax


def plot_irregularity_psd(
    ds: xr.Dataset,
    *,
    ax: Axes | None = None,
    logx: bool = True,
    ylim: tuple[float, float] | str | None = "auto",
) -> Axes:
    """Plot the temporal irregularity PSD the run applied (m^2/Hz) against frequency.

    Parameters
    ----------
    ds : xarray.Dataset
        A result dataset (its ``irregularity_psd``).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on.
    logx : bool
        Logarithmic frequency axis.
    ylim : (float, float), "auto" or None
        PSD axis limits in m^2/Hz (see :func:`plot_psd`).

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _new_axes(ax, (7, 4))
    da = ds["irregularity_psd"]
    ax.plot(da["frequency"], da, color="k")
    _log(ax, "y")
    if logx:
        _log(ax, "x")
    _limits(ax, da.values, ylim)
    ax.set_xlabel(axis_label(ds["frequency"]))
    ax.set_ylabel(axis_label(da))
    ax.grid(True, which="both", alpha=0.3)
    return ax


def plot_pad_stiffness(
    ds: xr.Dataset, *, axes: tuple[Axes, Axes] | None = None, logx: bool = True
) -> tuple[Axes, Axes]:
    """Plot the pad's storage stiffness K'(f) (kN/mm) and loss factor K''/K' (-) of a run.

    Parameters
    ----------
    ds : xarray.Dataset
        A result dataset (its complex ``pad_stiffness``, N/m, at the case's temperature).
    axes : (Axes, Axes), optional
        Axes for K' and the loss factor; a new two-panel figure when None.
    logx : bool
        Logarithmic frequency axis.

    Returns
    -------
    (matplotlib.axes.Axes, matplotlib.axes.Axes)
    """
    if axes is None:  # for interactive use: a pyplot figure, in the user's backend
        import matplotlib.pyplot as plt

        _, axes = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True)
    ax_k, ax_eta = axes
    k = np.asarray(ds["pad_stiffness"].values)
    f = ds["frequency"].values
    ax_k.plot(f, k.real / _KN_PER_MM, color="C0")
    ax_eta.plot(f, k.imag / k.real, color="C1")
    ax_k.set_ylabel("storage stiffness K' [kN/mm]")
    ax_eta.set_ylabel("loss factor K''/K' [-]")
    ax_eta.set_xlabel(axis_label(ds["frequency"]))
    for ax in axes:
        if logx:
            ax.set_xscale("log")
        ax.grid(True, which="both", alpha=0.3)
    for ax in axes if logx else ():  # after both scales: a shared axis resets the formatters
        label_log_axis(ax.xaxis)
    return ax_k, ax_eta


#: margins of a one-panel overview figure, inches: those ``tight_layout`` finds for the
#: log-log PSD figures (two-digit negative exponents on the PSD axis, one line of
#: suptitle), so they need not be measured from the drawn text for every figure (a
#: third of the drawing time); the top grows by one line height per suptitle line
OVERVIEW_MARGINS_IN = {"left": 0.84, "right": 0.15, "bottom": 0.59, "top": 0.66, "line": 0.19}


def _titled(fig: Figure, ax: Axes, ds: xr.Dataset, what: str, *, tight: bool = False) -> Figure:
    """Title `ax` and the figure (the case), and lay the figure out.

    `tight`: by ``tight_layout`` (the two-panel pad figure, whose linear tick labels
    vary); else with :data:`OVERVIEW_MARGINS_IN`.
    """
    ax.set_title(what, y=1.0)  # where matplotlib puts it, without measuring the axes
    lines = textwrap.wrap(case_title(ds), 90)
    fig.suptitle("\n".join(lines), fontsize="medium")
    if tight:
        fig.tight_layout()
        return fig
    m = OVERVIEW_MARGINS_IN
    width, height = fig.get_size_inches()
    top = m["top"] + m["line"] * (max(len(lines), 1) - 1)
    fig.subplots_adjust(
        left=m["left"] / width,
        right=1.0 - m["right"] / width,
        bottom=m["bottom"] / height,
        top=1.0 - top / height,
    )
    return fig


def _one_panel(ds: xr.Dataset, logx: bool) -> list[tuple[str, str, Callable[..., object]]]:
    """The one-panel figures of :func:`overview_figures`: (file stem, title, drawing)."""
    out: list[tuple[str, str, Callable[..., object]]] = []
    labels = {str(r) for r in ds["response"].values}
    for stem, title, responses in OVERVIEW_GROUPS:
        present = [r for r in responses if r in labels]
        if not present:  # a train: the same figure for its leading car
            present = [r for r in map(leading_car_label, responses) if r in labels]
            title = f"{title} (leading car)" if present else title
        if not present:
            continue
        out.append((stem, title, partial(plot_psd, ds, present, logx=logx, ylim="auto")))
    if "psd_force" in ds:
        draw = partial(plot_wheel_psd, ds, "psd_force", logx=logx)
        out.append(("psd_force", "Wheel-rail contact forces", draw))
    if "irregularity_psd" in ds:
        draw = partial(plot_irregularity_psd, ds, logx=logx)
        out.append(("irregularity_psd", "Irregularity applied", draw))
    return out


def _pad_figure(ds: xr.Dataset, logx: bool) -> Figure:
    """The two-panel pad figure of :func:`overview_figures`, laid out."""
    fig, (ax_k, ax_eta) = new_figure(figsize=(7, 5.5), nrows=2, ncols=1, sharex=True)
    plot_pad_stiffness(ds, axes=(ax_k, ax_eta), logx=logx)
    return _titled(fig, ax_k, ds, "Railpad (beam model)", tight=True)


def overview_figures(ds: xr.Dataset, *, logx: bool = True) -> list[tuple[str, Figure]]:
    """The figures of ``railvib run``, not yet saved: ``(file stem, figure)`` pairs.

    Parameters
    ----------
    ds : xarray.Dataset
        A result dataset of :func:`railvib.run`.
    logx : bool
        Logarithmic frequency axes (the default of ``railvib run``).

    Returns
    -------
    list of (str, matplotlib.figure.Figure)
        One per group of :data:`OVERVIEW_GROUPS` with a response in `ds` (PSD axis
        from :func:`psd_ylim`), then ``psd_force`` (contact forces),
        ``irregularity_psd`` and ``pad_stiffness`` where `ds` has them; each titled
        with the case and its speed (:func:`case_title`).
    """
    out: list[tuple[str, Figure]] = []
    for stem, title, draw in _one_panel(ds, logx):
        fig, ax = new_figure(figsize=_ONE_PANEL_IN)
        draw(ax=ax)
        out.append((stem, _titled(fig, ax, ds, title)))
    if "pad_stiffness" in ds:
        out.append(("pad_stiffness", _pad_figure(ds, logx)))
    return out


def _emptied(ax: Axes) -> Axes:
    """`ax` without its lines and legend, its limits and colour cycle as when new."""
    for line in list(ax.lines):
        line.remove()
    legend = ax.get_legend()
    if legend is not None:
        legend.remove()
    ax.set_prop_cycle(None)
    ax.relim()
    ax.set_autoscale_on(True)
    return ax


def save_overview(
    ds: xr.Dataset,
    outdir: str | Path,
    *,
    logx: bool = True,
    stems: Collection[str] | None = None,
) -> list[Path]:
    """Write the figures of :func:`overview_figures` as ``<stem>.png`` to `outdir`.

    The one-panel figures are drawn in turn on one figure, emptied between them (the
    same pixels as :func:`overview_figures`' own figures; its axes' ticks, a third of
    the drawing time, are made once).

    Parameters
    ----------
    ds : xarray.Dataset
        A result dataset of :func:`railvib.run`.
    outdir : str or pathlib.Path
        Folder for the PNG files (each through :func:`railvib.io.save_figure`).
    logx : bool
        Logarithmic frequency axes.
    stems : collection of str, optional
        Only the figures of these file stems (of :data:`railvib.plot.OVERVIEW_STEMS`);
        None: all.

    Returns
    -------
    list of pathlib.Path
        The files written; a group with none of its responses in `ds` is skipped.
    """
    outdir = Path(outdir)
    files = []
    panels = [(s, t, d) for s, t, d in _one_panel(ds, logx) if stems is None or s in stems]
    if panels:
        fig, ax = new_figure(figsize=_ONE_PANEL_IN)
    for stem, title, draw in panels:
        draw(ax=_emptied(ax))
        files.append(save_figure(_titled(fig, ax, ds, title), outdir / f"{stem}.png", tight=False))
    if "pad_stiffness" in ds and (stems is None or "pad_stiffness" in stems):
        files.append(save_figure(_pad_figure(ds, logx), outdir / "pad_stiffness.png", tight=False))
    return files
