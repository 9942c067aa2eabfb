"""The unit of every result quantity of every response: the one table all writers read.

A response is translational (a bounce DOF, the rail: displacements in m) or
rotational (a pitch DOF: rad), :func:`railvib.response.displacement_unit`. The
unit of each quantity follows from that: an acceleration PSD is (m/s^2)^2/Hz for
a bounce response and (rad/s^2)^2/Hz for a pitch response; forces are N
whatever the wheel. Datasets, CSV headers, summary tables, Markdown and plot
labels all take their units from :func:`quantity_unit` (directly or through the
per-response units coordinates that :func:`with_unit_coordinates` adds), so a
figure never stands next to the unit of another quantity.

Layout of the units in a dataset: a variable over ``response`` whose unit
differs between responses keeps, as its ``units`` attribute, the unit of its
translational responses, and names in its ``units_coordinate`` attribute a
string coordinate over ``response`` holding the unit of each response
(``<quantity>_unit``, e.g. ``psd_acceleration_unit``; ``displacement_unit`` is
the displacement's).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence

import xarray as xr

from railvib.labels import displacement_unit

__all__ = [
    "QUANTITY_UNITS",
    "RMS_QUANTITY",
    "quantity_unit",
    "response_units",
    "rms_quantity",
    "summary_quantity",
    "unit_coordinate_name",
    "unit_coordinates",
    "with_unit_coordinates",
]

#: unit of each quantity; ``{d}`` is the displacement unit of the response (m or rad)
QUANTITY_UNITS: dict[str, str] = {
    "displacement": "{d}",
    "acceleration": "{d}/s^2",
    "psd_displacement": "{d}^2/Hz",
    "psd_acceleration": "({d}/s^2)^2/Hz",
    "frf_displacement": "{d}/m",
    "force": "N",
    "psd_force": "N^2/Hz",
    "frf_force": "N/m",
    "irregularity": "m",
    "irregularity_psd": "m^2/Hz",
    "frequency": "Hz",
}

#: the amplitude quantity of each PSD: the unit of its RMS (square root of the PSD times Hz)
RMS_QUANTITY: dict[str, str] = {
    "psd_displacement": "displacement",
    "psd_acceleration": "acceleration",
    "psd_force": "force",
    "irregularity_psd": "irregularity",
}


def quantity_unit(quantity: str, response: str | None = None) -> str:
    """Unit of `quantity` of response `response`.

    Parameters
    ----------
    quantity : str
        A key of :data:`QUANTITY_UNITS`, e.g. ``"psd_acceleration"`` or ``"acceleration"``.
    response : str, optional
        Response label (``"carbody.pitch"``, ``"rail@wheel1"``); None: a translational
        response (the unit in m).

    Returns
    -------
    str
        E.g. ``"(rad/s^2)^2/Hz"`` for the acceleration PSD of a pitch DOF.

    Raises
    ------
    KeyError
        `quantity` is not in :data:`QUANTITY_UNITS`.
    """
    d = "m" if response is None else displacement_unit(response)
    return QUANTITY_UNITS[quantity].format(d=d)


def rms_quantity(variable: str) -> str | None:
    """The quantity whose unit the RMS of PSD `variable` has (None if `variable` is no PSD)."""
    return RMS_QUANTITY.get(variable)


def summary_quantity(name: str, variable: str) -> str | None:
    """The quantity of summary statistic `name` of PSD `variable` (None: not in the table).

    Parameters
    ----------
    name : str
        ``peak``, ``dominant_frequency``, ``rms`` or ``rms_<lo>_<hi>_hz``.
    variable : str
        The PSD summarised, e.g. ``"psd_acceleration"``.

    Returns
    -------
    str or None
        ``variable`` for the peak, ``"frequency"`` for the dominant frequency, the
        amplitude quantity (:data:`RMS_QUANTITY`) for an RMS.
    """
    if name == "dominant_frequency":
        return "frequency"
    if variable not in QUANTITY_UNITS:
        return None
    return variable if name == "peak" else rms_quantity(variable)


def response_units(quantity: str, responses: Iterable[str]) -> list[str]:
    """Unit of `quantity` for each response label of `responses` (:func:`quantity_unit`)."""
    return [quantity_unit(quantity, str(r)) for r in responses]


def unit_coordinate_name(quantity: str) -> str:
    """Name of the per-response units coordinate of `quantity`: ``<quantity>_unit``."""
    return f"{quantity}_unit"


def unit_coordinates(
    quantities: Mapping[str, str], labels: Sequence[str]
) -> tuple[dict[str, xr.Variable], dict[str, str]]:
    """The per-response units coordinates of the variables `quantities` over responses `labels`.

    Parameters
    ----------
    quantities : mapping of str to str
        Variable name (over ``response``) -> its quantity (a key of :data:`QUANTITY_UNITS`).
    labels : sequence of str
        The response labels.

    Returns
    -------
    coords : dict of str to xarray.Variable
        ``<quantity>_unit`` -> the unit of each response, for each quantity whose unit
        differs between the responses.
    named : dict of str to str
        Variable name -> the name of its units coordinate (the variables of `coords`).
    """
    coords: dict[str, xr.Variable] = {}
    named: dict[str, str] = {}
    for name, quantity in quantities.items():
        units = response_units(quantity, labels)
        if len(set(units)) < 2:
            continue
        coord = unit_coordinate_name(quantity)
        if coord not in coords:
            attrs = {"long_name": f"unit of the {quantity.replace('_', ' ')} of each response"}
            coords[coord] = xr.Variable("response", units, attrs)
        named[name] = coord
    return coords, named


def with_unit_coordinates(ds: xr.Dataset, quantities: Mapping[str, str]) -> xr.Dataset:
    """`ds` with a per-response units coordinate for each variable whose unit varies by response.

    Parameters
    ----------
    ds : xarray.Dataset
        A dataset with a ``response`` dimension of response labels.
    quantities : mapping of str to str
        Data variable name -> its quantity (a key of :data:`QUANTITY_UNITS`).
        Variables without a ``response`` dimension, or whose unit is the same for
        every response, are left as they are.

    Returns
    -------
    xarray.Dataset
        A new dataset: coordinates ``<quantity>_unit`` over ``response`` and, on each
        such variable, the attribute ``units_coordinate`` naming its coordinate.
    """
    out = ds.copy()  # new variables (and attribute dicts) over the same data
    labels = [str(r) for r in ds["response"].values] if "response" in ds.dims else []
    over = {
        name: quantity
        for name, quantity in quantities.items()
        if name in out.data_vars and "response" in out[name].dims
    }
    coords, named = unit_coordinates(over, labels)
    for name, coord in named.items():
        # in place on the copy: assigning a variable would align the whole dataset again
        out.variables[name].attrs["units_coordinate"] = coord
    new = {k: v for k, v in coords.items() if k not in out.coords}
    return out.assign_coords(new) if new else out
