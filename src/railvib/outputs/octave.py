"""One-third-octave bands of IEC 61260-1:2014 and band levels of one-sided PSDs.

Band set (IEC 61260-1:2014, clause 5, base-10 system): octave ratio
``G = 10^(3/10)``, reference frequency ``f_r = 1000`` Hz; for bandwidth
designator ``b = 3`` (odd) the exact mid-band frequency of band ``x`` is
``f_m = f_r G^(x/b) = 1000 * 10^(x/10)`` Hz and its edges are
``f_m G^(-1/(2b))`` and ``f_m G^(+1/(2b))``, i.e. ``f_m 10^(-1/20)`` and
``f_m 10^(+1/20)``. The nominal mid-band frequencies (IEC 61260-1:2014,
Annex E, Table E.1) are the rounded values 1, 1.25, 1.6, 2, 2.5, 3.15, 4, 5,
6.3, 8 times a power of ten.

The mean square in a band is the integral of the PSD over the exact band edges,
with the PSD taken linear between grid points and at the edges interpolated
(not whole bins summed): on a grid, consecutive bands add up to the trapezoidal
integral over their union, the rule of every RMS railvib reports.

Levels (reference values of ISO 1683:2015, Table 1, except for force and VdB):

=============  ==============================  ==========================
quantity       level                           reference
=============  ==============================  ==========================
acceleration   ``10 log10(a^2 / a0^2)`` dB     a0 = 1e-6 m/s^2
velocity       dB                              v0 = 1e-9 m/s
velocity       VdB (US practice, FTA manual)   v0 = 1e-6 in/s = 2.54e-8 m/s
displacement   dB                              d0 = 1e-12 m
force          dB                              F0 = 1 N (issue 16's choice; ISO 1683: 1e-6 N)
=============  ==============================  ==========================
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError
from railvib.outputs.base import OUTPUTS, DerivedOutput
from railvib.registry import parameter

__all__ = [
    "BAND_EDGE_RATIO",
    "NOMINAL_MANTISSAS",
    "OCTAVE_QUANTITIES",
    "OCTAVE_SOURCES",
    "REFERENCES",
    "OctaveBands",
    "ThirdOctave",
    "band_mean_square",
    "level_db",
    "third_octave_bands",
]

#: upper / mid-band (and mid-band / lower) frequency of a one-third-octave band, 10^(1/20)
BAND_EDGE_RATIO = 10.0 ** (1.0 / 20.0)

#: nominal mid-band frequencies in one decade (IEC 61260-1:2014, Table E.1: 10 Hz to 80 Hz ...)
NOMINAL_MANTISSAS = (1.0, 1.25, 1.6, 2.0, 2.5, 3.15, 4.0, 5.0, 6.3, 8.0)

#: reference value of each level, in SI units (see the module docstring)
REFERENCES: dict[str, tuple[float, str]] = {
    "acceleration": (1e-6, "dB re 1e-6 m/s^2"),
    "velocity": (1e-9, "dB re 1e-9 m/s"),
    "velocity_vdb": (2.54e-8, "VdB re 1e-6 in/s"),
    "displacement": (1e-12, "dB re 1e-12 m"),
    "force": (1.0, "dB re 1 N"),
}

#: the PSD each band quantity is read from, and the quantity's unit; velocity is the
#: acceleration PSD over (2 pi f)^2 (translational responses: pitch is rad-based)
OCTAVE_SOURCES: dict[str, tuple[str, str]] = {
    "acceleration": ("psd_acceleration", "m/s^2"),
    "velocity": ("psd_acceleration", "m/s"),
    "displacement": ("psd_displacement", "m"),
    "force": ("psd_force", "N"),
    "support_force": ("psd_support_force", "N"),
}

#: the quantities of :meth:`ThirdOctave.levels`, in the order of its variables
OCTAVE_QUANTITIES = tuple(OCTAVE_SOURCES)


@dataclass(frozen=True)
class OctaveBands:
    """A set of consecutive one-third-octave bands.

    Attributes
    ----------
    index : numpy.ndarray
        Band numbers ``x`` (``f_m = 1000 * 10^(x/10)`` Hz), ascending, integers.
    """

    index: NDArray[np.int64]

    @property
    def exact(self) -> NDArray[np.float64]:
        """Exact mid-band frequencies ``1000 * 10^(x/10)``, Hz."""
        return 1000.0 * 10.0 ** (self.index / 10.0)

    @property
    def lower(self) -> NDArray[np.float64]:
        """Lower band edges ``f_m 10^(-1/20)``, Hz."""
        return self.exact / BAND_EDGE_RATIO

    @property
    def upper(self) -> NDArray[np.float64]:
        """Upper band edges ``f_m 10^(+1/20)``, Hz."""
        return self.exact * BAND_EDGE_RATIO

    @property
    def nominal(self) -> NDArray[np.float64]:
        """Nominal mid-band frequencies (IEC 61260-1:2014, Annex E), Hz."""
        decade, digit = np.divmod(self.index, 10)
        return np.array(NOMINAL_MANTISSAS)[digit] * 10.0 ** (decade + 3.0)


def third_octave_bands(f_lo: float, f_hi: float) -> OctaveBands:
    """The one-third-octave bands lying wholly within ``[f_lo, f_hi]`` Hz.

    Parameters
    ----------
    f_lo, f_hi : float
        Frequency range, Hz (``0 < f_lo < f_hi``).

    Returns
    -------
    OctaveBands
        Possibly empty.
    """
    # a band is kept when its edges are inside, up to rounding of the edge (1e-9 relative)
    first = int(np.ceil(10.0 * np.log10(f_lo * BAND_EDGE_RATIO / 1000.0) - 1e-8))
    last = int(np.floor(10.0 * np.log10(f_hi / BAND_EDGE_RATIO / 1000.0) + 1e-8))
    return OctaveBands(np.arange(first, last + 1, dtype=np.int64))


def band_mean_square(
    f: ArrayLike, psd: ArrayLike, lower: ArrayLike, upper: ArrayLike, axis: int = 0
) -> NDArray[np.float64]:
    """Integral of a one-sided PSD over each band, the PSD linear between grid points.

    Parameters
    ----------
    f : array_like
        Grid frequencies, Hz, ascending, ``(n_freq,)``.
    psd : array_like
        One-sided PSD in unit^2/Hz, `axis` over `f`.
    lower, upper : array_like
        Band edges, Hz, ``(n_band,)``, each within ``[f[0], f[-1]]``.
    axis : int
        The frequency axis of `psd`.

    Returns
    -------
    numpy.ndarray
        Mean square in unit^2, ``psd``'s shape with `axis` replaced by the bands.

    Raises
    ------
    ValueError
        A band edge lies outside the grid (the PSD is unknown there).
    """
    f = np.asarray(f, dtype=float)
    y = np.moveaxis(np.asarray(psd, dtype=float), axis, 0)
    lower = np.asarray(lower, dtype=float)
    upper = np.asarray(upper, dtype=float)
    if lower.size and (lower.min() < f[0] or upper.max() > f[-1]):
        raise ValueError(f"band edges outside the grid {f[0]:g}-{f[-1]:g} Hz")
    # cumulative trapezoid, then the integral from f[0] to any x by the linear piece at x
    steps = np.diff(f).reshape((-1,) + (1,) * (y.ndim - 1))
    cumulative = np.concatenate(
        [np.zeros((1, *y.shape[1:])), np.cumsum(steps * (y[1:] + y[:-1]) / 2.0, axis=0)]
    )

    def integral_to(x: NDArray[np.float64]) -> NDArray[np.float64]:
        i = np.clip(np.searchsorted(f, x, side="right") - 1, 0, f.size - 2)
        h = (x - f[i]).reshape((-1,) + (1,) * (y.ndim - 1))
        width = (f[i + 1] - f[i]).reshape(h.shape)
        y_x = y[i] + (y[i + 1] - y[i]) * h / width
        return np.asarray(cumulative[i] + h * (y[i] + y_x) / 2.0)

    out = integral_to(upper) - integral_to(lower)
    return np.moveaxis(out, 0, axis)


def level_db(mean_square: ArrayLike, reference: float) -> NDArray[np.float64]:
    """``10 log10(mean_square / reference^2)`` dB; ``-inf`` for a zero mean square.

    Parameters
    ----------
    mean_square : array_like
        Mean square, unit^2.
    reference : float
        Reference value, unit (e.g. 1e-6 m/s^2).

    Returns
    -------
    numpy.ndarray
        Level in dB.
    """
    with np.errstate(divide="ignore"):
        return np.asarray(10.0 * np.log10(np.asarray(mean_square, dtype=float) / reference**2))


def _band_coords(bands: OctaveBands) -> dict[str, tuple[str, NDArray[np.float64], dict[str, str]]]:
    """The ``band`` coordinate (exact mid-band frequency) and the nominal frequency and edges."""
    return {
        "band": ("band", bands.exact, {"units": "Hz", "long_name": "exact mid-band frequency"}),
        "band_nominal": (
            "band",
            bands.nominal,
            {"units": "Hz", "long_name": "nominal mid-band frequency (IEC 61260-1, Annex E)"},
        ),
        "band_lower": ("band", bands.lower, {"units": "Hz", "long_name": "lower band edge"}),
        "band_upper": ("band", bands.upper, {"units": "Hz", "long_name": "upper band edge"}),
    }


@OUTPUTS.register("third_octave")
@dataclass(frozen=True)
class ThirdOctave(DerivedOutput):
    """One-third-octave band levels of every response and contact force (IEC 61260-1:2014).

    Parameters
    ----------
    f_lo, f_hi : float
        Range of the bands, Hz: the bands wholly inside it are computed; 0 (the
        default) means the end of the frequency grid. A band edge outside the
        grid is an error, not an empty band.
    """

    f_lo: float = parameter(
        "Hz",
        "lowest frequency of the one-third-octave bands (0: the grid's first); "
        "case file: [criteria] octave_band_hz",
        default=0.0,
        ge=0.0,
    )
    f_hi: float = parameter(
        "Hz", "highest frequency of the bands (0: the grid's last)", default=0.0, ge=0.0
    )

    def bands(self, f: NDArray[np.float64]) -> OctaveBands:
        """The bands computed on the grid `f`.

        Parameters
        ----------
        f : numpy.ndarray
            The frequency grid, Hz.

        Returns
        -------
        OctaveBands

        Raises
        ------
        railvib.errors.CaseError
            ``criteria.octave_band_hz``: a range beyond the grid, or one holding no band.
        """
        lo = self.f_lo or float(f[0])
        hi = self.f_hi or float(f[-1])
        if lo < f[0] * (1 - 1e-12) or hi > f[-1] * (1 + 1e-12) or lo >= hi:
            raise CaseError(
                "criteria.octave_band_hz",
                [lo, hi],
                f"a range f_lo < f_hi within the frequency grid {f[0]:g}-{f[-1]:g} (Hz)",
            )
        bands = third_octave_bands(max(lo, float(f[0])), min(hi, float(f[-1])))
        if bands.index.size == 0:
            raise CaseError(
                "criteria.octave_band_hz",
                [lo, hi],
                "a range holding at least one whole one-third-octave band "
                "(a band spans a factor 10^(1/10) = 1.26) (Hz)",
            )
        return bands

    def compute(self, ds: xr.Dataset) -> dict[str, xr.DataArray]:
        """Band mean squares and levels of acceleration, velocity, displacement and force.

        Reads ``psd_acceleration``, ``psd_displacement`` (``frequency``, ``response``)
        and ``psd_force`` (``frequency``, ``wheel``), and ``psd_support_force``
        (``frequency``, ``wheel``, ``layer``) where the run has it. Velocity PSD is the acceleration
        PSD over ``(2 pi f)^2``. Pitch responses are in rad-based units; their levels
        use the same numbers as references (1e-6 rad/s^2, ...), which no standard
        defines: read them as relative levels only.
        """
        return self.levels(
            ds, OCTAVE_QUANTITIES[:4] + ("support_force",) * ("psd_support_force" in ds)
        )

    def levels(
        self, ds: xr.Dataset, quantities: tuple[str, ...] | None = None
    ) -> dict[str, xr.DataArray]:
        """Band mean squares ``octave_ms_<q>`` and levels ``octave_level_<q>`` of `quantities`.

        Parameters
        ----------
        ds : xarray.Dataset
            A result dataset: a run's, or a sweep's (its sweep dimensions are kept).
        quantities : tuple of str, optional
            From :data:`OCTAVE_QUANTITIES`, each read from its PSD
            (:data:`OCTAVE_SOURCES`); None: every one whose PSD `ds` holds.

        Returns
        -------
        dict of str to xarray.DataArray
            Over ``band`` (the exact mid-band frequency, Hz, with its nominal frequency
            and edges) and the PSD's other dimensions, with units; ``velocity`` also
            gives ``octave_level_velocity_vdb``.

        Raises
        ------
        railvib.errors.CaseError
            A quantity not in :data:`OCTAVE_QUANTITIES`, or whose PSD `ds` lacks.
        """
        available = tuple(q for q in OCTAVE_QUANTITIES if OCTAVE_SOURCES[q][0] in ds)
        for quantity in quantities or ():
            if quantity not in available:
                raise CaseError("quantity", quantity, f"one of {list(available)}")
        f = ds["frequency"].values
        bands = self.bands(f)
        coords = _band_coords(bands)
        lower, upper = bands.lower, bands.upper
        out: dict[str, xr.DataArray] = {}
        for quantity in available if quantities is None else quantities:
            variable, unit = OCTAVE_SOURCES[quantity]
            psd = ds[variable]
            divisor = (2.0 * np.pi * f) ** 2 if quantity == "velocity" else np.ones_like(f)
            axis = psd.get_axis_num("frequency")
            shape = [-1 if d == "frequency" else 1 for d in psd.dims]
            values = psd.values / np.reshape(divisor, shape)  # f > 0 on every grid
            ms = band_mean_square(f, values, lower, upper, axis=axis)
            dims = tuple("band" if d == "frequency" else d for d in psd.dims)
            band_coords: dict[Any, Any] = {
                **coords,
                **{k: psd[k] for k in psd.dims if k != "frequency" and k in psd.coords},
            }
            band_text = f"{quantity} mean square in one-third-octave bands (IEC 61260-1)"
            out[f"octave_ms_{quantity}"] = xr.DataArray(
                ms,
                dims=dims,
                coords=band_coords,
                attrs={"units": f"({unit})^2", "long_name": band_text},
            )
            names = [quantity, "velocity_vdb"] if quantity == "velocity" else [quantity]
            for name in names:
                ref, label = REFERENCES["force" if name == "support_force" else name]
                out[f"octave_level_{name}"] = xr.DataArray(
                    level_db(ms, ref),
                    dims=dims,
                    coords=band_coords,
                    attrs={
                        "units": label.split(" re ")[0],
                        "long_name": f"{quantity} level in one-third-octave bands, {label}",
                        "reference": f"{ref:g} {unit}",
                    },
                )
        return out
