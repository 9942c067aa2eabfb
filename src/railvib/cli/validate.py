"""``railvib validate CASE.toml``: symplectic + PEM vs finite track vs time-domain Monte Carlo.

The command parses its options, loads the case (:func:`railvib.case.load_case`,
:func:`railvib.case.build_system`), makes one library call,
:func:`railvib.validation.validate_to_folder`, under a rich progress bar (the
finite-track frequencies, then the Monte Carlo's Newmark steps), and prints the
per-response agreement in 80 columns (the full tables are in the Markdown report).
Everything it writes is written by the library.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING

import click

from railvib.errors import CaseError, RailvibDeprecationWarning

if TYPE_CHECKING:  # the library loads when a command runs, not when the CLI starts
    from rich.console import Console

    from railvib.coupling import CoupledSystem
    from railvib.spectra.base import SpatialSpectrum
    from railvib.validation import ValidationResult, ValidationSettings

__all__ = ["run_validation", "validate"]

DEFAULT_OUTPUT = Path("validation")


@contextmanager
def _progress_bar(
    console: Console, settings: ValidationSettings
) -> Iterator[tuple[Callable[[int], None], Callable[[int], None]]]:
    """Rich bars over the finite track's frequencies and the Monte Carlo's Newmark steps.

    Yields the two callbacks ``(frf_progress, progress)``.
    """
    from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

    from railvib.validation import monte_carlo_work

    columns = (
        TextColumn("[progress.description]{task.description}"),
        BarColumn(),
        TextColumn("{task.percentage:>3.0f}%"),
        TimeRemainingColumn(),
    )
    with Progress(*columns, console=console, transient=False) as bar:
        frf = bar.add_task("finite track (frequencies)", total=settings.n_frf)
        mc = bar.add_task("Monte Carlo (Newmark steps)", total=monte_carlo_work(settings))
        yield (lambda n: bar.advance(frf, n)), (lambda n: bar.advance(mc, n))


def _validate_and_print(
    system: CoupledSystem,
    spectrum: SpatialSpectrum,
    outdir: Path,
    settings: ValidationSettings,
    seed: int,
    name: str,
    console: Console,
) -> ValidationResult:
    from railvib.validation import agreement_text, validate_to_folder

    with _progress_bar(console, settings) as (frf_progress, progress):
        result = validate_to_folder(
            system,
            spectrum,
            outdir,
            settings=settings,
            seed=seed,
            progress=progress,
            name=name,
            frf_progress=frf_progress,
        )
    report = outdir / f"{name}_agreement.md"
    console.print(agreement_text(result, name, report), markup=False, highlight=False)
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
    from railvib.validation import ValidationSettings, check_scope

    folder = _output_folder(output, outdir)
    case = load_case(case_file)
    if case.mode != "stationary":  # the three ways are the stationary model's
        raise CaseError(
            "mode",
            case.mode,
            '"stationary" for `railvib validate` (PEM, finite track and Monte Carlo of the '
            "vehicle at a fixed position); the moving vehicle's time-domain check is "
            "railvib.validation.moving_vehicle.simulate_moving_vehicle (docs/moving-vehicle.md)",
        )
    system = build_system(case)
    check_scope(system)  # before the progress bar: an out-of-scope case is one line
    settings = ValidationSettings.quick() if quick else ValidationSettings()
    _validate_and_print(
        system,
        build_spectrum(case),
        folder,
        settings.with_realisations(realisations),
        seed,
        case_file.stem,
        Console(),
    )
