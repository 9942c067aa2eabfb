"""The files of a validation: overlay plots, agreement tables (Markdown) and datasets (netCDF).

:func:`validate_to_folder` is the library call behind ``railvib validate``: it runs
:func:`~railvib.validation.validate_case` and :func:`write_validation` writes, into
one folder and under one name prefix,

* ``<name>_carbody_bounce.png``, ``<name>_bogie1_bounce.png``,
  ``<name>_wheelset2_bounce.png``, ``<name>_rail_wheel1.png`` (overlays);
* ``<name>_agreement.md`` (per-response and per-band agreement, timings, PASSED/FAILED);
* ``<name>_frf.nc``, ``<name>_mc.nc``, ``<name>_table.nc`` (through
  :func:`railvib.results.save_netcdf`; read them back with
  :func:`railvib.results.load_netcdf`).

Every file is written atomically, and the set as a whole: the files are written into a
staging folder that replaces the earlier set only once all of them are complete
(:func:`railvib.io.staged_folder`), so a run killed or failing half-way leaves `outdir` as
it was.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from railvib.coupling import CoupledSystem
from railvib.io import staged_folder, write_text
from railvib.results.dataset import save_netcdf
from railvib.spectra.base import SpatialSpectrum
from railvib.validation.compare import validate_case
from railvib.validation.plots import DEFAULT_PLOT_RESPONSES, plot_file_name, plot_overlays
from railvib.validation.result import (
    BAND_FRACTION,
    FRF_TOLERANCE,
    ValidationResult,
    ValidationSettings,
)
from railvib.validation.scope import check_scope

__all__ = [
    "DATASETS",
    "agreement_markdown",
    "agreement_text",
    "validate_to_folder",
    "validation_files",
    "write_validation",
]

#: the datasets of a :class:`ValidationResult` written as ``<name>_<key>.nc``
DATASETS = ("frf", "mc", "table")


def validation_files(name: str) -> tuple[str, ...]:
    """The names of the files :func:`validate_to_folder` writes under the prefix `name`.

    Parameters
    ----------
    name : str
        Prefix of the file names.

    Returns
    -------
    tuple of str
        Overlay PNGs, the Markdown report and the netCDF datasets.
    """
    plots = tuple(plot_file_name(name, response) for response in DEFAULT_PLOT_RESPONSES)
    return (*plots, f"{name}_agreement.md", *(f"{name}_{key}.nc" for key in DATASETS))


def agreement_markdown(result: ValidationResult, name: str) -> str:
    """The Markdown report of `result`: agreement tables, timings (s) and the verdict.

    Parameters
    ----------
    result : ValidationResult
        Output of :func:`~railvib.validation.validate_case`.
    name : str
        Name of the case, for the title.

    Returns
    -------
    str
        The text of ``<name>_agreement.md``.
    """
    return (
        f"# Validation of {name}\n\n## Agreement per response\n\n{result.summary_markdown()}\n\n"
        f"## Agreement per frequency band\n\n{result.table_markdown()}\n\n"
        f"{_approximations(result)}Timings (s): {result.timings}\n\nAcceptance (issue 5): "
        f"{'PASSED' if result.passed else 'FAILED'}\n"
    )


def agreement_text(result: ValidationResult, name: str, report: str | Path | None = None) -> str:
    """The per-response agreement of `result` as a plain table for an 80-column terminal.

    The Markdown report (:func:`agreement_markdown`, written as ``<name>_agreement.md``)
    holds the same numbers and the per-band table, which is wider than a terminal.

    Parameters
    ----------
    result : ValidationResult
        Output of :func:`~railvib.validation.validate_case`.
    name : str
        Name of the case, for the title.
    report : str or pathlib.Path, optional
        The Markdown report file, named under the table.

    Returns
    -------
    str
        Lines of at most 72 characters: per response, the finite-track maximum relative
        error (1) and the fractions of Welch bins with PEM inside the Monte Carlo band
        (windowed and raw, %), then the verdict; then one (longer) line per causal fit
        of a hysteretic layer (``approximation: ...``).
    """
    raw = result.mc["inside_raw"].mean("frequency")
    lines = [
        f"Agreement per response ({name})",
        f"{'response':<18}{'FE max rel. error':>19}{'PEM in MC band':>17}{'raw PEM in':>14}",
    ]
    for resp in result.frf["response"].values:
        err = float(result.max_relative_error.sel(response=resp))
        inside = float(result.fraction_inside.sel(response=resp))
        lines.append(
            f"{resp!s:<18}{err:>19.2e}{inside:>16.1%} {float(raw.sel(response=resp)):>13.1%}"
        )
    verdict = "PASSED" if result.passed else "FAILED"
    lines.append(
        f"Acceptance (issue 5): {verdict} (FE error <= {FRF_TOLERANCE:.0%}, PEM in band "
        f">= {BAND_FRACTION:.0%})"
    )
    lines += [f"approximation: {note}" for note in result.approximations]
    if report is not None:
        lines.append(f"per-band tables and timings: {report}")
    return "\n".join(lines)


def _approximations(result: ValidationResult) -> str:
    """The report's paragraph on the causal fits all routes took (empty if none)."""
    if not result.approximations:
        return ""
    lines = "".join(f"- {note}\n" for note in result.approximations)
    return f"## Causal approximations (solved by all three routes)\n\n{lines}\n"


