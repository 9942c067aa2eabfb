"""The explorer's page: a Bokeh server application over :class:`railvib.explore.Explorer`.

Controls (speed, track, pad model, pad stiffness factor, pad temperature, FRA class,
vehicle) sit on the left; on the right, linked plots (one frequency axis) of the
response PSDs and the pad's K'(f) and loss factor, the 1/3-octave levels and the
summary table. A change of a control runs the case again (in the server, coalesced:
changes that arrive during a run give one more run with the latest values) and
replaces the plotted data. "Save case" writes the case on the page to the one file
named when the server was started, validated first (:meth:`Explorer.save`); the page
sends no other input that reaches the file system.

Bokeh is the optional extra ``explore`` and is imported only by :func:`make_document`
and :func:`serve` (docs/design/0007-live-explorer.md).
"""

from __future__ import annotations

import html
import socket
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from railvib.case import Case
from railvib.errors import RailvibError
from railvib.explore.state import (
    PAD_FACTOR_RANGE,
    SPEED_RANGE_KMH,
    TEMPERATURE_RANGE_C,
    Controls,
    Explorer,
    Frame,
    controls_from_values,
)

__all__ = [
    "DEFAULT_HOST",
    "DEFAULT_PORT",
    "MISSING_EXTRA",
    "make_document",
    "require_bokeh",
    "serve",
]

#: the address the explorer binds by default: this machine only
DEFAULT_HOST = "127.0.0.1"

#: the default port (Bokeh's)
DEFAULT_PORT = 5006

#: the one line printed when Bokeh is not installed
MISSING_EXTRA = "railvib explore needs the optional extra 'explore': pip install 'railvib[explore]'"

_COLORS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b")


def require_bokeh() -> None:
    """Refuse in one line when the extra ``explore`` (Bokeh) is missing.

    Raises
    ------
    railvib.errors.RailvibError
        :data:`MISSING_EXTRA`.
    """
    try:
        import bokeh  # noqa: F401
    except ModuleNotFoundError:
        raise RailvibError(MISSING_EXTRA) from None


def _options(choices: Any) -> list[Any]:
    """The options of a Select: the choices' names."""
    return [str(c) for c in choices]


def _psd_data(frame: Frame) -> dict[str, Any]:
    return {"frequency": frame.frequency, **frame.psd}


def _pad_data(frame: Frame) -> dict[str, Any]:
    return {
        "frequency": frame.frequency,
        "storage": frame.pad_storage_kn_per_mm,
        "loss_factor": frame.pad_loss_factor,
    }


def _octave_data(frame: Frame) -> dict[str, Any]:
    return {"band": frame.band_nominal, **frame.band_levels}


def _summary_html(frame: Frame) -> str:
    """The summary as an HTML table (a Bokeh DataTable kept its first cells, Bokeh 3.9)."""
    head = "<tr><th>response</th><th>RMS</th><th>unit</th><th>peak at [Hz]</th></tr>"
    body = "".join(
        f"<tr><td>{html.escape(r['response'])}</td><td>{r['rms']:.4g}</td>"
        f"<td>{html.escape(r['rms_unit'])}</td><td>{r['peak_hz']:.1f}</td></tr>"
        for r in frame.summary_rows
    )
    return f"<table class='summary' style='font-size:9pt'>{head}{body}</table>"


def _status(frame: Frame) -> str:
    notes = "".join(f"<br>{html.escape(n)}" for n in frame.notes)
    return f"<b>{html.escape(frame.case.title)}</b><br>run in {frame.seconds:.2f} s{notes}"


