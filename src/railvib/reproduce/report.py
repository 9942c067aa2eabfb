"""A self-contained HTML page: the figures, a summary, the comparison table, the causes.

The page reads, in order: the figures (interactive, zoomable with hover, and the PNG
written to the folder under each), a summary generated from the comparison table (how
many of the paper's numbers lie within 5 %, 5-20 % and over 20 % of ours, the
qualitative checks, the numbers reproduced and the large deviations with their causes),
the table itself, the causes of the differences (each written once, referenced from its
rows), the cases and the run. Every number in the prose comes from the table: nothing
of ours is written by hand here, so the text follows the results.

The interactive figures are Plotly figures
(:func:`railvib.plot.interactive.figure_to_plotly`) drawn by plotly.js, which the page
carries inline, once (``docs/design/0005-interactive-report.md``): the page needs no
network when it is viewed.
"""

from __future__ import annotations

import base64
import html
import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd
from matplotlib.colors import to_hex

from railvib.case import Case
from railvib.io import atomic_path
from railvib.reproduce.study import CASES, CAUSES
from railvib.reproduce.table import (
    AGREEMENT,
    format_difference,
    format_relative,
    format_value,
    summarize,
)

__all__ = ["PROSE_CLASS", "ReportFigure", "plotly_js", "render_report", "write_report"]

#: class of the page's generated prose (every number in it comes from the table)
PROSE_CLASS = "prose"

_CSS = """
body{font-family:system-ui,sans-serif;margin:2em auto;max-width:1300px;color:#222;padding:0 1em}
table{border-collapse:collapse;font-size:13px;margin:1em 0}
th,td{border:1px solid #ccc;padding:3px 6px;vertical-align:top}
th{background:#f0f0f0} td.num{text-align:right;white-space:nowrap}
tr.no td{background:#fde8e8} tr.over td.mag{background:#fdf0dc}
img{max-width:100%;border:1px solid #ddd}
pre{background:#f7f7f7;padding:8px;font-size:12px;overflow-x:auto} .small{font-size:12px}
.plot{width:100%;border:1px solid #eee} details{margin:.3em 0 1.5em}
.cause{border-left:3px solid #bbb;padding-left:.8em;margin:1em 0}
"""

_CITATION = """<p class="citation">Reproduction of Wang, Yang, Wei &amp; Zhou, <i>Stationary
random vibration analysis of vehicle-track coupled system with nonlinear stiffness of
railpads</i>, J. Vibroengineering 19(6), 2017 (DOI 10.21595/jve.2017.17947), sections 3.3
and 3.4; the study is described in <code>docs/paper-interpretation.md</code>.</p>"""

_READING = f"""<p class="{PROSE_CLASS}">Each case keeps its colour in every figure. Crosses
are the (frequency, PSD) pairs the paper states, circles the peaks we read (the band
searched is in the table), dotted lines the frequencies the paper states, and a thin
dash-dotted line the frequency where the two irregularity spectra join (a step of the input
spectrum by definition, not a resonance). Drag to zoom, double-click to reset, hover to read
a value; a click on a legend entry hides that case in every panel. PSDs are one-sided, per
Hz.</p>"""

_JS_RENDER = """
for (const [id, fig] of Object.entries(RAILVIB_FIGURES)) {
  Plotly.newPlot(id, fig.data, fig.layout, {responsive: true, displaylogo: false});
}
"""


@dataclass(frozen=True)
class ReportFigure:
    """One figure of the report: its PNG and, where drawn, its interactive version.

    Parameters
    ----------
    number : int
        The paper's figure number.
    png : pathlib.Path
        The PNG written to the output folder (embedded as base64).
    interactive : dict or None
        A Plotly figure (:func:`railvib.plot.interactive.figure_to_plotly`); None: the
        PNG alone is shown.
    """

    number: int
    png: Path
    interactive: Mapping[str, Any] | None = None


def plotly_js() -> str:
    """The plotly.js library shipped with the ``plotly`` package, as JavaScript text.

    Returns
    -------
    str
        The minified library (about 4.8 MB), inlined once in the report.
    """
    from plotly.offline import get_plotlyjs

    return str(get_plotlyjs())


def _img(path: Path) -> str:
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return f'<img alt="{html.escape(path.stem)}" src="data:image/png;base64,{data}">'


def _cell(value: object) -> str:
    if isinstance(value, float):
        return "" if math.isnan(value) else f"{value:.4g}"
    return html.escape(str(value))


def _cause_links(causes: str) -> str:
    return ", ".join(f'<a href="#cause-{c}">{html.escape(c)}</a>' for c in causes.split())


def _value(value: float, unit: str) -> str:
    text = format_value(value)
    return text if unit in ("-", "") else f"{text} {html.escape(unit)}"


