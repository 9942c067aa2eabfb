"""The frequency grid: one immutable, validated array of frequencies in Hz."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError

__all__ = ["MAX_GRID_SIZE", "FrequencyGrid", "trapezoid"]

#: most frequencies of any grid (50 million: the grid alone is 400 MB and a run of it,
#: at some 2 kB per frequency, 100 GB); a larger one is refused before it is allocated
MAX_GRID_SIZE = 50_000_000


@dataclass(frozen=True, eq=False)
class FrequencyGrid:
    """Strictly increasing, positive frequencies in Hz.

    Build it with :meth:`linear`, :meth:`logarithmic` or :meth:`from_array`.

    Parameters
    ----------
    f : numpy.ndarray
        Frequencies in Hz, 1-D, strictly increasing, all > 0.

    Examples
    --------
    >>> grid = FrequencyGrid.linear(0.5, 100.0, step=0.5)
    >>> grid.f[:3]
    array([0.5, 1. , 1.5])
    """

    f: NDArray[np.float64] = field(repr=False)

    def __post_init__(self) -> None:
        size = np.size(self.f)
        if size > MAX_GRID_SIZE:
            raise CaseError("frequency", f"{size:,} values", f"at most {MAX_GRID_SIZE:,} (Hz)")
        f = np.array(self.f, dtype=float)  # a copy: the caller's array stays theirs
        if f.ndim != 1 or f.size == 0:
            raise CaseError("frequency", f"array of shape {f.shape}", "a non-empty 1-D array (Hz)")
        if not np.all(np.isfinite(f)) or np.any(f <= 0.0):
            bad = f[~(np.isfinite(f) & (f > 0))][0]
            raise CaseError("frequency", float(bad), "every frequency must be finite and > 0 (Hz)")
        if f.size > 1 and np.any(np.diff(f) <= 0.0):
            raise CaseError("frequency", "non-increasing values", "strictly increasing (Hz)")
        f.setflags(write=False)
        object.__setattr__(self, "f", f)

    @classmethod
    def from_array(cls, f: ArrayLike) -> FrequencyGrid:
        """Grid from explicit frequencies in Hz.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, 1-D, strictly increasing, all > 0 (copied).

        Returns
        -------
        FrequencyGrid
        """
        return cls(np.asarray(f, dtype=float))

    @classmethod
    def linear(cls, f_min: float, f_max: float, step: float) -> FrequencyGrid:
        """Evenly spaced grid from `f_min` to `f_max` (inclusive where it lands) in Hz.

        Parameters
        ----------
        f_min : float
            First frequency in Hz (> 0).
        f_max : float
            Upper end of the band in Hz (> `f_min`); included when it falls on the grid.
        step : float
            Spacing in Hz (> 0).

        Returns
        -------
        FrequencyGrid
            ``f_min + step * k`` for ``k = 0, 1, ...`` up to `f_max`.

        Raises
        ------
        CaseError
            If the band or the step is not valid, or the grid would hold more than
            :data:`MAX_GRID_SIZE` frequencies.
        """
        n = cls.linear_size(f_min, f_max, step)
        return cls(np.asarray(f_min + step * np.arange(n), dtype=np.float64))

    @staticmethod
    def linear_size(f_min: float, f_max: float, step: float) -> int:
        """Number of frequencies of :meth:`linear` ``(f_min, f_max, step)``, without building it.

        Parameters
        ----------
        f_min : float
            First frequency in Hz (> 0).
        f_max : float
            Upper end of the band in Hz (> `f_min`).
        step : float
            Spacing in Hz (> 0).

        Returns
        -------
        int
            ``floor((f_max - f_min) / step) + 1`` (a grid point within 1e-9 steps of
            `f_max` counts).

        Raises
        ------
        CaseError
            If the band or the step is not valid, or the grid would hold more than
            :data:`MAX_GRID_SIZE` frequencies.
        """
        _check_band(f_min, f_max)
        if not (np.isfinite(step) and step > 0):
            raise CaseError("frequency.step", step, "must be a finite number > 0 (Hz)")
        count = np.floor((f_max - f_min) / step + 1e-9) + 1.0
        if not count <= MAX_GRID_SIZE:  # before int(): a huge float is no use as a count
            raise CaseError(
                "frequency.step",
                step,
                f"a grid of at most {MAX_GRID_SIZE:,} frequencies; this step gives "
                f"{count:.3g} over {f_min:g}-{f_max:g} Hz (Hz)",
            )
        return int(count)

    @classmethod
    def logarithmic(cls, f_min: float, f_max: float, n: int) -> FrequencyGrid:
        """`n` log-spaced frequencies from `f_min` to `f_max` in Hz."""
        _check_band(f_min, f_max)
        if not (isinstance(n, int | np.integer | float) and np.isfinite(n) and int(n) >= 2):
            raise CaseError("frequency.n", n, "must be an integer >= 2")
        if int(n) > MAX_GRID_SIZE:
            raise CaseError("frequency.n", n, f"at most {MAX_GRID_SIZE:,} frequencies")
        return cls(np.geomspace(f_min, f_max, int(n)))

    @property
    def omega(self) -> NDArray[np.float64]:
        """Circular frequencies in rad/s."""
        return 2.0 * np.pi * self.f

    def __len__(self) -> int:
        return int(self.f.size)

    def __repr__(self) -> str:
        return f"FrequencyGrid({self.f[0]:g}–{self.f[-1]:g} Hz, n={self.f.size})"


def _check_band(f_min: float, f_max: float) -> None:
    if not (np.isfinite(f_min) and f_min > 0):
        raise CaseError("frequency.f_min", f_min, "must be > 0 (Hz)")
    if not (np.isfinite(f_max) and f_max > f_min):
        raise CaseError("frequency.f_max", f_max, f"must be > f_min = {f_min} (Hz)")


def trapezoid(y: ArrayLike, f: ArrayLike, axis: int = -1) -> NDArray[np.float64]:
    """Trapezoidal integral of `y` over the frequencies `f` (Hz) along `axis`.

    The same arithmetic as :func:`scipy.integrate.trapezoid` with a 1-D `x`, so results
    are bit-identical to it, without importing :mod:`scipy.integrate` (which loads
    scipy.optimize: about 0.2 s at start-up).

    Parameters
    ----------
    y : array_like
        Samples, e.g. a one-sided PSD in unit^2/Hz; `axis` runs over `f`.
    f : array_like
        Frequencies in Hz, 1-D, one per sample along `axis`.
    axis : int
        The frequency axis of `y`.

    Returns
    -------
    numpy.ndarray
        ``sum((f[i+1] - f[i]) (y[i+1] + y[i]) / 2)`` over `axis`: `y`'s unit times Hz
        (a variance for a PSD); `y`'s shape without `axis`.
    """
    y = np.asarray(y)
    f = np.asarray(f)
    axis = axis % y.ndim
    d = f[1:] - f[:-1]
    d = d[tuple(slice(None) if i == axis else None for i in range(y.ndim))]
    upper = tuple(slice(1, None) if i == axis else slice(None) for i in range(y.ndim))
    lower = tuple(slice(None, -1) if i == axis else slice(None) for i in range(y.ndim))
    dtype = np.result_type(y.dtype, np.float64)
    return np.asarray(np.sum(d * (y[upper] + y[lower]) / 2.0, axis=axis, dtype=dtype))
