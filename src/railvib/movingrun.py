"""``railvib run`` of a ``mode = "moving"`` case: lines, cyclostationary PSDs, the comparison.

The vehicle moves over the sleepers at ``speed_kmh`` (:mod:`railvib.moving`). A run
writes, separately, the **deterministic sleeper-passing lines** of a smooth rail
(:func:`~railvib.moving.parametric_response`: contact forces, displacements and the
equivalent roughness at ``n v / d``) and the **random response** to the irregularity
(:func:`~railvib.moving.moving_frf`: the time-averaged PSDs and their variation over the
sleeper period), with the stationary (fixed-position) PSDs of the same case and their
difference per response and third-octave band: where it is small, the stationary model
is enough (docs/moving-vehicle.md).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from railvib.case import Case, build_grid, build_spectrum, build_system, case_header, load_case
from railvib.coupling import CoupledSystem
from railvib.errors import CaseError, PlausibilityWarning
from railvib.grid import FrequencyGrid
from railvib.io import railvib_version, staged_folder, write_text
from railvib.labels import displacement_unit
from railvib.moving import MovingSettings, check_moving, moving_frf, parametric_response
from railvib.outputs.octave import band_mean_square, third_octave_bands
from railvib.results.dataset import check_finite, save_netcdf
from railvib.spectra.base import SpatialSpectrum

__all__ = [
    "MANY_LOAD_FREQUENCIES",
    "MOVING_FILES",
    "MovingOutput",
    "moving_dataset",
    "moving_speed_sweep",
    "moving_summary_lines",
    "run_moving",
    "run_moving_to_folder",
]

#: every file a moving run may write to its folder (a later run replaces them)
MOVING_FILES = (
    "results.nc",
    "lines.csv",
    "bands.csv",
    "summary.md",
    "moving_psd.png",
    "moving_lines.png",
)

#: more moving-load frequencies ((2N+1) x grid points) than this and a run warns of its
#: cost: their table (interpolated in frequency, docs/moving-vehicle.md, Cost) holds
#: ``(N + 2) x`` the wheel gaps' receptances at each, some 0.2 GB per 10^5 for a 4-wheel
#: car, and the harmonic balance takes some 4 s of CPU per 10^5
MANY_LOAD_FREQUENCIES = 200_000

#: a band whose moving and stationary mean squares differ by less than this (dB) is one
#: where the stationary model is enough (the spread of a PSD estimate from a few minutes
#: of measurement is about as large)
ENOUGH_DB = 1.0


def _settings(case: Case) -> tuple[MovingSettings, int]:
    section = case.moving
    if section is None:
        return MovingSettings(), 8
    return MovingSettings(section.harmonic_order, section.tolerance), section.phases


def _prepared(
    case: Case,
) -> tuple[CoupledSystem, FrequencyGrid, SpatialSpectrum, MovingSettings, int]:
    """The case's physics, every moving-mode check done before anything is computed."""
    if case.mode != "moving":
        raise CaseError("mode", case.mode, 'must be "moving" for a moving-vehicle run')
    system = build_system(case)
    grid = build_grid(case)
    settings, phases = _settings(case)
    check_moving(system, float(grid.f.max()), settings, float(grid.f.min()))
    loads = grid.f.size * (2 * settings.harmonic_order + 1)
    if loads > MANY_LOAD_FREQUENCIES:
        warnings.warn(
            PlausibilityWarning(
                "frequency",
                f"{grid.f.size} frequencies",
                f"x {2 * settings.harmonic_order + 1} harmonics = {loads} moving-load "
                "frequencies, some 0.2 GB of memory and 4 s of CPU per 10^5 for 4 wheels "
                "(docs/moving-vehicle.md, Cost): a log grid of a few hundred points is usually "
                "enough",
            ),
            stacklevel=2,
        )
    return system, grid, build_spectrum(case), settings, phases


