"""Matplotlib figures as Plotly figure specifications: the same figure, zoomable, with hover.

:func:`figure_to_plotly` reads what a drawn :class:`matplotlib.figure.Figure` shows (each
axes' lines and markers, vertical lines and spans, texts, scales, limits, titles and axis
labels) and writes it as a Plotly figure (``{"data": [...], "layout": {...}}``, plain
JSON types) for ``Plotly.newPlot`` in a page that carries plotly.js itself. Nothing is
computed again, so the interactive figure shows exactly the numbers of the PNG; no Plotly
Python code is needed to build it.

Lines with a label (not starting with ``_``) get a legend entry; lines sharing a ``gid``
form one legend group (one click hides a case's curve, its markers and its crosses in
every panel), shown once. Uniformly spaced x data are written as ``x0``/``dx``, values
with :data:`DIGITS` significant digits, to keep a page of many figures small.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.colors import to_hex
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Rectangle
from matplotlib.text import Annotation

from railvib.plot.axes import PLAIN_RANGE

__all__ = ["DIGITS", "PX_PER_INCH", "figure_to_plotly"]

#: significant digits of the values written (the hover shows four)
DIGITS = 5
#: pixels per inch of figure size (a figure keeps its height on the page)
PX_PER_INCH = 96.0

_DASH = {"-": "solid", "--": "dash", ":": "dot", "-.": "dashdot"}
_SYMBOL = {"o": "circle", "x": "x-thin", "s": "square", "^": "triangle-up", "+": "cross-thin"}
_PT_TO_PX = 96.0 / 72.0


def _values(v: Any) -> list[float | None]:
    """Floats with :data:`DIGITS` significant digits; NaN and infinities as None (null)."""
    a = np.asarray(v, dtype=float).ravel()
    text = np.char.mod(f"%.{DIGITS}g", a)
    return [float(t) if math.isfinite(x) else None for t, x in zip(text, a, strict=True)]


def _axis_refs(i: int) -> tuple[str, str, str, str]:
    """Trace axis names (``x2``), and layout keys (``xaxis2``) of the `i`-th axes (from 1)."""
    n = "" if i == 1 else str(i)
    return f"x{n}", f"y{n}", f"xaxis{n}", f"yaxis{n}"


def _axis_layout(ax: Axes, which: str, anchor: str, domain: tuple[float, float]) -> dict:
    log = (ax.get_xscale() if which == "x" else ax.get_yscale()) == "log"
    lo, hi = ax.get_xlim() if which == "x" else ax.get_ylim()
    rng = [math.log10(lo), math.log10(hi)] if log else [lo, hi]
    label = ax.get_xlabel() if which == "x" else ax.get_ylabel()
    return {
        "type": "log" if log else "linear",
        "range": rng,
        "domain": list(domain),
        "anchor": anchor,
        "title": {"text": label, "font": {"size": 12}},
        "showgrid": True,
        "exponentformat": "none"
        if log and PLAIN_RANGE[0] <= min(lo, hi) and max(lo, hi) < PLAIN_RANGE[1]
        else "power",
        "zeroline": False,
    }


def _is_vertical(line: Line2D, ax: Axes) -> bool:
    """An ``axvline``: x in data coordinates, y in axes coordinates."""
    return line.get_transform() == ax.get_xaxis_transform()


def _line_trace(line: Line2D, xref: str, yref: str, ax: Axes) -> dict:
    x = np.asarray(line.get_xdata(), dtype=float).ravel()
    label = str(line.get_label())
    marker = str(line.get_marker())
    style = str(line.get_linestyle())
    has_line = style not in ("None", "none", "", " ")
    has_marker = marker not in ("None", "none", "", " ")
    color = to_hex(line.get_color())
    trace: dict[str, Any] = {
        "type": "scatter",
        "xaxis": xref,
        "yaxis": yref,
        "y": _values(line.get_ydata()),
        "mode": "+".join(m for m, on in (("lines", has_line), ("markers", has_marker)) if on),
        "name": "" if label.startswith("_") else label,
        "hovertemplate": (
            f"{'' if label.startswith('_') else label}<br>{ax.get_xlabel()}: %{{x:.4g}}<br>"
            f"{ax.get_ylabel()}: %{{y:.4g}}<extra></extra>"
        ),
    }
    step = np.diff(x)
    if x.size > 2 and np.allclose(step, step[0], rtol=1e-6, atol=0.0):
        trace["x0"], trace["dx"] = _values([x[0], step[0]])
    else:
        trace["x"] = _values(x)
    if has_line:
        trace["line"] = {
            "color": color,
            "width": round(float(line.get_linewidth()) * _PT_TO_PX, 2),
            "dash": _DASH.get(style, "solid"),
        }
    if has_marker:
        face = line.get_markerfacecolor()
        hollow = isinstance(face, str) and face.lower() == "none"
        symbol = _SYMBOL.get(marker, "circle")
        trace["marker"] = {
            "symbol": f"{symbol}-open" if hollow or symbol.endswith("-thin") else symbol,
            "size": round(float(line.get_markersize()) * _PT_TO_PX, 1),
            "color": to_hex(line.get_markeredgecolor()) if hollow else color,
            "line": {
                "width": round(float(line.get_markeredgewidth()) * _PT_TO_PX, 1),
                "color": to_hex(line.get_markeredgecolor()),
            },
        }
    return trace


def _log_data(ax: Axes, x: float, y: float) -> tuple[float, float]:
    """Data coordinates as Plotly places annotations: log10 of a log axis' value."""
    return (
        math.log10(x) if ax.get_xscale() == "log" else x,
        math.log10(y) if ax.get_yscale() == "log" else y,
    )


