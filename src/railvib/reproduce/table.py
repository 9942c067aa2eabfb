"""The paper-vs-ours table: every number the paper states beside our reading of it."""

from __future__ import annotations

import math
import operator
from collections.abc import Sequence
from pathlib import Path

import pandas as pd

from railvib.io import atomic_path
from railvib.reproduce.metrics import METRICS, Results
from railvib.reproduce.study import PAPER_NUMBERS, PaperNumber

__all__ = ["COLUMNS", "compare", "format_value", "to_markdown", "write_table"]

#: columns of the comparison table, in order
COLUMNS = (
    "id",
    "source",
    "quantity",
    "unit",
    "paper",
    "paper_text",
    "ours",
    "rel_diff_percent",
    "claim",
    "claim_holds",
    "reading",
    "note",
)

_OPS = {"<": operator.lt, "<=": operator.le, ">": operator.gt, ">=": operator.ge}


def _row(number: PaperNumber, results: Results) -> dict[str, object]:
    ours = METRICS[number.metric](results, **dict(number.args))
    paper = math.nan if number.paper is None else number.paper
    rel = 100.0 * (ours / paper - 1.0) if number.paper else math.nan
    claim, holds = "", ""
    if number.claim is not None:
        op, bound = number.claim
        claim = f"ours {op} {bound:g}"
        holds = "yes" if _OPS[op](ours, bound) else "no"
    return {
        "id": number.id,
        "source": number.source,
        "quantity": number.quantity,
        "unit": number.unit,
        "paper": paper,
        "paper_text": number.paper_text,
        "ours": ours,
        "rel_diff_percent": rel,
        "claim": claim,
        "claim_holds": holds,
        "reading": number.reading,
        "note": number.note,
    }


def compare(results: Results, numbers: Sequence[PaperNumber] = PAPER_NUMBERS) -> pd.DataFrame:
    """Read every paper number from `results` and set it beside the paper's value.

    Parameters
    ----------
    results : mapping of str to xarray.Dataset
        Study results by case key (:func:`railvib.reproduce.cases.run_cases`).
    numbers : sequence of PaperNumber
        The numbers to compare (default: all the paper states).

    Returns
    -------
    pandas.DataFrame
        One row per number with the columns :data:`COLUMNS`. ``rel_diff_percent`` is
        ``100 (ours / paper - 1)``; NaN where the paper gives no number.
    """
    return pd.DataFrame([_row(n, results) for n in numbers], columns=list(COLUMNS))


def format_value(value: float) -> str:
    """Four significant digits; empty for NaN.

    Parameters
    ----------
    value : float or None
        A number in any unit (that of the table's ``unit`` column); NaN or None gives "".

    Returns
    -------
    str
        ``f"{value:.4g}"``, or the empty string.
    """
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return ""
    return f"{value:.4g}"


def _display(table: pd.DataFrame) -> pd.DataFrame:
    out = table[
        [
            "id",
            "source",
            "quantity",
            "unit",
            "paper_text",
            "ours",
            "rel_diff_percent",
            "claim_holds",
        ]
    ].copy()
    out["ours"] = table["ours"].map(format_value)
    out["rel_diff_percent"] = table["rel_diff_percent"].map(
        lambda v: "" if math.isnan(v) else f"{v:+.1f}"
    )
    return out.rename(
        columns={
            "paper_text": "paper",
            "rel_diff_percent": "ours vs paper (%)",
            "claim_holds": "finding holds",
        }
    )


def to_markdown(table: pd.DataFrame) -> str:
    """The table as Markdown, followed by how each number is read and why we differ."""
    lines = [_display(table).to_markdown(index=False), "", "### How each number is read", ""]
    lines += [f"- **{r.id}**: {r.reading}." for r in table.itertuples()]
    lines += ["", "### Why ours differs", ""]
    lines += [f"- **{r.id}**: {r.note}" for r in table.itertuples() if r.note]
    return "\n".join(lines) + "\n"


def write_table(table: pd.DataFrame, outdir: str | Path) -> list[Path]:
    """Write ``paper_comparison.csv`` and ``paper_comparison.md`` to `outdir`, atomically.

    Parameters
    ----------
    table : pandas.DataFrame
        The comparison table (:func:`compare`).
    outdir : str or pathlib.Path
        Folder for the two files.

    Returns
    -------
    list of pathlib.Path
        The CSV and the Markdown file.
    """
    outdir = Path(outdir)
    csv_path, md_path = outdir / "paper_comparison.csv", outdir / "paper_comparison.md"
    with atomic_path(csv_path) as tmp:
        table.to_csv(tmp, index=False, float_format="%.6g")
    with atomic_path(md_path) as tmp:
        tmp.write_text("# Paper vs railvib\n\n" + to_markdown(table), encoding="utf-8")
    return [csv_path, md_path]