def moving_dataset(
    system: CoupledSystem,
    grid: FrequencyGrid,
    spectrum: SpatialSpectrum,
    settings: MovingSettings,
    *,
    phases: int = 8,
    attrs: dict[str, str] | None = None,
) -> xr.Dataset:
    """Lines, time-averaged and phase-resolved PSDs, the stationary PSDs and the band table.

    Parameters
    ----------
    system : CoupledSystem
        Vehicle, track, contact (N/m), leading wheel position (m) and speed (m/s).
    grid : FrequencyGrid
        Frequencies, Hz.
    spectrum : SpatialSpectrum
        Irregularity spectrum.
    settings : MovingSettings
        Harmonic order and tolerance.
    phases : int
        Instants per sleeper period of the phase-resolved PSD (a count).
    attrs : dict, optional
        Extra global attributes.

    Returns
    -------
    xarray.Dataset
        ``psd`` / ``contact_force_psd`` (time-averaged, moving), ``*_stationary`` (the
        vehicle standing at its leading wheel position), ``*_over_period`` (phase,
        frequency, ...), ``*_line_amplitude`` (line, ...) with ``line_frequency``, and
        ``*_band_difference_db`` (band, ...).
    """
    f = grid.f
    lines = parametric_response(system, settings, check=False)
    mov = moving_frf(system, f, settings, check=False)
    disp, force = mov.averaged_psd(spectrum)
    phase, disp_t, force_t = mov.phase_psd(spectrum, phases)
    stat = system.frf(f)
    s_r = spectrum.temporal(f, system.speed)
    disp_s = np.abs(stat.displacement) ** 2 * s_r[:, None]
    force_s = np.abs(stat.contact_force) ** 2 * s_r[:, None]
    labels = list(mov.labels)
    wheels = np.arange(1, force.shape[1] + 1)
    disp_units = "m^2/Hz (rad^2/Hz for pitch)"
    fd, fw = ("frequency", "response"), ("frequency", "wheel")
    line_f = lines.line_frequencies_hz

    def var(data: NDArray, dims: tuple[str, ...], units: str, name: str) -> xr.DataArray:
        return xr.DataArray(data, dims=dims, attrs={"units": units, "long_name": name})

    ds = xr.Dataset(
        {
            "psd": var(disp, fd, disp_units, "time-averaged displacement PSD, moving vehicle"),
            "contact_force_psd": var(
                force, fw, "N^2/Hz", "time-averaged contact-force PSD, moving vehicle"
            ),
            "psd_stationary": var(
                disp_s, fd, disp_units, "displacement PSD, vehicle at a fixed position"
            ),
            "contact_force_psd_stationary": var(
                force_s, fw, "N^2/Hz", "contact-force PSD, vehicle at a fixed position"
            ),
            "psd_over_period": var(
                disp_t,
                ("phase", *fd),
                disp_units,
                "displacement PSD at an instant of the sleeper period (by input frequency)",
            ),
            "contact_force_psd_over_period": var(
                force_t,
                ("phase", *fw),
                "N^2/Hz",
                "contact-force PSD at an instant of the sleeper period (by input frequency)",
            ),
            "irregularity_psd": var(s_r, ("frequency",), "m^2/Hz", "irregularity PSD"),
            "line_frequency": var(line_f, ("line",), "Hz", "sleeper-passing line n v/d"),
            "line_amplitude": var(
                lines.amplitude("displacement"),
                ("line", "response"),
                "m (rad for pitch)",
                "peak amplitude of the sleeper-passing line, smooth rail",
            ),
            "contact_force_line_amplitude": var(
                lines.amplitude("contact_force"),
                ("line", "wheel"),
                "N",
                "peak contact-force amplitude of the sleeper-passing line, smooth rail",
            ),
            "equivalent_roughness_amplitude": var(
                lines.amplitude("equivalent_roughness"),
                ("line", "wheel"),
                "m",
                "peak irregularity giving the lines' contact forces in the stationary model",
            ),
            "static_contact_load": var(
                lines.contact_force[lines.orders == 0][0].real,
                ("wheel",),
                "N",
                "mean contact force",
            ),
        },
        coords={
            "frequency": ("frequency", f, {"units": "Hz"}),
            "response": ("response", labels),
            "wheel": ("wheel", wheels),
            "phase": ("phase", phase, {"units": "1", "long_name": "t v / d, fraction of a period"}),
            "line": ("line", lines.lines),
        },
        attrs={
            "railvib_version": railvib_version(),
            "mode": "moving",
            "speed_m_per_s": system.speed,
            "sleeper_passing_hz": mov.passing_hz,
            "harmonic_order": settings.harmonic_order,
            "tolerance": settings.tolerance,
            "leading_wheel_position_m": system.leading_wheel_position,
            "coupled_harmonic_tail": mov.tail,
            "time_dependence": "exp(+i omega t)",
            **(attrs or {}),
        },
    )
    return ds.assign(_band_variables(ds))


