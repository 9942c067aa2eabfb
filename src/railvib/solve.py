"""The one public call that wires the pipeline: case -> coupled FRFs -> PSD dataset."""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr
from numpy.typing import NDArray

from railvib.case import Case, build_grid, build_spectrum, build_system, case_header, load_case
from railvib.case.schema import CriteriaSection
from railvib.coupling import CoupledSystem
from railvib.errors import CaseError, RailvibDeprecationWarning
from railvib.grid import FrequencyGrid, trapezoid
from railvib.io import railvib_version, staged_folder, write_text
from railvib.outputs import (
    DEFAULT_OUTPUTS,
    LOSS_OF_CONTACT_NOTE,
    ContactCheck,
    RideComfort,
    ThirdOctave,
    contact_line,
    contact_table,
    criteria_lines,
    criteria_table,
    derive,
    floor_geometry,
    is_linear_model_valid,
    linearity_note,
    octave_table,
    third_octave_bands,
)
from railvib.outputs.supports import (
    SUPPORT_COORDS,
    gives_seat_forces,
    seat_positions,
    support_force_data,
    support_force_psd,
    support_variables,
)
from railvib.outputs.weighting import COMFORT_RANGE_HZ
from railvib.plot import OVERVIEW_STEMS, RunFigures, save_run_figures, start_run_figures
from railvib.response import FRF
from railvib.results.dataset import (
    all_finite,
    assemble,
    check_finite_variables,
    open_netcdf,
    per_frequency_values,
    result_variables,
    save_csv,
    save_netcdf,
    value_arrays,
)
from railvib.results.report import summary_csv, summary_markdown, summary_text
from railvib.results.stats import summary, summary_table
from railvib.results.stream import RunningIntegral, netcdf_stream
from railvib.results.trains import car_table
from railvib.results.variables import VARIABLES, write_variables
from railvib.spectra.base import SpatialSpectrum

