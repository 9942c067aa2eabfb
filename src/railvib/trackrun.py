"""The track alone, case to folder (``railvib track``): FRFs, support forces, waves, TDR.

:func:`track_dataset` gathers the outputs of :mod:`railvib.track.outputs` for one
track on one grid into an :class:`xarray.Dataset` (every variable with ``units`` and
``long_name``); :func:`track_to_folder` writes it, the decay-rate table and the
figures of :mod:`railvib.plot.track` into a staging folder put in place at the end.
The track is the case's ``[track]`` table for one rail (a ``rail_pair`` case is not
doubled: the receptance of one rail is what is measured).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from railvib.case import Case, build_grid, build_track, load_case
from railvib.errors import CaseError
from railvib.grid import FrequencyGrid
from railvib.io import railvib_version, staged_folder, write_text
from railvib.results.dataset import save_netcdf
from railvib.track.base import SupportResponse, TrackModel
from railvib.track.outputs import (
    FRF_QUANTITIES,
    TrackDecay,
    band_edges,
    frf,
    third_octave_centres,
    track_decay_rate,
    wave_decay,
)
from railvib.track.periodic import PeriodicTrack

__all__ = [
    "TRACK_FILES",
    "TDR_BANDS_HZ",
    "TrackJob",
    "TrackOutput",
    "decay_rate_csv",
    "track_dataset",
    "track_to_folder",
]

#: the nominal one-third octave bands of the decay rate by default (EN 15461 6.6)
TDR_BANDS_HZ = (100.0, 5000.0)

#: observation points of the receptance, in sleeper spacings from the load
OBSERVATION_BAYS = (0.0, 0.5, 1.0, 2.0, 4.0, 8.0)

#: every file ``railvib track`` may write to its folder (a later run replaces them all)
TRACK_FILES = ("track.nc", "decay_rate.csv", "receptance.png", "decay_rate.png", "dispersion.png")


@dataclass(frozen=True)
class TrackJob:
    """What ``railvib track`` computes (its options).

    Parameters
    ----------
    f_min, f_max : float, optional
        Band of a logarithmic grid, Hz (``--fmin``/``--fmax``); None: the case's.
    n : int, optional
        Frequencies of that grid (``-n``); None: the case's grid when neither band end is
        given, else 400.
    load : {"mid-span", "support"}
        Where the unit force acts: mid-span of a bay or above a rail seat.
    tdr_bands : (float, float), optional
        Nominal first and last band of the decay rate, Hz (``--tdr-bands``); None: those of
        :data:`TDR_BANDS_HZ` within the grid.
    n_supports : int
        Rail seats on each side of the nearest one with forces in the dataset.
    plots : bool
        Draw the figures.
    """

    f_min: float | None = None
    f_max: float | None = None
    n: int | None = None
    load: Literal["mid-span", "support"] = "mid-span"
    tdr_bands: tuple[float, float] | None = None
    n_supports: int = 10
    plots: bool = True

    def __post_init__(self) -> None:
        for name, value in (("--fmin", self.f_min), ("--fmax", self.f_max)):
            if value is not None and not (np.isfinite(value) and value > 0):
                raise CaseError(name, value, "a finite frequency > 0 (Hz)")
        if self.n is not None and self.n < 2:
            raise CaseError("-n", self.n, "an integer >= 2 (frequencies)")
        if self.load not in ("mid-span", "support"):
            raise CaseError("--load", self.load, "'mid-span' or 'support'")
        if self.n_supports < 0:
            raise CaseError("--supports", self.n_supports, "an integer >= 0")
        if self.tdr_bands is not None:
            low, high = self.tdr_bands
            if not (np.isfinite(low) and np.isfinite(high) and 0 < low <= high):
                raise CaseError("--tdr-bands", f"{low:g},{high:g}", "0 < low <= high (Hz)")

    def grid(self, case: Case) -> FrequencyGrid:
        """The frequency grid: the case's, or the logarithmic one of the options.

        Parameters
        ----------
        case : Case
            A validated case.

        Returns
        -------
        FrequencyGrid
        """
        if self.f_min is None and self.f_max is None and self.n is None:
            return build_grid(case)
        f_min = case.frequency.f_min if self.f_min is None else self.f_min
        f_max = case.frequency.f_max if self.f_max is None else self.f_max
        if not f_max > f_min:
            raise CaseError("--fmax", f_max, f"must be > the lowest frequency {f_min:g} (Hz)")
        return FrequencyGrid.logarithmic(f_min, f_max, 400 if self.n is None else self.n)

    def bands(self, f: NDArray[np.float64]) -> tuple[float, float]:
        """The nominal first and last band of the decay rate, checked against the grid `f`.

        Parameters
        ----------
        f : numpy.ndarray
            The grid, Hz.

        Returns
        -------
        (float, float)
            Nominal frequencies, Hz.

        Raises
        ------
        CaseError
            ``--tdr-bands`` outside the grid, or no band of :data:`TDR_BANDS_HZ` in it.
        """
        f_lo, f_hi = float(f[0]), float(f[-1])
        if self.tdr_bands is not None:
            low, high = self.tdr_bands
            if low < f_lo / 1.01 or high > f_hi * 1.01:
                raise CaseError(
                    "--tdr-bands",
                    f"{low:g},{high:g}",
                    f"bands within the frequency grid, {f_lo:g} - {f_hi:g} Hz (Hz)",
                )
            return float(low), float(high)
        centres, _ = third_octave_centres(*TDR_BANDS_HZ)
        inside = centres[(centres >= f_lo / 1.01) & (centres <= f_hi * 1.01)]
        if inside.size == 0:
            raise CaseError(
                "frequency",
                f"{f_lo:g} - {f_hi:g} Hz",
                "a grid holding at least one one-third octave band of 100 Hz - 5 kHz for the "
                "track decay rate (EN 15461 6.6); widen it or give --tdr-bands (Hz)",
            )
        return float(inside[0]), float(inside[-1])


def _track(case: Case) -> PeriodicTrack:
    """The case's track for one rail (a ``rail_pair`` case is not doubled)."""
    return build_track(case.model_copy(update={"rail_model": "single_rail"}))


