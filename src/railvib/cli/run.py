"""``railvib run``: one case to dataset, summary and plots (a thin layer over run_to_folder)."""

from __future__ import annotations

from pathlib import Path

import click

from railvib.errors import LinearModelInvalid
from railvib.solve import run_to_folder

__all__ = ["run_case_command"]


def run_case_command(
    case_file: Path, outdir: Path, plots: bool = True, strict: bool = False
) -> None:
    """Run `case_file` into `outdir`, print its summary (:func:`railvib.solve.run_to_folder`).

    Parameters
    ----------
    case_file : pathlib.Path
        TOML case file.
    outdir : pathlib.Path
        Output folder (created if needed).
    plots : bool
        Draw the PSD overview figures.
    strict : bool
        Raise :class:`~railvib.errors.LinearModelInvalid` (exit code 3) after writing
        when the case is beyond the linear model.
    """
    out = run_to_folder(case_file, outdir, plots=plots)
    click.echo(out.text())
    click.echo(f"written to {outdir}/")
    if strict and not out.linear_model_valid:
        raise LinearModelInvalid(f"--strict: {out.contact}")
