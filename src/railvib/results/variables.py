"""Per-frequency result variables: defined once, computed from one :class:`~railvib.response.FRF`.

Every dataset railvib writes (one run, a sweep, a validation) takes the
variables' dimensions, units and long names from :data:`VARIABLES` and their
values from :func:`compute_variables`, so a new result variable is one entry
here.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from railvib.response import FRF
from railvib.results.units import QUANTITY_UNITS, quantity_unit

__all__ = [
    "PER_FREQUENCY",
    "VARIABLES",
    "ResultVariable",
    "compute_variables",
    "response_psds",
    "write_variables",
]

_Compute = Callable[[FRF, NDArray[np.float64]], NDArray[np.generic]]


@dataclass(frozen=True)
class ResultVariable:
    """One per-frequency result variable.

    Parameters
    ----------
    name : str
        Variable name in the dataset.
    extra_dim : {"response", "wheel"} or None
        The dimension after ``frequency`` (None: frequency only).
    units : str
        Units of the values (of the bounce responses where pitch differs; see `note`
        and :func:`railvib.results.units.quantity_unit`, which gives each response's).
    long_name : str
        Description for plots and files.
    note : str
        Further explanation (e.g. the unit of pitch responses), or "".
    compute : callable
        ``compute(frf, irregularity_psd)`` -> values ``(..., n_freq[, n])``; leading
        batch axes of `frf` and of the one-sided irregularity PSD (m^2/Hz,
        ``(..., n_freq)``) are kept.
    """

    name: str
    extra_dim: str | None
    units: str
    long_name: str
    note: str
    compute: _Compute

    @property
    def dims(self) -> tuple[str, ...]:
        """Dimensions of one case's values."""
        return ("frequency",) if self.extra_dim is None else ("frequency", self.extra_dim)

    @property
    def attrs(self) -> dict[str, str]:
        """``units``, ``long_name`` and (if any) ``note``."""
        out = {"units": self.units, "long_name": self.long_name}
        if self.note:
            out["note"] = self.note
        return out


def _psd(h: NDArray[np.complex128], s_r: NDArray[np.float64]) -> NDArray[np.float64]:
    """``|H|^2 S_r`` with the input PSD broadcast over the last (response) axis."""
    return np.abs(h) ** 2 * s_r[..., None]


def _omega4(f: NDArray[np.float64]) -> NDArray[np.float64]:
    return ((2.0 * np.pi * f) ** 4)[:, None]


def _psd_displacement(frf: FRF, s_r: NDArray[np.float64]) -> NDArray[np.float64]:
    return _psd(frf.displacement, s_r)


def _psd_acceleration(frf: FRF, s_r: NDArray[np.float64]) -> NDArray[np.float64]:
    return _psd_displacement(frf, s_r) * _omega4(frf.f)


def _psd_force(frf: FRF, s_r: NDArray[np.float64]) -> NDArray[np.float64]:
    return _psd(frf.contact_force, s_r)


def _variables(*items: ResultVariable) -> dict[str, ResultVariable]:
    return {v.name: v for v in items}


def _pitch(quantity: str) -> str:
    """The unit of `quantity` of a pitch (rotational) response."""
    return QUANTITY_UNITS[quantity].format(d="rad")


#: every per-frequency result variable, by name
VARIABLES: dict[str, ResultVariable] = _variables(
    ResultVariable(
        "psd_acceleration",
        "response",
        quantity_unit("psd_acceleration"),
        "acceleration PSD",
        f"pitch responses are in {_pitch('psd_acceleration')}",
        _psd_acceleration,
    ),
    ResultVariable(
        "psd_displacement",
        "response",
        quantity_unit("psd_displacement"),
        "displacement PSD",
        f"pitch responses are in {_pitch('psd_displacement')}",
        _psd_displacement,
    ),
    ResultVariable(
        "frf_displacement",
        "response",
        quantity_unit("frf_displacement"),
        "displacement per unit irregularity (complex)",
        f"pitch responses are in {_pitch('frf_displacement')}; exp(+i omega t); "
        "input = profile at the leading wheel",
        lambda frf, s_r: frf.displacement,
    ),
    ResultVariable(
        "psd_force",
        "wheel",
        quantity_unit("psd_force"),
        "dynamic wheel-rail contact force PSD",
        "",
        _psd_force,
    ),
    ResultVariable(
        "frf_force",
        "wheel",
        quantity_unit("frf_force"),
        "contact force per unit irregularity (complex)",
        "",
        lambda frf, s_r: frf.contact_force,
    ),
    ResultVariable(
        "irregularity_psd",
        None,
        quantity_unit("irregularity_psd"),
        "irregularity PSD applied",
        "",
        lambda frf, s_r: s_r,
    ),
)

#: the variables a sweep may store per frequency (the real-valued ones)
PER_FREQUENCY = ("psd_acceleration", "psd_displacement", "psd_force", "irregularity_psd")


def compute_variables(
    frf: FRF, irregularity_psd: NDArray[np.float64], names: Iterable[str]
) -> dict[str, NDArray[np.generic]]:
    """Values of the variables `names` for the responses `frf` to an irregularity.

    Parameters
    ----------
    frf : FRF
        Responses per metre of irregularity, optionally with leading batch axes.
    irregularity_psd : numpy.ndarray
        One-sided temporal irregularity PSD, m^2/Hz, ``(..., n_freq)`` with the same
        batch axes as `frf`.
    names : iterable of str
        Keys of :data:`VARIABLES`.

    Returns
    -------
    dict of numpy.ndarray
        Values ``(..., n_freq[, n_resp or n_wheel])`` by name.
    """
    s_r = np.asarray(irregularity_psd, dtype=float)
    return {name: VARIABLES[name].compute(frf, s_r) for name in names}


def write_variables(
    out: Mapping[str, NDArray[np.generic]], frf: FRF, irregularity_psd: NDArray[np.float64]
) -> None:
    """The values of every variable of :data:`VARIABLES` written into `out`, in place.

    The same operations on the same values as :func:`compute_variables` (bit for bit),
    without its temporaries: the vehicle's and the rail's parts written into their
    columns (no joined copy), ``psd_acceleration`` from the ``psd_displacement`` just
    written (``|H|^2 S_r`` once), each result straight into its place.

    Parameters
    ----------
    out : mapping of str to numpy.ndarray
        By name of every variable of :data:`VARIABLES`, the arrays to fill, ``(n_freq[,
        n_resp or n_wheel])`` (e.g. one block's rows of the whole grid's arrays).
    frf : FRF
        Responses per metre of irregularity, ``(n_freq, ...)`` (no batch axes).
    irregularity_psd : numpy.ndarray
        One-sided temporal irregularity PSD, m^2/Hz, ``(n_freq,)``.
    """
    s_r = np.asarray(irregularity_psd, dtype=float)
    n_dof = frf.vehicle.shape[-1]
    displacement = out["frf_displacement"]
    displacement[:, :n_dof] = frf.vehicle
    displacement[:, n_dof:] = frf.rail
    _psd_into(displacement, s_r, out["psd_displacement"])
    np.multiply(out["psd_displacement"], _omega4(frf.f), out=out["psd_acceleration"])
    out["frf_force"][...] = frf.contact_force
    _psd_into(frf.contact_force, s_r, out["psd_force"])
    out["irregularity_psd"][...] = s_r


def _psd_into(h: NDArray[np.generic], s_r: NDArray[np.float64], out: NDArray[np.generic]) -> None:
    """:func:`_psd` written into `out`: ``|H|`` there, squared and scaled in place."""
    np.abs(h, out=out)
    np.multiply(out, out, out=out)  # what ``** 2`` computes
    np.multiply(out, s_r[:, None], out=out)


def response_psds(
    frf: FRF, irregularity_psd: NDArray[np.float64], acceleration: bool
) -> NDArray[np.float64]:
    """``psd_acceleration`` (or ``psd_displacement``) of :data:`VARIABLES`, written in place.

    The same operations on the same values (bit for bit), the vehicle's and the rail's
    parts each written into its columns of the result: without the complex copy of
    :attr:`railvib.response.FRF.displacement` that joins them first, and without the
    intermediate arrays of the whole (half the time on a sweep's chunk of cases).

    Parameters
    ----------
    frf : FRF
        Responses per metre of irregularity, optionally with leading batch axes.
    irregularity_psd : numpy.ndarray
        One-sided temporal irregularity PSD, m^2/Hz, ``(..., n_freq)``.
    acceleration : bool
        Acceleration PSDs, (m/s^2)^2/Hz (else displacement PSDs, m^2/Hz); a pitch
        response's per radian.

    Returns
    -------
    numpy.ndarray
        ``(..., n_freq, n_resp)``, the vehicle's DOFs then the rail at each wheel.
    """
    s_r = np.asarray(irregularity_psd, dtype=float)[..., None]
    n_dof = frf.vehicle.shape[-1]
    out = np.empty((*frf.vehicle.shape[:-1], n_dof + frf.rail.shape[-1]))
    for part, columns in ((frf.vehicle, slice(0, n_dof)), (frf.rail, slice(n_dof, None))):
        if acceleration:
            np.multiply(np.abs(part) ** 2 * s_r, _omega4(frf.f), out=out[..., columns])
        else:
            np.multiply(np.abs(part) ** 2, s_r, out=out[..., columns])
    return out