def _annotation(text: Annotation, ax: Axes, xref: str, yref: str) -> dict | None:
    """``ax.annotate`` at a data point: its text, shifted by its offset in points."""
    if text.xycoords != "data" or not str(text.get_text()).strip():
        return None
    x, y = _log_data(ax, *text.xy)
    dx, dy = text.xyann if text.anncoords == "offset points" else (0.0, 0.0)
    return {
        "text": str(text.get_text()).strip().replace("\n", "<br>"),
        "x": x,
        "y": y,
        "xref": xref,
        "yref": yref,
        "xshift": dx * _PT_TO_PX,
        "yshift": dy * _PT_TO_PX,
        "showarrow": False,
        "xanchor": {"left": "left", "right": "right"}.get(text.get_horizontalalignment(), "center"),
        "yanchor": {"top": "top", "bottom": "bottom"}.get(text.get_verticalalignment(), "middle"),
        "font": {"size": 11},
    }


def _arrow_shape(text: Annotation, xref: str, yref: str) -> dict | None:
    """An arrow without text (``annotate("", xy, xytext, arrowprops=...)``) as a line."""
    if str(text.get_text()).strip() or text.arrow_patch is None or text.xycoords != "data":
        return None
    if text.anncoords != "data":
        return None
    (x0, y0), (x1, y1) = text.xyann, text.xy
    return {
        "type": "line",
        "xref": xref,
        "yref": yref,
        "x0": x0,
        "x1": x1,
        "y0": y0,
        "y1": y1,
        "line": {"color": "#333", "width": 1.3},
    }


def _text_annotation(text: Any, ax: Axes, xref: str, yref: str) -> dict | None:
    """A text of `ax` as a Plotly annotation, where its coordinates are those of the axes."""
    if isinstance(text, Annotation):
        return _annotation(text, ax, xref, yref)
    transform = text.get_transform()
    x, y = text.get_position()
    if transform == ax.transData:
        refs = (xref, yref)
    elif transform == ax.get_xaxis_transform():
        refs = (xref, f"{yref} domain")
    elif transform == ax.transAxes:
        refs = (f"{xref} domain", f"{yref} domain")
    else:
        return None
    content = str(text.get_text()).strip()
    if not content:
        return None
    if transform == ax.transData:
        x, y = _log_data(ax, x, y)
    elif transform == ax.get_xaxis_transform() and ax.get_xscale() == "log":
        x = math.log10(x)
    return {
        "text": content.replace("\n", "<br>"),
        "x": x,
        "y": y,
        "xref": refs[0],
        "yref": refs[1],
        "showarrow": False,
        "textangle": -float(text.get_rotation()),
        "xanchor": {"left": "left", "right": "right"}.get(text.get_ha(), "center"),
        "yanchor": {"top": "top", "bottom": "bottom"}.get(text.get_va(), "middle"),
        "font": {"size": 10, "color": "#444"},
    }


