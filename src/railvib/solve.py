"""The one public call that wires the pipeline: case -> coupled FRFs -> PSD dataset."""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr
from numpy.typing import NDArray

from railvib.case import Case, build_grid, build_spectrum, build_system, case_header, load_case
from railvib.coupling import CoupledSystem
from railvib.errors import RailvibDeprecationWarning
from railvib.grid import FrequencyGrid
from railvib.io import railvib_version, staged_folder, write_text
from railvib.outputs import (
    DEFAULT_OUTPUTS,
    LOSS_OF_CONTACT_NOTE,
    ContactCheck,
    contact_line,
    contact_table,
    derive,
    is_linear_model_valid,
    linearity_note,
)
from railvib.plot import OVERVIEW_STEMS
from railvib.results.dataset import build_dataset_blocks, check_finite, save_csv, save_netcdf
from railvib.results.report import summary_csv, summary_markdown, summary_text
from railvib.results.stats import summary, summary_table
from railvib.results.trains import car_table
from railvib.spectra.base import SpatialSpectrum

__all__ = [
    "LOSS_OF_CONTACT_NOTE",
    "PSD_CSV",
    "RUN_FILES",
    "RunOutput",
    "case_toml",
    "contact_check",
    "railvib_version",
    "run",
    "run_system",
    "run_to_folder",
]


def case_toml(case: Case) -> str:
    """The full, resolved case as TOML text (same as :meth:`railvib.case.Case.to_toml`)."""
    return case.to_toml()


def run_system(
    system: CoupledSystem,
    grid: FrequencyGrid,
    spectrum: SpatialSpectrum,
    attrs: dict[str, str] | None = None,
    *,
    loss_of_contact_threshold: float = LOSS_OF_CONTACT_NOTE,
) -> xr.Dataset:
    """Response PSDs and FRFs of a coupled system under a stationary irregularity.

    Parameters
    ----------
    system : CoupledSystem
        Vehicle, track, contact, wheel positions and speed.
    grid : FrequencyGrid
        Frequencies (Hz).
    spectrum : SpatialSpectrum
        Irregularity spectrum (spatial, one-sided).
    attrs : dict, optional
        Extra global attributes.
    loss_of_contact_threshold : float
        Largest probability of loss of contact (dimensionless) for which the result is
        flagged ``linear_model_valid`` (:class:`railvib.outputs.ContactCheck`).

    Returns
    -------
    xarray.Dataset
        See :func:`railvib.results.build_dataset` (built block by block of
        :data:`railvib.coupling.FREQUENCY_BLOCK` frequencies); with the contact check
        (``contact_force_rms``, ``loss_of_contact_probability``, ``linear_model_valid``).

    Raises
    ------
    railvib.errors.NonFiniteResult
        A response is NaN or infinite (parameters beyond what the solver resolves in
        floating point, e.g. a pad stiffness of 1e300 N/m), naming the variable.
    """
    f = grid.f
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # checked below
        s_r = spectrum.temporal(f, system.speed)
        pad_k = system.track.pad.stiffness(f, system.track.pad_temperature)
    extra = {
        "static_contact_load": xr.DataArray(
            system.vehicle.static_wheel_loads(),
            dims=("wheel",),
            attrs={"units": "N", "long_name": "static contact load"},
        ),
        "pad_stiffness": xr.DataArray(
            pad_k,
            dims=("frequency",),
            attrs={"units": "N/m", "long_name": "railpad dynamic stiffness K' + iK'' (beam model)"},
        ),
    }
    meta = {
        "railvib_version": railvib_version(),
        "speed_m_per_s": system.speed,
        "contact_stiffness_n_per_m": system.contact_stiffness,
        "wheel_positions_m": system.wheel_positions,
        "sleeper_spacing_m": system.track.sleeper_spacing,
        "time_dependence": "exp(+i omega t)",
        "sign_convention": "displacements positive downward; irregularity > 0 is a dip",
        **(attrs or {}),
    }
    settings = {"contact_check": {"loss_of_contact_threshold": loss_of_contact_threshold}}
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        ds = build_dataset_blocks(f, system.frf_blocks(f), s_r, attrs=meta, extra=extra)
    check_finite(ds)  # before the derived outputs, which assume finite PSDs
    return derive(ds, DEFAULT_OUTPUTS, settings)