__all__ = [
    "LOSS_OF_CONTACT_NOTE",
    "criteria_settings",
    "CRITERIA_FILES",
    "CRITERIA_STEMS",
    "PSD_CSV",
    "RUN_FILES",
    "RunOutput",
    "STREAM_FREQUENCIES",
    "case_toml",
    "contact_check",
    "railvib_version",
    "run",
    "run_system",
    "run_to_folder",
    "stream_to_netcdf",
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
    criteria: dict[str, dict[str, Any]] | None = None,
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
    criteria : dict, optional
        Derived outputs to add after the contact check, name -> settings
        (:func:`criteria_settings`); none by default.

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
    check = ContactCheck(loss_of_contact_threshold=loss_of_contact_threshold)
    seats = _seats(system, f)
    seat_rail = np.empty((f.size, 0 if seats is None else seats.size), dtype=np.complex128)
    n_dof, n_wheel = len(system.vehicle.dofs), len(system.vehicle.wheels)
    values = value_arrays(f.size, n_dof, n_wheel)
    # the responses written straight into the result's arrays where the fused kernel
    # solves them (the vehicle's and the rail's columns of frf_displacement, frf_force)
    frf_u = values["frf_displacement"]
    into = (frf_u[:, :n_dof], values["frf_force"], frf_u[:, n_dof:], seat_rail)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        blocks = _kept(system.frf_blocks(f, observe=seats, into=into), seat_rail)
        values, labels, n_wheel = per_frequency_values(f, blocks, s_r, out=values)
    # every variable wrapped, not copied, and the dataset built once at the end
    data, coords = result_variables(f, labels, n_wheel, values)
    loads = system.vehicle.static_wheel_loads()
    data |= _extra(loads, pad_k)
    check_finite_variables(data, f)  # before the derived outputs, which assume finite PSDs
    # a slab track gives its bearing forces from the contact forces (its seats share the slab)
    rail = None if seats is None else seat_rail
    support = support_force_data(system, {"frequency": coords["frequency"], **data}, rail=rail)
    support_coords = {k: support.pop(k) for k in SUPPORT_COORDS if k in support}
    data |= support
    mean_square = trapezoid(values["psd_force"], f, axis=0)
    data |= check.variables(mean_square, loads, ("wheel",), float(f[0]), float(f[-1]))
    ds = assemble(data, coords | support_coords, _meta(system, attrs))
    # the contact check from the arrays above; any other default output and the criteria
    later = [name for name in DEFAULT_OUTPUTS if name != "contact_check"] + list(criteria or {})
    return derive(ds, later, criteria) if later else ds


def stream_to_netcdf(
    system: CoupledSystem,
    grid: FrequencyGrid,
    spectrum: SpatialSpectrum,
    path: str | Path,
    attrs: dict[str, str] | None = None,
    *,
    loss_of_contact_threshold: float = LOSS_OF_CONTACT_NOTE,
    criteria: dict[str, dict[str, Any]] | None = None,
    block: int | None = None,
) -> xr.Dataset:
    """:func:`run_system` written to a netCDF file block by block, for grids too large to hold.

    Each block of frequencies is solved, its variables written to `path` and dropped
    (:class:`railvib.results.stream.NetCDFStream`), so memory is bounded by the block,
    not by the grid; the contact check and the support-force RMS are integrated block by
    block (:class:`railvib.results.stream.RunningIntegral`). The criteria, which need
    whole spectra, are computed from the written file one variable at a time and added
    to it. The file is written under a temporary name and renamed at the end: a run that
    fails or is stopped leaves no half-written file, and an earlier `path` as it was.

    Parameters
    ----------
    system : CoupledSystem
        Vehicle, track, contact, wheel positions and speed.
    grid : FrequencyGrid
        Frequencies (Hz).
    spectrum : SpatialSpectrum
        Irregularity spectrum (spatial, one-sided).
    path : str or pathlib.Path
        The netCDF file (``results.nc``).
    attrs : dict, optional
        Extra global attributes.
    loss_of_contact_threshold : float
        Largest probability of loss of contact (dimensionless), as in :func:`run_system`.
    criteria : dict, optional
        Derived outputs to add after the contact check, as in :func:`run_system`.
    block : int, optional
        Frequencies per block (default: :meth:`railvib.coupling.CoupledSystem.frf_blocks`'s).

    Returns
    -------
    xarray.Dataset
        The variables without a frequency dimension (static loads, the contact check,
        the support-force RMS, the criteria's), in memory. The file holds the result of
        :func:`run_system`: :func:`railvib.results.load_netcdf` of it equals
        :func:`railvib.results.save_netcdf`'s of the result held in memory (the RMS values
        to rounding: integrated block by block).

    Raises
    ------
    railvib.errors.NonFiniteResult
        A response is NaN or infinite (nothing is left at `path`).
    railvib.errors.OutputError
        `path` cannot be written (full disk, read-only folder).
    """
    f = grid.f
    check = ContactCheck(loss_of_contact_threshold=loss_of_contact_threshold)
    seats = _seats(system, f)
    loads = system.vehicle.static_wheel_loads()
    band = (float(f[0]), float(f[-1]))
    force_ms, support_ms = RunningIntegral(), RunningIntegral()
    support: dict[str, xr.Variable] = {}
    criteria_ds = xr.Dataset()
    checked = (*VARIABLES, "pad_stiffness")  # as run_system checks (not the support forces)
    with netcdf_stream(path, f.size) as stream:
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # checked below
            for sl, frf in system.frf_blocks(f, block=block, observe=seats):
                fb = f[sl]
                s_r = spectrum.temporal(fb, system.speed)
                pad_k = system.track.pad.stiffness(fb, system.track.pad_temperature)
                # the block's values filled as run_system fills its whole grid's (the same
                # operations: the file's values are the held run's bit for bit), a later
                # block's straight into the rows of the file's next write
                if sl.start == 0:
                    values = per_frequency_values(fb, [(slice(None), frf)], s_r)[0]
                else:
                    values = stream.rows(sl)
                    write_variables(values, frf, s_r)
                    values["frequency"][...] = fb
                    values["pad_stiffness"][...] = pad_k
                if sl.start == 0 or not all_finite(values[k] for k in checked):
                    # the variables (the first block: the file's layout; a block that fails
                    # the check: the message names the variable and the frequencies)
                    data, coords = result_variables(fb, frf.labels, frf.n_wheel, values)
                    data |= _extra(loads, pad_k)
                    check_finite_variables(data, fb, grid=f)
                rail = None if seats is None else frf.rail_observed
                parts = support_force_psd(system, fb, s_r, frf.contact_force, rail)
                if parts is not None:
                    support_ms.add(fb, parts[2])
                force_ms.add(fb, np.asarray(values["psd_force"], dtype=float))
                if sl.start == 0:  # the layout, with the whole-grid values as placeholders
                    support = support_variables(fb, parts)
                    support_coords = {k: support.pop(k) for k in SUPPORT_COORDS if k in support}
                    data |= support
                    data |= check.variables(force_ms.total, loads, ("wheel",), *band)
                    layout = assemble(data, coords | support_coords, _meta(system, attrs))
                    stream.first(layout)
                elif parts is not None:
                    values["psd_support_force"][...] = parts[2]
        whole = check.variables(force_ms.total, loads, ("wheel",), *band)
        if support:
            rms = support["support_force_rms"]
            whole["support_force_rms"] = rms.copy(data=np.sqrt(support_ms.total))
        stream.finish(whole)
        later = [name for name in DEFAULT_OUTPUTS if name != "contact_check"] + list(criteria or {})
        if later:
            with stream.open() as written:  # the criteria read the complex FRFs too
                derived = derive(written, later, criteria)
                added = [k for k in derived.variables if k not in written.variables]
                new = derived[[k for k in added if k in derived.data_vars]].load()
            new = new.drop_vars([k for k in new.coords if k not in added])
            stream.append(new)
            criteria_ds = new.drop_dims("frequency", errors="ignore")
    # the loads, coordinates and attributes of the layout, its placeholders replaced
    small = layout.drop_dims("frequency").assign(whole)
    return small.merge(criteria_ds)


def _seats(system: CoupledSystem, f: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """The rail seats under the wheels, m, where the track gives their forces (else None)."""
    if gives_seat_forces(system, f):
        return seat_positions(system.wheel_positions, system.track.sleeper_spacing)
    return None


def _extra(loads: NDArray[np.float64], pad_k: NDArray[np.complex128]) -> dict[str, xr.Variable]:
    """The static contact loads (N) and the pad stiffness over the grid (N/m) of a run."""
    return {
        "static_contact_load": xr.Variable(
            ("wheel",), loads, {"units": "N", "long_name": "static contact load"}
        ),
        "pad_stiffness": xr.Variable(
            ("frequency",),
            pad_k,
            {"units": "N/m", "long_name": "railpad dynamic stiffness K' + iK'' (beam model)"},
        ),
    }


def _meta(system: CoupledSystem, attrs: dict[str, str] | None) -> dict[str, Any]:
    """The global attributes of a run of `system`, then `attrs`."""
    return {
        "railvib_version": railvib_version(),
        "speed_m_per_s": system.speed,
        "contact_stiffness_n_per_m": system.contact_stiffness,
        "wheel_positions_m": system.wheel_positions,
        "sleeper_spacing_m": system.track.sleeper_spacing,
        "time_dependence": "exp(+i omega t)",
        "sign_convention": "displacements positive downward; irregularity > 0 is a dip",
        **(attrs or {}),
    }


def _kept(
    blocks: Iterator[tuple[slice, FRF]], observed: NDArray[np.complex128]
) -> Iterator[tuple[slice, FRF]]:
    """`blocks` as they are, each block's ``rail_observed`` kept into `observed` on the way."""
    for sl, frf in blocks:
        if frf.rail_observed is not None:
            observed[sl] = frf.rail_observed
        yield sl, frf


def _overlap(band: tuple[float, float], f: NDArray[np.float64]) -> tuple[float, float] | None:
    """`band` clipped to the grid `f` (Hz), or None where they do not overlap."""
    lo, hi = max(band[0], float(f[0])), min(band[1], float(f[-1]))
    return (lo, hi) if lo < hi else None


def criteria_settings(
    case: Case, system: CoupledSystem, f: NDArray[np.float64]
) -> dict[str, dict[str, Any]]:
    """The engineering criteria of a run and their settings, validated before anything is solved.

    Ride comfort is computed at the floor points of ``[criteria]`` (default: over the
    bogies and at the centre, :func:`railvib.outputs.floor_geometry`) over
    ``comfort_band_hz`` (default: 0.5-80 Hz where the grid reaches, none where it does
    not); the one-third-octave bands over ``octave_band_hz`` (default: the bands
    the grid holds); the wheel-rail force criteria always.

    Parameters
    ----------
    case : Case
        The case (its ``[criteria]`` section, if any).
    system : CoupledSystem
        Its system (the vehicle's geometry).
    f : numpy.ndarray
        The frequency grid, Hz.

    Returns
    -------
    dict
        Output name -> settings, for :func:`railvib.outputs.derive`.

    Raises
    ------
    railvib.errors.CaseError
        A ``criteria.<key>`` that does not apply: a body without pitch (a rail
        response), a floor point outside the car body, a band outside the grid or
        outside the range where the weighting is defined.
    """
    c = case.criteria or CriteriaSection.model_validate({})
    out: dict[str, dict[str, Any]] = {"wheel_rail_forces": {}}
    octave = ThirdOctave(*(c.octave_band_hz or (0.0, 0.0)))
    if c.octave_band_hz is not None or third_octave_bands(f[0], f[-1]).index.size:
        octave.bands(f)  # refuses a range beyond the grid or holding no band
        out["third_octave"] = {"f_lo": octave.f_lo, "f_hi": octave.f_hi}
    bodies = [b.name for b in system.vehicle.bodies if b.pitch_inertia is not None]
    body = c.comfort_body
    if "comfort_body" not in c.model_fields_set and f"car1.{body}" in bodies:
        body = f"car1.{body}"  # a train: the leading car's body unless another is named
    if body not in bodies:
        raise CaseError("criteria.comfort_body", body, f"a body with pitch: {bodies}")
    band = c.comfort_band_hz or _overlap(COMFORT_RANGE_HZ, f)
    if band is None:
        return out
    geometry = floor_geometry(system.vehicle, body)
    settings: dict[str, Any] = {
        "floor_positions_m": tuple(c.floor_positions_m or geometry.positions),
        "floor_extent_m": geometry.extent,
        "weighting": c.comfort_weighting,
        "band_hz": tuple(band),
        "body": body,
    }
    RideComfort(**settings).band(f)  # validates the settings and the band against the grid
    out["ride_comfort"] = settings
    return out


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


#: the library call that runs each other mode (``railvib run`` dispatches to them)
_OTHER_MODES = {
    "moving": "railvib.movingrun.run_moving / run_moving_to_folder (docs/moving-vehicle.md)",
    "nonstationary": "railvib.nonstationary.run_nonstationary_to_folder (docs/nonstationary.md)",
}


def _stationary_only(case: Case) -> None:
    """Refuse, in one line naming ``mode``, a case this stationary pipeline would misread."""
    if case.mode in _OTHER_MODES:
        raise CaseError(
            "mode",
            case.mode,
            f'"stationary" for railvib.run / run_to_folder (the fixed-position model); '
            f"run mode = {case.mode!r} with {_OTHER_MODES[case.mode]} or `railvib run`",
        )


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
        Response PSDs and FRFs on the case's grid (see :func:`run_system`), with the
        engineering criteria of :func:`criteria_settings`.

    Raises
    ------
    railvib.errors.CaseError
        Bad input, or a case of another ``mode`` (``moving``, ``nonstationary``: their own
        library calls), before anything is computed.

    Examples
    --------
    >>> import railvib
    >>> ds = railvib.run(railvib.load_preset_case())
    >>> float(ds.psd_acceleration.sel(response="wheelset2.bounce").max()) > 0
    True
    """
    if not isinstance(case, Case):
        case = load_case(case, force=force)
    _stationary_only(case)
    system, grid, spectrum, options = _prepared(case)
    return run_system(system, grid, spectrum, **options)


def _prepared(
    case: Case,
) -> tuple[CoupledSystem, FrequencyGrid, SpatialSpectrum, dict[str, Any]]:
    """The system, grid and spectrum of `case`, and the options of its run (validated)."""
    system, grid = build_system(case), build_grid(case)
    criteria = criteria_settings(case, system, grid.f)  # refuses bad settings before solving
    options = {
        "attrs": {"title": case.title, "case_toml": case.to_toml(), "rail_model": case.rail_model},
        "loss_of_contact_threshold": case.output.loss_of_contact_threshold,
        "criteria": criteria,
    }
    return system, grid, build_spectrum(case), options


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
    criteria : tuple of str
        The criteria lines (:func:`railvib.outputs.criteria_lines`).
    """

    dataset: xr.Dataset
    summary: pd.DataFrame
    files: tuple[Path, ...]
    notes: tuple[str, ...]
    header: tuple[str, ...] = ()
    contact: str = ""
    criteria: tuple[str, ...] = ()

    @property
    def linear_model_valid(self) -> bool:
        """Whether the case is within the linear model (loss of contact <= the threshold)."""
        return is_linear_model_valid(self.dataset)

    def text(self) -> str:
        """The summary as ``railvib run`` prints it: the case, the table, the contact check."""
        footer = [self.contact] if self.contact else []
        return summary_text(self.summary, self.header, [*footer, *self.criteria, *self.notes])


#: the PSD tables ``railvib run`` writes beside the dataset (file stem = variable)
PSD_CSV = ("psd_acceleration", "psd_displacement", "psd_force")

#: the criteria tables ``railvib run`` writes (docs/criteria.md)
CRITERIA_FILES = ("criteria.csv", "third_octave.csv")

#: the criteria figures ``railvib run`` draws (:mod:`railvib.plot.criteria`)
CRITERIA_STEMS = ("third_octave", "comfort")

#: grids of more frequencies than this are written to ``results.nc`` block by block by
#: :func:`run_to_folder` (:func:`stream_to_netcdf`): holding such a result would take
#: more than 60 MB (608 bytes a frequency)
STREAM_FREQUENCIES = 100_000

#: every file ``railvib run`` may write to its folder (a later run replaces them all)
RUN_FILES = (
    "results.nc",
    *(f"{name}.csv" for name in PSD_CSV),
    "summary.csv",
    "summary.md",
    *(f"{stem}.png" for stem in OVERVIEW_STEMS),
    *CRITERIA_FILES,
    *(f"{stem}.png" for stem in CRITERIA_STEMS),
)


def run_to_folder(
    case: Case | str | Path, outdir: str | Path, *, plots: bool = True, force: bool = False
) -> RunOutput:
    """Run one case and write its dataset, summary and plots to `outdir` (``railvib run``).

    Writes ``results.nc``, ``psd_acceleration.csv``, ``psd_displacement.csv``,
    ``psd_force.csv``, ``summary.csv`` and ``summary.md`` (each headed by the case:
    :func:`railvib.case.case_header`, the contact check and the criteria lines),
    ``criteria.csv`` and ``third_octave.csv`` (docs/criteria.md) and, with `plots`, the
    overview figures (:func:`railvib.plot.psd.save_overview`) and the criteria figures
    (:func:`railvib.plot.criteria.save_criteria_plots`). The files are written
    into a staging folder put in place at the end (:func:`railvib.io.staged_folder`):
    `outdir` then holds this run's complete set, an earlier run's files of
    :data:`RUN_FILES` are replaced or removed (other files are kept), and a run that
    fails or is stopped leaves `outdir` as it was.

    A grid of more than :data:`STREAM_FREQUENCIES` frequencies is written to
    ``results.nc`` block by block (:func:`stream_to_netcdf`), so memory is bounded by
    the block, not by the grid; the tables, summary and figures are then made from the
    file, one variable at a time, and the returned dataset holds the variables without a
    frequency dimension (the whole result is in ``results.nc``:
    :func:`railvib.results.load_netcdf`).

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
        Its ``dataset``: the result (:func:`run`), or for a streamed grid the variables
        without a frequency dimension (:func:`stream_to_netcdf`).

    Raises
    ------
    railvib.errors.CaseError
        Bad input, a case of another ``mode`` (see :func:`run`), or `outdir` is not a
        folder (before anything is computed or written).
    railvib.errors.OutputError
        `outdir` or one of its files cannot be written (read-only, full disk).
    railvib.errors.NonFiniteResult
        The result holds NaN or infinite values (nothing is written).
    """
    if not isinstance(case, Case):
        case = load_case(case, force=force)
    _stationary_only(case)  # before the folder is touched
    with staged_folder(outdir, RUN_FILES) as stage:
        system, grid, spectrum, options = _prepared(case)
        nc = stage.path / "results.nc"
        if grid.f.size > STREAM_FREQUENCIES:  # written block by block, then read from the file
            result = stream_to_netcdf(system, grid, spectrum, nc, **options)
            ds = open_netcdf(nc, drop=("frf_displacement", "frf_force"))
            figures = None
        else:
            ds = result = run_system(system, grid, spectrum, **options)
            # drawn in a second process while results.nc and the tables are written
            figures = start_run_figures(stage, ds) if plots else None
            save_netcdf(ds, nc)
        with ds:
            files, table, header, footer = _write_run(case, ds, stage.path, plots, figures)
    files = stage.finals([nc, *files])
    note = linearity_note(result)
    notes = () if note is None else (note,)
    return RunOutput(
        result, table, tuple(files), notes, tuple(header), footer[0], tuple(footer[1:])
    )


#: the per-frequency variables the figures draw line by line
_PLOTTED = ("psd_acceleration", "psd_force", "psd_floor_acceleration")


def _write_run(
    case: Case, ds: xr.Dataset, folder: Path, plots: bool, figures: RunFigures | None = None
) -> tuple[list[Path], pd.DataFrame, list[str], list[str]]:
    """The files of :func:`run_to_folder` besides ``results.nc``, its table and summary lines.

    `figures`: the figures already being drawn (:func:`railvib.plot.start_run_figures`),
    else drawn here with `plots`.
    """
    table = summary_table(summary(ds, bands=case.output.rms_bands))
    header = case_header(case)
    contact = contact_line(ds)
    footer = [contact, *criteria_lines(ds)]
    criteria = criteria_table(ds)
    per_car = car_table(table, ds)
    cars = [] if per_car is None else [("Per car and for the train", per_car)]
    extra = [("Contact check per wheel", contact_table(ds)), *cars, ("Criteria", criteria)]
    files = [
        *(save_csv(ds, folder / f"{name}.csv", variable=name) for name in PSD_CSV),
        write_text(
            folder / "summary.csv",
            summary_csv(table, header, footer, extra=cars),
        ),
        write_text(
            folder / "summary.md",
            summary_markdown(table, header, footer, title=case.title, extra=extra),
        ),
        write_text(folder / "criteria.csv", criteria.to_csv(index=False)),
    ]
    if "octave_level_acceleration" in ds:
        octaves = octave_table(ds).to_csv(float_format="%.2f")
        files.append(write_text(folder / "third_octave.csv", octaves))
    if figures is not None:
        files += figures.result()
    elif plots:
        for name in _PLOTTED:  # a streamed file's: read once, not once per line drawn
            if name in ds:
                ds[name].load()
        files += save_run_figures(ds, folder)
    return files, table, header, footer