def _span_shape(patch: Patch, ax: Axes, xref: str, yref: str) -> dict | None:
    """An ``axvspan`` (x in data, y in axes coordinates) as a Plotly rectangle."""
    if not isinstance(patch, Rectangle) or patch.get_data_transform() != ax.get_xaxis_transform():
        return None
    x = np.array([patch.get_x(), patch.get_x() + patch.get_width()], dtype=float)
    return {
        "type": "rect",
        "xref": xref,
        "yref": f"{yref} domain",
        "x0": float(x.min()),
        "x1": float(x.max()),
        "y0": 0,
        "y1": 1,
        "fillcolor": to_hex(patch.get_facecolor()),
        "opacity": float(patch.get_alpha() or 1.0) * 0.5,
        "line": {"width": 0},
        "layer": "below",
    }


def figure_to_plotly(fig: Figure) -> dict[str, Any]:
    """The Plotly figure specification of a drawn matplotlib `fig`.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A figure, laid out (its axes keep their positions on the page).

    Returns
    -------
    dict
        ``{"data": [...], "layout": {...}}`` of JSON types (None for NaN): one trace per
        line with data, each axes as a Plotly axis pair at the same place, ``axvline`` as
        shapes, ``axvspan`` as rectangles, texts as annotations; the figure's suptitle as
        the title and its height in pixels (:data:`PX_PER_INCH`).
    """
    data: list[dict[str, Any]] = []
    shapes: list[dict[str, Any]] = []
    annotations: list[dict[str, Any]] = []
    layout: dict[str, Any] = {}
    groups: set[str] = set()
    for i, ax in enumerate((a for a in fig.axes if a.get_visible()), start=1):
        xref, yref, xkey, ykey = _axis_refs(i)
        pos = ax.get_position()
        layout[xkey] = _axis_layout(ax, "x", yref, (pos.x0, pos.x1))
        layout[ykey] = _axis_layout(ax, "y", xref, (pos.y0, pos.y1))
        if ax.get_title():
            annotations.append(
                {
                    "text": ax.get_title(),
                    "x": 0.5,
                    "y": 1.0,
                    "xref": f"{xref} domain",
                    "yref": f"{yref} domain",
                    "yanchor": "bottom",
                    "showarrow": False,
                    "font": {"size": 13},
                }
            )
        for line in ax.get_lines():
            if _is_vertical(line, ax):
                x = float(np.asarray(line.get_xdata(), dtype=float)[0])
                shapes.append(
                    {
                        "type": "line",
                        "xref": xref,
                        "yref": f"{yref} domain",
                        "x0": x,
                        "x1": x,
                        "y0": 0,
                        "y1": 1,
                        "line": {
                            "color": to_hex(line.get_color()),
                            "width": round(float(line.get_linewidth()) * _PT_TO_PX, 2),
                            "dash": _DASH.get(str(line.get_linestyle()), "solid"),
                        },
                    }
                )
                continue
            trace = _line_trace(line, xref, yref, ax)
            group = str(line.get_gid() or trace["name"])
            trace["legendgroup"] = group
            trace["showlegend"] = bool(trace["name"]) and group not in groups
            if trace["showlegend"]:
                groups.add(group)
            data.append(trace)
        for patch in ax.patches:
            shape = _span_shape(patch, ax, xref, yref)
            if shape is not None:
                shapes.append(shape)
        for text in ax.texts:
            note = _text_annotation(text, ax, xref, yref)
            if note is not None:
                annotations.append(note)
            arrow = _arrow_shape(text, xref, yref) if isinstance(text, Annotation) else None
            if arrow is not None:
                shapes.append(arrow)
    suptitle = fig.get_suptitle()
    width, height = fig.get_size_inches()
    layout.update(
        {
            "title": {"text": suptitle.replace("\n", "<br>"), "font": {"size": 14}},
            "height": round(float(height) * PX_PER_INCH * 1.15),
            "shapes": shapes,
            "annotations": annotations,
            "legend": {
                "orientation": "h",
                "x": 0.5,
                "xanchor": "center",
                "y": 0.0,
                "yanchor": "bottom",
            },
            "hovermode": "closest",
            "margin": {"t": 70, "l": 70, "r": 20, "b": 40},
            "template": {"layout": {"paper_bgcolor": "white", "plot_bgcolor": "white"}},
            "meta": {"aspect": round(float(width / height), 3)},
        }
    )
    return {"data": data, "layout": layout}