def contact_check(
    system: CoupledSystem,
    f: NDArray[np.float64],
    force_frf: NDArray[np.complex128],
    irregularity_psd: NDArray[np.float64],
) -> dict[str, xr.DataArray]:
    """Deprecated: the contact check is the derived output :class:`railvib.outputs.ContactCheck`.

    Parameters
    ----------
    system : CoupledSystem
        The system (its static wheel loads, N).
    f : numpy.ndarray
        Frequencies, Hz.
    force_frf : numpy.ndarray
        Contact force per metre of irregularity, ``(n_freq, n_wheel)``, N/m.
    irregularity_psd : numpy.ndarray
        One-sided irregularity PSD, m^2/Hz, ``(n_freq,)``.

    Returns
    -------
    dict of xarray.DataArray
        ``contact_force_rms`` (N), ``static_contact_load`` (N) and
        ``loss_of_contact_probability`` (-), over ``wheel``.
    """
    warnings.warn(
        "railvib.solve.contact_check is deprecated; every run carries the check "
        "(railvib.outputs.ContactCheck().compute(ds))",
        RailvibDeprecationWarning,
        stacklevel=2,
    )
    psd = np.abs(force_frf) ** 2 * irregularity_psd[:, None]
    ds = xr.Dataset(
        {
            "psd_force": (("frequency", "wheel"), psd),
            "static_contact_load": (("wheel",), system.vehicle.static_wheel_loads()),
        },
        coords={"frequency": f},
    )
    out = ContactCheck().compute(ds)
    load = ds["static_contact_load"].assign_attrs(units="N", long_name="static contact load")
    return {
        "contact_force_rms": out["contact_force_rms"],
        "static_contact_load": load,
        "loss_of_contact_probability": out["loss_of_contact_probability"],
    }


def run(case: Case | str | Path, *, force: bool = False) -> xr.Dataset:
    """Run one case (a validated :class:`~railvib.case.Case` or a TOML path).

    Parameters
    ----------
    case : Case, str or pathlib.Path
        A validated case or a TOML case file.
    force : bool
        Run a case file whose grid has more than
        :data:`railvib.case.plausibility.MAX_FREQUENCIES` frequencies (see
        :func:`railvib.case.load_case`).

    Returns
    -------
    xarray.Dataset
        Response PSDs and FRFs on the case's grid (see :func:`run_system`).

    Examples
    --------
    >>> import railvib
    >>> ds = railvib.run(railvib.load_preset_case())
    >>> float(ds.psd_acceleration.sel(response="wheelset2.bounce").max()) > 0
    True
    """
    if not isinstance(case, Case):
        case = load_case(case, force=force)
    return run_system(
        build_system(case),
        build_grid(case),
        build_spectrum(case),
        attrs={"title": case.title, "case_toml": case.to_toml(), "rail_model": case.rail_model},
        loss_of_contact_threshold=case.output.loss_of_contact_threshold,
    )


