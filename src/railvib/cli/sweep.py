"""``railvib sweep``: parameter sweeps, batched and resumable, locally or on a Dask cluster.

``railvib sweep SWEEP.toml`` is short for ``railvib sweep run SWEEP.toml``.
"""

from __future__ import annotations

from pathlib import Path

import click

from railvib.cli.options import output_option
from railvib.plot import DEFAULT_SWEEP_RESPONSES

__all__ = ["plot", "sweep"]


class _SweepGroup(click.Group):
    """A group whose first argument may be a sweep file (then ``run`` is implied)."""

    def resolve_command(
        self, ctx: click.Context, args: list[str]
    ) -> tuple[str | None, click.Command | None, list[str]]:
        if args and args[0] not in self.commands and not args[0].startswith("-"):
            args = ["run", *args]
        return super().resolve_command(ctx, args)


@click.group(cls=_SweepGroup)
def sweep() -> None:
    """Parameter sweeps: many cases over axes, batched, resumable, local or on Dask.

    Run with "railvib sweep SWEEP.toml [-o OUT] [--plot]" (the same command resumes
    an interrupted sweep); add "--scheduler tcp://HOST:8786" for a Dask cluster.
    "railvib sweep plot OUT" draws the summary, "railvib sweep export OUT" writes
    netCDF/CSV.
    """


@sweep.command("run")
@click.argument("sweep_file", type=click.Path(dir_okay=False, path_type=Path))
@output_option(None, "output folder [default: <SWEEP_FILE stem>.sweep]")
@click.option(
    "-j",
    "--workers",
    type=click.IntRange(min=1),
    default=None,
    help="local worker processes [default: all cores]",
)
@click.option(
    "--scheduler",
    metavar="ADDRESS",
    default=None,
    help="Dask distributed scheduler, e.g. tcp://10.0.0.1:8786",
)
@click.option(
    "--scheduler-timeout",
    type=click.FloatRange(min=0.0, min_open=True),
    default=5.0,
    show_default=True,
    metavar="SECONDS",
    help="how long to wait for the Dask scheduler to answer",
)
@click.option("--plot", "make_plots", is_flag=True, help="draw summary plots into OUT/plots")
@click.option("--netcdf", "netcdf", is_flag=True, help="also write OUT/sweep.nc")
@click.option("--csv", "csv", is_flag=True, help="also write the summary as OUT/summary.csv")
@click.option(
    "--overwrite",
    is_flag=True,
    help="discard finished chunks of a DIFFERENT sweep in OUT instead of refusing",
)
@click.option("--no-progress", is_flag=True, help="no progress bar")
@click.option(
    "--strict",
    is_flag=True,
    help="exit with code 3 when a case is beyond the linear model (loss of contact above "
    "output.loss_of_contact_threshold); the results are written all the same",
)
def run_command(
    sweep_file: Path,
    outdir: Path | None,
    workers: int | None,
    scheduler: str | None,
    scheduler_timeout: float,
    make_plots: bool,
    netcdf: bool,
    csv: bool,
    overwrite: bool,
    no_progress: bool,
    strict: bool,
) -> None:
    """Run SWEEP_FILE; rerunning the same command resumes an interrupted sweep."""
    from railvib.errors import LinearModelInvalid
    from railvib.outputs import is_linear_model_valid
    from railvib.sweep import (
        check_scheduler,
        connect_scheduler,
        default_output_folder,
        describe_run,
        linear_model_line,
        load_sweep,
        run_sweep,
        save_sweep_extras,
    )

    check_scheduler(scheduler)  # the address's form, before anything is read or written
    spec = load_sweep(sweep_file)
    out = outdir if outdir is not None else default_output_folder(sweep_file)
    with connect_scheduler(scheduler, scheduler_timeout) as client:  # before anything is said
        click.echo(describe_run(spec, out, scheduler=scheduler), err=True)
        try:
            ds = run_sweep(
                spec,
                out,
                workers=workers,
                scheduler=client,
                progress=not no_progress,
                overwrite=overwrite,
            )
        except KeyboardInterrupt:
            click.echo(err=True)  # end the ^C line
            raise click.Abort(
                f"finished chunks are kept in {out}/chunks - rerun the same command to resume"
            ) from None
    assert ds is not None  # run_sweep assembles by default
    for path in save_sweep_extras(ds, out, netcdf=netcdf, csv=csv, plots=make_plots):
        click.echo(f"written {path}", err=True)
    click.echo(f"written {out}/sweep.zarr; {linear_model_line(ds)}", err=True)
    if strict and not is_linear_model_valid(ds):
        raise LinearModelInvalid(f"--strict: {linear_model_line(ds)}")