def write_validation(
    result: ValidationResult, outdir: str | Path, name: str = "case"
) -> list[Path]:
    """Write the overlays, the Markdown report and the three datasets of `result`.

    Parameters
    ----------
    result : ValidationResult
        Output of :func:`~railvib.validation.validate_case`.
    outdir : str or pathlib.Path
        Output folder (created if missing).
    name : str
        Prefix of the file names.

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    written = plot_overlays(result, out, prefix=name)
    written.append(write_text(out / f"{name}_agreement.md", agreement_markdown(result, name)))
    for key in DATASETS:
        written.append(save_netcdf(getattr(result, key), out / f"{name}_{key}.nc"))
    return written


def validate_to_folder(
    system: CoupledSystem,
    spectrum: SpatialSpectrum,
    outdir: str | Path,
    *,
    settings: ValidationSettings | None = None,
    seed: int = 0,
    progress: Callable[[int], None] | None = None,
    name: str = "case",
    frf_progress: Callable[[int], None] | None = None,
) -> ValidationResult:
    """Validate one coupled system three ways and write the comparison into `outdir`.

    A case outside the reference models' scope is refused before anything is
    computed or written (:func:`railvib.validation.scope.check_scope`).

    Parameters
    ----------
    system : CoupledSystem
        Vehicle on the periodic track: k_H in N/m, leading wheel position in m,
        speed in m/s.
    spectrum : SpatialSpectrum
        One-sided irregularity spectrum, m^2/(rad/m).
    outdir : str or pathlib.Path
        Output folder (checked first, so an unwritable path fails before the run; the
        files land there together at the end).
    settings : ValidationSettings, optional
        Defaults to ``ValidationSettings()``; ``ValidationSettings.quick()`` runs in
        about 20 s.
    seed : int
        Base seed of the Monte Carlo.
    progress : callable, optional
        Called with Newmark steps done (times realisations); the total is
        :func:`~railvib.validation.monte_carlo_work`.
    name : str
        Prefix of the file names (see :func:`write_validation`).
    frf_progress : callable, optional
        Called with 1 after each frequency of the finite-track comparison; the total
        is ``settings.n_frf``.

    Returns
    -------
    ValidationResult
        PSDs in (m/s^2)^2/Hz ((rad/s^2)^2/Hz for pitch), timings in s.
    """
    check_scope(system)
    with staged_folder(outdir, validation_files(name)) as stage:
        result = validate_case(
            system,
            spectrum,
            settings=settings,
            seed=seed,
            progress=progress,
            frf_progress=frf_progress,
        )
        write_validation(result, stage.path, name)
    return result
