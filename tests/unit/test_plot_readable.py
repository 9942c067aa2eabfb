"""Issue 12: plain log tick labels (railvib.plot.axes) and matplotlib -> Plotly (interactive)."""

import json
import math

import numpy as np
import pytest
import xarray as xr
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from railvib.plot.axes import log_axis
from railvib.plot.interactive import DIGITS, figure_to_plotly
from railvib.plot.psd import plot_psd


def _labels(ax, which):
    axis = ax.xaxis if which == "x" else ax.yaxis
    FigureCanvasAgg(ax.figure).draw()
    lo, hi = sorted(axis.get_view_interval())
    ticks = [*axis.get_major_ticks(), *axis.get_minor_ticks()]
    return {
        t.label1.get_text()
        for t in ticks
        if t.label1.get_text() and lo <= t.get_loc() <= hi and t.label1.get_visible()
    }


def test_a_narrow_log_axis_has_plain_labels():
    ax = Figure().subplots()
    ax.plot([25.0, 70.0], [1.0, 2.0])
    log_axis(ax, "x")
    ax.set_xlim(25.0, 70.0)
    labels = _labels(ax, "x")
    # the example: 30, 40, 60, not 3x10^1, 4x10^1, 6x10^1
    assert {"30", "40", "60"} <= labels
    assert not any("×" in t or "¹" in t for t in labels)


def test_a_frequency_axis_over_decades_reads_1_10_100():
    ax = Figure().subplots()
    ax.plot([0.5, 1000.0], [1.0, 2.0])
    log_axis(ax, "x")
    ax.set_xlim(0.5, 1000.0)
    assert {"1", "10", "100", "1000"} <= _labels(ax, "x")


def test_a_psd_axis_over_many_decades_keeps_powers():
    ax = Figure().subplots()
    ax.plot([1.0, 2.0], [1e-9, 10.0])
    log_axis(ax, "y", minor=False)
    ax.set_ylim(1e-9, 20.0)
    labels = _labels(ax, "y")
    assert "10⁻⁵" in labels
    assert not any(t in labels for t in ("0.00001", "1e-05"))


def test_a_psd_axis_of_one_decade_gets_more_than_one_label():
    ax = Figure().subplots()
    ax.plot([1.0, 2.0], [3.0, 40.0])
    log_axis(ax, "y", minor=False)  # a PSD axis: no minor ticks
    ax.set_ylim(3.0, 40.0)
    labels = _labels(ax, "y")
    assert len(labels) >= 2
    assert "10" in labels


def test_run_figures_get_the_plain_labels_too():
    f = np.linspace(1.0, 200.0, 200)
    ds = xr.Dataset(
        {"psd_acceleration": (("frequency", "response"), np.ones((200, 1)))},
        coords={"frequency": f, "response": ["carbody.bounce"]},
    )
    ax = Figure().subplots()
    plot_psd(ds, ["carbody.bounce"], ax=ax, logx=True)
    assert {"10", "100"} <= _labels(ax, "x")


def _spec():
    fig = Figure(figsize=(6.0, 4.0))
    ax = fig.subplots()
    f = np.arange(1.0, 101.0, 0.5)  # uniform: written as x0 / dx
    ax.plot(f, 1.0 / f, color="tab:blue", label="case A", gid="A")
    ax.plot([10.0], [0.1], "o", mfc="none", mec="tab:blue", label="ours: peak (A)", gid="A")
    ax.plot([3.0, 7.0, 50.0], [0.2, 0.3, 0.01], "x", color="k", label="_hidden")
    ax.axvline(22.2, color="0.5", ls=":")
    ax.axvspan(40.0, 60.0, color="0.8")
    ax.text(22.2, 0.9, "join", transform=ax.get_xaxis_transform())
    ax.set_yscale("log")
    ax.set_xlim(1.0, 100.0)
    ax.set_ylim(1e-3, 2.0)
    ax.set_xlabel("frequency [Hz]")
    ax.set_title("(a) panel")
    fig.suptitle("Fig. X")
    return figure_to_plotly(fig), f


def test_the_plotly_figure_shows_the_same_data():
    spec, f = _spec()
    json.dumps(spec, allow_nan=False)  # plain JSON, no NaN
    curve, circle, crosses = spec["data"]
    assert curve["x0"] == 1.0
    assert curve["dx"] == 0.5
    # DIGITS significant digits: the value written is within half a unit of the last digit
    assert np.allclose(curve["y"], 1.0 / f, rtol=0.5 * 10.0 ** (1 - DIGITS), atol=0.0)
    assert curve["line"]["color"] == "#1f77b4"  # tab:blue
    assert curve["mode"] == "lines"
    assert circle["mode"] == "markers"
    assert circle["marker"]["symbol"] == "circle-open"
    assert crosses["x"] == [3.0, 7.0, 50.0]
    # one legend entry per group (gid): the circle goes with its case's curve
    assert curve["showlegend"]
    assert not circle["showlegend"]
    assert circle["legendgroup"] == curve["legendgroup"] == "A"
    assert not crosses["showlegend"]  # label "_hidden": no entry


def test_the_plotly_layout_keeps_scales_limits_lines_and_texts():
    spec, _ = _spec()
    layout = spec["layout"]
    assert layout["xaxis"]["type"] == "linear"
    assert layout["xaxis"]["range"] == [1.0, 100.0]
    assert layout["yaxis"]["type"] == "log"
    assert layout["yaxis"]["range"] == pytest.approx([-3.0, math.log10(2.0)], abs=1e-12)
    assert layout["xaxis"]["title"]["text"] == "frequency [Hz]"
    lines = [s for s in layout["shapes"] if s["type"] == "line"]
    rects = [s for s in layout["shapes"] if s["type"] == "rect"]
    assert [s["x0"] for s in lines] == [22.2]
    assert [(s["x0"], s["x1"]) for s in rects] == [(40.0, 60.0)]
    texts = {a["text"] for a in layout["annotations"]}
    assert {"join", "(a) panel"} <= texts
    assert layout["title"]["text"] == "Fig. X"