def _complex(values: NDArray[np.complex128]) -> NDArray[np.complex128]:
    return np.asarray(values, dtype=np.complex128)


def track_dataset(
    track: TrackModel,
    f: NDArray[np.float64],
    x_load: float,
    decay: TrackDecay,
    n_supports: int = 10,
    attrs: dict[str, str] | None = None,
) -> xr.Dataset:
    """The track-alone outputs on the grid `f` for a unit force at `x_load`.

    Parameters
    ----------
    track : TrackModel
        The track.
    f : numpy.ndarray
        Frequencies, Hz.
    x_load : float
        Position of the unit force, m.
    decay : TrackDecay
        The decay rate in bands (:func:`railvib.track.outputs.track_decay_rate`).
    n_supports : int
        Rail seats on each side of the nearest one (support forces and displacements).
    attrs : dict, optional
        Extra global attributes.

    Returns
    -------
    xarray.Dataset
        Dims ``frequency`` (Hz), ``position`` (m, observation points), ``support`` (m,
        rail seats), ``wave``, ``band`` (exact centre, Hz). Receptance (complex,
        magnitude, phase), mobility and accelerance magnitude; support displacements and
        layer forces per unit force (magnitudes); propagation constants, decay per wave,
        pass bands; EN 15461 decay rate and the least-attenuated wave's decay per band.
    """
    d = track.sleeper_spacing
    x_obs = x_load + np.asarray(OBSERVATION_BAYS) * d
    alpha = frf(track, f, [x_load], x_obs)[:, :, 0]
    omega = 2.0 * np.pi * f
    fp = ("frequency", "position")
    data: dict[str, tuple[tuple[str, ...], object, dict[str, str]]] = {
        "receptance": (fp, alpha, _attrs("m/N", "rail receptance (displacement per unit force)")),
        "receptance_magnitude": (fp, np.abs(alpha), _attrs("m/N", "|receptance|")),
        "receptance_phase": (fp, np.angle(alpha), _attrs("rad", "phase of the receptance")),
    }
    for name, (power, unit) in FRF_QUANTITIES.items():
        if power:
            data[f"{name}_magnitude"] = (
                fp,
                np.abs(alpha) * omega[:, None] ** power,
                _attrs(unit, f"|{name}|"),
            )
    try:
        sup: SupportResponse | None = track.support_response(f, x_load, n_supports)
    except NotImplementedError:  # a slab track: its supports are not modelled one by one
        sup = None
    if sup is not None:
        fs = ("frequency", "support")
        for mass, values in sup.displacement.items():
            if mass != "rail":
                data[f"{mass}_displacement"] = (
                    fs,
                    np.abs(values),
                    _attrs("m/N", f"|{mass.replace('_', ' ')} displacement| per unit force"),
                )
        data["rail_seat_displacement"] = (
            fs,
            np.abs(sup.displacement["rail"]),
            _attrs(
                "m/N", "|rail displacement| at each support (a slab bay: its centre) per unit force"
            ),
        )
        for layer, values in sup.force.items():
            data[f"{layer}_force"] = (
                fs,
                np.abs(values),
                _attrs("N/N", f"|force in the {layer}| per unit force"),
            )
        data["foundation_force"] = (
            fs,
            np.abs(sup.foundation_force),
            _attrs(
                "N/N", f"|force transmitted to the ground| (the {sup.foundation}) per unit force"
            ),
        )
    mu = track.propagation_constants(f)
    decay_db, propagates = wave_decay(mu, track.period)
    fw = ("frequency", "wave")
    data["propagation_constant"] = (
        fw,
        _complex(mu),
        _attrs("1", "propagation constant mu = exp(-gamma period) of each right-going wave"),
    )
    data["wave_decay"] = (fw, decay_db, _attrs("dB/m", "decay of each wave, -20 lg|mu| / period"))
    data["wavenumber"] = (
        fw,
        np.abs(np.angle(mu)) / track.period,
        _attrs("rad/m", "phase constant of each wave, |arg mu| / period"),
    )
    data["propagates"] = (fw, propagates, _attrs("1", "wave in a pass band"))
    lower, upper = band_edges(decay.centres)
    data.update(
        decay_rate=(
            ("band",),
            decay.rate,
            _attrs("dB/m", f"track decay rate, EN 15461 Formula 1 ({decay.method})"),
        ),
        wave_decay_band=(
            ("band",),
            decay.wave,
            _attrs("dB/m", "decay of the least-attenuated wave, band mean"),
        ),
        decay_rate_suitable=(
            ("band",),
            decay.suitable,
            _attrs("1", "EN 15461 clause 7: rate >= 2 DR_min (else an upper bound)"),
        ),
        band_lower=(("band",), lower, _attrs("Hz", "lower band edge")),
        band_upper=(("band",), upper, _attrs("Hz", "upper band edge")),
    )
    coords = {
        "frequency": ("frequency", f, _attrs("Hz", "frequency")),
        "position": ("position", x_obs, _attrs("m", "observation point along the rail")),
        "wave": (
            "wave",
            np.arange(1, mu.shape[1] + 1),
            _attrs("1", "wave, least-attenuated first"),
        ),
        "band": ("band", decay.centres, _attrs("Hz", "one-third octave band centre (exact)")),
        "band_nominal": ("band", decay.nominal, {"long_name": "nominal band frequency, Hz"}),
    }
    if sup is not None:
        coords["support"] = (
            "support",
            sup.x,
            _attrs("m", "rail seat (bearing, slab bay centre) along the rail"),
        )
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(
        {
            "title": "railvib track: the track alone",
            "railvib_version": railvib_version(),
            "load_position_m": float(x_load),
            "period_m": float(track.period),
            "sleeper_spacing_m": float(d),
            "decay_rate_floor_db_per_m": 2.0 * decay.minimum_measurable,
            "decay_rate_method": (
                "EN 15461:2008+A1:2010 clause 7 Formula 1 (Annex A), excitation grid of 6.7 / "
                f"Figure 2 from x = {decay.x_response:g} m; "
                + (
                    "band-averaged |accelerance|^2"
                    if decay.method == "band"
                    else "at the band centre frequencies"
                )
            ),
            **(attrs or {}),
        }
    )
    return ds


