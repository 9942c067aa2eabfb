"""The paper's figures redrawn from our results: Figs. 9-16 (PSDs); Figs. 6-8 in pad_figures.

Every figure is drawn the same way, from the study data: each case in its one colour
(``color`` of the case in the study file) in every figure; one legend per figure, below
the panels, so it covers no curve; our peaks (circles) and the paper's stated points
(crosses) in the legend in the colours of their cases; the frequencies where the
irregularity spectrum jumps by definition (the class 5 / Shi-tai join) marked with a thin
line and a short label, at the frequency computed from each case's spectrum and speed;
and, where the study asks for it (``zoom``), a panel of a few comb teeth with the tooth
spacing we measure annotated.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.legend_handler import HandlerTuple
from matplotlib.lines import Line2D

from railvib.case import Case, build_spectrum
from railvib.io import new_figure, save_figure
from railvib.plot.psd import plot_psd
from railvib.reproduce.metrics import comb_peaks, comb_spacing, peak, peak_frequency, psd
from railvib.reproduce.study import CASES, COMPARISONS, FigureSpec, StudyCase
from railvib.units import kmh_to_ms

__all__ = [
    "LEGEND_GID",
    "SpectrumStep",
    "draw_figure",
    "irregularity_steps",
    "legend_entries",
    "save_paper_figure",
]

_CASES: Mapping[str, StudyCase] = {c.key: c for c in CASES}
_PANEL_LETTERS = "abcdef"
#: gid of the one legend of every figure (below the panels)
LEGEND_GID = "figure-legend"
_LEGEND_ROW_IN = 0.24  # height of one legend row at fontsize "small", inch
_PAPER_LINE: dict[str, Any] = {"color": "0.35", "ls": ":", "lw": 1.2}
_STEP_LINE: dict[str, Any] = {"color": "0.55", "ls": "-.", "lw": 0.7}
_TEXT: dict[str, Any] = {
    "fontsize": "x-small",
    "color": "0.25",
    "rotation": 90,
    "bbox": {"facecolor": "white", "alpha": 0.75, "lw": 0, "pad": 1.0},
}


@dataclass(frozen=True)
class SpectrumStep:
    """A jump of the irregularity spectrum by definition, as seen in a temporal PSD.

    Parameters
    ----------
    frequency_hz : float
        Where it appears at the case's speed, ``v / wavelength``, Hz.
    wavelength_m : float
        The wavelength of the jump (the join of two spectra), m.
    """

    frequency_hz: float
    wavelength_m: float


def irregularity_steps(cases: Mapping[str, Case]) -> tuple[SpectrumStep, ...]:
    """The jumps of every case's irregularity spectrum, at the frequency its speed gives.

    Parameters
    ----------
    cases : mapping of str to Case
        Validated cases (their ``[irregularity]`` and ``speed_kmh``).

    Returns
    -------
    tuple of SpectrumStep
        One per distinct frequency (to 1 mHz), ascending: ``f = v Omega / (2 pi)`` for each
        wavenumber Omega of :meth:`railvib.spectra.SpatialSpectrum.steps_rad_per_m`.
    """
    found: dict[float, SpectrumStep] = {}
    for case in cases.values():
        speed = kmh_to_ms(case.speed_kmh)
        for om in build_spectrum(case).steps_rad_per_m():
            f = speed * om / (2.0 * math.pi)
            found.setdefault(round(f, 3), SpectrumStep(f, 2.0 * math.pi / om))
    return tuple(found[k] for k in sorted(found))


def _comparison_cases(spec: FigureSpec) -> list[StudyCase]:
    comparison = next(c for c in COMPARISONS if c.key == spec.comparison)
    return [_CASES[key] for key in comparison.cases]


def _vline(ax: Axes, f: float, text: str, style: Mapping[str, Any], label: str) -> None:
    """A vertical line at `f` (Hz) with `text` written along it, near the top."""
    ax.axvline(f, label=label, **style)
    ax.text(f, 0.98, f" {text}", transform=ax.get_xaxis_transform(), ha="right", va="top", **_TEXT)


def _draw_panel(
    ax: Axes,
    spec: FigureSpec,
    results: Mapping[str, xr.Dataset],
    xlim: tuple[float, float],
    steps: Sequence[SpectrumStep],
) -> None:
    cases = _comparison_cases(spec)
    for case in cases:
        plot_psd(
            results[case.key],
            [spec.response],
            ax=ax,
            xlim=xlim,
            label=case.label,
            color=case.color,
            lw=0.9,
            gid=case.label,
        )
    for mark in spec.marks:
        band = (max(mark.band[0], xlim[0]), min(mark.band[1], xlim[1]))
        if band[0] >= band[1]:
            continue
        for case in cases:
            f = peak_frequency(results, case.key, spec.response, band)
            v = peak(results, case.key, spec.response, band)
            ax.plot(
                f,
                v,
                "o",
                mfc="none",
                mec=case.color,
                ms=7,
                label=f"ours: peak read ({case.label})",
                gid=case.label,
            )
            if case is cases[0]:
                ax.annotate(
                    mark.label, (f, v), textcoords="offset points", xytext=(5, 6), fontsize="small"
                )
    for p in spec.paper_points:
        if xlim[0] <= p.frequency_hz <= xlim[1]:
            case = _CASES[p.case]
            ax.plot(
                p.frequency_hz,
                p.psd,
                "x",
                color=case.color,
                ms=8,
                mew=2,
                label=f"paper: stated point ({case.label})",
                gid=case.label,
            )
    for f, text in spec.paper_lines:
        if xlim[0] <= f <= xlim[1]:
            _vline(ax, f, text, _PAPER_LINE, text)
    for step in steps:
        if xlim[0] < step.frequency_hz < xlim[1]:
            text = f"spectra join (λ = {step.wavelength_m:g} m)"
            _vline(ax, step.frequency_hz, text, _STEP_LINE, text)
    ax.set_xlim(*xlim)
    ax.set_ylabel("acceleration PSD [(m/s²)²/Hz]")
    legend = ax.get_legend()
    if legend is not None:  # plot_psd's: the figure has one legend, below the panels
        legend.remove()


def _draw_zoom(
    ax: Axes, spec: FigureSpec, results: Mapping[str, xr.Dataset], panel: tuple[float, float]
) -> None:
    """Annotate the comb spacing measured over `panel` (Hz) between two teeth of the zoom."""
    assert spec.zoom is not None
    key = _comparison_cases(spec)[0].key
    spacing = comb_spacing(results, key, spec.response, panel)
    teeth = comb_peaks(results, key, spec.response, panel)
    inside = teeth[(teeth >= spec.zoom[0]) & (teeth <= spec.zoom[1])]
    curve = psd(results, key, spec.response)
    if inside.size >= 2:
        f1, f2 = float(inside[0]), float(inside[1])
        top = max(float(curve.sel(frequency=f, method="nearest")) for f in (f1, f2))
        low, high = ax.get_ylim()
        y = top * 1.6
        ax.set_ylim(low, max(high, y * 2.5))
        ax.annotate(
            "", (f1, y), (f2, y), arrowprops={"arrowstyle": "<->", "color": "0.2", "lw": 1.0}
        )
        ax.annotate(
            f"f_int = {spacing:.3g} Hz\n(mean tooth spacing, {panel[0]:g}-{panel[1]:g} Hz)",
            ((f1 + f2) / 2, y),
            textcoords="offset points",
            xytext=(0, 5),
            ha="center",
            va="bottom",
            fontsize="small",
        )


def legend_entries(
    spec: FigureSpec, steps: Sequence[SpectrumStep], panels: Sequence[tuple[float, float]]
) -> tuple[list[Any], list[str]]:
    """The handles and labels of a figure's one legend (below its panels).

    Parameters
    ----------
    spec : FigureSpec
        The figure.
    steps : sequence of SpectrumStep
        The spectrum jumps marked.
    panels : sequence of (float, float)
        The frequency range of each panel, Hz.

    Returns
    -------
    (list, list of str)
        A line per case in its colour; then, where drawn, our peaks and the paper's
        points, each as a tuple of markers in the colours of their cases; the paper's
        stated frequencies; the spectrum join.
    """
    cases = _comparison_cases(spec)
    handles: list[Any] = [Line2D([], [], color=c.color, lw=1.5) for c in cases]
    labels = [c.label for c in cases]
    if spec.marks:
        handles.append(
            tuple(
                Line2D([], [], ls="none", marker="o", mfc="none", mec=c.color, ms=7) for c in cases
            )
        )
        labels.append("ours: peak read (band in the table)")
    pointed = [c for c in cases if any(p.case == c.key for p in spec.paper_points)]
    if pointed:
        handles.append(
            tuple(
                Line2D([], [], ls="none", marker="x", color=c.color, ms=8, mew=2) for c in pointed
            )
        )
        labels.append("paper: stated (frequency, PSD)")
    if spec.paper_lines:
        handles.append(Line2D([], [], **_PAPER_LINE))
        labels.append("paper: stated frequency")
    if any(lo < s.frequency_hz < hi for s in steps for lo, hi in panels):
        handles.append(Line2D([], [], **_STEP_LINE))
        labels.append("irregularity spectra join (a step by definition)")
    return handles, labels


def _legend_below(fig: Figure, handles: Sequence[Any], labels: Sequence[str]) -> float:
    """Put the figure's one legend below the axes; the fraction of the height it takes."""
    ncol = min(len(handles), 3)
    rows = math.ceil(len(handles) / ncol)
    legend = fig.legend(
        list(handles),
        list(labels),
        loc="lower center",
        ncol=ncol,
        fontsize="small",
        frameon=False,
        handler_map={tuple: HandlerTuple(ndivide=None)},
        bbox_to_anchor=(0.5, 0.0),
    )
    legend.set_gid(LEGEND_GID)
    return (rows * _LEGEND_ROW_IN + 0.1) / float(fig.get_size_inches()[1])


