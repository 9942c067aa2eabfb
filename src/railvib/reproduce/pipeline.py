"""The whole reproduction: run the cases, draw the figures, compare, write the report."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

import pandas as pd
import xarray as xr
from matplotlib.figure import Figure

from railvib.io import railvib_version, save_figure, staged_folder, write_text
from railvib.plot.interactive import figure_to_plotly
from railvib.reproduce.cases import load_study_cases, run_cases
from railvib.reproduce.figures import draw_figure, irregularity_steps
from railvib.reproduce.pad_figures import PAD_FIGURE_FILES, draw_pad_figures, study_prediction
from railvib.reproduce.report import ReportFigure, write_report
from railvib.reproduce.study import CASES, FIGURES
from railvib.reproduce.table import compare, write_table

__all__ = [
    "DEFAULT_OUTDIR",
    "ReproduceResult",
    "n_steps",
    "report_figure",
    "reproduce",
    "reproduce_files",
]

#: default output folder of ``railvib reproduce``
DEFAULT_OUTDIR = Path("railvib-reproduce")


@dataclass(frozen=True)
class ReproduceResult:
    """What :func:`reproduce` computed and wrote.

    Parameters
    ----------
    outdir : pathlib.Path
        The output folder.
    results : dict of str to xarray.Dataset
        Result dataset of every case, by case key.
    table : pandas.DataFrame
        Paper-vs-ours comparison (:func:`railvib.reproduce.table.compare`).
    files : list of pathlib.Path
        Every file written.
    seconds : float
        Wall time of the whole reproduction, s.
    """

    outdir: Path
    results: dict[str, xr.Dataset]
    table: pd.DataFrame
    files: list[Path]
    seconds: float


def n_steps() -> int:
    """Number of progress steps :func:`reproduce` reports (cases, figures, pad figures, writes)."""
    return len(CASES) + len(FIGURES) + 4


def reproduce_files() -> tuple[str, ...]:
    """Every file :func:`reproduce` writes, relative to its folder (POSIX paths).

    Returns
    -------
    tuple of str
        The resolved case files (``cases/<preset>.toml``), the figures, the comparison
        table and ``report.html``: the set a later reproduction replaces.
    """
    return (
        *(f"cases/{c.preset}.toml" for c in CASES),
        *PAD_FIGURE_FILES.values(),
        *(f"{spec.stem}.png" for spec in FIGURES),
        "paper_comparison.csv",
        "paper_comparison.md",
        "report.html",
    )


def reproduce(
    outdir: str | Path = DEFAULT_OUTDIR,
    progress: Callable[[str], None] | None = None,
) -> ReproduceResult:
    """Run the paper's study and write figures, table and HTML report to `outdir`.

    Parameters
    ----------
    outdir : str or pathlib.Path
        Output folder (created if needed). The files are written into a staging
        folder put in place at the end (:func:`railvib.io.staged_folder`): `outdir`
        holds one reproduction's complete set (:func:`reproduce_files`; other files
        are kept), and one that fails or is stopped leaves it as it was.
    progress : callable, optional
        Called with a short description after each of :func:`n_steps` steps.

    Returns
    -------
    ReproduceResult

    Raises
    ------
    railvib.errors.CaseError
        `outdir` is not a folder (before any case runs).
    railvib.errors.OutputError
        `outdir` or one of its files cannot be written (read-only, full disk).
    """
    start = time.perf_counter()
    tick = progress or (lambda _msg: None)
    with staged_folder(outdir, reproduce_files()) as stage:
        out = stage.path
        cases = load_study_cases()
        results = run_cases(on_case=lambda c: tick(f"ran {c.preset}"))
        files: list[Path] = []
        for c in CASES:
            files.append(write_text(out / "cases" / f"{c.preset}.toml", cases[c.key].to_toml()))
        tick("wrote the resolved case files")
        figures = [
            report_figure(number, fig, out / name)
            for number, fig, name in draw_pad_figures(cases, study_prediction())
        ]
        tick("drew Figs. 6-8 (the pad predicted from the 0.3 Hz sweep)")
        steps = irregularity_steps(cases)
        for spec in FIGURES:
            fig = draw_figure(spec, results, steps)
            figures.append(report_figure(spec.number, fig, out / f"{spec.stem}.png"))
            tick(f"drew Fig. {spec.number}")
        files += [f.png for f in figures]
        table = compare(results)
        files += write_table(table, out)
        tick("wrote the comparison table")
        meta = {
            "railvib version": railvib_version(),
            "written": datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"),
            "frequency grid": _grid_text(next(iter(results.values()))),
            "PSD convention": str(next(iter(results.values())).attrs.get("psd_convention", "")),
            "compute time": f"{time.perf_counter() - start:.1f} s",
        }
        files.append(write_report(out / "report.html", table, figures, cases, meta))
        tick("wrote report.html")
    seconds = time.perf_counter() - start
    return ReproduceResult(Path(outdir), results, table, stage.finals(files), seconds)


def report_figure(number: int, fig: Figure, path: Path) -> ReportFigure:
    """Write a drawn, laid-out `fig` as the PNG `path` and keep its interactive version.

    Parameters
    ----------
    number : int
        The paper's figure number.
    fig : matplotlib.figure.Figure
        The figure, laid out (it is not laid out again).
    path : pathlib.Path
        The PNG file (through :func:`railvib.io.save_figure`).

    Returns
    -------
    ReportFigure
        The PNG and the Plotly figure of the report.
    """
    interactive = figure_to_plotly(fig)
    return ReportFigure(number, save_figure(fig, path, tight=False), interactive)


def _grid_text(ds: xr.Dataset) -> str:
    f = ds["frequency"].values
    return f"{f[0]:g}-{f[-1]:g} Hz, {f.size} points, step {f[1] - f[0]:.3g} Hz"
