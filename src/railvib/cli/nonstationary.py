"""``railvib run`` of a ``mode = "nonstationary"`` case, with a progress bar of the time steps."""

from __future__ import annotations

import sys
from pathlib import Path

import click
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

from railvib.case import Case
from railvib.nonstationary import run_nonstationary_to_folder
from railvib.nonstationary.build import build_run
from railvib.nonstationary.exact import time_axis

__all__ = ["run_nonstationary_command"]


def run_nonstationary_command(case: Case, outdir: Path, plots: bool = True) -> None:
    """Run the non-stationary `case` into `outdir` and print its summary.

    Parameters
    ----------
    case : Case
        A validated case with ``mode = "nonstationary"``.
    outdir : pathlib.Path
        Output folder.
    plots : bool
        Draw the figures.
    """
    run = build_run(case)  # bad input is refused here, before the bar and the folder
    steps = time_axis(run.profile.duration, run.dt).size
    columns = (
        TextColumn("[bold]time steps"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeRemainingColumn(),
    )
    quiet = not sys.stderr.isatty()
    with Progress(*columns, transient=True, disable=quiet) as bar:
        task = bar.add_task("steps", total=steps)
        out = run_nonstationary_to_folder(
            case, outdir, plots=plots, progress=lambda n: bar.advance(task, n)
        )
    click.echo(out.text())
    click.echo(f"written to {outdir}/")
