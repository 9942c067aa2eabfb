"""``railvib track``: the track alone, case to folder (a thin layer over track_to_folder)."""

from __future__ import annotations

from pathlib import Path

import click

from railvib.cli.options import output_option
from railvib.errors import CaseError

__all__ = ["track"]


def _bands(text: str | None) -> tuple[float, float] | None:
    if text is None:
        return None
    try:
        low, high = (float(x) for x in text.split(","))
    except ValueError:
        raise CaseError(
            "--tdr-bands", text, "two comma-separated frequencies LOW,HIGH (Hz)"
        ) from None
    return low, high


@click.command()
@click.argument("case_file", type=click.Path(dir_okay=False, path_type=Path))
@output_option(Path("railvib-track"))
@click.option(
    "--fmin",
    type=float,
    default=None,
    help="lowest frequency of a log grid, Hz [default: the case's]",
)
@click.option(
    "--fmax",
    type=float,
    default=None,
    help="highest frequency of a log grid, Hz [default: the case's]",
)
@click.option(
    "-n", "n_freq", type=int, default=None, help="frequencies of the log grid [default: 400]"
)
@click.option(
    "--load",
    type=click.Choice(["mid-span", "support"]),
    default="mid-span",
    show_default=True,
    help="where the unit force acts: mid-span of a bay or above a rail seat",
)
@click.option(
    "--tdr-bands",
    default=None,
    help="nominal first and last 1/3-octave band of the decay rate, LOW,HIGH in Hz "
    "[default: 100,5000 within the grid]",
)
@click.option(
    "--supports",
    type=int,
    default=10,
    show_default=True,
    help="rail seats each side of the load with support forces in the dataset",
)
@click.option("--no-plots", is_flag=True, help="skip the PNG figures")
def track(
    case_file: Path,
    outdir: Path,
    fmin: float | None,
    fmax: float | None,
    n_freq: int | None,
    load: str,
    tdr_bands: str | None,
    supports: int,
    no_plots: bool,
) -> None:
    """The track of CASE_FILE alone: receptance, support forces, waves, decay rate.

    Writes to OUTPUT track.nc (receptance, mobility, accelerance at points from the
    load; sleeper displacement and layer forces per rail seat; propagation constants
    and wave decay; the EN 15461 track decay rate in 1/3-octave bands),
    decay_rate.csv and three plots. The [track] table is taken for one rail.
    """
    from railvib.trackrun import TrackJob, track_to_folder

    job = TrackJob(
        f_min=fmin,
        f_max=fmax,
        n=n_freq,
        load=load,  # type: ignore[arg-type]
        tdr_bands=_bands(tdr_bands),
        n_supports=supports,
        plots=not no_plots,
    )
    out = track_to_folder(case_file, outdir, job)
    click.echo(out.text())
    click.echo(f"written to {outdir}/")
