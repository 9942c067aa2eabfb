"""``railvib validate CASE.toml``: symplectic + PEM vs finite track vs time-domain Monte Carlo.

The command is a thin adapter: it loads the case with :func:`railvib.case.load_case`,
builds the coupled system with :func:`railvib.case.build_system` and hands the core
objects to :func:`run_validation`, which writes the overlay plots, the agreement
tables (Markdown) and the datasets (netCDF) into the output folder.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import click
from rich.console import Console
from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

from railvib.coupling import CoupledSystem
from railvib.io import atomic_path
from railvib.spectra.base import SpatialSpectrum
from railvib.validation import (
    ValidationResult,
    ValidationSettings,
    monte_carlo_work,
    plot_overlays,
    validate_case,
)

__all__ = ["run_validation", "validate"]


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
    console = console or Console()
    settings = ValidationSettings.quick() if quick else ValidationSettings()
    if realisations is not None:
        settings = replace(
            settings, monte_carlo=replace(settings.monte_carlo, realisations=int(realisations))
        )
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    columns = (
        TextColumn("[progress.description]{task.description}"),
        BarColumn(),
        TextColumn("{task.percentage:>3.0f}%"),
        TimeRemainingColumn(),
    )
    with Progress(*columns, console=console, transient=False) as bar:
        task = bar.add_task("Monte Carlo (Newmark steps)", total=monte_carlo_work(settings))
        result = validate_case(
            system,
            spectrum,
            settings=settings,
            seed=seed,
            progress=lambda n: bar.advance(task, n),
        )
    plot_overlays(result, out, prefix=name)
    text = (
        f"# Validation of {name}\n\n## Agreement per response\n\n{result.summary_markdown()}\n\n"
        f"## Agreement per frequency band\n\n{result.table_markdown()}\n\n"
        f"Timings (s): {result.timings}\n\nAcceptance (issue 5): "
        f"{'PASSED' if result.passed else 'FAILED'}\n"
    )
    with atomic_path(out / f"{name}_agreement.md") as tmp:
        tmp.write_text(text, encoding="utf-8")
    for key in ("frf", "mc", "table"):
        ds = getattr(result, key).copy()
        ds.attrs = {k: str(v) for k, v in ds.attrs.items()}
        for var in ds.data_vars:
            if ds[var].dtype == bool:
                ds[var] = ds[var].astype("i1")
        with atomic_path(out / f"{name}_{key}.nc") as tmp:
            ds.to_netcdf(tmp, engine="h5netcdf")
    console.print(text)
    return result


@click.command("validate")
@click.argument("case_file", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--quick", is_flag=True, help="Short Monte Carlo (runs inside the test suite).")
@click.option(
    "-o",
    "--outdir",
    type=click.Path(file_okay=False, path_type=Path),
    default=Path("validation"),
    show_default=True,
    help="Output folder for figures, tables and datasets.",
)
@click.option("--realisations", type=click.IntRange(min=1), default=None, help="MC realisations.")
@click.option("--seed", type=int, default=0, show_default=True, help="Base seed of the MC.")
def validate(
    case_file: Path, quick: bool, outdir: Path, realisations: int | None, seed: int
) -> None:
    """Run CASE_FILE three ways (PEM, finite track, Monte Carlo) and write the comparison."""
    from railvib.case import build_spectrum, build_system, load_case

    case = load_case(case_file)
    run_validation(
        build_system(case),
        build_spectrum(case),
        outdir,
        quick=quick,
        realisations=realisations,
        seed=seed,
        name=case_file.stem,
    )
