"""Linearity check: the dynamic contact force against the static load of each contact.

PEM (like any linear model) assumes the wheels never leave the rail. For a
Gaussian force with RMS ``sigma`` over the analysed band, the probability that
the dynamic force exceeds the static load ``P0`` in tension is ``Phi(-P0/sigma)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr
from scipy.integrate import trapezoid
from scipy.stats import norm

from railvib.outputs.base import OUTPUTS, DerivedOutput

__all__ = ["LOSS_OF_CONTACT_NOTE", "ContactCheck", "linearity_note"]

#: probability of loss of contact above which ``railvib run`` prints a note
LOSS_OF_CONTACT_NOTE = 0.01


@OUTPUTS.register("contact_check")
@dataclass(frozen=True)
class ContactCheck(DerivedOutput):
    """Contact-force RMS over the band and the Gaussian probability of loss of contact."""

    def compute(self, ds: xr.Dataset) -> dict[str, xr.DataArray]:
        """``contact_force_rms`` (N) and ``loss_of_contact_probability`` (-), over ``wheel``.

        Reads ``psd_force`` (N^2/Hz) and ``static_contact_load`` (N) of `ds`.
        """
        f = ds["frequency"].values
        sigma = np.sqrt(trapezoid(ds["psd_force"].values, f, axis=0))
        p0 = ds["static_contact_load"].values
        probability = norm.cdf(-p0 / np.maximum(sigma, np.finfo(float).tiny))
        band = f"{f[0]:g}-{f[-1]:g} Hz"
        return {
            "contact_force_rms": xr.DataArray(
                sigma,
                dims=("wheel",),
                attrs={"units": "N", "long_name": f"contact force RMS, {band}"},
            ),
            "loss_of_contact_probability": xr.DataArray(
                probability,
                dims=("wheel",),
                attrs={
                    "units": "1",
                    "long_name": "probability of loss of contact, Phi(-P0/sigma), Gaussian",
                },
            ),
        }


def linearity_note(ds: xr.Dataset) -> str | None:
    """A warning for the reader when loss of contact is likely (above :data:`LOSS_OF_CONTACT_NOTE`).

    Parameters
    ----------
    ds : xarray.Dataset
        A result with the contact check (``loss_of_contact_probability``, ...).

    Returns
    -------
    str or None
        The note, or None when contact is almost surely kept.
    """
    worst = float(ds["loss_of_contact_probability"].max())
    if worst <= LOSS_OF_CONTACT_NOTE:
        return None
    return (
        f"note: dynamic contact force RMS {float(ds['contact_force_rms'].max()):.3g} N against "
        f"a static load of {float(ds['static_contact_load'].min()):.3g} N: loss of wheel-rail "
        f"contact has probability {worst:.1%} (Gaussian estimate). PEM assumes permanent "
        "contact, so treat the results near the contact resonances with care."
    )
