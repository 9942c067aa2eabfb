"""The paper-vs-ours table: every number the paper states beside our reading of it."""

from __future__ import annotations

import math
import operator
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from railvib.io import atomic_path
from railvib.reproduce.metrics import METRICS, Results
from railvib.reproduce.study import CAUSES, PAPER_NUMBERS, PaperNumber

__all__ = [
    "AGREEMENT",
    "COLUMNS",
    "Summary",
    "compare",
    "format_difference",
    "format_relative",
    "format_value",
    "summarize",
    "summary_line",
    "to_markdown",
    "write_table",
]

#: magnitude classes of ``|ours / paper - 1|``: (upper bound in %, inclusive; name)
AGREEMENT: tuple[tuple[float, str], ...] = (
    (5.0, "within 5 %"),
    (20.0, "5-20 %"),
    (math.inf, "over 20 %"),
)

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
    "difference",
    "difference_unit",
    "agreement",
    "causes",
    "remark",
)

_OPS = {"<": operator.lt, "<=": operator.le, ">": operator.gt, ">=": operator.ge}


def _agreement(rel_diff_percent: float) -> str:
    """The :data:`AGREEMENT` class of a relative difference in %; "" for NaN (no value)."""
    if math.isnan(rel_diff_percent):
        return ""
    return next(name for bound, name in AGREEMENT if abs(rel_diff_percent) <= bound)


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
        "difference": ours - paper,
        "difference_unit": ("pp" if number.unit == "%" else number.unit) if number.paper else "",
        "agreement": _agreement(rel),
        "causes": " ".join(number.causes),
        "remark": number.remark,
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
        ``100 (ours / paper - 1)``; ``difference`` is ``ours - paper`` in the row's unit,
        percentage points (``difference_unit = "pp"``) for a value in %; ``agreement`` is
        the :data:`AGREEMENT` class of ``rel_diff_percent``; all NaN or "" where the paper
        gives no number. ``causes``: the names of the shared causes (space-separated,
        :data:`railvib.reproduce.study.CAUSES`); ``remark``: the row's own note.
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


def format_difference(value: float, unit: str) -> str:
    """``ours - paper`` with its sign and unit (``-14.6 pp``, ``+1.3 Hz``); "" for NaN.

    Parameters
    ----------
    value : float
        The difference, in `unit`.
    unit : str
        The unit of the row's values; ``"pp"`` (percentage points) for values in %, ``"-"``
        for a dimensionless one (written without a unit).

    Returns
    -------
    str
    """
    if math.isnan(value):
        return ""
    return f"{value:+.3g}" + ("" if unit in ("-", "") else f" {unit}")


def format_relative(value: float) -> str:
    """A relative difference in % with its sign and one decimal (``-16.5 %``); "" for NaN.

    Parameters
    ----------
    value : float
        ``100 (ours / paper - 1)``, in % (dimensionless ratio times 100).

    Returns
    -------
    str
    """
    return "" if math.isnan(value) else f"{value:+.1f} %"


def _check(claim: str, holds: str) -> str:
    return f"{claim}: {holds}" if claim else ""


def _display(table: pd.DataFrame) -> pd.DataFrame:
    return pd.DataFrame(
        {
            "id": table["id"],
            "source": table["source"],
            "quantity": table["quantity"],
            "unit": table["unit"],
            "paper": table["paper_text"],
            "ours": table["ours"].map(format_value),
            "ours - paper": [
                format_difference(v, u)
                for v, u in zip(table["difference"], table["difference_unit"], strict=True)
            ],
            "relative": table["rel_diff_percent"].map(format_relative),
            "magnitude": table["agreement"],
            "qualitative check (sign or bound only)": [
                _check(c, h) for c, h in zip(table["claim"], table["claim_holds"], strict=True)
            ],
            "causes": table["causes"],
        }
    )


@dataclass(frozen=True)
class Summary:
    """The counts of a comparison table (:func:`summarize`).

    Parameters
    ----------
    numbers : int
        Rows (numbers and statements of the paper compared).
    with_value : int
        Rows where the paper gives a value (printed or derived from printed ones).
    agreement : mapping of str to int
        Rows with a value in each :data:`AGREEMENT` class, in that order.
    checks : int
        Rows with a qualitative check (a sign or a bound).
    checks_hold : int
        Of those, the ones that hold on our numbers.
    """

    numbers: int
    with_value: int
    agreement: Mapping[str, int]
    checks: int
    checks_hold: int


def summarize(table: pd.DataFrame) -> Summary:
    """Count a comparison table: magnitude classes and qualitative checks.

    Parameters
    ----------
    table : pandas.DataFrame
        The comparison table (:func:`compare`).

    Returns
    -------
    Summary
    """
    agreement = {name: int((table["agreement"] == name).sum()) for _, name in AGREEMENT}
    checks = table["claim_holds"] != ""
    return Summary(
        numbers=len(table),
        with_value=int((table["agreement"] != "").sum()),
        agreement=agreement,
        checks=int(checks.sum()),
        checks_hold=int((table["claim_holds"] == "yes").sum()),
    )


def summary_line(table: pd.DataFrame) -> str:
    """One line: the magnitude classes of the numbers with a value, then the checks.

    Parameters
    ----------
    table : pandas.DataFrame
        The comparison table (:func:`compare`).

    Returns
    -------
    str
        E.g. ``39 paper numbers compared; of the 31 with a value, 9 within 5 %, 8 at
        5-20 % and 14 over 20 % of the paper's; 14/14 qualitative checks (sign or bound)
        hold``.
    """
    s = summarize(table)
    within, middle, over = (s.agreement[name] for _, name in AGREEMENT)
    return (
        f"{s.numbers} paper numbers compared; of the {s.with_value} with a value, "
        f"{within} within 5 %, {middle} at 5-20 % and {over} over 20 % of the paper's; "
        f"{s.checks_hold}/{s.checks} qualitative checks (sign or bound) hold"
    )


def to_markdown(table: pd.DataFrame) -> str:
    """The table as Markdown, then how each number is read, and the causes of the differences.

    Parameters
    ----------
    table : pandas.DataFrame
        The comparison table (:func:`compare`).

    Returns
    -------
    str
        The summary line, the table (``ours - paper`` in percentage points for values in
        %, the magnitude class and the qualitative check apart), how each number is read,
        each row's own remark and the causes it refers to, and each cause once.
    """
    lines = [summary_line(table) + ".", "", _display(table).to_markdown(index=False), ""]
    lines += ["### How each number is read", ""]
    lines += [f"- **{r.id}**: {r.reading}." for r in table.itertuples()]
    lines += ["", "### Why ours differs", ""]
    for r in table.itertuples():
        refs = ", ".join(f"[{c}](#cause-{c})" for c in str(r.causes).split())
        text = " ".join(p for p in (str(r.remark), f"Causes: {refs}." if refs else "") if p)
        if text:
            lines.append(f"- **{r.id}**: {text}")
    lines += ["", "### Causes", ""]
    used = dict.fromkeys(c for cs in table["causes"] for c in str(cs).split())
    for cause in used:
        rows = ", ".join(r.id for r in table.itertuples() if cause in str(r.causes).split())
        lines += [f'<a id="cause-{cause}"></a>**{cause}** ({rows}): {CAUSES[cause]}', ""]
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
