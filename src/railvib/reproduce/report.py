"""A self-contained HTML page: figures (embedded PNGs), the comparison table, the cases."""

from __future__ import annotations

import base64
import html
import math
from collections.abc import Mapping, Sequence
from pathlib import Path

import pandas as pd

from railvib.case import Case
from railvib.io import atomic_path
from railvib.reproduce.study import CASES

__all__ = ["render_report", "write_report"]

_CSS = """
body{font-family:system-ui,sans-serif;margin:2em auto;max-width:1300px;color:#222}
table{border-collapse:collapse;font-size:13px;margin:1em 0}
th,td{border:1px solid #ccc;padding:3px 6px;vertical-align:top}
th{background:#f0f0f0} td.num{text-align:right;white-space:nowrap}
tr.no td{background:#fde8e8} img{max-width:100%;border:1px solid #ddd}
pre{background:#f7f7f7;padding:8px;font-size:12px;overflow-x:auto} .small{font-size:12px}
"""

_INTRO = """<p>Reproduction of Wang, Yang, Wei &amp; Zhou, <i>Stationary random vibration analysis
of vehicle-track coupled system with nonlinear stiffness of railpads</i>, J. Vibroengineering
19(6), 2017 (DOI 10.21595/jve.2017.17947), sections 3.3 and 3.4: the type-B metro car at
80 km/h on the embedded-sleeper slab track with WJ-7 railpads, American class 5 (wavelength
&gt; 1 m) plus Shi-tai (&lt; 1 m) irregularity. PSDs are one-sided, per Hz. Crosses on the
figures are the (frequency, PSD) pairs the paper states; circles are the peaks we read
(the band searched is given in the table).</p>
<p><b>Where we differ and why, in short.</b> The frequencies the model itself fixes are
reproduced (bogie bounce 7.0 Hz, wheel peak of the constant pad 46 vs 47.9 Hz, rail comb
v/(2 l<sub>t</sub>) = 10.1 Hz, rail peak near 840 Hz, bogie peak A near 70 Hz) and so is
every qualitative finding. Three differences remain, none tuned away: (1) the paper does not
print the K<sub>0</sub> of its 20 &deg;C frequency-dependent pad; with K<sub>0</sub> = 50 kN/mm
at f<sub>0</sub> = 5 Hz the wheel peak moves by about 1 Hz, not the paper's 9 Hz;
(2) with the physical temperature pairing (colder is stiffer) our wheel peaks at -30/-10/+20
&deg;C sit 12-23 Hz below the paper's, whose +20 &deg;C result matches our K<sub>0</sub> =
70.8 kN/mm case; (3) our absolute PSD levels differ from the paper's (see the % column; pad damping
read as 5e4 N&nbsp;s/m where the paper prints kN&nbsp;s/m; no convention factor explains the
gap). The abstract's "3.3 times" and "20.6 Hz" cannot
be rebuilt from the paper's own figure values. Details: the note column and
<code>docs/paper-interpretation.md</code>.</p>
"""


def _img(path: Path) -> str:
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return f'<img alt="{html.escape(path.stem)}" src="data:image/png;base64,{data}">'


def _cell(value: object) -> str:
    if isinstance(value, float):
        return "" if math.isnan(value) else f"{value:.4g}"
    return html.escape(str(value))


def _table_html(table: pd.DataFrame) -> str:
    cols = [
        "id",
        "source",
        "quantity",
        "unit",
        "paper_text",
        "ours",
        "rel_diff_percent",
        "claim_holds",
        "reading",
        "note",
    ]
    heads = [
        "id",
        "source",
        "quantity",
        "unit",
        "paper",
        "ours",
        "ours vs paper (%)",
        "finding holds",
        "how we read it",
        "why ours differs",
    ]
    rows = []
    for r in table.itertuples():
        rel = "" if math.isnan(r.rel_diff_percent) else f"{r.rel_diff_percent:+.1f}"
        cells = [_cell(getattr(r, c)) for c in cols]
        cells[cols.index("rel_diff_percent")] = rel
        tds = "".join(
            f'<td class="num">{c}</td>' if name in ("ours", "rel_diff_percent") else f"<td>{c}</td>"
            for name, c in zip(cols, cells, strict=True)
        )
        cls = ' class="no"' if r.claim_holds == "no" else ""
        rows.append(f"<tr{cls}>{tds}</tr>")
    head = "".join(f"<th>{h}</th>" for h in heads)
    return f"<table><tr>{head}</tr>{''.join(rows)}</table>"


def _cases_html(cases: Mapping[str, Case]) -> str:
    rows = []
    for c in CASES:
        case = cases[c.key]
        pad = ", ".join(f"{k} = {v}" for k, v in case.track.pad.items())
        rows.append(
            f"<tr><td>{html.escape(c.key)}</td><td>{html.escape(c.preset)}</td>"
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


def render_report(
    table: pd.DataFrame,
    figures: Sequence[tuple[int, Path]],
    cases: Mapping[str, Case],
    meta: Mapping[str, str],
) -> str:
    """The HTML text of the report.

    Parameters
    ----------
    table : pandas.DataFrame
        The comparison table (:func:`railvib.reproduce.table.compare`).
    figures : sequence of (int, pathlib.Path)
        Each figure's number in the paper and its PNG file (embedded as base64).
    cases : mapping of str to Case
        The study's validated cases by key.
    meta : mapping of str to str
        Run information shown at the end (version, run time, ...).

    Returns
    -------
    str
        A complete, self-contained HTML page.
    """
    figs = "".join(f"<h3>Fig. {number}</h3>{_img(path)}" for number, path in figures)
    info = "".join(f"<li>{html.escape(k)}: {html.escape(v)}</li>" for k, v in meta.items())
    return (
        '<!DOCTYPE html><html><head><meta charset="utf-8">'
        "<title>railvib: reproduction of Wang et al. 2017</title>"
        f"<style>{_CSS}</style></head><body>"
        "<h1>railvib reproduce: Wang et al. 2017, Figs. 8-16</h1>"
        f"{_INTRO}<h2>Paper vs railvib</h2>{_table_html(table)}"
        f"<h2>Figures</h2>{figs}<h2>Cases</h2>{_cases_html(cases)}"
        f'<h2>Run</h2><ul class="small">{info}</ul></body></html>\n'
    )


def write_report(
    path: str | Path,
    table: pd.DataFrame,
    figures: Sequence[tuple[int, Path]],
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
    figures : sequence of (int, pathlib.Path)
        Each figure's number in the paper and its PNG file (embedded as base64).
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