def _attrs(unit: str, long_name: str) -> dict[str, str]:
    return {"units": unit, "long_name": long_name}


def decay_rate_csv(ds: xr.Dataset, header: list[str] | None = None) -> str:
    """The decay-rate table of a track dataset as CSV text (``"# "`` header lines first).

    Parameters
    ----------
    ds : xarray.Dataset
        A dataset of :func:`track_dataset`.
    header : list of str, optional
        Lines written first, each after ``"# "``.

    Returns
    -------
    str
        Columns: nominal and exact band centre (Hz), decay rate and least-attenuated wave's
        decay (dB/m), suitable (EN 15461 clause 7).
    """
    lines = [f"# {line}" for line in (header or [])]
    lines.append(f"# {ds.attrs['decay_rate_method']}")
    lines.append(f"# suitable: rate >= 2 DR_min = {ds.attrs['decay_rate_floor_db_per_m']:.4g} dB/m")
    lines.append(
        "band_nominal_hz,band_centre_hz,decay_rate_db_per_m,least_attenuated_wave_db_per_m,suitable"
    )
    for nominal, centre, rate, wave, ok in zip(
        ds["band_nominal"].values,
        ds["band"].values,
        ds["decay_rate"].values,
        ds["wave_decay_band"].values,
        ds["decay_rate_suitable"].values,
        strict=True,
    ):
        lines.append(f"{nominal},{centre:.6g},{rate:.6g},{wave:.6g},{str(bool(ok)).lower()}")
    return "\n".join(lines) + "\n"


