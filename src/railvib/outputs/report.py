"""The engineering criteria of one run as summary lines and tables (``railvib run``)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import xarray as xr

from railvib.labels import wheel_name
from railvib.outputs.comfort import mean_comfort_category
from railvib.outputs.octave import REFERENCES

__all__ = ["criteria_lines", "criteria_table", "octave_table"]


def _floor_label(s: float) -> str:
    return f"floor s = {s:+g} m"


def criteria_table(ds: xr.Dataset) -> pd.DataFrame:
    """Every criterion of a run, a row per criterion and location, with its unit and category.

    Parameters
    ----------
    ds : xarray.Dataset
        A run's result with the derived outputs (those absent are left out).

    Returns
    -------
    pandas.DataFrame
        Columns ``criterion``, ``where``, ``value``, ``unit``, ``category``, ``standard``.
    """
    rows: list[dict[str, object]] = []
    if "comfort_aw" in ds:
        weighting = ds["comfort_aw"].attrs["weighting"]
        for k, s in enumerate(ds["floor"].values):
            where = _floor_label(float(s))
            a_w = float(ds["comfort_aw"].values[k])
            n_mv = float(ds["mean_comfort_index"].values[k])
            rows += [
                {
                    "criterion": f"a_w ({weighting})",
                    "where": where,
                    "value": a_w,
                    "unit": "m/s^2",
                    "category": str(ds["comfort_category"].values[k]),
                    "standard": "ISO 2631-1:1997, clause 6 and Annex C",
                },
                {
                    "criterion": "N_MV (vertical, from PSD)",
                    "where": where,
                    "value": n_mv,
                    "unit": "1",
                    "category": mean_comfort_category(n_mv),
                    "standard": "EN 12299:2009, mean comfort (approximated: docs/criteria.md)",
                },
                {
                    "criterion": "Sperling Wz",
                    "where": where,
                    "value": float(ds["sperling_wz"].values[k]),
                    "unit": "1",
                    "category": "",
                    "standard": "Sperling (1941), filter form",
                },
            ]
    for j in range(ds.sizes["wheel"]):
        where = wheel_name(ds["response"].values, j)
        rows.append(
            {
                "criterion": "contact force RMS",
                "where": where,
                "value": float(ds["contact_force_rms"].values[j]),
                "unit": "N",
                "category": "",
                "standard": "",
            }
        )
        if "dynamic_load_factor" in ds:
            rows += [
                {
                    "criterion": "3-sigma dynamic load",
                    "where": where,
                    "value": float(ds["dynamic_load_3sigma"].values[j]),
                    "unit": "N",
                    "category": "",
                    "standard": "",
                },
                {
                    "criterion": "dynamic load factor 1 + 3 sigma/P0",
                    "where": where,
                    "value": float(ds["dynamic_load_factor"].values[j]),
                    "unit": "1",
                    "category": "",
                    "standard": "",
                },
            ]
        if "support_force_rms" in ds:
            rows += [
                {
                    "criterion": f"{layer} force RMS at the seat under the wheel",
                    "where": f"{where} (seat at x = {float(ds['support_position'].values[j]):g} m)",
                    "value": float(ds["support_force_rms"].sel(layer=layer).values[j]),
                    "unit": "N",
                    "category": "",
                    "standard": "per seat of one rail",
                }
                for layer in ds["layer"].values
            ]
        rows.append(
            {
                "criterion": "loss-of-contact probability",
                "where": where,
                "value": float(ds["loss_of_contact_probability"].values[j]),
                "unit": "1",
                "category": "",
                "standard": "Gaussian: Phi(-P0/sigma)",
            }
        )
    return pd.DataFrame(
        rows, columns=["criterion", "where", "value", "unit", "category", "standard"]
    )


def criteria_lines(ds: xr.Dataset) -> list[str]:
    """A few lines for a run's summary: ride comfort, the dynamic load factor, seat forces.

    Parameters
    ----------
    ds : xarray.Dataset
        A run's result with the derived outputs (those absent are left out).

    Returns
    -------
    list of str
        E.g. ``"ride comfort (a_w (Wb), 0.5-80 Hz): floor s = +6.3 m: a_w 0.118 m/s^2
        (not uncomfortable), N_MV 0.707 (very comfortable), Wz 2.42; ..."``.
    """
    lines = []
    if "comfort_aw" in ds:
        band = ds["comfort_aw"].attrs["band"]
        parts = []
        for k, s in enumerate(ds["floor"].values):
            a_w = float(ds["comfort_aw"].values[k])
            n_mv = float(ds["mean_comfort_index"].values[k])
            parts.append(
                f"{_floor_label(float(s))}: a_w {a_w:.3g} m/s^2 "
                f"({ds['comfort_category'].values[k]}), N_MV {n_mv:.3g} "
                f"({mean_comfort_category(n_mv)}), Wz {float(ds['sperling_wz'].values[k]):.3g}"
            )
        weighting = ds["comfort_aw"].attrs["weighting"]
        lines.append(f"ride comfort ({weighting}, {band}): " + "; ".join(parts))
    elif "frf_displacement" in ds:
        lines.append("ride comfort: not computed (the grid does not reach 0.5-80 Hz)")
    if "dynamic_load_factor" in ds:
        factor = ds["dynamic_load_factor"]
        j = int(np.argmax(factor.values))
        lines.append(
            f"wheel-rail forces: dynamic load factor 1 + 3 sigma/P0 = {float(factor[j]):.3g} "
            f"at the worst wheel ({wheel_name(ds['response'].values, j)}: 3 sigma = "
            f"{float(ds['dynamic_load_3sigma'].values[j]):.3g} N)"
        )
    if "support_force_rms" in ds:
        rms = ds["support_force_rms"].transpose("wheel", "layer").values
        j = int(np.argmax(rms[:, 0]))
        layers = ", ".join(
            f"{layer} {rms[j, k]:.3g} N" for k, layer in enumerate(ds["layer"].values)
        )
        lines.append(
            f"rail-seat forces (per seat of one rail, RMS): {layers} at the seat under the "
            f"worst wheel ({wheel_name(ds['response'].values, j)}, x = "
            f"{float(ds['support_position'].values[j]):.4g} m)"
        )
    if "octave_level_acceleration" in ds:
        nominal = ds["band_nominal"].values
        lines.append(
            f"one-third-octave levels: {nominal[0]:g}-{nominal[-1]:g} Hz bands in "
            f"third_octave.csv ({REFERENCES['acceleration'][1]}, {REFERENCES['force'][1]})"
        )
    return lines


def octave_table(ds: xr.Dataset) -> pd.DataFrame:
    """One-third-octave levels of a run: a row per band, a column per response and wheel.

    Parameters
    ----------
    ds : xarray.Dataset
        A run's result with the output ``third_octave``.

    Returns
    -------
    pandas.DataFrame
        Index ``nominal [Hz]``; columns ``exact [Hz]``, ``<response> [dB re 1e-6 m/s^2]``
        (acceleration; pitch responses re 1e-6 rad/s^2) and ``wheel<j> [dB re 1 N]``.
    """
    acc = ds["octave_level_acceleration"].transpose("band", "response")
    force = ds["octave_level_force"].transpose("band", "wheel")
    table = {"exact [Hz]": ds["band"].values}
    acc_ref = REFERENCES["acceleration"][1]
    units = ds["displacement_unit"].values if "displacement_unit" in ds.coords else None
    for k, label in enumerate(ds["response"].values):
        ref = (
            acc_ref if units is None or units[k] == "m" else acc_ref.replace(" m/", f" {units[k]}/")
        )
        table[f"{label} [{ref}]"] = acc.values[:, k]
    for j, wheel in enumerate(ds["wheel"].values):
        table[f"wheel{int(wheel)} [{REFERENCES['force'][1]}]"] = force.values[:, j]
    return pd.DataFrame(table, index=pd.Index(ds["band_nominal"].values, name="nominal [Hz]"))