def _table_html(table: pd.DataFrame) -> str:
    heads = [
        "id",
        "source",
        "quantity",
        "unit",
        "paper",
        "ours",
        "ours &minus; paper",
        "relative",
        "magnitude",
        "qualitative check (sign or bound only)",
        "how we read it",
        "why ours differs",
    ]
    rows = []
    for r in table.itertuples():
        check = f"{html.escape(r.claim)}: {r.claim_holds}" if r.claim else ""
        why = html.escape(str(r.remark))
        if r.causes:
            why += f"{' ' if why else ''}Causes: {_cause_links(str(r.causes))}."
        diff = html.escape(format_difference(r.difference, r.difference_unit))
        cells = [
            f"<td>{_cell(r.id)}</td>",
            f"<td>{_cell(r.source)}</td>",
            f"<td>{_cell(r.quantity)}</td>",
            f"<td>{_cell(r.unit)}</td>",
            f"<td>{_cell(r.paper_text)}</td>",
            f'<td class="num">{format_value(r.ours)}</td>',
            f'<td class="num">{diff}</td>',
            f'<td class="num">{format_relative(r.rel_diff_percent)}</td>',
            f'<td class="mag">{html.escape(r.agreement)}</td>',
            f"<td>{check}</td>",
            f"<td>{_cell(r.reading)}</td>",
            f"<td>{why}</td>",
        ]
        cls = "no" if r.claim_holds == "no" else ("over" if r.agreement == AGREEMENT[-1][1] else "")
        rows.append(f'<tr id="row-{html.escape(r.id)}" class="{cls}">{"".join(cells)}</tr>')
    head = "".join(f"<th>{h}</th>" for h in heads)
    return f"<table><tr>{head}</tr>{''.join(rows)}</table>"


def _deviations_html(rows: pd.DataFrame) -> str:
    order = rows.reindex(rows["rel_diff_percent"].abs().sort_values(ascending=False).index)
    body = "".join(
        f'<tr><td><a href="#row-{html.escape(r.id)}">{html.escape(r.id)}</a></td>'
        f"<td>{html.escape(r.quantity)}</td>"
        f'<td class="num">{_value(r.paper, r.unit)}</td>'
        f'<td class="num">{_value(r.ours, r.unit)}</td>'
        f'<td class="num">{html.escape(format_difference(r.difference, r.difference_unit))}</td>'
        f'<td class="num">{format_relative(r.rel_diff_percent)}</td>'
        f"<td>{_cause_links(str(r.causes)) or html.escape(str(r.remark))}</td></tr>"
        for r in order.itertuples()
    )
    return (
        f'<table class="{PROSE_CLASS}"><tr><th>id</th><th>quantity</th><th>paper</th>'
        "<th>ours</th><th>ours &minus; paper</th><th>relative</th><th>cause</th></tr>"
        f"{body}</table>"
    )


def _summary_html(table: pd.DataFrame) -> str:
    s = summarize(table)
    within, middle, over_n = s.agreement.values()
    reproduced = table[table["agreement"] == AGREEMENT[0][1]]
    over = table[table["agreement"] == AGREEMENT[-1][1]]
    items = "".join(
        f"<li>{html.escape(r.quantity)}: {_value(r.ours, r.unit)} "
        f"(paper {_value(r.paper, r.unit)})</li>"
        for r in reproduced.itertuples()
    )
    failed = table[table["claim_holds"] == "no"]
    failed_text = (
        "; failing: " + ", ".join(html.escape(i) for i in failed["id"]) if len(failed) else ""
    )
    return (
        f'<p class="{PROSE_CLASS}">The paper states <b>{s.numbers}</b> numbers and findings; '
        f"<b>{s.with_value}</b> have a value (printed, or derived from printed ones). Relative "
        f"to the paper's value, <b>{within}</b> of ours are {html.escape(AGREEMENT[0][1])}, "
        f"<b>{middle}</b> at {html.escape(AGREEMENT[1][1])} and <b>{over_n}</b> "
        f"{html.escape(AGREEMENT[2][1])}.</p>"
        f'<p class="{PROSE_CLASS}"><b>{s.checks_hold}/{s.checks}</b> qualitative checks hold'
        f"{failed_text}. A check tests a sign or a bound (the paper's direction of an effect, "
        "or its &ldquo;curves overlap&rdquo;), not a magnitude: a check that holds beside a "
        "value far from the paper's means the direction agrees and the size does not.</p>"
        f"<h3>Reproduced: {html.escape(AGREEMENT[0][1])} of the paper</h3>"
        f'<ul class="{PROSE_CLASS}">{items}</ul>'
        f"<h3>Large deviations ({html.escape(AGREEMENT[-1][1])}), largest first</h3>"
        f"{_deviations_html(over)}"
    )


def _causes_html(table: pd.DataFrame) -> str:
    used = dict.fromkeys(c for cs in table["causes"] for c in str(cs).split())
    blocks = []
    for cause in used:
        ids = [r.id for r in table.itertuples() if cause in str(r.causes).split()]
        links = ", ".join(f'<a href="#row-{html.escape(i)}">{html.escape(i)}</a>' for i in ids)
        blocks.append(
            f'<div class="cause" id="cause-{html.escape(cause)}"><h3>{html.escape(cause)}</h3>'
            f'<p>{html.escape(CAUSES[cause])}</p><p class="small">Rows: {links}</p></div>'
        )
    return "".join(blocks)