def make_document(explorer: Explorer, output: Path) -> Callable[[Any], None]:
    """The Bokeh application function of the explorer (one document per browser tab).

    Parameters
    ----------
    explorer : Explorer
        The base case's choices and runs.
    output : pathlib.Path
        The case file "Save case" writes.

    Returns
    -------
    callable
        ``modify_doc(doc)`` for :class:`bokeh.application.handlers.FunctionHandler`.
    """
    from bokeh.layouts import column, row
    from bokeh.models.ranges import Range1d
    from bokeh.models.sources import ColumnDataSource
    from bokeh.models.widgets.buttons import Button
    from bokeh.models.widgets.inputs import Select
    from bokeh.models.widgets.markups import Div
    from bokeh.models.widgets.sliders import Slider
    from bokeh.plotting import figure

    from railvib.plot.psd import psd_ylim

    def modify_doc(doc: Any) -> None:
        start = explorer.initial()
        frame = explorer.frame(start)
        responses = list(frame.psd)
        speed_lo = min(SPEED_RANGE_KMH[0], start.speed_kmh)
        speed_hi = max(SPEED_RANGE_KMH[1], start.speed_kmh)
        temp_lo = min(TEMPERATURE_RANGE_C[0], start.pad_temperature_c)
        temp_hi = max(TEMPERATURE_RANGE_C[1], start.pad_temperature_c)
        widgets: dict[str, Any] = {
            "speed_kmh": Slider(
                title="speed [km/h]",
                start=speed_lo,
                end=speed_hi,
                step=5.0,
                value=start.speed_kmh,
                name="speed_kmh",
            ),
            "track": Select(
                title="track", options=_options(explorer.tracks), value=start.track, name="track"
            ),
            "pad": Select(
                title="pad model", options=_options(explorer.pads), value=start.pad, name="pad"
            ),
            "pad_factor": Slider(
                title="pad stiffness factor [-]",
                start=PAD_FACTOR_RANGE[0],
                end=PAD_FACTOR_RANGE[1],
                step=0.05,
                value=start.pad_factor,
                name="pad_factor",
            ),
            "pad_temperature_c": Slider(
                title="pad temperature [degC]",
                start=temp_lo,
                end=temp_hi,
                step=1.0,
                value=start.pad_temperature_c,
                name="pad_temperature_c",
            ),
            "fra_class": Select(
                title="irregularity: FRA class (1 worst, 6 best)",
                options=_options([str(c) for c in explorer.fra_classes] or ["none in the case"]),
                value=str(start.fra_class) if start.fra_class is not None else "none in the case",
                disabled=start.fra_class is None,
                name="fra_class",
            ),
            "vehicle": Select(
                title="vehicle",
                options=_options(explorer.vehicles),
                value=start.vehicle,
                name="vehicle",
            ),
        }
        save = Button(label=f"Save case to {output.name}", button_type="primary", name="save")
        status = Div(text=_status(frame), width=380, name="status")
        saved = Div(text="", width=380, name="saved")

        psd_source = ColumnDataSource(_psd_data(frame), name="psd_source")
        pad_source = ColumnDataSource(_pad_data(frame), name="pad_source")
        octave_source = ColumnDataSource(_octave_data(frame), name="octave_source")

        unit = "; ".join(dict.fromkeys(frame.psd_units.values()))
        lo, hi = psd_ylim(list(frame.psd.values())) or (1e-12, 1.0)
        psd_plot = figure(
            title="acceleration PSD",
            x_axis_type="log",
            y_axis_type="log",
            x_axis_label="frequency [Hz]",
            y_axis_label=f"acceleration PSD [{unit}]",
            width=720,
            height=330,
            y_range=Range1d(start=lo, end=hi),
            name="psd_plot",
        )
        pad_plot = figure(
            title="pad: storage stiffness K' (the beam model's, at the pad temperature)",
            x_axis_type="log",
            x_range=psd_plot.x_range,  # linked: one frequency axis
            x_axis_label="frequency [Hz]",
            y_axis_label="K' [kN/mm]",
            width=720,
            height=220,
            name="pad_plot",
        )
        octave_plot = figure(
            title="1/3-octave acceleration levels (IEC 61260-1)",
            x_axis_type="log",
            x_axis_label="nominal mid-band frequency [Hz]",
            y_axis_label="level [dB re 1e-6 m/s^2]",
            width=720,
            height=260,
            name="octave_plot",
        )
        for i, r in enumerate(responses):
            color = _COLORS[i % len(_COLORS)]
            psd_plot.line("frequency", r, source=psd_source, color=color, legend_label=r)
            octave_plot.line("band", r, source=octave_source, color=color, legend_label=r)
            octave_plot.scatter("band", r, source=octave_source, color=color, size=4)
        pad_plot.line("frequency", "storage", source=pad_source, color="#1f77b4")
        loss = figure(
            title="pad: loss factor",
            x_axis_type="log",
            x_range=psd_plot.x_range,
            x_axis_label="frequency [Hz]",
            y_axis_label="loss factor K''/K' [-]",
            width=720,
            height=160,
            name="loss_plot",
        )
        loss.line("frequency", "loss_factor", source=pad_source, color="#ff7f0e")
        for plot in (psd_plot, octave_plot):
            plot.legend.location = "bottom_left"
            plot.legend.label_text_font_size = "8pt"
        table = Div(text=_summary_html(frame), width=720, name="summary_table")

        pending = {"scheduled": False}

        def controls() -> Controls:
            values = {name: widget.value for name, widget in widgets.items()}
            if start.fra_class is None:
                values["fra_class"] = None
            return controls_from_values(start, values)

        def update() -> None:
            pending["scheduled"] = False
            try:
                new = explorer.frame(controls(), responses)
            except RailvibError as exc:  # a case railvib run refuses: said, plots kept
                status.text = f"<span style='color:#b00'>error: {html.escape(str(exc))}</span>"
                return
            begin = time.perf_counter()
            psd_source.data = _psd_data(new)
            limits = psd_ylim(list(new.psd.values()))
            if limits is not None:
                psd_plot.y_range.update(start=limits[0], end=limits[1])
            pad_source.data = _pad_data(new)
            octave_source.data = _octave_data(new)
            table.text = _summary_html(new)
            status.text = _status(new) + f" (page data {time.perf_counter() - begin:.3f} s)"

        def changed(attr: str, old: Any, new: Any) -> None:
            if not pending["scheduled"]:  # changes during a run: one more run, latest values
                pending["scheduled"] = True
                doc.add_next_tick_callback(update)

        for widget in widgets.values():
            widget.on_change("value", changed)

        def on_save() -> None:
            try:
                path = explorer.save(controls(), output)
            except (RailvibError, OSError) as exc:
                saved.text = f"<span style='color:#b00'>error: {html.escape(str(exc))}</span>"
                return
            saved.text = f"saved {html.escape(str(path))}"

        save.on_click(on_save)
        panel = column(*widgets.values(), save, saved, status, width=400)
        plots = column(psd_plot, pad_plot, loss, octave_plot, table)
        doc.add_root(row(panel, plots))
        doc.title = "railvib explore"

    return modify_doc