@dataclass(frozen=True, eq=False)
class RunOutput:
    """What :func:`run_to_folder` computed and wrote.

    Parameters
    ----------
    dataset : xarray.Dataset
        The result (see :func:`run`).
    summary : pandas.DataFrame
        Peak, dominant frequency and RMS per response, each with its unit
        (:func:`railvib.results.stats.summary_table`).
    files : tuple of pathlib.Path
        Every file written.
    notes : tuple of str
        Warnings for the reader (e.g. likely loss of contact).
    header : tuple of str
        The case lines heading every summary (:func:`railvib.case.case_header`).
    contact : str
        The contact-check line (:func:`railvib.outputs.contact_line`).
    """

    dataset: xr.Dataset
    summary: pd.DataFrame
    files: tuple[Path, ...]
    notes: tuple[str, ...]
    header: tuple[str, ...] = ()
    contact: str = ""

    @property
    def linear_model_valid(self) -> bool:
        """Whether the case is within the linear model (loss of contact <= the threshold)."""
        return is_linear_model_valid(self.dataset)

    def text(self) -> str:
        """The summary as ``railvib run`` prints it: the case, the table, the contact check."""
        footer = [self.contact] if self.contact else []
        return summary_text(self.summary, self.header, [*footer, *self.notes])


#: the PSD tables ``railvib run`` writes beside the dataset (file stem = variable)
PSD_CSV = ("psd_acceleration", "psd_displacement", "psd_force")

#: every file ``railvib run`` may write to its folder (a later run replaces them all)
RUN_FILES = (
    "results.nc",
    *(f"{name}.csv" for name in PSD_CSV),
    "summary.csv",
    "summary.md",
    *(f"{stem}.png" for stem in OVERVIEW_STEMS),
)


def run_to_folder(
    case: Case | str | Path, outdir: str | Path, *, plots: bool = True, force: bool = False
) -> RunOutput:
    """Run one case and write its dataset, summary and plots to `outdir` (``railvib run``).

    Writes ``results.nc``, ``psd_acceleration.csv``, ``psd_displacement.csv``,
    ``psd_force.csv``, ``summary.csv`` and ``summary.md`` (each headed by the case:
    :func:`railvib.case.case_header`, and the contact check) and, with `plots`, the
    overview figures (:func:`railvib.plot.psd.save_overview`). The files are written
    into a staging folder put in place at the end (:func:`railvib.io.staged_folder`):
    `outdir` then holds this run's complete set, an earlier run's files of
    :data:`RUN_FILES` are replaced or removed (other files are kept), and a run that
    fails or is stopped leaves `outdir` as it was.

    Parameters
    ----------
    case : Case, str or pathlib.Path
        A validated case or a TOML case file.
    outdir : str or pathlib.Path
        Output folder (created if needed).
    plots : bool
        Draw the PSD overview figures.
    force : bool
        Run a case file whose grid has more than
        :data:`railvib.case.plausibility.MAX_FREQUENCIES` frequencies
        (``railvib run --force``).

    Returns
    -------
    RunOutput

    Raises
    ------
    railvib.errors.CaseError
        Bad input, or `outdir` is not a folder (before anything is computed).
    railvib.errors.OutputError
        `outdir` or one of its files cannot be written (read-only, full disk).
    railvib.errors.NonFiniteResult
        The result holds NaN or infinite values (nothing is written).
    """
    if not isinstance(case, Case):
        case = load_case(case, force=force)
    with staged_folder(outdir, RUN_FILES) as stage:
        ds = run(case)
        table = summary_table(summary(ds, bands=case.output.rms_bands))
        header = case_header(case)
        contact = contact_line(ds)
        contacts = [("Contact check per wheel", contact_table(ds))]
        per_car = car_table(table, ds)
        if per_car is not None:
            contacts.append(("Per car and for the train", per_car))
        files = [
            save_netcdf(ds, stage.path / "results.nc"),
            *(save_csv(ds, stage.path / f"{name}.csv", variable=name) for name in PSD_CSV),
            write_text(stage.path / "summary.csv", summary_csv(table, header, [contact])),
            write_text(
                stage.path / "summary.md",
                summary_markdown(table, header, [contact], title=case.title, extra=contacts),
            ),
        ]
        if plots:
            from railvib.plot.psd import save_overview  # matplotlib: only when plotting

            files += save_overview(ds, stage.path)
    files = stage.finals(files)
    note = linearity_note(ds)
    notes = () if note is None else (note,)
    return RunOutput(ds, table, tuple(files), notes, tuple(header), contact)