@dataclass(frozen=True, eq=False)
class TrackOutput:
    """What :func:`track_to_folder` computed and wrote.

    Parameters
    ----------
    dataset : xarray.Dataset
        The outputs (:func:`track_dataset`).
    files : tuple of pathlib.Path
        Every file written.
    """

    dataset: xr.Dataset
    files: tuple[Path, ...]

    def text(self) -> str:
        """The decay rates as ``railvib track`` prints them, one band a line."""
        ds = self.dataset
        lines = ["band (Hz)  TDR (dB/m)  wave (dB/m)"]
        for nominal, rate, wave, ok in zip(
            ds["band_nominal"].values,
            ds["decay_rate"].values,
            ds["wave_decay_band"].values,
            ds["decay_rate_suitable"].values,
            strict=True,
        ):
            mark = "" if ok else "  (upper bound: below 2 DR_min, EN 15461 clause 7)"
            lines.append(f"{nominal:>9}  {rate:10.3g}  {wave:11.3g}{mark}")
        return "\n".join(lines)


def track_to_folder(
    case: Case | str | Path, outdir: str | Path, job: TrackJob | None = None
) -> TrackOutput:
    """Compute the track-alone outputs of a case and write them to `outdir` (``railvib track``).

    Writes ``track.nc`` (:func:`track_dataset`), ``decay_rate.csv``
    (:func:`decay_rate_csv`) and, with ``job.plots``, ``receptance.png``,
    ``decay_rate.png`` and ``dispersion.png`` (:func:`railvib.plot.track.save_track_plots`)
    into a staging folder put in place at the end (:func:`railvib.io.staged_folder`):
    `outdir` holds this run's complete set (:data:`TRACK_FILES`; other files are kept),
    and a run that fails or is stopped leaves it as it was. Every input is checked
    before the folder is touched.

    Parameters
    ----------
    case : Case, str or pathlib.Path
        A validated case or a TOML case file.
    outdir : str or pathlib.Path
        Output folder (created if needed).
    job : TrackJob, optional
        The options; default :class:`TrackJob`.

    Returns
    -------
    TrackOutput

    Raises
    ------
    railvib.errors.CaseError
        Bad input (named), or `outdir` is not a folder, before anything is written.
    railvib.errors.OutputError
        `outdir` or one of its files cannot be written.
    """
    job = TrackJob() if job is None else job
    if not isinstance(case, Case):
        case = load_case(case)
    track = _track(case)
    f = job.grid(case).f
    track.check_frequencies(f)
    low, high = job.bands(f)
    top = float(band_edges(third_octave_centres(low, high)[0])[1][-1])
    if top > track.max_frequency_hz:
        raise CaseError(
            "--tdr-bands",
            f"{low:g},{high:g}",
            f"bands below {track.max_frequency_hz:.4g} Hz, the highest frequency this rail and "
            "sleeper spacing are solved at (its last band reaches "
            f"{top:.4g} Hz) (Hz)",
        )
    d = track.sleeper_spacing
    x_load = 0.5 * d if job.load == "mid-span" else 0.0
    with staged_folder(outdir, TRACK_FILES) as stage:
        decay = track_decay_rate(track, low, high)
        ds = track_dataset(
            track,
            f,
            x_load,
            decay,
            job.n_supports,
            {"case_toml": case.to_toml(), "case_title": case.title},
        )
        header = [f"railvib track: {case.title}", f"unit force at x = {x_load:g} m ({job.load})"]
        files = [
            save_netcdf(ds, stage.path / "track.nc"),
            write_text(stage.path / "decay_rate.csv", decay_rate_csv(ds, header)),
        ]
        if job.plots:
            from railvib.plot.track import save_track_plots  # matplotlib: only when plotting

            files += save_track_plots(ds, stage.path)
    return TrackOutput(ds, tuple(stage.finals(files)))
