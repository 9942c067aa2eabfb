"""The xarray accessor ``ds.railvib``: a result's statistics and figures without raw arrays.

Registered on ``xarray.Dataset`` by ``import railvib`` (the facade installs it when
xarray is, or is already, imported; :func:`railvib._register_accessor`), so it works on
every railvib result: the dataset of :func:`railvib.run`, a ``results.nc`` of ``railvib
run`` opened with :func:`railvib.load_netcdf` or :func:`xarray.open_dataset`, and a
sweep's dataset (its sweep dimensions are kept). Each method is one call of the
library's own function (:func:`railvib.results.summary`,
:meth:`railvib.outputs.ThirdOctave.levels`, :func:`railvib.plot.psd.plot_psd`), so
the figures agree with ``railvib run``'s files; units come from the variables'
``units`` attributes and go into the plot labels.

Examples
--------
>>> import railvib
>>> ds = railvib.run(railvib.load_preset_case())
>>> rms = ds.railvib.rms((0.5, 20.0))
>>> rms.attrs["units"], round(float(rms.sel(response="carbody.bounce")), 3)
('m/s^2', 0.11)
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import product
from typing import TYPE_CHECKING, Any

import numpy as np
import xarray as xr

from railvib.errors import CaseError
from railvib.labels import leading_car_label
from railvib.outputs import ThirdOctave
from railvib.results.stats import summary, summary_names

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = ["DEFAULT_RESPONSES", "RailvibAccessor"]

#: responses drawn by :meth:`RailvibAccessor.plot_psd` when none is given (a train's:
#: those of its leading car)
DEFAULT_RESPONSES = ("carbody.bounce", "bogie1.bounce", "wheelset1.bounce", "rail@wheel1")


class RailvibAccessor:
    """``ds.railvib``: statistics, band levels and PSD plots of a railvib result.

    Parameters
    ----------
    ds : xarray.Dataset
        A railvib result with a ``frequency`` dimension (Hz) and PSD variables
        (``psd_acceleration`` at least).
    """

    def __init__(self, ds: xr.Dataset) -> None:
        self._ds = ds

    def _psd(self, variable: str) -> xr.DataArray:
        """The PSD `variable`, or a one-line error naming the ones the dataset holds."""
        if variable not in self._ds or "frequency" not in self._ds[variable].dims:
            psds = [str(k) for k, v in self._ds.data_vars.items() if "frequency" in v.dims]
            raise CaseError("variable", variable, f"a PSD of this dataset: {psds}")
        return self._ds[variable]

    def summary(
        self, bands: Sequence[tuple[float, float]] = (), variable: str = "psd_acceleration"
    ) -> xr.Dataset:
        """Peak, dominant frequency and RMS (grid and `bands`) of every response.

        Parameters
        ----------
        bands : sequence of (float, float)
            Frequency bands ``(f_lo, f_hi)`` in Hz for band RMS values.
        variable : str
            The PSD summarised (``psd_acceleration``, ``psd_displacement``, ...).

        Returns
        -------
        xarray.Dataset
            :func:`railvib.results.summary`: ``peak``, ``dominant_frequency``, ``rms``
            and ``rms_<lo>_<hi>_hz``, with units (over the sweep dimensions too).
        """
        self._psd(variable)  # a one-line error for a PSD the dataset lacks
        return summary(self._ds, bands, variable)

    def rms(
        self, band: tuple[float, float] | None = None, variable: str = "psd_acceleration"
    ) -> xr.DataArray:
        """RMS of every response over `band` (trapezoidal integral of the one-sided PSD).

        Parameters
        ----------
        band : (float, float), optional
            ``(f_lo, f_hi)`` in Hz, inclusive; None: the whole grid.
        variable : str
            The PSD integrated.

        Returns
        -------
        xarray.DataArray
            In the PSD's amplitude unit (``units`` attribute, e.g. m/s^2; rad-based for
            pitch, in the ``units_coordinate`` it names).

        Raises
        ------
        ValueError
            `band` holds no grid frequency.
        """
        bands = [] if band is None else [(float(band[0]), float(band[1]))]
        name = summary_names(bands)[-1]
        return self.summary(bands, variable)[name]

    def octave_bands(
        self,
        quantities: Sequence[str] | None = None,
        f_lo: float = 0.0,
        f_hi: float = 0.0,
    ) -> xr.Dataset:
        """One-third-octave band mean squares and levels (IEC 61260-1:2014).

        Parameters
        ----------
        quantities : sequence of str, optional
            From :data:`railvib.outputs.octave.OCTAVE_QUANTITIES` (``acceleration``,
            ``velocity``, ``displacement``, ``force``, ``support_force``); None: every one
            whose PSD the dataset holds (a sweep holds accelerations only).
        f_lo, f_hi : float
            Range of the bands, Hz; 0: the end of the grid.

        Returns
        -------
        xarray.Dataset
            ``octave_ms_<quantity>`` (unit^2) and ``octave_level_<quantity>`` (dB, the
            reference in the ``reference`` attribute) over ``band`` (exact mid-band
            frequency, Hz; ``band_nominal``, ``band_lower`` and ``band_upper`` with it).

        Raises
        ------
        railvib.errors.CaseError
            A quantity the dataset has no PSD for; a range beyond the grid
            (``criteria.octave_band_hz``).
        """
        octave = ThirdOctave(f_lo=f_lo, f_hi=f_hi)
        return xr.Dataset(
            octave.levels(self._ds, None if quantities is None else tuple(quantities))
        )

    def default_responses(self) -> list[str]:
        """The responses :meth:`plot_psd` draws when none is given.

        Returns
        -------
        list of str
            Those of :data:`DEFAULT_RESPONSES` the dataset holds (a train's: its leading
            car's).
        """
        labels = {str(r) for r in self._ds["response"].values}
        present = [r for r in DEFAULT_RESPONSES if r in labels]
        return present or [r for r in map(leading_car_label, DEFAULT_RESPONSES) if r in labels]

    def plot_psd(
        self,
        responses: Sequence[str] | None = None,
        *,
        variable: str = "psd_acceleration",
        ax: Axes | None = None,
        logx: bool = True,
        ylim: tuple[float, float] | str | None = "auto",
        label: str = "",
        **line_kw: Any,
    ) -> Axes:
        """Plot the PSDs of `responses` against frequency (one line per sweep point too).

        Parameters
        ----------
        responses : sequence of str, optional
            Response labels; None: :meth:`default_responses`.
        variable : str
            The PSD drawn (``psd_acceleration``, ``psd_displacement``).
        ax : matplotlib.axes.Axes, optional
            Axes to draw on; None: a new pyplot figure (the user's backend).
        logx : bool
            Logarithmic frequency axis.
        ylim : (float, float), "auto" or None
            PSD axis limits in the unit of `variable`; ``"auto"``: from the data drawn.
        label : str
            Prefix of the legend labels (e.g. the case's name).
        **line_kw
            Passed to ``Axes.plot``.

        Returns
        -------
        matplotlib.axes.Axes
            Labelled ``long_name [units]`` from the attributes (the pitch responses'
            rad-based unit where drawn); a sweep's lines are labelled by their point
            (``speed_kmh=80``).

        Raises
        ------
        railvib.errors.CaseError
            A response or `variable` the dataset does not hold.
        """
        from railvib.plot.psd import plot_psd, psd_ylim

        da = self._psd(variable)
        chosen = list(responses) if responses is not None else self.default_responses()
        labels = [str(r) for r in self._ds["response"].values]
        for r in chosen:
            if r not in labels:
                raise CaseError("response", r, f"one of {labels}")
        extra = [d for d in da.dims if d not in ("frequency", "response")]
        points = list(product(*(range(self._ds.sizes[d]) for d in extra)))
        for point in points:
            at = dict(zip(extra, point, strict=True))
            one = self._ds.isel(at) if at else self._ds
            where = [f"{d}={_text(one[d].item())}" for d in extra if d in one.coords]
            text = " ".join([label, *where]).strip()
            ax = plot_psd(
                one, chosen, variable=variable, ax=ax, logx=logx, label=text, ylim=None, **line_kw
            )
        if ax is None:
            raise CaseError(
                "variable", variable, "a PSD with a point to draw (a dimension is empty)"
            )
        if ylim == "auto":
            auto = psd_ylim(np.asarray(da.sel(response=chosen).values))
            if auto is not None:
                ax.set_ylim(*auto)
        elif ylim is not None and not isinstance(ylim, str):
            ax.set_ylim(*ylim)
        return ax


def _text(value: Any) -> str:
    """A sweep coordinate's value in a legend: numbers in ``%g``, anything else as is."""
    return (
        f"{value:g}"
        if isinstance(value, int | float) and not isinstance(value, bool)
        else str(value)
    )
