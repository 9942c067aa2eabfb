"""Summary tables as text: the terminal, CSV with a header block, and Markdown.

Every writer puts the same header block first (the case: title, speed, pad,
irregularity, frequency band; then the contact check) so a reader sees which case
and which validity a table belongs to, and keeps the table's unit columns
(``peak_unit``, ``rms_unit``; :func:`railvib.results.stats.summary_table`).
"""

from __future__ import annotations

from collections.abc import Sequence

import pandas as pd

__all__ = ["UNITS_NOTE", "summary_csv", "summary_markdown", "summary_text"]

#: how to read the units of a summary table (one line, in every header block)
UNITS_NOTE = (
    "units: peak in the peak_unit of its row; rms and rms_<lo>_<hi>_hz (RMS over the grid and "
    "over each band, Hz) in the rms_unit of its row; dominant_frequency in Hz; PSDs are "
    "one-sided per Hz"
)


def _float(v: float) -> str:
    return f"{v:.4g}"


def summary_text(
    table: pd.DataFrame, header: Sequence[str] = (), footer: Sequence[str] = ()
) -> str:
    """The summary as the terminal shows it: header lines, the table, then `footer`.

    Parameters
    ----------
    table : pandas.DataFrame
        A summary table (:func:`railvib.results.stats.summary_table`).
    header : sequence of str
        Lines above the table (the case, :func:`railvib.case.case_header`).
    footer : sequence of str
        Lines below it (the contact check).

    Returns
    -------
    str
        Text, numbers with 4 significant digits, ending with a newline.
    """
    parts = [*header, UNITS_NOTE, "", table.to_string(float_format=_float)]
    if footer:
        parts += ["", *footer]
    return "\n".join(parts) + "\n"


def summary_csv(
    table: pd.DataFrame,
    header: Sequence[str] = (),
    footer: Sequence[str] = (),
    extra: Sequence[tuple[str, pd.DataFrame]] = (),
) -> str:
    """The summary as CSV text: ``"# "`` comment lines (header, footer, units), then the table.

    Parameters
    ----------
    table : pandas.DataFrame
        A summary table (:func:`railvib.results.stats.summary_table`).
    header : sequence of str
        The case lines.
    footer : sequence of str
        Further lines of the header block (the contact check).
    extra : sequence of (str, pandas.DataFrame)
        Further tables (a train's per-car table), each written in the comment block as
        ``# <title>:`` and its CSV lines, each after ``"# "`` (strip it to read the table).

    Returns
    -------
    str
        Read it back with ``pandas.read_csv(path, comment="#", index_col=0)``.
    """
    tables = [
        line
        for title, frame in extra
        for line in (f"{title}:", *frame.to_csv(float_format="%.6g").splitlines())
    ]
    lines = [
        'railvib summary (pandas.read_csv(path, comment="#", index_col=0))',
        *header,
        *footer,
        *tables,
        UNITS_NOTE,
    ]
    block = "".join(f"# {line}\n" for line in lines)
    return block + table.to_csv(float_format="%.6g")


def summary_markdown(
    table: pd.DataFrame,
    header: Sequence[str] = (),
    footer: Sequence[str] = (),
    *,
    title: str = "railvib summary",
    extra: Sequence[tuple[str, pd.DataFrame]] = (),
) -> str:
    """The summary as Markdown: a title, the header as a list, the table, then `extra` tables.

    Parameters
    ----------
    table : pandas.DataFrame
        A summary table (:func:`railvib.results.stats.summary_table`).
    header : sequence of str
        The case lines (a bullet list).
    footer : sequence of str
        Lines after the header list (the contact check), as paragraphs.
    title : str
        The level-1 heading.
    extra : sequence of (str, pandas.DataFrame)
        Further tables with their level-2 headings (e.g. the contact check per wheel).

    Returns
    -------
    str
        Markdown text ending with a newline.
    """
    parts = [f"# {title}", "", *(f"- {line}" for line in header), ""]
    for line in footer:
        parts += [line, ""]
    parts += [UNITS_NOTE, "", "## Responses", "", table.to_markdown(floatfmt=".4g"), ""]
    for heading, df in extra:
        parts += [f"## {heading}", "", df.to_markdown(floatfmt=".4g"), ""]
    return "\n".join(parts)