def _band_variables(ds: xr.Dataset) -> dict[str, xr.DataArray]:
    """Mean squares per third-octave band, moving and stationary, and their ratio in dB."""
    f = ds.frequency.values
    bands = third_octave_bands(float(f[0]), float(f[-1]))
    out: dict[str, xr.DataArray] = {}
    if bands.index.size == 0:
        return out
    coords = {"band": ("band", bands.nominal, {"units": "Hz", "long_name": "band centre"})}
    for stem, dim, units in (("", "response", "dB"), ("contact_force_", "wheel", "dB")):
        moving = band_mean_square(f, ds[f"{stem}psd"].values, bands.lower, bands.upper)
        still = band_mean_square(f, ds[f"{stem}psd_stationary"].values, bands.lower, bands.upper)
        with np.errstate(divide="ignore", invalid="ignore"):
            db = 10.0 * np.log10(moving / still)
        out[f"{stem}band_difference_db"] = xr.DataArray(
            db,
            dims=("band", dim),
            coords=coords,
            attrs={
                "units": units,
                "long_name": "moving minus stationary mean square in the band",
            },
        )
    return out


def moving_speed_sweep(
    system: CoupledSystem,
    grid: FrequencyGrid,
    spectrum: SpatialSpectrum,
    speeds: ArrayLike,
    settings: MovingSettings,
    *,
    random: bool = True,
) -> xr.Dataset:
    """Where the moving vehicle departs from the stationary one: lines and bands over speed.

    Parameters
    ----------
    system : CoupledSystem
        Vehicle, track, contact (N/m) and leading wheel position (m); its speed is replaced.
    grid : FrequencyGrid
        Frequencies, Hz (the random part).
    spectrum : SpatialSpectrum
        Irregularity spectrum (the random part).
    speeds : array_like
        Speeds, m/s, ``(n_speed,)``; each checked by :func:`~railvib.moving.check_moving`.
    settings : MovingSettings
        Harmonic order and tolerance.
    random : bool
        Also the random PSDs' band differences (costly: :func:`moving_dataset` per speed);
        False: the sleeper-passing lines only.

    Returns
    -------
    xarray.Dataset
        ``contact_force_line_amplitude`` (speed, line, wheel), ``line_frequency`` (speed,
        line); with `random`, ``contact_force_band_difference_db`` and ``band_difference_db``
        (speed, band, ...).
    """
    v = np.atleast_1d(np.asarray(speeds, dtype=float))
    parts = []
    for speed in v:
        at = replace(system, speed=float(speed))
        check_moving(at, float(grid.f.max()) if random else 0.0, settings, float(grid.f.min()))
        if random:
            ds = moving_dataset(at, grid, spectrum, settings, phases=1)
            keep = [k for k in ds.data_vars if "line" in str(k) or "band_difference" in str(k)]
            parts.append(ds[keep])
        else:
            lines = parametric_response(at, settings, check=False)
            parts.append(
                xr.Dataset(
                    {
                        "line_frequency": ("line", lines.line_frequencies_hz),
                        "contact_force_line_amplitude": (
                            ("line", "wheel"),
                            lines.amplitude("contact_force"),
                        ),
                    },
                    coords={"line": lines.lines, "wheel": np.arange(1, lines.rail.shape[1] + 1)},
                )
            )
    out = xr.concat(parts, dim="speed").assign_coords(speed=("speed", v, {"units": "m/s"}))
    out["contact_force_line_amplitude"].attrs.update(units="N", long_name="peak line amplitude")
    out["line_frequency"].attrs.update(units="Hz", long_name="sleeper-passing line n v/d")
    return out


def run_moving(case: Case | str | Path) -> xr.Dataset:
    """Run a ``mode = "moving"`` case (a validated case or a TOML path).

    Parameters
    ----------
    case : Case, str or pathlib.Path
        The case.

    Returns
    -------
    xarray.Dataset
        See :func:`moving_dataset`.

    Raises
    ------
    CaseError
        Bad input, before anything is computed (:func:`railvib.moving.check_moving`).
    """
    if not isinstance(case, Case):
        case = load_case(case)
    return _computed(case, _prepared(case))


