"""Ride comfort from car-body acceleration PSDs: ISO 2631-1 a_w, EN 12299 N_MV, Sperling Wz.

The vertical acceleration of the floor at ``s`` (m, from the body's centre, positive
forward) is ``z_c + s phi_c`` (``railvib.vehicle.Vehicle``: a pitch ``phi`` moves a
point at ``x`` by ``x phi``), so its one-sided PSD is
``(2 pi f)^4 |H_z + s H_phi|^2 S_r`` from the complex responses per metre of
irregularity ``H`` and the irregularity PSD ``S_r``.

* ``a_w = sqrt(integral of W(f)^2 S_a(f) df)`` over the comfort band (ISO 2631-1:1997,
  clause 6, basic evaluation method, written for a PSD: the RMS of the weighted signal), with W the
  weighting of :mod:`railvib.outputs.weighting` (Wb by default, the weighting of
  ISO 2631-4 and EN 12299 for vertical vibration in rail vehicles).
* Comfort category: ISO 2631-1:1997, Annex C, C.2.3 (its ranges overlap; every
  range holding a_w is named).
* Mean comfort index ``N_MV ~ 6 a_zWb`` (EN 12299:2009, mean comfort, standard method,
  ``N_MV = 6 sqrt(a_XP95^2 + a_YP95^2 + a_ZP95^2)``). Approximated: the standard
  takes the 95th percentile of 5-s RMS values of measured time histories; here the
  response is stationary and Gaussian, and the percentile is replaced by the RMS
  over the band (the 5-s values scatter about it, so N_MV is underestimated by the
  spread of the 5-s RMS values: a few per cent for a band of several Hz); the
  lateral and longitudinal terms are absent from a pitch-plane model, so the index
  is the vertical part only. Scale: that of EN 12299:2009 for N_MV.
* Sperling ride index, filter form: ``Wz = (100 sqrt(2) a_B)^0.3`` with
  ``a_B = sqrt(integral of B(f)^2 S_a(f) df)`` in m/s^2 (the classical
  ``Wz = (a^3 B^3)^0.1`` for a harmonic of amplitude a in cm/s^2, with a
  Gaussian signal's RMS in place of ``a / sqrt(2)``: ``Wz = 4.42 a_B^0.3``); an
  integral over frequency, it does not depend on the grid step as the sum over
  spectral lines ``(sum Wz_i^10)^0.1`` does.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.outputs.base import OUTPUTS, DerivedOutput
from railvib.outputs.octave import band_mean_square
from railvib.outputs.weighting import COMFORT_RANGE_HZ, WEIGHTINGS, sperling_weighting
from railvib.registry import parameter
from railvib.vehicle import Vehicle

__all__ = [
    "EN12299_SCALE",
    "ISO2631_COMFORT",
    "FloorGeometry",
    "RideComfort",
    "comfort_arrays",
    "comfort_category",
    "floor_acceleration_psd",
    "floor_geometry",
    "mean_comfort_category",
    "sperling_index",
    "weighted_rms",
]

#: ISO 2631-1:1997, Annex C, C.2.3: likely reactions of passengers to a_w (m/s^2) ranges
ISO2631_COMFORT: tuple[tuple[float, float, str], ...] = (
    (0.0, 0.315, "not uncomfortable"),
    (0.315, 0.63, "a little uncomfortable"),
    (0.5, 1.0, "fairly uncomfortable"),
    (0.8, 1.6, "uncomfortable"),
    (1.25, 2.5, "very uncomfortable"),
    (2.0, np.inf, "extremely uncomfortable"),
)

#: EN 12299:2009: the scale of the mean comfort index N_MV (upper bounds)
EN12299_SCALE: tuple[tuple[float, str], ...] = (
    (1.0, "very comfortable"),
    (2.0, "comfortable"),
    (4.0, "medium"),
    (5.0, "uncomfortable"),
    (np.inf, "very uncomfortable"),
)


@dataclass(frozen=True)
class FloorGeometry:
    """Where a body's floor can be evaluated.

    Attributes
    ----------
    body : str
        The body (``"carbody"``).
    positions : tuple of float
        Default floor points, m from the body's centre, positive forward: over each
        secondary suspension (the bogie centres) and the centre.
    extent : tuple of float
        ``(rear, front)``, m from the body's centre: for the car body the outermost wheels
        (the vehicle model carries no car-body length; floor points are taken within
        the wheelbase).
    """

    body: str
    positions: tuple[float, ...]
    extent: tuple[float, float]


def floor_geometry(vehicle: Vehicle, body: str = "carbody") -> FloorGeometry:
    """The default floor points and the extent of `body`, from the vehicle's parts.

    The default points are over the suspensions `body` rests on (for the car body: the
    secondary suspensions, over the bogie centres) and its centre; the extent is the
    vehicle's wheelbase for the top body (one that hangs on no suspension), else the
    span of the suspensions it rests on (in a train, a car's wheelbase: its own wheels).

    Parameters
    ----------
    vehicle : Vehicle
        The assembled vehicle (read through ``bodies``, ``suspensions``, ``wheels``).
    body : str
        A body with a pitch DOF.

    Returns
    -------
    FloorGeometry
    """
    x0 = next(b.x for b in vehicle.bodies if b.name == body)
    under = sorted({s.upper.x - x0 for s in vehicle.suspensions if s.upper.body == body})
    positions = tuple(dict.fromkeys([*under[-1:], 0.0, *under[:1]]))
    if any(s.lower.body == body for s in vehicle.suspensions):
        extent = (min(under, default=0.0), max(under, default=0.0))
    else:
        car = body.rpartition(".")[0]  # a train's car: its own wheels ("car2.wheel1", ...)
        wheels = [w.x - x0 for w in vehicle.wheels if w.name.rpartition(".")[0] == car]
        extent = (min(wheels), max(wheels))
    return FloorGeometry(body, positions, extent)


def floor_acceleration_psd(
    f: ArrayLike,
    h_bounce: ArrayLike,
    h_pitch: ArrayLike,
    irregularity_psd: ArrayLike,
    positions: ArrayLike,
) -> NDArray[np.float64]:
    """One-sided vertical acceleration PSD of floor points, ``(2 pi f)^4 |H_z + s H_phi|^2 S_r``.

    Parameters
    ----------
    f : array_like
        Frequencies, Hz, ``(n_freq,)``.
    h_bounce, h_pitch : array_like
        Body bounce (m/m) and pitch (rad/m) per metre of irregularity, ``(..., n_freq)``.
    irregularity_psd : array_like
        One-sided irregularity PSD, m^2/Hz, ``(..., n_freq)``.
    positions : array_like
        Floor points ``s``, m from the body's centre, positive forward, ``(n_pos,)``.

    Returns
    -------
    numpy.ndarray
        (m/s^2)^2/Hz, ``(..., n_freq, n_pos)``.
    """
    s = np.asarray(positions, dtype=float)
    h = np.asarray(h_bounce)[..., None] + np.asarray(h_pitch)[..., None] * s
    omega4 = ((2.0 * np.pi * np.asarray(f, dtype=float)) ** 4)[:, None]
    return np.asarray(
        np.abs(h) ** 2 * omega4 * np.asarray(irregularity_psd, dtype=float)[..., None]
    )


def weighted_rms(
    f: ArrayLike, psd: ArrayLike, weight: ArrayLike, band: tuple[float, float], axis: int = 0
) -> NDArray[np.float64]:
    """``sqrt(integral over band of weight^2 psd df)`` (PSD linear between grid points).

    Parameters
    ----------
    f : array_like
        Frequencies, Hz, ``(n_freq,)``.
    psd : array_like
        One-sided PSD, unit^2/Hz, `axis` over `f`.
    weight : array_like
        Weighting magnitude at `f` (dimensionless), ``(n_freq,)``.
    band : (float, float)
        Integration band, Hz, within the grid.
    axis : int
        Frequency axis of `psd`.

    Returns
    -------
    numpy.ndarray
        Weighted RMS in unit, `psd`'s shape without `axis`.
    """
    y = np.moveaxis(np.asarray(psd, dtype=float), axis, 0)
    w2 = (np.asarray(weight, dtype=float) ** 2).reshape((-1,) + (1,) * (y.ndim - 1))
    ms = band_mean_square(f, w2 * y, np.array([band[0]]), np.array([band[1]]), axis=0)
    return np.asarray(np.sqrt(ms[0]))


def sperling_index(a_b: ArrayLike) -> NDArray[np.float64]:
    """Sperling's ride index ``Wz = (100 sqrt(2) a_B)^0.3`` from the B-weighted RMS `a_b` (m/s^2).

    Parameters
    ----------
    a_b : array_like
        RMS of the acceleration weighted by :func:`railvib.outputs.weighting.sperling_weighting`,
        m/s^2.

    Returns
    -------
    numpy.ndarray
        Wz, dimensionless (1 very good ... 4.5 unfit for service).
    """
    return np.asarray((100.0 * np.sqrt(2.0) * np.asarray(a_b, dtype=float)) ** 0.3)


def comfort_category(a_w: float) -> str:
    """Likely passenger reaction to `a_w` (m/s^2), ISO 2631-1:1997, Annex C, C.2.3.

    Parameters
    ----------
    a_w : float
        Frequency-weighted RMS acceleration, m/s^2.

    Returns
    -------
    str
        The ranges holding `a_w`, e.g. ``"a little uncomfortable / fairly uncomfortable"``
        (the standard's ranges overlap).
    """
    names = [name for lo, hi, name in ISO2631_COMFORT if lo <= a_w < hi]
    return " / ".join(names)


def mean_comfort_category(n_mv: float) -> str:
    """The comfort of a mean comfort index `n_mv` (dimensionless), on the scale of EN 12299:2009.

    Parameters
    ----------
    n_mv : float
        Mean comfort index N_MV.

    Returns
    -------
    str
        E.g. ``"comfortable"``.
    """
    return next(name for upper, name in EN12299_SCALE if n_mv < upper)


@OUTPUTS.register("ride_comfort")
@dataclass(frozen=True)
class RideComfort(DerivedOutput):
    """Ride comfort at floor points of the car body (ISO 2631-1, EN 12299, Sperling).

    Parameters
    ----------
    floor_positions_m : tuple of float
        Floor points, m from the body's centre, positive forward.
    floor_extent_m : tuple of float
        ``(rear, front)`` limits of a floor point, m (:func:`floor_geometry`).
    weighting : str
        ``"Wb"`` (ISO 2631-4 / EN 12299, rail vehicles) or ``"Wk"`` (ISO 2631-1).
    band_hz : tuple of float
        ``(f_lo, f_hi)`` of a_w, N_MV and Wz, Hz, within ISO 2631-1's 0.5-80 Hz.
    body : str
        The body whose floor is evaluated (its bounce and pitch responses).
    """

    floor_positions_m: tuple[float, ...] = parameter(
        "m",
        "floor points, from the car body's centre, positive forward "
        "(default: over the bogies and at the centre); case file: [criteria] floor_positions_m",
        default=(),
    )
    floor_extent_m: tuple[float, ...] = parameter(
        "m", "(rear, front) limits of a floor point", default=(-1e3, 1e3)
    )
    weighting: str = parameter(
        "",
        "frequency weighting of a_w: Wb (ISO 2631-4, EN 12299: rail vehicles) or Wk "
        "(ISO 2631-1); case file: [criteria] comfort_weighting",
        default="Wb",
        choices=("Wb", "Wk"),
    )
    band_hz: tuple[float, ...] = parameter(
        "Hz",
        "band of a_w, N_MV and Wz, within 0.5-80 Hz (ISO 2631-1); case file: "
        "[criteria] comfort_band_hz",
        default=COMFORT_RANGE_HZ,
    )
    body: str = parameter("", "body whose floor is evaluated", default="carbody")

    def __post_init__(self) -> None:
        super().__post_init__()
        self.validate_settings()

    def validate_settings(self) -> None:
        """Floor points within the extent, the band within ISO 2631-1's range.

        Raises
        ------
        railvib.errors.CaseError
            ``criteria.floor_positions_m`` or ``criteria.comfort_band_hz``.
        """
        lo, hi = self.floor_extent_m
        for i, s in enumerate(self.floor_positions_m):
            if not (lo <= s <= hi):
                raise CaseError(
                    f"criteria.floor_positions_m[{i}]",
                    s,
                    f"a point of the {self.body} floor, {lo:g} <= s <= {hi:g} from its centre "
                    "(for the car body: between the outermost wheels) (m)",
                )
        f_lo, f_hi = self.band_hz
        if not (COMFORT_RANGE_HZ[0] <= f_lo < f_hi <= COMFORT_RANGE_HZ[1]):
            raise CaseError(
                "criteria.comfort_band_hz",
                [f_lo, f_hi],
                f"{COMFORT_RANGE_HZ[0]:g} <= f_lo < f_hi <= {COMFORT_RANGE_HZ[1]:g}, the range "
                "where ISO 2631-1 defines its weightings for comfort (Hz)",
            )

    def band(self, f: NDArray[np.float64]) -> tuple[float, float]:
        """The band evaluated on the grid `f`: `band_hz`, refused where the grid does not reach.

        Parameters
        ----------
        f : numpy.ndarray
            The frequency grid, Hz.

        Returns
        -------
        (float, float)
            Hz.

        Raises
        ------
        railvib.errors.CaseError
            ``criteria.comfort_band_hz``: the band is not inside the grid.
        """
        f_lo, f_hi = (float(x) for x in self.band_hz)
        if f_lo < f[0] * (1 - 1e-12) or f_hi > f[-1] * (1 + 1e-12):
            raise CaseError(
                "criteria.comfort_band_hz",
                [f_lo, f_hi],
                f"a band within the frequency grid {f[0]:g}-{f[-1]:g} (set [criteria] "
                "comfort_band_hz or widen [frequency]) (Hz)",
            )
        return max(f_lo, float(f[0])), min(f_hi, float(f[-1]))

    def floor_coordinate(self) -> dict[str, tuple[str, NDArray[np.float64], dict[str, str]]]:
        """The ``floor`` coordinate: the floor points, m from the body's centre, forward."""
        positions = np.asarray(self.floor_positions_m, dtype=float)
        attrs = {"units": "m", "long_name": f"floor point of the {self.body}, from its centre"}
        return {"floor": ("floor", positions, attrs)}

    def variable_attrs(self, band: tuple[float, float]) -> dict[str, dict[str, str]]:
        """``units``, ``long_name`` and the standard of each variable :meth:`compute` returns.

        Parameters
        ----------
        band : (float, float)
            The band evaluated, Hz (:meth:`band`).

        Returns
        -------
        dict of dict
            By variable name.
        """
        text = f"{band[0]:g}-{band[1]:g} Hz"
        return {
            "psd_floor_acceleration": {
                "units": "(m/s^2)^2/Hz",
                "long_name": f"vertical acceleration PSD of the {self.body} floor",
            },
            "comfort_aw": {
                "units": "m/s^2",
                "long_name": f"weighted RMS acceleration a_w ({self.weighting}), {text}",
                "weighting": self.weighting,
                "band": text,
                "standard": WEIGHTINGS[self.weighting].source + "; ISO 2631-1:1997, clause 6",
            },
            "mean_comfort_index": {
                "units": "1",
                "long_name": f"mean comfort index N_MV ~ 6 a_zWb (vertical part), {text}",
                "standard": "EN 12299:2009, mean comfort (standard method); the 95th percentile "
                "of 5-s RMS values replaced by the RMS of the stationary response",
            },
            "sperling_wz": {
                "units": "1",
                "long_name": f"Sperling ride index Wz = (100 sqrt(2) a_B)^0.3, {text}",
                "standard": "Sperling (1941); filter B(f) of Garg and Dukkipati (1984)",
            },
            "comfort_category": {
                "units": "1",
                "long_name": "comfort category, ISO 2631-1:1997, Annex C, C.2.3",
            },
        }

    def compute(self, ds: xr.Dataset) -> dict[str, xr.DataArray]:
        """Floor PSDs and a_w, category, N_MV and Wz at each floor point (dimension ``floor``).

        Reads ``frf_displacement`` (complex, ``frequency`` x ``response``, optionally
        leading dimensions such as the cases of a sweep) and ``irregularity_psd``. The
        category (text) is given for one run only (no leading dimension).
        """
        f = ds["frequency"].values
        band = self.band(f)
        labels = [str(r) for r in ds["response"].values]
        bounce, pitch = f"{self.body}.bounce", f"{self.body}.pitch"
        if bounce not in labels or pitch not in labels:
            bodies = [lab.split(".")[0] for lab in labels if lab.endswith(".pitch")]
            raise CaseError(
                "criteria.comfort_body", self.body, f"a body with bounce and pitch: {bodies}"
            )
        h = ds["frf_displacement"].transpose(..., "frequency", "response")
        psd = floor_acceleration_psd(
            f,
            h.sel(response=bounce).values,
            h.sel(response=pitch).values,
            ds["irregularity_psd"].transpose(..., "frequency").values,
            self.floor_positions_m,
        )
        axis = psd.ndim - 2
        a_w = weighted_rms(f, psd, WEIGHTINGS[self.weighting].magnitude(f), band, axis=axis)
        a_wb = weighted_rms(f, psd, WEIGHTINGS["Wb"].magnitude(f), band, axis=axis)
        a_s = weighted_rms(f, psd, sperling_weighting(f), band, axis=axis)
        lead = tuple(str(d) for d in h.dims if d not in ("frequency", "response"))
        floor = self.floor_coordinate()
        attrs = self.variable_attrs(band)
        values = {
            "psd_floor_acceleration": (psd, (*lead, "frequency", "floor")),
            "comfort_aw": (a_w, (*lead, "floor")),
            "mean_comfort_index": (6.0 * a_wb, (*lead, "floor")),
            "sperling_wz": (sperling_index(a_s), (*lead, "floor")),
        }
        if not lead:
            values["comfort_category"] = (
                np.array([comfort_category(float(a)) for a in a_w]),
                ("floor",),
            )
        return {
            name: xr.DataArray(v, dims=dims, coords=floor, attrs=attrs[name])
            for name, (v, dims) in values.items()
        }


def comfort_arrays(
    comfort: RideComfort,
    f: NDArray[np.float64],
    h_bounce: NDArray[np.complex128],
    h_pitch: NDArray[np.complex128],
    irregularity_psd: NDArray[np.float64],
) -> dict[str, NDArray[np.float64]]:
    """:meth:`RideComfort.compute`'s a_w, N_MV and Wz of many cases, in NumPy arrays.

    The same operations on the same values (bit for bit), without labelled arrays: for
    a sweep's chunk of cases, where building the datasets costs more than the criteria.

    Parameters
    ----------
    comfort : RideComfort
        The criteria's settings (body, floor points, weighting, band).
    f : numpy.ndarray
        Frequencies, Hz, ``(n_freq,)``.
    h_bounce, h_pitch : numpy.ndarray
        The body's bounce (m/m) and pitch (rad/m) per metre of irregularity, ``(...,
        n_freq)``.
    irregularity_psd : numpy.ndarray
        One-sided irregularity PSD, m^2/Hz, ``(..., n_freq)``.

    Returns
    -------
    dict of numpy.ndarray
        ``comfort_aw`` (m/s^2), ``mean_comfort_index`` and ``sperling_wz`` (1), ``(...,
        n_floor)``.
    """
    band = comfort.band(f)
    psd = floor_acceleration_psd(f, h_bounce, h_pitch, irregularity_psd, comfort.floor_positions_m)
    axis = psd.ndim - 2
    a_w = weighted_rms(f, psd, WEIGHTINGS[comfort.weighting].magnitude(f), band, axis=axis)
    a_wb = weighted_rms(f, psd, WEIGHTINGS["Wb"].magnitude(f), band, axis=axis)
    a_s = weighted_rms(f, psd, sperling_weighting(f), band, axis=axis)
    return {"comfort_aw": a_w, "mean_comfort_index": 6.0 * a_wb, "sperling_wz": sperling_index(a_s)}