@click.command("plot")
@click.argument("result", type=click.Path(exists=True, path_type=Path))
@click.option(
    "-v",
    "--variable",
    "variables",
    multiple=True,
    default=("peak", "dominant_frequency"),
    show_default=True,
    help="summary variable(s), repeated or comma-separated: peak, dominant_frequency, rms, "
    "rms_<lo>_<hi>_hz (e.g. -v peak,rms_20_100_hz), or a criterion: comfort_aw, "
    "mean_comfort_index, sperling_wz, dynamic_load_factor (docs/criteria.md)",
)
@click.option(
    "-r",
    "--response",
    "responses",
    multiple=True,
    help="response label(s), repeated or comma-separated (-r wheelset2.bounce,rail@wheel1): "
    "carbody.bounce, carbody.pitch, bogie1.bounce ... bogie2.pitch, wheelset1.bounce ... "
    "wheelset4.bounce, rail@wheel1 ... rail@wheel4 "
    f"[default: {', '.join(DEFAULT_SWEEP_RESPONSES)}]",
)
@click.option("--x", "x", default=None, help="sweep dimension on the horizontal axis")
@click.option("--y", "y", default=None, help="sweep dimension for a heat map")
@output_option(None, "folder for the PNGs [default: RESULT/plots or next to it]")
def plot(
    result: Path,
    variables: tuple[str, ...],
    responses: tuple[str, ...],
    x: str | None,
    y: str | None,
    outdir: Path | None,
) -> None:
    """Plot the summary of a sweep RESULT (folder, sweep.zarr or .nc) over its axes."""
    from railvib.plot.sweep import save_sweep_plots
    from railvib.sweep import default_plot_folder, load_sweep_dataset

    ds = load_sweep_dataset(result)
    folder = outdir if outdir is not None else default_plot_folder(result)
    for path in save_sweep_plots(ds, folder, _split(variables), _split(responses), x=x, y=y):
        click.echo(f"written {path}")


def _split(values: tuple[str, ...]) -> list[str]:
    """Repeated and comma-separated option values, in order: ``("a,b", "c")`` -> a, b, c."""
    return [v.strip() for value in values for v in value.split(",") if v.strip()]


sweep.add_command(plot)


@sweep.command("export")
@click.argument("result", type=click.Path(exists=True, path_type=Path))
@click.option(
    "--netcdf",
    "nc_path",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="write the whole dataset to this netCDF file",
)
@click.option(
    "--csv",
    "csv_path",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="write the summary table to this CSV file",
)
def export(result: Path, nc_path: Path | None, csv_path: Path | None) -> None:
    """Export a sweep RESULT (folder or sweep.zarr) to netCDF and/or CSV."""
    from railvib.sweep import load_sweep_dataset, save_sweep_csv, save_sweep_netcdf

    if nc_path is None and csv_path is None:
        raise click.UsageError("give --netcdf FILE and/or --csv FILE")
    ds = load_sweep_dataset(result)
    if nc_path is not None:
        click.echo(f"written {save_sweep_netcdf(ds, nc_path)}")
    if csv_path is not None:
        click.echo(f"written {save_sweep_csv(ds, csv_path)}")