def _cases_html(cases: Mapping[str, Case]) -> str:
    rows = []
    for c in CASES:
        case = cases[c.key]
        pad = ", ".join(f"{k} = {v}" for k, v in case.track.pad.items())
        swatch = f'<span style="color:{to_hex(c.color)}">&#9632;</span>'
        rows.append(
            f"<tr><td>{swatch} {html.escape(c.key)}</td><td>{html.escape(c.preset)}</td>"
            f"<td>{html.escape(c.label)}</td><td>{case.track.pad_temperature_c}</td>"
            f"<td>{html.escape(pad)}</td></tr>"
        )
    head = (
        "<tr><th>case</th><th>preset</th><th>legend</th><th>pad temperature (&deg;C)</th>"
        "<th>railpad (SI)</th></tr>"
    )
    base = cases[CASES[0].key]
    return (
        f"<table>{head}{''.join(rows)}</table>"
        "<p>All cases share everything else; the full resolved constant case:</p>"
        f"<pre>{html.escape(base.to_toml())}</pre>"
    )


def _figure_entries(
    figures: Sequence[ReportFigure | tuple[int, Path]],
) -> list[ReportFigure]:
    return [f if isinstance(f, ReportFigure) else ReportFigure(f[0], Path(f[1])) for f in figures]


def _figures_html(figures: Sequence[ReportFigure]) -> str:
    parts = []
    for i, f in enumerate(figures):
        if f.interactive is None:
            parts.append(f'<section id="fig-{i}"><h3>Fig. {f.number}</h3>{_img(f.png)}</section>')
            continue
        height = int(f.interactive["layout"].get("height", 500))
        parts.append(
            f'<section id="fig-{i}"><h3>Fig. {f.number}</h3>'
            f'<div class="plot" id="plot-{i}" style="height:{height}px"></div>'
            f"<details><summary>static figure ({html.escape(f.png.name)})</summary>"
            f"{_img(f.png)}</details></section>"
        )
    return "".join(parts)


def _script(figures: Sequence[ReportFigure], library: str) -> str:
    specs = {f"plot-{i}": f.interactive for i, f in enumerate(figures) if f.interactive}
    if not specs:
        return ""
    data = json.dumps(specs, separators=(",", ":"), allow_nan=False).replace("</", "<\\/")
    return f"<script>{library}</script><script>const RAILVIB_FIGURES = {data};{_JS_RENDER}</script>"


def render_report(
    table: pd.DataFrame,
    figures: Sequence[ReportFigure | tuple[int, Path]],
    cases: Mapping[str, Case],
    meta: Mapping[str, str],
) -> str:
    """The HTML text of the report.

    Parameters
    ----------
    table : pandas.DataFrame
        The comparison table (:func:`railvib.reproduce.table.compare`).
    figures : sequence of ReportFigure or (int, pathlib.Path)
        The figures in page order; a (number, PNG) pair is shown as the PNG alone.
    cases : mapping of str to Case
        The study's validated cases by key.
    meta : mapping of str to str
        Run information shown at the end (version, run time, ...).

    Returns
    -------
    str
        A complete, self-contained HTML page; plotly.js is inlined once when a figure
        is interactive.
    """
    entries = _figure_entries(figures)
    library = plotly_js() if any(f.interactive for f in entries) else ""
    info = "".join(f"<li>{html.escape(k)}: {html.escape(v)}</li>" for k, v in meta.items())
    return (
        '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8">'
        "<title>railvib: reproduction of Wang et al. 2017</title>"
        f"<style>{_CSS}</style></head><body>"
        "<h1>railvib reproduce: Wang et al. 2017</h1>"
        f"{_CITATION}{_READING}"
        f'<h2 id="figures">Figures</h2>{_figures_html(entries)}'
        f'<h2 id="summary">Summary</h2>{_summary_html(table)}'
        f'<h2 id="table">Paper vs railvib</h2>{_table_html(table)}'
        f'<h2 id="causes">Why ours differs: the causes</h2>{_causes_html(table)}'
        f"<h2>Cases</h2>{_cases_html(cases)}"
        f'<h2>Run</h2><ul class="small">{info}</ul>'
        f"{_script(entries, library)}</body></html>\n"
    )


def write_report(
    path: str | Path,
    table: pd.DataFrame,
    figures: Sequence[ReportFigure | tuple[int, Path]],
    cases: Mapping[str, Case],
    meta: Mapping[str, str],
) -> Path:
    """Write :func:`render_report` to `path`, atomically.

    Parameters
    ----------
    path : str or pathlib.Path
        The HTML file.
    table : pandas.DataFrame
        The comparison table (:func:`railvib.reproduce.table.compare`).
    figures : sequence of ReportFigure or (int, pathlib.Path)
        The figures in page order; a (number, PNG) pair is shown as the PNG alone.
    cases : mapping of str to Case
        The study's validated cases by key.
    meta : mapping of str to str
        Run information shown at the end (version, run time, ...).

    Returns
    -------
    pathlib.Path
        `path`.
    """
    path = Path(path)
    text = render_report(table, figures, cases, meta)
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return path
