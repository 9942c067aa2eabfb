"""Linearity check: the dynamic contact force against the static load of each contact.

PEM (like any linear model) assumes the wheels never leave the rail. For a
Gaussian force with RMS ``sigma`` over the analysed band, the probability that
the dynamic force exceeds the static load ``P0`` in tension is ``Phi(-P0/sigma)``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr
from numpy.typing import NDArray
from scipy.special import ndtr  # Phi, the standard normal CDF (what scipy.stats.norm.cdf calls)

from railvib.grid import trapezoid
from railvib.labels import wheel_name
from railvib.outputs.base import OUTPUTS, DerivedOutput
from railvib.registry import parameter

__all__ = [
    "LOSS_OF_CONTACT_NOTE",
    "ContactCheck",
    "contact_line",
    "contact_table",
    "is_linear_model_valid",
    "loss_of_contact_arrays",
    "linearity_note",
    "loss_of_contact_threshold",
]

#: probability of loss of contact above which a case is beyond the linear model (the default
#: of ``output.loss_of_contact_threshold``; ``railvib run`` prints a note, ``--strict`` fails)
LOSS_OF_CONTACT_NOTE = 0.01


def _percent(p: float) -> str:
    """A probability as a percentage, e.g. ``"1 %"``."""
    return f"{100.0 * p:.3g} %"


@OUTPUTS.register("contact_check")
@dataclass(frozen=True)
class ContactCheck(DerivedOutput):
    """Contact-force RMS over the band and the Gaussian probability of loss of contact.

    A case is within the linear model (``linear_model_valid``) when the probability
    of loss of contact at its worst wheel is at most `loss_of_contact_threshold`.

    Parameters
    ----------
    loss_of_contact_threshold : float
        Largest probability of loss of contact (dimensionless, 0..1) for which the
        linear, permanent-contact model is trusted; default :data:`LOSS_OF_CONTACT_NOTE`.
    """

    loss_of_contact_threshold: float = parameter(
        "-",
        "largest probability of loss of contact (worst wheel) for which the linear "
        "(permanent-contact) model is trusted; case file: [output] loss_of_contact_threshold",
        default=LOSS_OF_CONTACT_NOTE,
        gt=0.0,
        lt=1.0,
        typical=(1e-3, 0.1),
        log=True,
    )

    def variable_attrs(self, f_lo: float, f_hi: float) -> dict[str, dict[str, Any]]:
        """``units`` and ``long_name`` (and the criterion) of each variable :meth:`compute` returns.

        Parameters
        ----------
        f_lo, f_hi : float
            The band of the force RMS, Hz (the ends of the frequency grid).

        Returns
        -------
        dict of dict
            By variable name: ``contact_force_rms`` (N), ``loss_of_contact_probability``
            (1) and ``linear_model_valid`` (boolean; its attributes give the threshold).
        """
        band = f"{f_lo:g}-{f_hi:g} Hz"
        threshold = self.loss_of_contact_threshold
        return {
            "contact_force_rms": {"units": "N", "long_name": f"contact force RMS, {band}"},
            "loss_of_contact_probability": {
                "units": "1",
                "long_name": "probability of loss of contact, Phi(-P0/sigma), Gaussian",
            },
            "linear_model_valid": {
                "units": "1",
                "long_name": "within the linear model: loss of contact at every wheel "
                f"<= {_percent(threshold)}",
                "loss_of_contact_threshold": threshold,
                "criterion": "max over wheels of loss_of_contact_probability "
                "<= loss_of_contact_threshold (output.loss_of_contact_threshold)",
            },
        }

    def compute(self, ds: xr.Dataset) -> dict[str, xr.DataArray]:
        """``contact_force_rms`` (N), ``loss_of_contact_probability`` and ``linear_model_valid``.

        Reads ``psd_force`` (N^2/Hz, over ``frequency`` and ``wheel``, optionally other
        dimensions such as the cases of a sweep) and ``static_contact_load`` (N, over
        ``wheel`` and optionally the same other dimensions) of `ds`. The force RMS and
        the probability are over ``wheel`` (and the other dimensions), the flag over
        the other dimensions only (a scalar for one run).
        """
        f = ds["frequency"].values
        psd = ds["psd_force"]
        axis = psd.get_axis_num("frequency")
        dims = tuple(str(d) for d in psd.dims if d != "frequency")
        p0 = ds["static_contact_load"].broadcast_like(psd.isel(frequency=0, drop=True))
        checked = self.variables(
            trapezoid(psd.values, f, axis=axis),
            p0.transpose(*dims).values,
            dims,
            float(f[0]),
            float(f[-1]),
        )
        return {name: xr.DataArray(var) for name, var in checked.items()}

    def variables(
        self,
        mean_square: NDArray[np.float64],
        static_load: NDArray[np.float64],
        dims: tuple[str, ...],
        f_lo: float,
        f_hi: float,
    ) -> dict[str, xr.Variable]:
        """The variables of :meth:`compute` from the mean square of the contact forces.

        Parameters
        ----------
        mean_square : numpy.ndarray
            Integral of each contact force's PSD over the grid, N^2 (over `dims`).
        static_load : numpy.ndarray
            The static load of each contact, N, the shape of `mean_square`.
        dims : tuple of str
            The dimensions of `mean_square`, ``wheel`` among them.
        f_lo, f_hi : float
            The band of the integral, Hz (the ends of the frequency grid).

        Returns
        -------
        dict of xarray.Variable
            ``contact_force_rms`` (N) and ``loss_of_contact_probability`` over `dims`,
            ``linear_model_valid`` over `dims` without ``wheel``.
        """
        sigma = np.sqrt(mean_square)
        probability = ndtr(-static_load / np.maximum(sigma, np.finfo(float).tiny))
        attrs = self.variable_attrs(f_lo, f_hi)
        # the worst wheel, NaN skipped as xarray's max skips it
        worst = np.fmax.reduce(probability, axis=dims.index("wheel"))
        rest = tuple(d for d in dims if d != "wheel")
        return {
            "contact_force_rms": xr.Variable(dims, sigma, attrs["contact_force_rms"]),
            "loss_of_contact_probability": xr.Variable(
                dims, probability, attrs["loss_of_contact_probability"]
            ),
            "linear_model_valid": xr.Variable(
                rest, worst <= self.loss_of_contact_threshold, attrs["linear_model_valid"]
            ),
        }


def loss_of_contact_threshold(ds: xr.Dataset) -> float:
    """The threshold (probability, dimensionless) `ds` was checked against.

    Parameters
    ----------
    ds : xarray.Dataset
        A result with the contact check; one computed before the flag existed gives
        :data:`LOSS_OF_CONTACT_NOTE`.

    Returns
    -------
    float
        The ``loss_of_contact_threshold`` attribute of ``linear_model_valid``.
    """
    if "linear_model_valid" in ds:
        return float(
            ds["linear_model_valid"].attrs.get("loss_of_contact_threshold", LOSS_OF_CONTACT_NOTE)
        )
    return LOSS_OF_CONTACT_NOTE


def is_linear_model_valid(ds: xr.Dataset) -> bool:
    """Whether every case of `ds` is within the linear model (loss of contact <= the threshold).

    Parameters
    ----------
    ds : xarray.Dataset
        A result with the contact check (one run, or a sweep: all its cases).

    Returns
    -------
    bool
        ``linear_model_valid`` of every case; for a dataset without the flag, the
        worst ``loss_of_contact_probability`` against :data:`LOSS_OF_CONTACT_NOTE`.
    """
    if "linear_model_valid" in ds:
        return bool(ds["linear_model_valid"].all())
    return float(ds["loss_of_contact_probability"].max()) <= LOSS_OF_CONTACT_NOTE


def contact_line(ds: xr.Dataset) -> str:
    """One line for a run's summary: the worst wheel's loss of contact against the threshold.

    Parameters
    ----------
    ds : xarray.Dataset
        A run's result with the contact check (over ``wheel`` only).

    Returns
    -------
    str
        E.g. ``"loss of contact: probability 0.132 % at the worst wheel (wheel 1: contact
        force RMS 2.62e+04 N, static load 8.02e+04 N); threshold 1 %: linear model valid"``.
    """
    prob = ds["loss_of_contact_probability"]
    j = int(prob.argmax("wheel"))
    wheel = wheel_name(ds["response"].values if "response" in ds.coords else (), j)
    rms = float(ds["contact_force_rms"].values[j])
    load = float(ds["static_contact_load"].values[j])
    verdict = (
        "linear model valid"
        if is_linear_model_valid(ds)
        else "BEYOND THE LINEAR MODEL (PEM assumes permanent contact)"
    )
    return (
        f"loss of contact: probability {_percent(float(prob.values[j]))} at the worst wheel "
        f"({wheel}: contact force RMS {rms:.3g} N, static load {load:.3g} N); "
        f"threshold {_percent(loss_of_contact_threshold(ds))}: {verdict}"
    )


def contact_table(ds: xr.Dataset) -> pd.DataFrame:
    """The contact check of one run per wheel: static load, force RMS (N) and probability.

    Parameters
    ----------
    ds : xarray.Dataset
        A run's result with the contact check (over ``wheel`` only).

    Returns
    -------
    pandas.DataFrame
        Indexed by ``wheel`` (its number; a train's wheel by its label, ``car2.wheel1``);
        columns ``static load [N]``, ``contact force RMS [N]`` and
        ``loss-of-contact probability [1]``.
    """
    wheels = ds["wheel"].values if "wheel" in ds.coords else np.arange(1, ds.sizes["wheel"] + 1)
    responses = ds["response"].values if "response" in ds.coords else ()
    names = [wheel_name(responses, j) for j in range(len(wheels))]
    if all("." in name for name in names):  # a train's wheels: by their label (car2.wheel1)
        wheels = np.array(names)
    return pd.DataFrame(
        {
            "static load [N]": ds["static_contact_load"].values,
            "contact force RMS [N]": ds["contact_force_rms"].values,
            "loss-of-contact probability [1]": ds["loss_of_contact_probability"].values,
        },
        index=pd.Index(wheels, name="wheel"),
    )


def linearity_note(ds: xr.Dataset) -> str | None:
    """A warning for the reader when loss of contact is likely (above the case's threshold).

    Parameters
    ----------
    ds : xarray.Dataset
        A result with the contact check (``loss_of_contact_probability``, ...).

    Returns
    -------
    str or None
        The note, or None when the loss of contact is at most the threshold
        (:func:`loss_of_contact_threshold`, by default :data:`LOSS_OF_CONTACT_NOTE`).
    """
    worst = float(ds["loss_of_contact_probability"].max())
    if worst <= loss_of_contact_threshold(ds):
        return None
    return (
        f"note: dynamic contact force RMS {float(ds['contact_force_rms'].max()):.3g} N against "
        f"a static load of {float(ds['static_contact_load'].min()):.3g} N: loss of wheel-rail "
        f"contact has probability {worst:.1%} (Gaussian estimate). PEM assumes permanent "
        "contact, so treat the results near the contact resonances with care."
    )


def loss_of_contact_arrays(
    sigma: NDArray[np.float64], static_load: NDArray[np.float64], threshold: float
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """:meth:`ContactCheck.compute`'s probability and flag from the force RMS, in NumPy arrays.

    The same operations on the same values (bit for bit), without labelled arrays.

    Parameters
    ----------
    sigma : numpy.ndarray
        Contact force RMS over the grid, N, ``(..., n_wheel)``.
    static_load : numpy.ndarray
        Static load of each contact, N, broadcastable to `sigma`.
    threshold : float
        Largest probability of loss of contact within the linear model (dimensionless).

    Returns
    -------
    probability : numpy.ndarray
        ``Phi(-P0 / sigma)``, ``(..., n_wheel)``.
    valid : numpy.ndarray
        Whether every wheel's probability is at most `threshold`, ``(...)``.
    """
    probability = ndtr(-static_load / np.maximum(sigma, np.finfo(float).tiny))
    return probability, probability.max(axis=-1) <= threshold
