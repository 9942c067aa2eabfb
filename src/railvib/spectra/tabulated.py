"""A user-supplied spatial spectrum, interpolated linearly in log-log."""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from railvib.errors import CaseError, excerpt
from railvib.io import MAX_TABLE_BYTES, read_text
from railvib.registry import Parameter
from railvib.spectra._checks import as_wavenumber
from railvib.spectra.base import SPECTRA, SpatialSpectrum

__all__ = ["Tabulated"]

#: Abscissa columns and their conversion to wavenumber Omega in rad/m.
ABSCISSA_COLUMNS = {
    "wavelength_m": lambda x: 2.0 * np.pi / x,
    "spatial_frequency_cycle_per_m": lambda x: 2.0 * np.pi * x,
    "wavenumber_rad_per_m": lambda x: x,
}
#: PSD columns and their conversion to m^2/(rad/m): S(Omega) = S(n) / (2 pi).
PSD_COLUMNS = {
    "psd_m2_per_cycle_per_m": lambda s: s / (2.0 * np.pi),
    "psd_m2_per_rad_per_m": lambda s: s,
}
COLUMN_UNITS = {
    "wavelength_m": "m",
    "spatial_frequency_cycle_per_m": "cycle/m",
    "wavenumber_rad_per_m": "rad/m",
    "psd_m2_per_cycle_per_m": "m^2/(cycle/m)",
    "psd_m2_per_rad_per_m": "m^2/(rad/m)",
}


#: largest wavenumber of a table, rad/m (a wavelength of 6 um: below any roughness measured)
MAX_WAVENUMBER_RAD_PER_M = 1e6
#: largest PSD of a table, m^2/(rad/m) (FRA class 1, the worst track, stays below 1e-4 above
#: 0.01 rad/m): keeps every response PSD finite
MAX_PSD_M2_PER_RAD_PER_M = 1.0


def _check_column(name: str, values: NDArray[np.float64], unit: str) -> None:
    ok = np.isfinite(values) & (values > 0.0)
    if not np.all(ok):
        bad = float(values[~ok][0])
        raise CaseError(name, bad, f"every value must be finite and > 0 ({unit})")


def _check_at_most(name: str, values: NDArray[np.float64], limit: float, unit: str) -> None:
    if np.any(values > limit):
        bad = float(values[values > limit][0])
        raise CaseError(name, bad, f"every value must be <= {limit:g} ({unit})")


#: keys of a ``type = "tabulated"`` table: a CSV file, or the two arrays inline
TABLE_PARAMETERS = (
    Parameter(
        "path",
        "",
        "CSV file (relative to the case file): one abscissa and one PSD column",
        "path",
        default=None,
    ),
    Parameter("delimiter", "", "field separator of the CSV file", "text", default=","),
    Parameter(
        "wavenumber_rad_per_m",
        "rad/m",
        "wavenumbers, inline",
        "numbers",
        default=None,
        gt=0.0,
        le=MAX_WAVENUMBER_RAD_PER_M,
    ),
    Parameter(
        "psd_m2_per_rad_per_m",
        "m^2/(rad/m)",
        "PSD values, inline",
        "numbers",
        default=None,
        gt=0.0,
        le=MAX_PSD_M2_PER_RAD_PER_M,
    ),
)


