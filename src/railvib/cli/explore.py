"""``railvib explore``: the live explorer in the browser (a thin layer over explore.app.serve)."""

from __future__ import annotations

from pathlib import Path

import click

__all__ = ["explore"]


@click.command()
@click.argument("case_file", required=False, type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "-o",
    "--output",
    "output",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="the case file 'Save case' writes [default: <CASE_FILE stem>-explored.toml, or "
    "explored.toml]",
)
@click.option("--host", default="127.0.0.1", show_default=True, help="address to bind")
@click.option(
    "--port",
    type=click.IntRange(0, 65535),
    default=5006,
    show_default=True,
    help="TCP port (0: any free one)",
)
@click.option("--show", is_flag=True, help="open the page in the default web browser")
def explore(case_file: Path | None, output: Path | None, host: str, port: int, show: bool) -> None:
    """Vary CASE_FILE (default: the paper's case) in a local web page, plots redrawn live.

    Controls for the speed, the track, the pad model, its stiffness and temperature, the
    irregularity class and the vehicle; linked plots of the response PSDs, the pad's
    K(f), the 1/3-octave levels and the summary. 'Save case' writes the case on the page
    to OUTPUT, validated like any case file. Needs the extra: pip install 'railvib[explore]'.
    """
    from railvib.case import load_case, load_preset_case
    from railvib.explore.app import require_bokeh, serve

    require_bokeh()  # one line before the case is even read
    base = load_case(case_file) if case_file is not None else load_preset_case()
    if output is None:
        output = Path(f"{case_file.stem}-explored.toml" if case_file else "explored.toml")

    def ready(url: str) -> None:
        click.echo(f"railvib explore: {url} (saves to {output}; Ctrl-C to stop)")

    serve(base, output, host=host, port=port, show=show, ready=ready)