def draw_figure(
    spec: FigureSpec,
    results: Mapping[str, xr.Dataset],
    steps: Sequence[SpectrumStep] = (),
) -> Figure:
    """Draw one paper figure: one panel per zoom range, every case of its comparison.

    Parameters
    ----------
    spec : FigureSpec
        Which figure (component, comparison, panels, points, zoom).
    results : mapping of str to xarray.Dataset
        Study results by case key.
    steps : sequence of SpectrumStep
        Jumps of the irregularity spectrum to mark (:func:`irregularity_steps`).

    Returns
    -------
    matplotlib.figure.Figure
        Circles mark the peaks we read (labelled with the paper's point names);
        crosses mark the (frequency, PSD) pairs the paper states; dotted lines the
        frequencies it states. With a `spec.zoom`, a last panel draws that band again,
        with the mean tooth spacing of the panel containing it (``comb_spacing``).
    """
    panels = list(spec.panels) + ([spec.zoom] if spec.zoom is not None else [])
    n = len(panels)
    rows = math.ceil(len(legend_entries(spec, steps, panels)[0]) / 3)
    fig, axes = new_figure(
        figsize=(max(5.6 * n, 9.0), 4.2 + rows * _LEGEND_ROW_IN),
        nrows=1,
        ncols=n,
        squeeze=False,
    )
    for i, (ax, xlim) in enumerate(zip(axes[0], panels, strict=True)):
        _draw_panel(ax, spec, results, xlim, steps)
        prefix = f"({_PANEL_LETTERS[i]}) " if n > 1 else ""
        ax.set_title(f"{prefix}{xlim[0]:g}-{xlim[1]:g} Hz", fontsize="medium")
    if spec.zoom is not None:
        i = next(j for j, (lo, hi) in enumerate(spec.panels) if lo <= spec.zoom[0] <= hi)
        axes[0][i].axvspan(*spec.zoom, color="0.85", alpha=0.6, lw=0, label="zoomed band")
        zoom_ax = axes[0][n - 1]
        zoom_ax.set_title(
            f"({_PANEL_LETTERS[n - 1]}) zoom of ({_PANEL_LETTERS[i]}): "
            f"{spec.zoom[0]:g}-{spec.zoom[1]:g} Hz",
            fontsize="medium",
        )
        _draw_zoom(zoom_ax, spec, results, spec.panels[i])
    comparison = next(c for c in COMPARISONS if c.key == spec.comparison)
    fig.suptitle(
        f"Fig. {spec.number}: {spec.component} ({spec.response})\n{comparison.title}",
        fontsize="medium",
    )
    bottom = _legend_below(fig, *legend_entries(spec, steps, panels))
    fig.tight_layout(rect=(0.0, bottom, 1.0, 1.0))
    return fig


def save_paper_figure(
    spec: FigureSpec,
    results: Mapping[str, xr.Dataset],
    outdir: str | Path,
    steps: Sequence[SpectrumStep] = (),
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
    steps : sequence of SpectrumStep
        Jumps of the irregularity spectrum to mark (:func:`irregularity_steps`).

    Returns
    -------
    pathlib.Path
        The file written.
    """
    fig = draw_figure(spec, results, steps)
    return save_figure(fig, Path(outdir) / f"{spec.stem}.png", tight=False)
