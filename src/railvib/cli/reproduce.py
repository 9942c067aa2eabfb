"""``railvib reproduce``: the paper's study, figures, table and HTML report in one command."""

from __future__ import annotations

from pathlib import Path

import click

from railvib.cli.options import output_option

__all__ = ["reproduce"]


@click.command(short_help="The paper's study: Figs. 8-16, its numbers beside ours, HTML report.")
@output_option(Path("railvib-reproduce"))
@click.option("--quiet", is_flag=True, help="no progress bar, no summary")
def reproduce(outdir: Path, quiet: bool) -> None:
    """Reproduce Wang et al. 2017 (Figs. 8-16 and every number it states).

    Runs the constant vs frequency-dependent railpad comparison at 20 degC and the
    -30/-10/+20 degC series (presets wang2017_*), then writes to OUTPUT: one PNG per
    paper figure, paper_comparison.md/.csv (paper vs ours, relative difference, how
    each number is read, why we differ), report.html (self-contained) and the resolved
    case files.
    """
    from rich.console import Console
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    from railvib.reproduce import n_steps
    from railvib.reproduce import reproduce as run_study
    from railvib.reproduce.table import summary_line

    console = Console(stderr=True)
    with Progress(
        TextColumn("[bold]reproduce[/]"),
        BarColumn(),
        TextColumn("{task.description}"),
        TimeElapsedColumn(),
        console=console,
        disable=quiet,
        transient=False,
    ) as bar:
        task = bar.add_task("running the cases", total=n_steps())
        try:
            out = run_study(outdir, progress=lambda m: bar.update(task, advance=1, description=m))
        except BaseException:
            bar.live.transient = True  # the error is the one line shown, not a stopped bar
            raise
    if quiet:
        return
    click.echo(f"{summary_line(out.table)}; {out.seconds:.1f} s")
    click.echo(f"report: {out.outdir / 'report.html'}")
    click.echo(f"table:  {out.outdir / 'paper_comparison.md'}")
