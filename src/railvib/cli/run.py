"""``railvib run``: one case to dataset, summary and plots (a thin layer over run_to_folder)."""

from __future__ import annotations

from pathlib import Path

import click

from railvib.solve import run_to_folder

__all__ = ["run_case_command"]


def run_case_command(case_file: Path, outdir: Path, plots: bool = True) -> None:
    """Run `case_file` into `outdir`, print its summary (:func:`railvib.solve.run_to_folder`).

    Parameters
    ----------
    case_file : pathlib.Path
        TOML case file.
    outdir : pathlib.Path
        Output folder (created if needed).
    plots : bool
        Draw the PSD overview figures.
    """
    out = run_to_folder(case_file, outdir, plots=plots)
    click.echo(out.summary.to_string(float_format=lambda v: f"{v:.4g}"))
    for note in out.notes:
        click.echo(f"\n{note}")
    click.echo(f"\nwritten to {outdir}/")