@dataclass(frozen=True, eq=False)
class Tabulated(SpatialSpectrum):
    """Tabulated one-sided spatial PSD, interpolated linearly in log(S) against log(Omega).

    Outside the tabulated wavenumber range the PSD is **zero**: no content is invented
    beyond what the user measured. Combine it with another spectrum via
    :class:`~railvib.spectra.Combined` to cover a wider band.

    Parameters
    ----------
    wavenumber_rad_per_m : array_like
        Spatial circular frequencies Omega in rad/m: 1-D, at least 2, finite, > 0, distinct
        (any order; they are sorted).
    psd_m2_per_rad_per_m : array_like
        One-sided PSD in m^2/(rad/m) at those wavenumbers: same length, finite, > 0.
    """

    wavenumber_rad_per_m: NDArray[np.float64] = field(repr=False)
    psd_m2_per_rad_per_m: NDArray[np.float64] = field(repr=False)

    def validate(self) -> None:
        """A 1-D table of >= 2 distinct, positive wavenumbers and positive PSDs (sorted here)."""
        om = np.asarray(self.wavenumber_rad_per_m, dtype=float)
        s = np.asarray(self.psd_m2_per_rad_per_m, dtype=float)
        if om.ndim != 1 or om.size < 2:
            raise CaseError(
                "wavenumber_rad_per_m", f"array of shape {om.shape}", "a 1-D table of >= 2 rows"
            )
        if s.shape != om.shape:
            raise CaseError(
                "psd_m2_per_rad_per_m", f"array of shape {s.shape}", f"shape {om.shape}"
            )
        _check_column("wavenumber_rad_per_m", om, "rad/m")
        _check_column("psd_m2_per_rad_per_m", s, "m^2/(rad/m)")
        _check_at_most("wavenumber_rad_per_m", om, MAX_WAVENUMBER_RAD_PER_M, "rad/m")
        _check_at_most("psd_m2_per_rad_per_m", s, MAX_PSD_M2_PER_RAD_PER_M, "m^2/(rad/m)")
        order = np.argsort(om)
        om, s = om[order], s[order]
        if np.any(np.diff(om) <= 0.0):
            dup = float(om[1:][np.diff(om) <= 0.0][0])
            raise CaseError("wavenumber_rad_per_m", dup, "distinct wavenumbers (rad/m)")
        for name, arr in (("wavenumber_rad_per_m", om), ("psd_m2_per_rad_per_m", s)):
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)

    @classmethod
    def from_csv(cls, path: str | Path, *, delimiter: str = ",") -> Tabulated:
        """Read a table from a CSV file with a header row.

        Parameters
        ----------
        path : str or pathlib.Path
            CSV file. Exactly two columns: one abscissa, ``wavelength_m`` (m),
            ``spatial_frequency_cycle_per_m`` (cycle/m) or ``wavenumber_rad_per_m`` (rad/m);
            and one PSD, ``psd_m2_per_cycle_per_m`` (m^2/(cycle/m)) or
            ``psd_m2_per_rad_per_m`` (m^2/(rad/m)). Converted to Omega and m^2/(rad/m).
        delimiter : str
            Field separator. Default ",".

        Raises
        ------
        CaseError
            A file :func:`railvib.io.read_text` refuses (unreadable, not a regular file,
            over :data:`railvib.io.MAX_TABLE_BYTES`, binary, not UTF-8), a file that is
            not such a table, unknown / missing / repeated column, non-numeric cell, or a
            table that fails the checks of :class:`Tabulated`. Messages show at most a
            short excerpt of the file.
        """
        _check_delimiter(delimiter)
        text = read_text(path, "path", "CSV table", max_bytes=MAX_TABLE_BYTES)
        try:
            rows = [
                r
                for r in csv.reader(io.StringIO(text, newline=""), delimiter=delimiter)
                if any(c.strip() for c in r)
            ]
        except csv.Error as exc:
            raise CaseError("path", str(path), f"a CSV table ({exc})") from None
        if not rows:
            raise CaseError("path", str(path), "a CSV file with a header row and >= 2 data rows")
        header = [c.strip() for c in rows[0]]
        allowed = ", ".join([*ABSCISSA_COLUMNS, *PSD_COLUMNS])
        if not any(name in ABSCISSA_COLUMNS or name in PSD_COLUMNS for name in header):
            raise CaseError(
                "path",
                str(path),
                f"a CSV table whose header row names its columns, two of {allowed}; the "
                "first line of this file names none of them: it is not such a table",
            )
        for name in header:
            if name not in ABSCISSA_COLUMNS and name not in PSD_COLUMNS:
                raise CaseError("column", excerpt(name, 24), f"one of {allowed}")
        if len(set(header)) != len(header):
            raise CaseError("column", header, "each column at most once")
        x_cols = [c for c in header if c in ABSCISSA_COLUMNS]
        s_cols = [c for c in header if c in PSD_COLUMNS]
        if len(x_cols) != 1:
            raise CaseError("column", x_cols, f"exactly one of {', '.join(ABSCISSA_COLUMNS)}")
        if len(s_cols) != 1:
            raise CaseError("column", s_cols, f"exactly one of {', '.join(PSD_COLUMNS)}")
        data = np.empty((len(rows) - 1, 2))
        for i, row in enumerate(rows[1:], start=2):
            if len(row) != len(header):
                raise CaseError(f"row {i}", excerpt(delimiter.join(row)), f"{len(header)} cells")
            try:
                cells = dict(zip(header, (float(c) for c in row), strict=True))
            except ValueError:
                raise CaseError(f"row {i}", excerpt(delimiter.join(row)), "numbers only") from None
            data[i - 2] = cells[x_cols[0]], cells[s_cols[0]]
        x, s = data[:, 0], data[:, 1]
        if x.size < 2:
            raise CaseError("path", str(path), "a table with >= 2 data rows")
        _check_column(x_cols[0], x, COLUMN_UNITS[x_cols[0]])
        _check_column(s_cols[0], s, COLUMN_UNITS[s_cols[0]])
        return cls(ABSCISSA_COLUMNS[x_cols[0]](x), PSD_COLUMNS[s_cols[0]](s))

    def psd(self, wavenumber: ArrayLike) -> NDArray[np.float64]:
        """One-sided PSD in m^2/(rad/m) at `wavenumber` (rad/m, > 0); zero outside the table."""
        om = as_wavenumber(wavenumber)
        log_om = np.log(self.wavenumber_rad_per_m)
        log_s = np.log(self.psd_m2_per_rad_per_m)
        s = np.exp(np.interp(np.log(om), log_om, log_s))
        inside = (om >= self.wavenumber_rad_per_m[0]) & (om <= self.wavenumber_rad_per_m[-1])
        return np.where(inside, s, 0.0)


