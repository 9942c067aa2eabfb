"""Wheel-rail force criteria: dynamic force RMS, the 3-sigma dynamic load and load factor.

With the dynamic contact force Gaussian, of RMS ``sigma`` over the band, and the
static load ``P0`` of the wheel, the design dynamic load is ``3 sigma`` (exceeded
with probability 0.13 %) and the dynamic load factor ``1 + 3 sigma / P0`` (the
"3-sigma" rule of track design, e.g. Esveld, *Modern Railway Track*, 2001, 4.4).
The probability of loss of contact ``Phi(-P0/sigma)`` is the contact check
(:class:`railvib.outputs.ContactCheck`), reported among these criteria.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from railvib.grid import trapezoid
from railvib.outputs.base import OUTPUTS, DerivedOutput

__all__ = ["WheelRailForces", "dynamic_load_arrays"]


@OUTPUTS.register("wheel_rail_forces")
@dataclass(frozen=True)
class WheelRailForces(DerivedOutput):
    """The 3-sigma dynamic load and the dynamic load factor of each wheel and of the car."""

    def variable_attrs(self, f_lo: float, f_hi: float) -> dict[str, dict[str, str]]:
        """``units`` and ``long_name`` of each variable :meth:`compute` returns.

        Parameters
        ----------
        f_lo, f_hi : float
            The band of the force RMS, Hz (the ends of the frequency grid).

        Returns
        -------
        dict of dict
            By variable name.
        """
        band = f"{f_lo:g}-{f_hi:g} Hz"
        return {
            "dynamic_load_3sigma": {
                "units": "N",
                "long_name": f"3-sigma dynamic contact load, {band}",
            },
            "dynamic_load_factor": {
                "units": "1",
                "long_name": f"dynamic load factor 1 + 3 sigma / P0, {band}",
            },
            "car_dynamic_load_factor": {
                "units": "1",
                "long_name": f"dynamic load factor of the car (worst wheel), {band}",
            },
        }

    def compute(self, ds: xr.Dataset) -> dict[str, xr.DataArray]:
        """``dynamic_load_3sigma`` (N) and ``dynamic_load_factor`` per wheel; the car's worst.

        Reads ``psd_force`` (N^2/Hz, ``frequency`` x ``wheel``, optionally other dimensions)
        and ``static_contact_load`` (N, over ``wheel``).
        """
        f = ds["frequency"].values
        psd = ds["psd_force"]
        dims = tuple(d for d in psd.dims if d != "frequency")
        sigma = xr.DataArray(
            np.sqrt(trapezoid(psd.values, f, axis=psd.get_axis_num("frequency"))), dims=dims
        )
        p0 = ds["static_contact_load"].broadcast_like(sigma)
        attrs = self.variable_attrs(float(f[0]), float(f[-1]))
        factor = 1.0 + 3.0 * sigma / p0
        return {
            "dynamic_load_3sigma": (3.0 * sigma).assign_attrs(attrs["dynamic_load_3sigma"]),
            "dynamic_load_factor": factor.assign_attrs(attrs["dynamic_load_factor"]),
            "car_dynamic_load_factor": factor.max("wheel").assign_attrs(
                attrs["car_dynamic_load_factor"]
            ),
        }


def dynamic_load_arrays(
    sigma: NDArray[np.float64], static_load: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """:meth:`WheelRailForces.compute`'s load factors from the force RMS, in NumPy arrays.

    The same operations on the same values (bit for bit), without labelled arrays.

    Parameters
    ----------
    sigma : numpy.ndarray
        Contact force RMS over the grid, N, ``(..., n_wheel)``.
    static_load : numpy.ndarray
        Static load of each wheel, N, broadcastable to `sigma`.

    Returns
    -------
    factor : numpy.ndarray
        ``1 + 3 sigma / P0`` of each wheel, ``(..., n_wheel)``.
    car_factor : numpy.ndarray
        The worst wheel's, ``(...)``.
    """
    factor = 1.0 + 3.0 * sigma / static_load
    return factor, factor.max(axis=-1)
