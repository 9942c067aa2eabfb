"""``railvib validate CASE.toml``: symplectic + PEM vs finite track vs time-domain Monte Carlo.

The command parses its options, loads the case (:func:`railvib.case.load_case`,
:func:`railvib.case.build_system`), makes one library call,
:func:`railvib.validation.validate_to_folder`, under a rich progress bar, and
prints the agreement report. Everything it writes is written by the library.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING

import click

from railvib.errors import RailvibDeprecationWarning

if TYPE_CHECKING:  # the library loads when a command runs, not when the CLI starts
    from rich.console import Console

    from railvib.coupling import CoupledSystem
    from railvib.spectra.base import SpatialSpectrum
    from railvib.validation import ValidationResult, ValidationSettings

__all__ = ["run_validation", "validate"]

DEFAULT_OUTPUT = Path("validation")


@contextmanager
def _progress_bar(console: Console, total: int) -> Iterator[Callable[[int], None]]:
    """A rich bar over the Monte Carlo's Newmark steps; yields the `progress` callback."""
    from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

    columns = (
        TextColumn("[progress.description]{task.description}"),
        BarColumn(),
        TextColumn("{task.percentage:>3.0f}%"),
        TimeRemainingColumn(),
    )
    with Progress(*columns, console=console, transient=False) as bar:
        task = bar.add_task("Monte Carlo (Newmark steps)", total=total)
        yield lambda n: bar.advance(task, n)


def _validate_and_print(
    system: CoupledSystem,
    spectrum: SpatialSpectrum,
    outdir: Path,
    settings: ValidationSettings,
    seed: int,
    name: str,
    console: Console,
) -> ValidationResult:
    from railvib.validation import agreement_markdown, monte_carlo_work, validate_to_folder

    with _progress_bar(console, monte_carlo_work(settings)) as progress:
        result = validate_to_folder(
            system, spectrum, outdir, settings=settings, seed=seed, progress=progress, name=name
        )
    console.print(agreement_markdown(result, name))
    return result


def run_validation(
    system: CoupledSystem,
    spectrum: SpatialSpectrum,
    outdir: str | Path,
    *,
    quick: bool = False,
    realisations: int | None = None,
    seed: int = 0,
    console: Console | None = None,
    name: str = "case",
) -> ValidationResult:
    """Validate one coupled system and write figures, tables and datasets to `outdir`.

    .. deprecated::
        Use :func:`railvib.validation.validate_to_folder` (the library function; this
        alias adds the progress bar and prints the report).

    Parameters
    ----------
    system : CoupledSystem
        Vehicle, periodic track, contact stiffness (N/m), leading wheel position (m), speed (m/s).
    spectrum : SpatialSpectrum
        Irregularity spectrum, m^2/(rad/m).
    outdir : str or pathlib.Path
        Output folder.
    quick : bool
        Short Monte Carlo (test-suite settings).
    realisations : int, optional
        Number of Monte Carlo realisations (overrides the default).
    seed : int
        Base seed.
    console : rich.console.Console, optional
        Where to print the progress bar and the summary.
    name : str
        Prefix of the output files.

    Returns
    -------
    ValidationResult
    """
    warnings.warn(
        "railvib.cli.validate.run_validation is deprecated; call "
        "railvib.validation.validate_to_folder(system, spectrum, outdir, settings=..., "
        "seed=..., progress=..., name=...) instead",
        RailvibDeprecationWarning,
        stacklevel=2,
    )
    from rich.console import Console

    from railvib.validation import ValidationSettings

    settings = (ValidationSettings.quick() if quick else ValidationSettings()).with_realisations(
        realisations
    )
    return _validate_and_print(
        system, spectrum, Path(outdir), settings, seed, name, console or Console()
    )


def _output_folder(output: Path, outdir: Path | None) -> Path:
    """The folder from ``-o/--output`` or the deprecated ``--outdir``."""
    if outdir is None:
        return output
    source = click.get_current_context().get_parameter_source("output")
    if source is not click.core.ParameterSource.DEFAULT:
        raise click.UsageError("give the output folder once, with -o/--output")
    click.echo("warning: --outdir is deprecated; use -o/--output", err=True)
    return outdir


@click.command("validate")
@click.argument("case_file", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--quick", is_flag=True, help="Short Monte Carlo (runs inside the test suite).")
@click.option(
    "-o",
    "--output",
    type=click.Path(file_okay=False, path_type=Path),
    default=DEFAULT_OUTPUT,
    show_default=True,
    help="Output folder for figures, tables and datasets.",
)
@click.option(
    "--outdir",
    type=click.Path(file_okay=False, path_type=Path),
    default=None,
    hidden=True,
    help="Deprecated spelling of -o/--output.",
)
@click.option("--realisations", type=click.IntRange(min=1), default=None, help="MC realisations.")
@click.option("--seed", type=int, default=0, show_default=True, help="Base seed of the MC.")
def validate(
    case_file: Path,
    quick: bool,
    output: Path,
    outdir: Path | None,
    realisations: int | None,
    seed: int,
) -> None:
    """Run CASE_FILE three ways (PEM, finite track, Monte Carlo) and write the comparison."""
    from rich.console import Console

    from railvib.case import build_spectrum, build_system, load_case
    from railvib.validation import ValidationSettings

    folder = _output_folder(output, outdir)
    case = load_case(case_file)
    settings = ValidationSettings.quick() if quick else ValidationSettings()
    _validate_and_print(
        build_system(case),
        build_spectrum(case),
        folder,
        settings.with_realisations(realisations),
        seed,
        case_file.stem,
        Console(),
    )