def _free_port(host: str, port: int) -> int:
    """`port` if it is free on `host` now (0: any free port), else a one-line error."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # as the server will
        try:
            s.bind((host, port))
        except socket.gaierror as exc:
            raise RailvibError(
                f"--host = {host!r}: an address of this machine ({exc.strerror})"
            ) from None
        except OSError as exc:
            raise RailvibError(
                f"--port = {port}: cannot listen on {host}:{port} ({exc.strerror})"
            ) from None
        return int(s.getsockname()[1])


def serve(
    base: Case,
    output: Path,
    *,
    host: str = DEFAULT_HOST,
    port: int = DEFAULT_PORT,
    show: bool = False,
    ready: Callable[[str], None] | None = None,
) -> None:
    """Serve the explorer of `base` until interrupted (Ctrl-C).

    Parameters
    ----------
    base : Case
        The case the page starts from.
    output : pathlib.Path
        The case file "Save case" writes (the page can write no other).
    host : str
        Address to bind (default: this machine only).
    port : int
        TCP port (0: a free one).
    show : bool
        Open the page in the default web browser.
    ready : callable, optional
        Called with the page's URL once the server listens.

    Raises
    ------
    railvib.errors.RailvibError
        Bokeh (the extra ``explore``) is not installed, the port is taken, or the case
        cannot run (e.g. :class:`railvib.errors.NonFiniteResult`).
    """
    require_bokeh()
    from bokeh.application import Application
    from bokeh.application.handlers.function import FunctionHandler
    from bokeh.server.server import Server

    port = _free_port(host, port)  # before the case is run for the page
    explorer = Explorer(base)
    explorer.frame(explorer.initial())  # a case that cannot run is refused before serving
    origins = [f"{host}:{port}", f"localhost:{port}", f"127.0.0.1:{port}"]
    try:
        server = Server(
            {"/": Application(FunctionHandler(make_document(explorer, output)))},
            address=host,
            port=port,
            allow_websocket_origin=origins,
        )
    except OSError as exc:
        raise RailvibError(
            f"--port = {port}: cannot listen on {host}:{port} ({exc.strerror})"
        ) from None
    server.start()
    url = f"http://{host}:{port}/"
    if ready is not None:
        ready(url)
    if show:
        server.io_loop.add_callback(server.show, "/")
    try:
        server.io_loop.start()
    finally:
        server.stop()