#: characters a CSV delimiter cannot be: they belong to numbers, quotes or line breaks
_NOT_DELIMITERS = set(".+-eE\"'\r\n")


def _check_delimiter(delimiter: Any) -> None:
    """Refuse a delimiter that is not one character a table of numbers can be split at."""
    ok = (
        isinstance(delimiter, str)
        and len(delimiter) == 1
        and not delimiter.isalnum()
        and delimiter not in _NOT_DELIMITERS
    )
    if not ok:
        raise CaseError(
            "delimiter",
            delimiter,
            "one character that is not a letter, digit, '.', '+', '-', quote or line break "
            "(e.g. ',', ';' or a tab)",
        )


def _from_table(**d: Any) -> Tabulated:
    """Build a :class:`Tabulated` from a table's keys (see :data:`TABLE_PARAMETERS`)."""
    has_path = "path" in d
    has_arrays = "wavenumber_rad_per_m" in d or "psd_m2_per_rad_per_m" in d
    if has_path == has_arrays:
        raise CaseError(
            "", sorted(d), "either 'path' or both 'wavenumber_rad_per_m' and 'psd_m2_per_rad_per_m'"
        )
    if has_path:
        return Tabulated.from_csv(
            d["path"], **({"delimiter": d["delimiter"]} if "delimiter" in d else {})
        )
    if "delimiter" in d:
        raise CaseError("delimiter", d["delimiter"], "only together with 'path'")
    for key in ("wavenumber_rad_per_m", "psd_m2_per_rad_per_m"):
        if key not in d:
            raise CaseError(key, None, "required with the other array (list)")
    return Tabulated(**d)


SPECTRA.register("tabulated", parameters=TABLE_PARAMETERS, build=_from_table)(Tabulated)
