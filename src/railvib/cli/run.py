"""``railvib run``: one case to dataset, summary and plots (a thin layer over run_to_folder)."""

from __future__ import annotations

from pathlib import Path

import click

from railvib.case import load_case
from railvib.cli.dask_probe import defer_dask_probe
from railvib.errors import CaseError, LinearModelInvalid
from railvib.solve import run_to_folder

__all__ = ["run_case_command"]


def run_case_command(
    case_file: Path,
    outdir: Path,
    plots: bool = True,
    strict: bool = False,
    force: bool = False,
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
        when the case is beyond the linear model; refused (``CaseError`` on ``mode``,
        before anything is written) for a moving or non-stationary case.
    force : bool
        Run a grid of more than 2,000,000 frequencies.
    """
    defer_dask_probe()  # a run makes no dask array: xarray need not import dask to know
    case = load_case(case_file, force=force)
    if strict and case.mode != "stationary":  # before anything is computed or written
        raise CaseError(
            "mode",
            case.mode,
            '"stationary" with --strict (its loss-of-contact check is that of the '
            "stationary model; this mode has none): run without --strict",
        )
    if case.mode == "nonstationary":  # docs/nonstationary.md
        from railvib.cli.nonstationary import run_nonstationary_command

        run_nonstationary_command(case, outdir, plots=plots)
        return
    if case.mode == "moving":  # docs/moving-vehicle.md
        from railvib.movingrun import run_moving_to_folder

        moving = run_moving_to_folder(case, outdir, plots=plots)
        click.echo(moving.text())
        click.echo(f"written to {outdir}/")
        return
    out = run_to_folder(case, outdir, plots=plots, force=force)
    click.echo(out.text())
    click.echo(f"written to {outdir}/")
    if strict and not out.linear_model_valid:
        raise LinearModelInvalid(f"--strict: {out.contact}")