def _computed(
    case: Case,
    prepared: tuple[CoupledSystem, FrequencyGrid, SpatialSpectrum, MovingSettings, int],
) -> xr.Dataset:
    """The dataset of a checked case (:func:`_prepared`)."""
    system, grid, spectrum, settings, phases = prepared
    attrs = {"title": case.title, "case_toml": case.to_toml(), "rail_model": case.rail_model}
    ds = moving_dataset(system, grid, spectrum, settings, phases=phases, attrs=attrs)
    check_finite(ds.drop_vars([v for v in ds.data_vars if "band_difference" in str(v)]))
    return ds


def _rms(f: NDArray[np.float64], psd: NDArray[np.float64]) -> NDArray[np.float64]:
    y = np.moveaxis(psd, -2, 0)  # frequency first
    steps = np.diff(f).reshape((-1,) + (1,) * (y.ndim - 1))
    return np.asarray(np.sqrt(np.sum(steps * (y[1:] + y[:-1]) / 2.0, axis=0)), dtype=np.float64)


def moving_summary_lines(ds: xr.Dataset) -> list[str]:
    """The summary of a moving run: the lines, then moving against stationary per response.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`run_moving`.

    Returns
    -------
    list of str
        Markdown lines.
    """
    f = ds.frequency.values
    fs = float(ds.attrs["sleeper_passing_hz"])
    out = [
        f"moving vehicle: sleeper-passing frequency v/d = {fs:.4g} Hz, harmonics |n| <= "
        f"{int(ds.attrs['harmonic_order'])} (tolerance {float(ds.attrs['tolerance']):g}; the "
        f"coupled contact-force harmonics |n| = N reach "
        f"{float(ds.attrs['coupled_harmonic_tail']):.2g} of the largest)",
        "",
        "Sleeper-passing lines on a smooth rail (peak amplitudes):",
        "",
        "| line | f (Hz) | contact force, wheel 1..n (N) | % of the static load "
        "| equivalent roughness (um) |",
        "|---|---|---|---|---|",
    ]
    load = ds.static_contact_load.values
    for i, n in enumerate(ds.line.values):
        p = ds.contact_force_line_amplitude.values[i]
        r = ds.equivalent_roughness_amplitude.values[i]
        out.append(
            f"| {int(n)} | {float(ds.line_frequency[i]):.4g} | "
            + ", ".join(f"{x:.4g}" for x in p)
            + " | "
            + ", ".join(f"{100 * x / w:.3g}" for x, w in zip(p, load, strict=True))
            + " | "
            + ", ".join(f"{1e6 * x:.3g}" for x in r)
            + " |"
        )
    out += [
        "",
        "Random response (irregularity): RMS over the grid, moving (time-averaged) against "
        f"stationary (the vehicle at {float(ds.attrs['leading_wheel_position_m']):g} m after a "
        f"sleeper), and the third-octave band where they differ most; |difference| < "
        f"{ENOUGH_DB:g} dB in every band: the stationary model is enough.",
        "",
        "| response | RMS moving | RMS stationary | difference (dB) | largest band difference "
        "(dB, at Hz) | RMS over the sleeper period (min-max) | stationary enough |",
        "|---|---|---|---|---|---|---|",
    ]
    for stem, dim in (("contact_force_", "wheel"), ("", "response")):
        moving = _rms(f, ds[f"{stem}psd"].values)
        still = _rms(f, ds[f"{stem}psd_stationary"].values)
        over = _rms(f, ds[f"{stem}psd_over_period"].values)  # (phase, ...)
        bands = ds.get(f"{stem}band_difference_db")
        for j, label in enumerate(ds[dim].values):
            unit = "N" if dim == "wheel" else displacement_unit(str(label))
            name = f"contact force wheel {label}" if dim == "wheel" else str(label)
            diff = 20.0 * np.log10(moving[j] / still[j]) if still[j] > 0 else float("nan")
            worst, enough = "-", "-"
            if bands is not None:
                col = bands.values[:, j]
                finite = np.isfinite(col)
                if finite.any():
                    k = int(np.nanargmax(np.where(finite, np.abs(col), np.nan)))
                    worst = f"{col[k]:+.2f} at {float(bands.band[k]):g}"
                    enough = "yes" if np.all(np.abs(col[finite]) < ENOUGH_DB) else "no"
            out.append(
                f"| {name} | {moving[j]:.4g} {unit} | {still[j]:.4g} {unit} | {diff:+.2f} | "
                f"{worst} | {over[:, j].min():.4g}-{over[:, j].max():.4g} {unit} | {enough} |"
            )
    return out


