"""The summary of a train car by car: each car's worst responses, and the train's worst.

A train's responses carry their car (``car2.carbody.bounce``, ``rail@car3.wheel2``;
:func:`railvib.vehicle.make_train`); one row per car gathers the car body's bounce RMS,
the worst rail RMS under its wheels and the worst contact check of its wheels, and the
last row, ``train``, the worst of every car.
"""

from __future__ import annotations

import re

import numpy as np
import pandas as pd
import xarray as xr

__all__ = ["car_table"]

_CAR = re.compile(r"^(?:rail@)?car(\d+)\.")


def car_table(table: pd.DataFrame, ds: xr.Dataset) -> pd.DataFrame | None:
    """One row per car of a train, and one for the whole train; None for a single vehicle.

    Parameters
    ----------
    table : pandas.DataFrame
        The run's summary table (:func:`railvib.results.stats.summary_table`), indexed by
        response, with its ``rms`` and ``rms_unit`` columns.
    ds : xarray.Dataset
        The run's result, with the contact check per wheel (``contact_force_rms`` in N,
        ``loss_of_contact_probability``), wheels in the order of the ``rail@`` responses.

    Returns
    -------
    pandas.DataFrame or None
        Indexed ``car1`` ... ``car<n>``, ``train``; columns ``car body bounce RMS``,
        ``worst rail RMS`` (in the unit of ``rms_unit``), ``worst contact force RMS [N]``
        and ``worst loss-of-contact probability [1]``.
    """
    cars = sorted({int(m.group(1)) for r in table.index if (m := _CAR.match(str(r)))})
    if len(cars) < 2:
        return None
    rails = [str(r) for r in ds["response"].values if str(r).startswith("rail@")]
    force = np.asarray(ds["contact_force_rms"].values, dtype=float)
    prob = np.asarray(ds["loss_of_contact_probability"].values, dtype=float)
    body_unit = _unit(table, f"car{cars[0]}.carbody.bounce")
    rail_unit = _unit(table, rails[0]) if rails else ""
    rows = {}
    for car in cars:
        mine = [j for j, r in enumerate(rails) if r.startswith(f"rail@car{car}.")]
        body = f"car{car}.carbody.bounce"
        rows[f"car{car}"] = {
            f"car body bounce RMS [{body_unit}]": (
                float(table.loc[body, "rms"]) if body in table.index else np.nan
            ),
            f"worst rail RMS [{rail_unit}]": max(float(table.loc[rails[j], "rms"]) for j in mine),
            "worst contact force RMS [N]": float(force[mine].max()),
            "worst loss-of-contact probability [1]": float(prob[mine].max()),
        }
    out = pd.DataFrame.from_dict(rows, orient="index")
    out.loc["train"] = out.max(axis=0)
    out.index.name = "car"
    return out


def _unit(table: pd.DataFrame, label: str) -> str:
    return str(table.loc[label, "rms_unit"]) if label in table.index else ""
