"""The paper's figures redrawn from our results: Figs. 9-16 (PSDs); Figs. 6-8 in pad_figures."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from railvib.io import new_figure, save_figure
from railvib.plot.psd import plot_psd
from railvib.reproduce.metrics import peak, peak_frequency
from railvib.reproduce.study import (
    CASES,
    COMPARISONS,
    FigureSpec,
    StudyCase,
)

__all__ = ["draw_figure", "save_paper_figure"]

_CASES: Mapping[str, StudyCase] = {c.key: c for c in CASES}
_PANEL_LETTERS = "abcdef"


def _draw_panel(
    ax: Axes, spec: FigureSpec, results: Mapping[str, xr.Dataset], xlim: tuple[float, float]
) -> None:
    comparison = next(c for c in COMPARISONS if c.key == spec.comparison)
    for key in comparison.cases:
        case = _CASES[key]
        plot_psd(
            results[key],
            [spec.response],
            ax=ax,
            xlim=xlim,
            label=case.label,
            color=case.color,
            lw=0.9,
        )
    for mark in spec.marks:
        band = (max(mark.band[0], xlim[0]), min(mark.band[1], xlim[1]))
        if band[0] >= band[1]:
            continue
        for key in comparison.cases:
            f = peak_frequency(results, key, spec.response, band)
            v = peak(results, key, spec.response, band)
            ax.plot(f, v, "o", mfc="none", mec=_CASES[key].color, ms=7)
            if key == comparison.cases[0]:
                ax.annotate(
                    mark.label, (f, v), textcoords="offset points", xytext=(5, 6), fontsize="small"
                )
    shown = [p for p in spec.paper_points if xlim[0] <= p.frequency_hz <= xlim[1]]
    for p in shown:
        ax.plot(p.frequency_hz, p.psd, "x", color=_CASES[p.case].color, ms=8, mew=2)
    if shown:
        ax.plot([], [], "x", color="gray", ms=8, mew=2, label="paper's stated peak")
    for f, text in spec.paper_lines:
        if xlim[0] <= f <= xlim[1]:
            ax.axvline(f, color="gray", ls=":", lw=1.2, label=text)
    ax.set_xlim(*xlim)
    ax.set_ylabel("acceleration PSD [(m/s²)²/Hz]")
    ax.legend(fontsize="x-small", loc="upper right")


def draw_figure(spec: FigureSpec, results: Mapping[str, xr.Dataset]) -> Figure:
    """Draw one paper figure: one panel per zoom range, every case of its comparison.

    Parameters
    ----------
    spec : FigureSpec
        Which figure (component, comparison, panels, points).
    results : mapping of str to xarray.Dataset
        Study results by case key.

    Returns
    -------
    matplotlib.figure.Figure
        Circles mark the peaks we read (labelled with the paper's point names);
        crosses mark the (frequency, PSD) pairs the paper states.
    """
    n = len(spec.panels)
    fig, axes = new_figure(figsize=(max(6.2 * n, 9.0), 4.4), nrows=1, ncols=n, squeeze=False)
    comparison = next(c for c in COMPARISONS if c.key == spec.comparison)
    for i, (ax, xlim) in enumerate(zip(axes[0], spec.panels, strict=True)):
        _draw_panel(ax, spec, results, xlim)
        prefix = f"({_PANEL_LETTERS[i]}) " if n > 1 else ""
        ax.set_title(f"{prefix}{xlim[0]:g}-{xlim[1]:g} Hz", fontsize="medium")
    fig.suptitle(
        f"Fig. {spec.number}: {spec.component} ({spec.response})\n{comparison.title}",
        fontsize="medium",
    )
    fig.tight_layout()
    return fig


def save_paper_figure(
    spec: FigureSpec, results: Mapping[str, xr.Dataset], outdir: str | Path
) -> Path:
    """Draw `spec` and write it as ``<outdir>/<spec.stem>.png``, atomically.

    Parameters
    ----------
    spec : FigureSpec
        The figure to draw (see :func:`draw_figure`).
    results : mapping of str to xarray.Dataset
        Study results: case key -> result dataset of :func:`railvib.run`.
    outdir : str or pathlib.Path
        Folder for the PNG file.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    return save_figure(draw_figure(spec, results), Path(outdir) / f"{spec.stem}.png", tight=False)