@dataclass(frozen=True, eq=False)
class MovingOutput:
    """What :func:`run_moving_to_folder` computed and wrote.

    Parameters
    ----------
    dataset : xarray.Dataset
        The result.
    files : tuple of pathlib.Path
        Every file written.
    lines : tuple of str
        The summary: the case header, then :func:`moving_summary_lines`.
    """

    dataset: xr.Dataset
    files: tuple[Path, ...]
    lines: tuple[str, ...]

    def text(self) -> str:
        """The summary as printed by ``railvib run``."""
        return "\n".join(self.lines)


def run_moving_to_folder(
    case: Case | str | Path, outdir: str | Path, *, plots: bool = True
) -> MovingOutput:
    """Run a moving case; write ``results.nc``, ``lines.csv``, ``bands.csv``, ``summary.md``, plots.

    Every check runs before the folder is touched; the files are written into a staging
    folder put in place at the end (:func:`railvib.io.staged_folder`).

    Parameters
    ----------
    case : Case, str or pathlib.Path
        The case (``mode = "moving"``).
    outdir : str or pathlib.Path
        Output folder (created if needed).
    plots : bool
        Draw ``moving_psd.png`` and ``moving_lines.png``.

    Returns
    -------
    MovingOutput
    """
    if not isinstance(case, Case):
        case = load_case(case)
    prepared = _prepared(case)  # every check before the folder is touched
    with staged_folder(outdir, MOVING_FILES) as stage:
        ds = _computed(case, prepared)
        lines = [*case_header(case), *moving_summary_lines(ds)]
        files = [
            save_netcdf(ds, stage.path / "results.nc"),
            write_text(stage.path / "lines.csv", _lines_csv(ds)),
            write_text(stage.path / "bands.csv", _bands_csv(ds)),
            write_text(
                stage.path / "summary.md", "\n".join([f"# {case.title}", "", *lines]) + "\n"
            ),
        ]
        if plots:
            from railvib.plot.moving import save_moving_plots  # matplotlib

            files += save_moving_plots(ds, stage.path)
    return MovingOutput(ds, tuple(stage.finals(files)), tuple(lines))


def _lines_csv(ds: xr.Dataset) -> str:
    """One row per line: frequency, contact force and equivalent roughness per wheel."""
    wheels = [int(w) for w in ds.wheel.values]
    cols = ["line", "frequency (Hz)"]
    cols += [f"contact force wheel{w} (N)" for w in wheels]
    cols += [f"equivalent roughness wheel{w} (m)" for w in wheels]
    cols += [f"{r} ({displacement_unit(str(r))})" for r in ds.response.values]
    rows = [",".join(cols)]
    for i, n in enumerate(ds.line.values):
        values = [float(ds.line_frequency[i])]
        values += list(ds.contact_force_line_amplitude.values[i])
        values += list(ds.equivalent_roughness_amplitude.values[i])
        values += list(ds.line_amplitude.values[i])
        rows.append(f"{int(n)}," + ",".join(f"{x:.6g}" for x in values))
    return "\n".join(rows) + "\n"


def _bands_csv(ds: xr.Dataset) -> str:
    """Moving minus stationary mean square per third-octave band (dB), one column each."""
    if "band_difference_db" not in ds:
        return "band centre (Hz)\n"
    cols = ["band centre (Hz)"]
    cols += [f"contact force wheel{int(w)} (dB)" for w in ds.wheel.values]
    cols += [f"{r} (dB)" for r in ds.response.values]
    table = np.column_stack(
        [
            ds.band.values,
            ds.contact_force_band_difference_db.values,
            ds.band_difference_db.values,
        ]
    )
    rows = [",".join(cols)] + [",".join(f"{x:.6g}" for x in row) for row in table]
    return "\n".join(rows) + "\n"
